// Hierarchical sample warping down the RSM weight pyramid [Clarberg et al. 2005], shared by
// VPL and VSGL sampling. The including shader declares the bindings
//   pyramid: array<f32>        (2×2 sums, level 0 first; see passes/pdf_mips.wgsl)
//   level_offsets: array<u32>  (start of each level in `pyramid`)
// and passes the RSM side and level count explicitly.
// vsgl:include-only (validated inside the shaders that include it)
#include "common/constants.wgsl"

// 1/φ, the Fibonacci lattice's irrational step.
const INV_GOLDEN_RATIO: f32 = 0.618033988749895;
// Largest f32 below 1: rescaled sample coordinates stay in [0, 1).
const ONE_MINUS_ULP: f32 = 0.99999994;

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

// Sample i of `count` in [0,1)²: a Fibonacci lattice (stratified = true) [Tok16 §5, stratified
// centres] or seeded random numbers, both rotated by a per-seed shift (Cranley–Patterson) so
// different seeds give independent estimates.
fn warp_sample_point(i: u32, count: u32, stratified: bool, seed: u32) -> vec2f {
    let shift = vec2f(unit_float(pcg_hash(seed * 2u + 1u)), unit_float(pcg_hash(seed * 2u + 2u)));
    var u: vec2f;
    if (stratified) {
        u = vec2f((f32(i) + 0.5) / f32(count), fract(f32(i) * INV_GOLDEN_RATIO));
    } else {
        let h = pcg_hash(i ^ pcg_hash(seed + 0x9e3779b9u));
        u = vec2f(unit_float(h), unit_float(pcg_hash(h)));
    }
    return fract(u + shift);
}

fn warp_weight(level: u32, size: u32, xy: vec2u) -> f32 {
    let side = size >> level;
    return pyramid[level_offsets[level] + xy.y * side + xy.x];
}

// Chooses between children of weights a and b with u ∈ [0,1) and rescales u to [0,1) within
// the chosen one. Returns 0 or 1.
fn warp_choice(a: f32, b: f32, u: ptr<function, f32>) -> u32 {
    let total = a + b;
    let split = select(0.5, a / total, total > 0.0);
    if (*u < split) {
        *u = min(*u / max(split, FLT_MIN), ONE_MINUS_ULP);
        return 0u;
    }
    *u = min((*u - split) / max(1.0 - split, FLT_MIN), ONE_MINUS_ULP);
    return 1u;
}

struct WarpResult {
    // Chosen level-0 texel.
    texel: vec2u,
    // Position inside it, [0,1)² (the leftover of the warped sample): texel + offset is a
    // continuous sample position distributed ∝ the weights.
    offset: vec2f,
}

// Descends from the 1×1 top (level `levels` − 1) to level 0.
fn warp_descend(u_in: vec2f, size: u32, levels: u32) -> WarpResult {
    return warp_descend_from(u_in, size, levels - 1u, vec2u(0u, 0u));
}

// Descends from node `start` of level `start_level` to level 0: a texel of that node drawn ∝
// the weights.
fn warp_descend_from(u_in: vec2f, size: u32, start_level: u32, start: vec2u) -> WarpResult {
    var ux = u_in.x;
    var uy = u_in.y;
    var xy = start;
    for (var level = i32(start_level) - 1; level >= 0; level--) {
        let l = u32(level);
        let c = 2u * xy;
        let w00 = warp_weight(l, size, c);
        let w10 = warp_weight(l, size, c + vec2u(1u, 0u));
        let w01 = warp_weight(l, size, c + vec2u(0u, 1u));
        let w11 = warp_weight(l, size, c + vec2u(1u, 1u));
        let column = warp_choice(w00 + w01, w10 + w11, &ux);
        var row: u32;
        if (column == 0u) {
            row = warp_choice(w00, w01, &uy);
        } else {
            row = warp_choice(w10, w11, &uy);
        }
        xy = c + vec2u(column, row);
    }
    return WarpResult(xy, vec2f(ux, uy));
}
