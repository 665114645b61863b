// VPL sampling from the reflective shadow map (compute).
// `importance`: N VPLs with probability p(s) ∝ Φ·(R_d + R_s) [Tok15 §4.2 default importance] by
// hierarchical sample warping down the weight pyramid [Clarberg et al. 2005]; sample points are
// a Fibonacci lattice [Tok16, stratified centres] or seeded random numbers, both shifted per
// seed (Cranley–Patterson rotation) so seeds give independent estimates; or, for
// sampling="metropolis", the texels of the Metropolis–Hastings chains' states (`samples`,
// written by passes/metropolis_step.wgsl, distributed ∝ the same weights at equilibrium).
// The estimator weight of a VPL is Φ·R / (N p(s)), with p of this frame's RSM.
// `every_texel`: texels [first, first + count) as VPLs with weight Φ·R (the reference).
#include "common/constants.wgsl"
#include "common/frame.wgsl"
#include "common/vpl.wgsl"
#include "common/rsm_warp.wgsl"

struct SampleParams {
    // Number of VPLs to write.
    count: u32,
    // Pyramid levels (RSM side N = 2^(levels − 1)).
    levels: u32,
    rsm_size: u32,
    // 0 = stratified (Fibonacci lattice), 1 = random, 2 = the Metropolis chains' `samples`.
    mode: u32,
    seed: u32,
    // First texel (every_texel) .
    first: u32,
    _pad0: u32,
    _pad1: u32,
}

const WORKGROUP: u32 = 64u;

@group(0) @binding(0) var<uniform> params: SampleParams;
@group(0) @binding(1) var<storage, read> light: LightRaw;
@group(0) @binding(2) var<storage, read> pyramid: array<f32>;
// Start of each pyramid level in `pyramid`, level 0 first.
@group(0) @binding(3) var<storage, read> level_offsets: array<u32>;
@group(0) @binding(4) var<storage, read> rsm_position: array<vec4f>;
@group(0) @binding(5) var<storage, read> rsm_normal: array<vec4f>;
@group(0) @binding(6) var<storage, read> rsm_flux_diffuse: array<vec4f>;
@group(0) @binding(7) var<storage, read> rsm_flux_specular: array<vec4f>;
@group(0) @binding(8) var<storage, read_write> vpls: array<Vpl>;
// mode 2: per VPL (continuous RSM position in texels, p); otherwise any buffer, unread.
@group(0) @binding(9) var<storage, read> samples: array<vec4f>;

fn write_vpl(out_index: u32, texel: u32, scale: f32) {
    let pos = rsm_position[texel].xyz;
    let n = rsm_normal[texel];
    var v: Vpl;
    // RSM positions are relative to the RSM's view origin, which `light.position` holds relative
    // to the frame origin (for a directional light: its image plane's centre, rsm_lights.rs).
    v.position = pos + light.position;
    v.roughness = n.w;
    v.normal = n.xyz;
    v.flux_diffuse = rsm_flux_diffuse[texel].rgb * scale;
    v.flux_specular = vec3f(0.0);
    if (HAS_SPECULAR) {
        v.flux_specular = rsm_flux_specular[texel].rgb * scale;
    }
    // Towards the light: from the texel to the light's position for a spot or point light; a
    // directional light's RSM positions are relative to its image plane, and every texel is
    // lit from −direction.
    let len = length(pos);
    v.to_light = select(vec3f(0.0, 1.0, 0.0), -pos / len, len > 0.0);
    if (light.kind == LIGHT_KIND_DIRECTIONAL) {
        v.to_light = -light.direction;
    }
    vpls[out_index] = v;
}

@compute @workgroup_size(WORKGROUP, 1, 1)
fn importance(@builtin(global_invocation_id) gid: vec3u) {
    let i = gid.x;
    if (i >= params.count) {
        return;
    }
    var xy: vec2u;
    if (params.mode == 2u) {
        xy = min(vec2u(samples[i].xy), vec2u(params.rsm_size - 1u));
    } else {
        xy = warp_descend(warp_sample_point(i, params.count, params.mode == 0u, params.seed), params.rsm_size, params.levels).texel;
    }
    let texel = xy.y * params.rsm_size + xy.x;
    let total = pyramid[level_offsets[params.levels - 1u]];
    let w = pyramid[texel];
    // Estimator weight 1/(N p(s)) with p(s) = w(s)/W. A texel of weight 0 is never chosen when
    // W > 0; when nothing is lit (W = 0) every VPL carries nothing.
    let scale = select(0.0, total / (f32(params.count) * w), w > 0.0 && total > 0.0);
    write_vpl(i, texel, scale);
}

@compute @workgroup_size(WORKGROUP, 1, 1)
fn every_texel(@builtin(global_invocation_id) gid: vec3u) {
    let i = gid.x;
    if (i >= params.count) {
        return;
    }
    write_vpl(i, params.first + i, 1.0);
}
