// Two VSGLs by parallel summation, subgroup implementation: each subgroup sums its lanes'
// moments with subgroupAdd (in registers, no barrier), then the per-subgroup sums (at most
// GROUP / subgroup size of them) are added by a pairwise tree in workgroup memory. Same
// dispatches, partials and records as passes/vsgl2_reduce.wgsl; used when the adapter has
// wgpu's SUBGROUP feature (lavapipe and NVIDIA do), chosen by `vsgl2_reduction`. No
// `enable subgroups;` directive: naga 30 rejects it and gates the built-ins on the device
// feature instead, so this module is only created on devices that have it.
#include "common/vsgl2_moments.wgsl"

// One slot per subgroup. Sized for subgroups of one lane (wgpu exposes no minimum subgroup
// size), so it is as large as the shared-memory variant's array; the gain is fewer barriers.
var<workgroup> subgroup_sums: array<Moments2, GROUP>;

fn subgroup_sum(m: Moments2) -> Moments2 {
    return Moments2(
        subgroupAdd(m.diffuse_power),
        subgroupAdd(m.diffuse_direction),
        subgroupAdd(m.diffuse_position),
        subgroupAdd(m.specular_power),
        subgroupAdd(m.specular_direction),
        subgroupAdd(m.specular_position),
        subgroupAdd(m.plane),
    );
}

// The workgroup total of `m` (valid in thread 0). Called in uniform control flow. The
// per-subgroup sums are added by a pairwise tree over `count` slots (any count, not only
// powers of two: the stride starts at the power of two below it).
fn workgroup_sum(m: Moments2, lid: u32, lane: u32, sid: u32, count: u32) -> Moments2 {
    let s = subgroup_sum(m);
    if (lane == 0u) {
        subgroup_sums[sid] = s;
    }
    var stride = 1u;
    while (2u * stride < count) {
        stride = 2u * stride;
    }
    for (; stride > 0u; stride = stride / 2u) {
        workgroupBarrier();
        if (lid < stride && lid + stride < count) {
            subgroup_sums[lid] = moments_add(subgroup_sums[lid], subgroup_sums[lid + stride]);
        }
    }
    workgroupBarrier();
    return subgroup_sums[0];
}

// One workgroup per 8×8 RSM tile as in the shared-memory variant, but declared 1-D (naga
// allows the subgroup built-ins only in 1-D workgroups): lane `lid` takes texel (lid % 8, lid / 8).
@compute @workgroup_size(GROUP, 1, 1)
fn tiles(
    @builtin(local_invocation_index) lid: u32,
    @builtin(workgroup_id) wid: vec3u,
    @builtin(num_workgroups) groups: vec3u,
    @builtin(subgroup_invocation_id) lane: u32,
    @builtin(subgroup_id) sid: u32,
    @builtin(num_subgroups) count: u32,
) {
    let xy = wid.xy * TILE + vec2u(lid % TILE, lid / TILE);
    let total = workgroup_sum(texel_moments(xy), lid, lane, sid, count);
    if (lid == 0u) {
        partial_out[wid.y * groups.x + wid.x] = total;
    }
}

@compute @workgroup_size(GROUP, 1, 1)
fn merge(
    @builtin(local_invocation_index) lid: u32,
    @builtin(workgroup_id) wid: vec3u,
    @builtin(subgroup_invocation_id) lane: u32,
    @builtin(subgroup_id) sid: u32,
    @builtin(num_subgroups) count: u32,
) {
    let total = workgroup_sum(merge_inputs(wid.x, lid), lid, lane, sid, count);
    if (lid != 0u) {
        return;
    }
    partial_out[wid.x] = total;
    if (params.finish == 1u) {
        write_records(total);
    }
}
