//! Bind groups kept from frame to frame. A frame's buffers and targets are kept
//! ([`super::FrameResources`]) and its pipelines are cached ([`super::PipelineVariants`]), so
//! the bind group a pass makes for the same (pipeline, group, resources) is the same every
//! frame: made once, then reused. What no frame asked for in the last
//! [`super::resources::RETAIN_FRAMES`] frames is dropped (its key holds the resources alive).

use super::frame_log::note_bind_group_created;
use super::Gpu;
use std::collections::HashMap;

/// The pipeline whose automatic layout a bind group follows.
#[derive(Clone, Copy)]
pub enum PipelineRef<'p> {
    Compute(&'p wgpu::ComputePipeline),
    Render(&'p wgpu::RenderPipeline),
}

impl PipelineRef<'_> {
    fn layout(&self, group: u32) -> wgpu::BindGroupLayout {
        match self {
            PipelineRef::Compute(p) => p.get_bind_group_layout(group),
            PipelineRef::Render(p) => p.get_bind_group_layout(group),
        }
    }

    fn key(&self) -> PipelineKey {
        match self {
            PipelineRef::Compute(p) => PipelineKey::Compute((*p).clone()),
            PipelineRef::Render(p) => PipelineKey::Render((*p).clone()),
        }
    }
}

/// Pipelines are keyed by identity (wgpu handles hash by id); the layouts they hand out
/// are not, as each `get_bind_group_layout` call may return a new handle.
#[derive(Clone, PartialEq, Eq, Hash)]
enum PipelineKey {
    Compute(wgpu::ComputePipeline),
    Render(wgpu::RenderPipeline),
}

/// One binding by identity.
#[derive(Clone, PartialEq, Eq, Hash)]
enum ResourceKey {
    Buffer(wgpu::Buffer, u64, Option<wgpu::BufferSize>),
    TextureView(wgpu::TextureView),
    Sampler(wgpu::Sampler),
}

fn resource_key(r: &wgpu::BindingResource<'_>) -> Option<ResourceKey> {
    match r {
        wgpu::BindingResource::Buffer(b) => Some(ResourceKey::Buffer(b.buffer.clone(), b.offset, b.size)),
        wgpu::BindingResource::TextureView(v) => Some(ResourceKey::TextureView((*v).clone())),
        wgpu::BindingResource::Sampler(s) => Some(ResourceKey::Sampler((*s).clone())),
        // Arrays are not used by any pass; they are bound fresh.
        _ => None,
    }
}

type Key = (PipelineKey, u32, Vec<ResourceKey>);

/// The bind groups of one renderer.
#[derive(Default)]
pub struct BindGroupCache {
    entries: HashMap<Key, (wgpu::BindGroup, u64)>,
}

impl BindGroupCache {
    /// The bind group of `pipeline`'s group `group` with `resources` in binding order 0, 1, …
    /// (made now if no earlier frame made it). `frame` is the frame counter of the caller.
    pub fn get(&mut self, gpu: &Gpu, frame: u64, label: &str, pipeline: PipelineRef<'_>, group: u32, resources: &[wgpu::BindingResource<'_>]) -> wgpu::BindGroup {
        let make = || {
            note_bind_group_created();
            gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some(label),
                layout: &pipeline.layout(group),
                entries: &super::entries(resources),
            })
        };
        let Some(keys) = resources.iter().map(resource_key).collect::<Option<Vec<_>>>() else { return make() };
        let key = (pipeline.key(), group, keys);
        if let Some((bind, last)) = self.entries.get_mut(&key) {
            *last = frame;
            return bind.clone();
        }
        let bind = make();
        self.entries.insert(key, (bind.clone(), frame));
        bind
    }

    /// Drops what was not used since frame `oldest_kept`.
    pub fn retain_since(&mut self, oldest_kept: u64) {
        self.entries.retain(|_, (_, last)| *last >= oldest_kept);
    }
}
