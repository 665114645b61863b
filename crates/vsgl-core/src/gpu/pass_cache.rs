//! The passes a renderer has created, one of each type, made on first use: a frame asks for the
//! passes its method records, so a renderer that only ever renders `direct` never compiles the
//! VSGL pipelines, and no pass is created twice.

use super::Gpu;
use crate::error::Result;
use std::any::{Any, TypeId};
use std::collections::HashMap;
use std::sync::{Arc, Mutex};

/// A GPU pass: its pipelines are created once, from the device alone.
pub trait Pass: Send + Sync + Sized + 'static {
    fn create(gpu: &Gpu) -> Result<Self>;
}

type AnyPass = Arc<dyn Any + Send + Sync>;

pub struct PassCache {
    gpu: Arc<Gpu>,
    created: Mutex<HashMap<TypeId, AnyPass>>,
}

impl PassCache {
    pub fn new(gpu: Arc<Gpu>) -> Self {
        Self { gpu, created: Mutex::new(HashMap::new()) }
    }

    /// The pass of type `P`, created now if this is its first use.
    pub fn get<P: Pass>(&self) -> Result<Arc<P>> {
        let mut created = self.created.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(p) = created.get(&TypeId::of::<P>()) {
            if let Ok(p) = p.clone().downcast::<P>() {
                return Ok(p);
            }
        }
        let pass = Arc::new(P::create(&self.gpu)?);
        created.insert(TypeId::of::<P>(), pass.clone());
        Ok(pass)
    }
}
