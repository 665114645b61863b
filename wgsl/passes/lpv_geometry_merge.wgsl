// LPV geometry-volume merge (compute, `method="lpv"` with `lpv_occlusion` and more than one
// light): folds one light's geometry volume (its RSMs' surfels, lpv_geometry.wgsl) into the
// frame's, keeping per cell the lobe with the larger DC term (the more surface seen).
// Why not a sum: every light's RSM samples the same surfaces again, so summing the lights'
// blocking potentials would block light once per light that sees the occluder (two lights at
// the same place halved the bounce). The surface a cell holds is what the view that saw most of
// it saw; a cell whose surfaces are seen part by one light and part by another keeps the larger
// part only (docs/methods/lpv.md, "Geometry volume").
#include "common/constants.wgsl"

const WORKGROUP: u32 = 64u;

struct MergeParams {
    // Geometry cells over all cascades ((side + 1)³ each).
    cells: u32,
}

@group(0) @binding(0) var<uniform> params: MergeParams;
// One light's volume (two-band SH per cell, the f32 bits lpv_geometry's atomic adds leave).
@group(0) @binding(1) var<storage, read> light_geometry: array<vec4f>;
@group(0) @binding(2) var<storage, read_write> geometry: array<vec4f>;

@compute @workgroup_size(WORKGROUP, 1, 1)
fn main(@builtin(global_invocation_id) gid: vec3u) {
    if (gid.x >= params.cells) {
        return;
    }
    let candidate = light_geometry[gid.x];
    if (candidate.x > geometry[gid.x].x) {
        geometry[gid.x] = candidate;
    }
}
