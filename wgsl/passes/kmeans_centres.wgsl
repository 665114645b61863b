// k-means centres (compute), one thread per cluster [Tok16 Appendix D]: "cluster centres are
// sampled from the same density as the filtered importance sampling" — the RSM weight pyramid,
// warped as vsgl_gen.wgsl warps its kernel centres (random or the Fibonacci lattice) — and
// placed in the clustering space: the sample's texel position ("kmeans2d") or its texel's
// world position ("kmeans3d", relative to the light). w holds the sample's density p on the
// unit RSM square (diagnostics, as vsgl_gen's records keep it).
#include "common/constants.wgsl"
#include "common/rsm_warp.wgsl"
#include "common/kmeans_space.wgsl"

struct CentreParams {
    count: u32,
    rsm_size: u32,
    levels: u32,
    chain_len: u32,
    seed: u32,
    // 1: the Fibonacci lattice (sampling="stratified"), 0: random.
    stratified: u32,
    space: u32,
    _pad: u32,
}

const WORKGROUP: u32 = 64u;

@group(0) @binding(0) var<uniform> params: CentreParams;
@group(0) @binding(1) var<storage, read> pyramid: array<f32>;
@group(0) @binding(2) var<storage, read> level_offsets: array<u32>;
@group(0) @binding(3) var<storage, read> moments: array<vec4f>;
@group(0) @binding(4) var<storage, read_write> centres: array<vec4f>;

@compute @workgroup_size(WORKGROUP, 1, 1)
fn main(@builtin(global_invocation_id) gid: vec3u) {
    let i = gid.x;
    if (i >= params.count) {
        return;
    }
    let total = pyramid[level_offsets[params.levels - 1u]];
    if (!(total > 0.0)) {
        centres[i] = vec4f(0.0);
        return;
    }
    let warped = warp_descend(warp_sample_point(i, params.count, params.stratified == 1u, params.seed), params.rsm_size, params.levels);
    let texel = warped.texel.y * params.rsm_size + warped.texel.x;
    let p = f32(params.rsm_size * params.rsm_size) * pyramid[texel] / total;
    if (params.space == 0u) {
        centres[i] = vec4f(vec2f(warped.texel) + warped.offset, 0.0, p);
    } else {
        centres[i] = vec4f(kmeans_texel_point(1u, texel, params.rsm_size, params.chain_len), p);
    }
}
