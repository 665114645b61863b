//! One GPU pass per module. Each owns its pipeline(s) and records itself into an encoder;
//! `crate::renderer` wires them top to bottom.

pub mod denoise;
pub mod direct;
pub mod material;
pub mod moment_mips;
pub mod pathtrace;
pub mod pdf_mips;
pub mod rsm_flux;
pub mod shadow_map;
pub mod visibility;
pub mod vpl_sample;
pub mod vpl_shading;
pub mod vsgl2_reduce;
pub mod vsgl_gen;
pub mod vsgl_moments;
pub mod vsgl_shading;

use crate::gpu::{Gpu, PassTimer};
use std::cell::RefCell;

/// What a frame did besides its passes, logged while it is recorded on this thread.
#[derive(Clone, Debug, Default)]
pub struct FrameLog {
    /// (label, bytes summed over allocations with that label), in first-use order
    /// (`frame.memory_bytes`).
    pub allocations: Vec<(String, u64)>,
    /// Every pipeline variant the frame bound: (shader path, entry point, override flags).
    pub variants: Vec<(String, String, Vec<(&'static str, bool)>)>,
}

thread_local! {
    /// The frame being recorded on this thread logs here (see [`log_frame`]).
    static FRAME_LOG: RefCell<Option<FrameLog>> = const { RefCell::new(None) };
}

fn with_frame_log(f: impl FnOnce(&mut FrameLog)) {
    FRAME_LOG.with(|log| {
        if let Some(log) = log.borrow_mut().as_mut() {
            f(log);
        }
    });
}

/// Notes that the frame allocated `bytes` for `label` (a no-op outside [`log_frame`]).
pub fn note_allocation(label: &str, bytes: u64) {
    with_frame_log(|log| match log.allocations.iter_mut().find(|(l, _)| l == label) {
        Some((_, b)) => *b += bytes,
        None => log.allocations.push((label.to_string(), bytes)),
    });
}

/// Notes that the frame bound this pipeline variant (a no-op outside [`log_frame`]).
pub fn note_variant(shader: &str, entry: &str, flags: &[(&'static str, bool)]) {
    with_frame_log(|log| {
        if !log.variants.iter().any(|(s, e, f)| s == shader && e == entry && f.as_slice() == flags) {
            log.variants.push((shader.to_string(), entry.to_string(), flags.to_vec()));
        }
    });
}

/// Runs `f` and returns what it logged: the allocations made through [`storage_buffer`] and
/// the other noted targets, and the pipeline variants bound.
pub fn log_frame<T>(f: impl FnOnce() -> T) -> (T, FrameLog) {
    let outer = FRAME_LOG.with(|log| log.borrow_mut().replace(FrameLog::default()));
    let value = f();
    let logged = FRAME_LOG.with(|log| std::mem::replace(&mut *log.borrow_mut(), outer)).unwrap_or_default();
    (value, logged)
}

/// Bind group entries for buffers/views in binding order 0, 1, 2, …
pub fn entries<'a>(resources: &[wgpu::BindingResource<'a>]) -> Vec<wgpu::BindGroupEntry<'a>> {
    resources
        .iter()
        .enumerate()
        .map(|(i, r)| wgpu::BindGroupEntry { binding: i as u32, resource: r.clone() })
        .collect()
}

/// Records one timed compute dispatch: bind group `g` gets `groups[g]` in binding order
/// (the pipeline's automatic layout), then `workgroups` are dispatched.
pub fn run_compute(
    gpu: &Gpu,
    enc: &mut wgpu::CommandEncoder,
    timer: &mut PassTimer,
    label: &str,
    pipeline: &wgpu::ComputePipeline,
    groups: &[&[wgpu::BindingResource<'_>]],
    workgroups: (u32, u32, u32),
) {
    let binds: Vec<wgpu::BindGroup> = groups
        .iter()
        .enumerate()
        .map(|(g, resources)| {
            gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some(label),
                layout: &pipeline.get_bind_group_layout(g as u32),
                entries: &entries(resources),
            })
        })
        .collect();
    let q = timer.begin(label);
    let mut pass = enc.begin_compute_pass(&wgpu::ComputePassDescriptor { label: Some(label), timestamp_writes: timer.compute_writes(q) });
    pass.set_pipeline(pipeline);
    for (g, b) in binds.iter().enumerate() {
        pass.set_bind_group(g as u32, b, &[]);
    }
    if workgroups.0 > 0 && workgroups.1 > 0 && workgroups.2 > 0 {
        pass.dispatch_workgroups(workgroups.0, workgroups.1, workgroups.2);
    }
}

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

/// A uniform buffer holding `value` (a `#[repr(C)]` twin of a WGSL struct).
pub fn uniform_buffer<T: bytemuck::Pod>(gpu: &Gpu, label: &str, value: &T) -> wgpu::Buffer {
    wgpu::util::DeviceExt::create_buffer_init(
        &gpu.device,
        &wgpu::util::BufferInitDescriptor { label: Some(label), contents: bytemuck::bytes_of(value), usage: wgpu::BufferUsages::UNIFORM },
    )
}

/// A storage buffer of `size` bytes (at least 16, as wgpu rejects empty bindings).
pub fn storage_buffer(gpu: &Gpu, label: &str, size: u64) -> wgpu::Buffer {
    note_allocation(label, size.max(16));
    gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: size.max(16),
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}
