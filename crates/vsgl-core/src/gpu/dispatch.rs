//! Recording compute work: bind groups in binding order, timed and labelled dispatches, and
//! workgroup counts from thread counts.

use super::{Gpu, PassTimer};

/// Workgroups needed to cover `threads` with groups of `group` (callers count threads, not
/// groups, as kajiya does).
pub fn groups(threads: u32, group: u32) -> u32 {
    threads.div_ceil(group)
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
