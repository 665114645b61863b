// LPV geometry volume (compute, `method="lpv"`, `lpv_occlusion=True`): every RSM texel is a
// surfel of area A that blocks light crossing it; its blocking potential, the probability that
// light arriving from direction ω is stopped inside a cell of side s, is
//   B(ω) = A·max(0, n·ω) / s²          [Kaplanyan & Dachsbacher 2010],
// projected on two-band SH and added to the geometry-volume cell centred on the light-volume
// corner nearest the surfel (the geometry volume is offset by half a cell). A is the
// texel's cross-section towards the light over the cosine between its normal and the light
// (common/rsm_texel.wgsl, rsm_texel_area); A/s² is capped at 1, a fully blocked cell.
// Only the lights' RSMs are injected, not the camera's G-buffer (the paper injects both):
// surfaces no light reaches do not block.
#include "common/constants.wgsl"
#include "common/gbuffer.wgsl"
#include "common/lpv.wgsl"
#include "common/rsm_texel.wgsl"

const WORKGROUP: u32 = 8u;

struct GeometryParams {
    // The light's position relative to the eye (RSM positions are relative to the light).
    light_offset: vec3f,
    rsm_size: u32,
    // LightRaw::rsm_light_dir and LightRsm::texel_footprint (rsm_texel_area).
    light_dir: vec4f,
    texel_footprint: vec4f,
}

@group(0) @binding(0) var<uniform> grid: LpvGrid;
@group(0) @binding(1) var<uniform> params: GeometryParams;
@group(0) @binding(2) var<storage, read> rsm_position: array<vec4f>;
@group(0) @binding(3) var<storage, read> rsm_normal: array<vec4f>;
// The geometry volume of every cascade, f32 bits (see atomic_float.wgsl).
@group(0) @binding(4) var<storage, read_write> float_sums: array<atomic<u32>>;

#include "common/atomic_float.wgsl"

@compute @workgroup_size(WORKGROUP, WORKGROUP, 1)
fn main(@builtin(global_invocation_id) gid: vec3u) {
    let n_rsm = params.rsm_size;
    if (gid.x >= n_rsm || gid.y >= n_rsm) {
        return;
    }
    let i = gid.y * n_rsm + gid.x;
    let position = rsm_position[i];
    if (position.w == GBUFFER_BACKGROUND) {
        return;
    }
    let normal = normalize(rsm_normal[i].xyz);
    let area = rsm_texel_area(position.xyz, normal, params.light_dir, params.texel_footprint);
    let p = position.xyz + params.light_offset;
    let side = grid.side;
    for (var c = 0u; c < grid.cascade_count; c++) {
        let g = grid.cascades[c];
        // Nearest corner: corners sit at whole cell coordinates.
        let u = (p - g.xyz) / g.w + 0.5;
        if (any(u < vec3f(0.0)) || any(u >= vec3f(f32(side + 1u)))) {
            continue;
        }
        let corner = min(vec3u(u), vec3u(side));
        let sh = sh_clamped_cosine(normal) * min(area / (g.w * g.w), 1.0);
        let base = 4u * lpv_geometry_index(c, corner, side);
        for (var k = 0u; k < 4u; k++) {
            atomic_add_float(base + k, sh[k]);
        }
    }
}
