// Two VSGLs by parallel summation, shared-memory implementation (the fallback where the adapter
// has no subgroup operations): the moments of wgsl/common/vsgl2_moments.wgsl summed by a pairwise
// tree in workgroup memory [the 2015 poster, Fig. 2: 8×8 tiles, then merges].
#include "common/vsgl2_moments.wgsl"

var<workgroup> shared_moments: array<Moments2, GROUP>;

// Pairwise tree over shared_moments[0 … GROUP); the total ends in shared_moments[0]. Called in
// uniform control flow by every thread of the workgroup.
fn reduce_shared(lid: u32) {
    for (var stride = GROUP / 2u; stride > 0u; stride = stride / 2u) {
        workgroupBarrier();
        if (lid < stride) {
            shared_moments[lid] = moments_add(shared_moments[lid], shared_moments[lid + stride]);
        }
    }
    workgroupBarrier();
}

@compute @workgroup_size(TILE, TILE, 1)
fn tiles(
    @builtin(global_invocation_id) gid: vec3u,
    @builtin(local_invocation_index) lid: u32,
    @builtin(workgroup_id) wid: vec3u,
    @builtin(num_workgroups) groups: vec3u,
) {
    shared_moments[lid] = texel_moments(gid.xy);
    reduce_shared(lid);
    if (lid == 0u) {
        partial_out[wid.y * groups.x + wid.x] = shared_moments[0];
    }
}

@compute @workgroup_size(GROUP, 1, 1)
fn merge(@builtin(local_invocation_index) lid: u32, @builtin(workgroup_id) wid: vec3u) {
    shared_moments[lid] = merge_inputs(wid.x, lid);
    reduce_shared(lid);
    if (lid != 0u) {
        return;
    }
    let total = shared_moments[0];
    partial_out[wid.x] = total;
    if (params.finish == 1u) {
        write_records(total);
    }
}
