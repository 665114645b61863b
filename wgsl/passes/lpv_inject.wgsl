// LPV light injection (compute, `method="lpv"`): every lit RSM texel becomes a small diffuse
// emitter — a virtual point light of flux Φ·R_d whose radiant intensity is the clamped cosine
// about its normal, I(ω) = Φ·R_d/π · max(0, n·ω) [Kaplanyan & Dachsbacher 2010], projected on two-band SH (common/lpv.wgsl) and
// added to the cell of every cascade that holds its position moved half a cell along n (the
// shift keeps a surface's own light out of the cells behind it, where it would light the
// surface itself).
// Only diffuse reflection is injected: the papers compare LPVs on the light–diffuse–diffuse–eye
// path alone (the 2015 poster, Table 1), and a glossy texel's lobe does not fit two SH bands.
#include "common/constants.wgsl"
#include "common/gbuffer.wgsl"
#include "common/lpv.wgsl"

const WORKGROUP: u32 = 8u;

struct InjectParams {
    // The light's position relative to the eye (RSM positions are relative to the light).
    light_offset: vec3f,
    rsm_size: u32,
}

@group(0) @binding(0) var<uniform> grid: LpvGrid;
@group(0) @binding(1) var<uniform> params: InjectParams;
@group(0) @binding(2) var<storage, read> rsm_position: array<vec4f>;
@group(0) @binding(3) var<storage, read> rsm_normal: array<vec4f>;
@group(0) @binding(4) var<storage, read> rsm_flux_diffuse: array<vec4f>;
// The light volume of every cascade, f32 bits (see atomic_float.wgsl).
@group(0) @binding(5) var<storage, read_write> float_sums: array<atomic<u32>>;

#include "common/atomic_float.wgsl"

@compute @workgroup_size(WORKGROUP, WORKGROUP, 1)
fn main(@builtin(global_invocation_id) gid: vec3u) {
    let n_rsm = params.rsm_size;
    if (gid.x >= n_rsm || gid.y >= n_rsm) {
        return;
    }
    let i = gid.y * n_rsm + gid.x;
    let position = rsm_position[i];
    let flux = rsm_flux_diffuse[i].rgb;
    if (position.w == GBUFFER_BACKGROUND || all(flux <= vec3f(0.0))) {
        return;
    }
    let normal = normalize(rsm_normal[i].xyz);
    let p = position.xyz + params.light_offset;
    let lobe = sh_clamped_cosine(normal) * INV_PI;
    let side = grid.side;
    for (var c = 0u; c < grid.cascade_count; c++) {
        let g = grid.cascades[c];
        let u = (p + 0.5 * g.w * normal - g.xyz) / g.w;
        if (any(u < vec3f(0.0)) || any(u >= vec3f(f32(side)))) {
            continue;
        }
        let cell = min(vec3u(u), vec3u(side - 1u));
        let base = 4u * lpv_cell_index(c, cell, side);
        for (var ch = 0u; ch < 3u; ch++) {
            let sh = lobe * flux[ch];
            for (var k = 0u; k < 4u; k++) {
                atomic_add_float(base + 4u * ch + k, sh[k]);
            }
        }
    }
}
