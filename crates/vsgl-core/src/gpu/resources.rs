//! GPU buffers and textures a renderer keeps from frame to frame. A frame asks for each by
//! label; the n-th request of a label in a frame gets the buffer the n-th request of the
//! previous frames got, when its size, usage (and for textures, shape and format) match, so an
//! unchanged configuration creates nothing on its second frame (`frame.settings["allocated_bytes"]`).
//! What a frame no longer asks for is dropped after [`RETAIN_FRAMES`] frames.
//!
//! Contents: a storage buffer handed out is zero, as a new one is (a reused one is cleared on the
//! GPU first, so no pass can read the previous frame's data); uniform and initialised buffers
//! are written with `Queue::write_buffer`, which the queue orders after earlier submissions and
//! before the next one, so a frame never changes what an earlier frame still reads.

use super::bind_groups::{BindGroupCache, PipelineRef};
use super::frame_log::{note_allocation, note_use};
use super::Gpu;
use std::collections::HashMap;

/// Frames an unused resource is kept for (so alternating between two configurations, as the
/// benchmark's `--plans auto,full` does, does not re-create both every frame).
pub const RETAIN_FRAMES: u64 = 2;

#[derive(Clone, Debug, PartialEq, Eq)]
enum Shape {
    Buffer { size: u64, usage: wgpu::BufferUsages },
    Texture { size: wgpu::Extent3d, format: wgpu::TextureFormat, usage: wgpu::TextureUsages },
}

#[derive(Clone)]
enum Resource {
    Buffer(wgpu::Buffer),
    Texture(wgpu::Texture),
}

struct Entry {
    shape: Shape,
    resource: Resource,
    last_frame: u64,
}

/// The resources of one renderer, by (label, n-th request in a frame).
#[derive(Default)]
pub struct FrameResources {
    entries: HashMap<(String, u32), Entry>,
    requests: HashMap<String, u32>,
    frame: u64,
    bind_groups: BindGroupCache,
    /// Views of kept textures, so the bind groups over them can be kept too.
    views: HashMap<(wgpu::Texture, ViewKey), (wgpu::TextureView, u64)>,
}

/// What distinguishes the views of one texture that the passes make.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
struct ViewKey {
    dimension: Option<wgpu::TextureViewDimension>,
    base_array_layer: u32,
    array_layer_count: Option<u32>,
}

impl FrameResources {
    /// Starts a frame: request counts start again from zero.
    pub fn begin_frame(&mut self) {
        self.frame += 1;
        self.requests.clear();
    }

    /// Ends a frame: drops what no frame asked for in the last [`RETAIN_FRAMES`] frames.
    pub fn end_frame(&mut self) {
        let frame = self.frame;
        self.entries.retain(|_, e| frame - e.last_frame < RETAIN_FRAMES);
        let oldest_kept = (frame + 1).saturating_sub(RETAIN_FRAMES);
        self.bind_groups.retain_since(oldest_kept);
        self.views.retain(|_, (_, last)| *last >= oldest_kept);
    }

    /// A view of `texture` (one this renderer keeps): the same view every frame, so bind groups
    /// over it are kept too. `desc` may set the label, dimension and array layers.
    pub fn texture_view(&mut self, texture: &wgpu::Texture, desc: &wgpu::TextureViewDescriptor<'_>) -> wgpu::TextureView {
        let key = ViewKey { dimension: desc.dimension, base_array_layer: desc.base_array_layer, array_layer_count: desc.array_layer_count };
        let frame = self.frame;
        let (view, last) = self.views.entry((texture.clone(), key)).or_insert_with(|| (texture.create_view(desc), frame));
        *last = frame;
        view.clone()
    }

    /// The bind group of `pipeline`'s group `group` with `resources` in binding order, kept
    /// from an earlier frame when it bound the same resources ([`BindGroupCache`]).
    pub fn bind_group(&mut self, gpu: &Gpu, label: &str, pipeline: PipelineRef<'_>, group: u32, resources: &[wgpu::BindingResource<'_>]) -> wgpu::BindGroup {
        self.bind_groups.get(gpu, self.frame, label, pipeline, group, resources)
    }

    /// The resource for this request and whether it is new; `make` creates it when none fits.
    fn get(&mut self, label: &str, shape: Shape, bytes: u64, make: impl FnOnce() -> Resource) -> (Resource, bool) {
        let n = self.requests.entry(label.to_string()).or_insert(0);
        let key = (label.to_string(), *n);
        *n += 1;
        note_use(label, bytes);
        if let Some(e) = self.entries.get_mut(&key) {
            if e.shape == shape {
                e.last_frame = self.frame;
                return (e.resource.clone(), false);
            }
        }
        note_allocation(label, bytes);
        let resource = make();
        self.entries.insert(key, Entry { shape, resource: resource.clone(), last_frame: self.frame });
        (resource, true)
    }

    /// A buffer of `size` bytes (at least 16: wgpu rejects empty bindings) and `usage`; whether
    /// it is new (else the caller must not assume its contents).
    pub fn buffer(&mut self, gpu: &Gpu, label: &str, size: u64, usage: wgpu::BufferUsages) -> (wgpu::Buffer, bool) {
        let size = size.max(16);
        let make = || Resource::Buffer(gpu.device.create_buffer(&wgpu::BufferDescriptor { label: Some(label), size, usage, mapped_at_creation: false }));
        match self.get(label, Shape::Buffer { size, usage }, size, make) {
            (Resource::Buffer(b), new) => (b, new),
            // A key always holds the kind its shape says.
            (Resource::Texture(_), _) => unreachable!("a buffer key holds a texture"),
        }
    }

    /// A texture as described (its `label` names it); `bytes` is what `frame.memory_bytes`
    /// counts for it.
    pub fn texture(&mut self, gpu: &Gpu, desc: &wgpu::TextureDescriptor<'_>, bytes: u64) -> wgpu::Texture {
        let label = desc.label.unwrap_or("unlabelled_texture");
        let shape = Shape::Texture { size: desc.size, format: desc.format, usage: desc.usage };
        match self.get(label, shape, bytes, || Resource::Texture(gpu.device.create_texture(desc))) {
            (Resource::Texture(t), _) => t,
            (Resource::Buffer(_), _) => unreachable!("a texture key holds a buffer"),
        }
    }

    /// Bytes held across frames (what a renderer keeps between renders).
    pub fn held_bytes(&self) -> u64 {
        self.entries
            .values()
            .map(|e| match &e.shape {
                Shape::Buffer { size, .. } => *size,
                Shape::Texture { size, format, .. } => {
                    size.width as u64 * size.height as u64 * size.depth_or_array_layers as u64 * format.block_copy_size(None).unwrap_or(4) as u64
                }
            })
            .sum()
    }
}
