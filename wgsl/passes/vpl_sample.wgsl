// VPL sampling from the reflective shadow map (compute).
// `importance`: N VPLs with probability p(s) ∝ Φ·(R_d + R_s) [Tok15 §4.2 default importance] by
// hierarchical sample warping down the weight pyramid [Clarberg et al. 2005]; sample points are
// a Fibonacci lattice [Tok16, stratified centres] or seeded random numbers, both shifted per
// seed (Cranley–Patterson rotation) so seeds give independent estimates. The estimator weight
// of a VPL is Φ·R / (N p(s)).
// `every_texel`: texels [first, first + count) as VPLs with weight Φ·R (the reference).
#include "common/constants.wgsl"
#include "common/frame.wgsl"
#include "common/vpl.wgsl"

struct SampleParams {
    // Number of VPLs to write.
    count: u32,
    // Pyramid levels (RSM side N = 2^(levels − 1)).
    levels: u32,
    rsm_size: u32,
    // 0 = stratified (Fibonacci lattice), 1 = random.
    mode: u32,
    seed: u32,
    // First texel (every_texel) .
    first: u32,
    _pad0: u32,
    _pad1: u32,
}

const WORKGROUP: u32 = 64u;
// 1/φ, the Fibonacci lattice's irrational step.
const INV_GOLDEN_RATIO: f32 = 0.618033988749895;

@group(0) @binding(0) var<uniform> params: SampleParams;
@group(0) @binding(1) var<storage, read> light: SpotLightRaw;
@group(0) @binding(2) var<storage, read> pyramid: array<f32>;
// Start of each pyramid level in `pyramid`, level 0 first.
@group(0) @binding(3) var<storage, read> level_offsets: array<u32>;
@group(0) @binding(4) var<storage, read> rsm_position: array<vec4f>;
@group(0) @binding(5) var<storage, read> rsm_normal: array<vec4f>;
@group(0) @binding(6) var<storage, read> rsm_flux_diffuse: array<vec4f>;
@group(0) @binding(7) var<storage, read> rsm_flux_specular: array<vec4f>;
@group(0) @binding(8) var<storage, read_write> vpls: array<Vpl>;

// PCG hash [Jarzynski & Olano 2020], for seeded random numbers.
fn pcg_hash(x: u32) -> u32 {
    let state = x * 747796405u + 2891336453u;
    let word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// A float in [0, 1) from the top 24 bits.
fn unit_float(x: u32) -> f32 {
    return f32(x >> 8u) * (1.0 / 16777216.0);
}

fn sample_point(i: u32) -> vec2f {
    let shift = vec2f(unit_float(pcg_hash(params.seed * 2u + 1u)), unit_float(pcg_hash(params.seed * 2u + 2u)));
    var u: vec2f;
    if (params.mode == 0u) {
        u = vec2f((f32(i) + 0.5) / f32(params.count), fract(f32(i) * INV_GOLDEN_RATIO));
    } else {
        let h = pcg_hash(i ^ pcg_hash(params.seed + 0x9e3779b9u));
        u = vec2f(unit_float(h), unit_float(pcg_hash(h)));
    }
    return fract(u + shift);
}

fn weight_at(level: u32, xy: vec2u) -> f32 {
    let size = params.rsm_size >> level;
    return pyramid[level_offsets[level] + xy.y * size + xy.x];
}

// Chooses between two children of weights a and b with u ∈ [0,1), rescaling u to [0,1) inside
// the chosen one. Returns 0 or 1.
fn warp_choice(a: f32, b: f32, u: ptr<function, f32>) -> u32 {
    let total = a + b;
    let split = select(0.5, a / total, total > 0.0);
    if (*u < split) {
        *u = min(*u / max(split, FLT_MIN), 0.99999994);
        return 0u;
    }
    *u = min((*u - split) / max(1.0 - split, FLT_MIN), 0.99999994);
    return 1u;
}

fn write_vpl(out_index: u32, texel: u32, scale: f32) {
    let pos = rsm_position[texel].xyz;
    let n = rsm_normal[texel];
    var v: Vpl;
    v.position = pos + light.position;
    v.roughness = n.w;
    v.normal = n.xyz;
    v.flux_diffuse = rsm_flux_diffuse[texel].rgb * scale;
    v.flux_specular = rsm_flux_specular[texel].rgb * scale;
    let len = length(pos);
    v.to_light = select(vec3f(0.0, 1.0, 0.0), -pos / len, len > 0.0);
    vpls[out_index] = v;
}

@compute @workgroup_size(WORKGROUP, 1, 1)
fn importance(@builtin(global_invocation_id) gid: vec3u) {
    let i = gid.x;
    if (i >= params.count) {
        return;
    }
    let u = sample_point(i);
    var ux = u.x;
    var uy = u.y;
    var xy = vec2u(0u, 0u);
    for (var level = i32(params.levels) - 2; level >= 0; level--) {
        let l = u32(level);
        let c = 2u * xy;
        let w00 = weight_at(l, c);
        let w10 = weight_at(l, c + vec2u(1u, 0u));
        let w01 = weight_at(l, c + vec2u(0u, 1u));
        let w11 = weight_at(l, c + vec2u(1u, 1u));
        let column = warp_choice(w00 + w01, w10 + w11, &ux);
        var row: u32;
        if (column == 0u) {
            row = warp_choice(w00, w01, &uy);
        } else {
            row = warp_choice(w10, w11, &uy);
        }
        xy = c + vec2u(column, row);
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
