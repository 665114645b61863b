//! Recording compute work: bind groups in binding order, timed and labelled dispatches, and
//! workgroup counts from thread counts.

use super::{FrameResources, Gpu, PassTimer, PipelineRef};

/// Workgroups needed to cover `threads` with groups of `group` (callers count threads, not
/// groups, as kajiya does).
pub fn groups(threads: u32, group: u32) -> u32 {
    threads.div_ceil(group)
}

/// Workgroups of an interleaved shading pass over `size` pixels (`wgsl/common/interleave.wgsl`):
/// per axis, k classes × the workgroups one class's pixels need.
pub fn interleaved_groups(size: (u32, u32), k: u32, group: u32) -> (u32, u32, u32) {
    interleaved_block_groups(size, k, (group, group))
}

/// [`interleaved_groups`] for workgroups that each cover `footprint` pixels of their class along
/// x and y (`interleaved_block_pixel` in `wgsl/common/interleave.wgsl`): threads that shade
/// several pixels each.
pub fn interleaved_block_groups(size: (u32, u32), k: u32, footprint: (u32, u32)) -> (u32, u32, u32) {
    (k * groups(size.0.div_ceil(k), footprint.0), k * groups(size.1.div_ceil(k), footprint.1), 1)
}

/// Bind group entries for buffers/views in binding order 0, 1, 2, …
pub fn entries<'a>(resources: &[wgpu::BindingResource<'a>]) -> Vec<wgpu::BindGroupEntry<'a>> {
    resources
        .iter()
        .enumerate()
        .map(|(i, r)| wgpu::BindGroupEntry { binding: i as u32, resource: r.clone() })
        .collect()
}

/// Where a frame's GPU work is recorded: the device, the current command encoder and the
/// frame's timer. Passes take one instead of the three; a frame that must submit part of its
/// work early (long jobs, readbacks in the middle) continues in a fresh encoder.
pub struct Recorder<'a> {
    pub gpu: &'a Gpu,
    pub enc: wgpu::CommandEncoder,
    pub timer: &'a mut PassTimer,
    /// Buffers and textures kept from frame to frame (see [`FrameResources`]).
    pub resources: &'a mut FrameResources,
}

impl<'a> Recorder<'a> {
    pub fn new(gpu: &'a Gpu, timer: &'a mut PassTimer, resources: &'a mut FrameResources) -> Self {
        Self { gpu, enc: Self::encoder(gpu), timer, resources }
    }

    /// A zero storage buffer of `size` bytes (new, or kept from an earlier frame and cleared).
    pub fn storage(&mut self, label: &str, size: u64) -> wgpu::Buffer {
        let usage = wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST;
        let (buffer, new) = self.resources.buffer(self.gpu, label, size, usage);
        if !new {
            // As a new buffer is: passes that accumulate (shading adds into its targets) rely on it.
            self.enc.clear_buffer(&buffer, 0, None);
        }
        buffer
    }

    /// A storage buffer every word of which the caller writes before anything reads it (so a
    /// kept one is not cleared).
    pub fn storage_written(&mut self, label: &str, size: u64) -> wgpu::Buffer {
        let usage = wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST;
        self.resources.buffer(self.gpu, label, size, usage).0
    }

    /// A read-only storage buffer holding `bytes`.
    pub fn storage_init(&mut self, label: &str, bytes: &[u8]) -> wgpu::Buffer {
        let usage = wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST;
        let (buffer, _) = self.resources.buffer(self.gpu, label, bytes.len() as u64, usage);
        self.gpu.queue.write_buffer(&buffer, 0, bytes);
        buffer
    }

    /// A uniform buffer holding `value` (a `#[repr(C)]` twin of a WGSL struct).
    pub fn uniform<T: bytemuck::Pod>(&mut self, label: &str, value: &T) -> wgpu::Buffer {
        let usage = wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST;
        let bytes = bytemuck::bytes_of(value);
        let (buffer, _) = self.resources.buffer(self.gpu, label, bytes.len() as u64, usage);
        self.gpu.queue.write_buffer(&buffer, 0, bytes);
        buffer
    }

    /// A texture as described (kept from frame to frame like the buffers); `bytes` is what
    /// `frame.memory_bytes` counts for it.
    pub fn texture(&mut self, desc: &wgpu::TextureDescriptor<'_>, bytes: u64) -> wgpu::Texture {
        self.resources.texture(self.gpu, desc, bytes)
    }

    /// A view of a kept texture, the same every frame (see [`FrameResources::texture_view`]).
    pub fn texture_view(&mut self, texture: &wgpu::Texture, desc: &wgpu::TextureViewDescriptor<'_>) -> wgpu::TextureView {
        self.resources.texture_view(texture, desc)
    }

    fn encoder(gpu: &Gpu) -> wgpu::CommandEncoder {
        gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("frame_encoder") })
    }

    /// Submits what is recorded so far and continues in a fresh encoder; returns the
    /// submission, for a readback in the middle of a frame to wait on.
    pub fn submit_so_far(&mut self) -> wgpu::SubmissionIndex {
        let done = std::mem::replace(&mut self.enc, Self::encoder(self.gpu));
        self.gpu.queue.submit([done.finish()])
    }

    /// Records `f`'s passes inside a debug group called `label` (what GPU debuggers show).
    /// `f` must not submit: a group cannot span encoders.
    pub fn in_debug_group<T>(&mut self, label: &str, f: impl FnOnce(&mut Self) -> T) -> T {
        self.enc.push_debug_group(label);
        let value = f(self);
        self.enc.pop_debug_group();
        value
    }

    /// Records one timed compute dispatch in its own debug group: bind group `g` gets
    /// `groups[g]` in binding order (the pipeline's automatic layout), then `workgroups` are
    /// dispatched.
    pub fn compute(&mut self, label: &str, pipeline: &wgpu::ComputePipeline, groups: &[&[wgpu::BindingResource<'_>]], workgroups: (u32, u32, u32)) {
        let binds: Vec<wgpu::BindGroup> = groups
            .iter()
            .enumerate()
            .map(|(g, resources)| self.bind_group(label, PipelineRef::Compute(pipeline), g as u32, resources))
            .collect();
        self.in_debug_group(label, |rec| {
            let q = rec.timer.begin(label);
            let mut pass = rec.enc.begin_compute_pass(&wgpu::ComputePassDescriptor { label: Some(label), timestamp_writes: rec.timer.compute_writes(q) });
            pass.set_pipeline(pipeline);
            for (g, b) in binds.iter().enumerate() {
                pass.set_bind_group(g as u32, b, &[]);
            }
            if workgroups.0 > 0 && workgroups.1 > 0 && workgroups.2 > 0 {
                pass.dispatch_workgroups(workgroups.0, workgroups.1, workgroups.2);
            }
        });
    }

    /// The bind group of `pipeline`'s group `group` with `resources` in binding order 0, 1, …,
    /// kept from frame to frame.
    pub fn bind_group(&mut self, label: &str, pipeline: PipelineRef<'_>, group: u32, resources: &[wgpu::BindingResource<'_>]) -> wgpu::BindGroup {
        self.resources.bind_group(self.gpu, label, pipeline, group, resources)
    }

    /// Records `f`'s passes without timing or logging them (work that is not a pass of the
    /// frame, such as clearing a placeholder target).
    pub fn untimed<T>(&mut self, f: impl FnOnce(&mut Recorder<'_>) -> T) -> T {
        let mut off = PassTimer::new_disabled();
        // The spare encoder swapped in is dropped unused.
        let enc = std::mem::replace(&mut self.enc, Self::encoder(self.gpu));
        let mut inner = Recorder { gpu: self.gpu, enc, timer: &mut off, resources: &mut *self.resources };
        let value = f(&mut inner);
        self.enc = inner.enc;
        value
    }

    /// The encoder, for the frame's final submission.
    pub fn finish(self) -> wgpu::CommandEncoder {
        self.enc
    }
}

/// Most virtual lights per pixel one shading dispatch loops over with shadow rays
/// (`visibility="raytrace"`), where every light also loops over BVH nodes.
///
/// lavapipe (Mesa's llvmpipe) ends shader loops once an invocation has run 65535 loop
/// iterations in all, counted over every loop of the invocation, nested ones included. An
/// invocation past the cap loses its whole output: measured on glossy_cornell at 64², the
/// workgroups of the back wall behind the sphere, whose shadow rays pass the sphere's 4096
/// triangles, wrote 0 for every pixel from 896 VSGLs per dispatch on (1024 at 1000), while
/// 768 were right. So on a CPU adapter a dispatch takes `CPU_TRACED_LIGHTS_PER_DISPATCH`,
/// which leaves ~1000 BVH iterations per shadow ray; GPUs have no such cap and keep
/// `TRACED_LIGHTS_PER_DISPATCH` (fewer dispatches, each re-reading the G-buffer).
pub fn traced_lights_per_dispatch(gpu: &Gpu) -> u32 {
    if gpu.caps_loop_iterations() {
        CPU_TRACED_LIGHTS_PER_DISPATCH
    } else {
        TRACED_LIGHTS_PER_DISPATCH
    }
}

/// See [`traced_lights_per_dispatch`].
pub const TRACED_LIGHTS_PER_DISPATCH: u32 = 1024;
/// See [`traced_lights_per_dispatch`].
pub const CPU_TRACED_LIGHTS_PER_DISPATCH: u32 = 64;

/// Calls `dispatch(first, count)` for consecutive chunks of at most `chunk` of `total` items:
/// the shading passes split long light lists over dispatches (lavapipe ends shader loops after
/// 65536 iterations) that add into the same targets.
pub fn for_each_chunk(total: u32, chunk: u32, mut dispatch: impl FnMut(u32, u32)) {
    let mut first = 0;
    while first < total {
        let count = (total - first).min(chunk);
        dispatch(first, count);
        first += count;
    }
}
