//! How a long render reports its progress and is stopped: below every layer that runs GPU work
//! (the passes and methods that loop over batches ask it; the frame script and the Python edge
//! give it), so none of them reaches up into the renderer for it.

use crate::error::Result;

/// A check that a long render makes between GPU batches, told how far it is; `Err` stops it
/// (e.g. [`crate::Error::Interrupted`] when the user pressed Ctrl-C).
#[derive(Clone)]
pub struct StopCheck(pub std::sync::Arc<dyn Fn(Progress) -> Result<()> + Send + Sync>);

/// How far a long render is: `done` of `total` units of `unit` (e.g. "spp", "texels").
#[derive(Clone, Copy, Debug)]
pub struct Progress {
    pub done: u64,
    pub total: u64,
    pub unit: &'static str,
}

impl StopCheck {
    pub fn check(&self, progress: Progress) -> Result<()> {
        (self.0)(progress)
    }
}

impl std::fmt::Debug for StopCheck {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("StopCheck")
    }
}
