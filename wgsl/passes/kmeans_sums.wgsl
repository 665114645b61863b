// k-means cluster sums and VSGLs (compute) [Tok16 Appendix D]: after the texels are sorted by
// cluster id (passes/radix_sort.wgsl), each cluster is a run of the sorted texels; its sums of
// every moment chain (passes/vsgl_moments.wgsl: ΣΦR_d, ΣΦR_s, ΣΦR ξ̄, ΣΦ(R_d + R_s)y,
// ΣΦ(R_d + R_s)(‖y‖² + v), and the tangent-plane chain) turn into a VSGL exactly as the sampled
// kernels' moments do in vsgl_gen.wgsl [Tok16 Appendix B; Tok15 §3.1] — with the cluster's exact
// totals, so every lit texel's power is in exactly one VSGL. Two entry points:
//   parts:    one thread per run of at most PART sorted texels (a run starts at a cluster's
//             first texel or at a multiple of PART), its sums into `partials`;
//   clusters: one thread per cluster: its runs' sums (at most M/PART + 1 of them), the VSGL, its
//             candidate shadow targets, and the weighted mean of its texels as the next
//             iteration's centre (kmeans_iterations > 0: Lloyd's update).
// The paper has one thread per cluster sum all of its texels; the two levels keep every
// invocation's loop short (a cluster may hold most of the RSM, and lavapipe ends a shader
// invocation after 65535 loop iterations), and the sums' order is fixed by the stable sort, so
// a frame's VSGLs are the same floats every run.
#include "common/constants.wgsl"
#include "common/vsgl_cluster.wgsl"
#include "common/rsm_warp.wgsl"
#include "common/kmeans_space.wgsl"

struct SumParams {
    // Number of clusters N.
    count: u32,
    rsm_size: u32,
    space: u32,
    chain_len: u32,
    light_offset: vec3f,
    // 1: chain F exists (the tangent plane).
    planes: u32,
    levels: u32,
    // Candidate shadow targets per VSGL written to `shadow_candidates` (0: none).
    shadow_candidates: u32,
    seed: u32,
    _pad: u32,
}

const WORKGROUP: u32 = 64u;
const PART: u32 = 256u;
// vec4f rows of one run's sums: the six chains, then (Σw·x, Σw·y, texels, 0) in texel units.
const PARTIAL_ROWS: u32 = 7u;

@group(0) @binding(0) var<uniform> params: SumParams;
@group(0) @binding(1) var<storage, read> moments: array<vec4f>;
@group(0) @binding(2) var<storage, read> keys: array<u32>;
@group(0) @binding(3) var<storage, read> texels: array<u32>;
@group(0) @binding(4) var<storage, read_write> partials: array<vec4f>;
@group(0) @binding(5) var<storage, read> centres: array<vec4f>;
@group(0) @binding(6) var<storage, read_write> next_centres: array<vec4f>;
@group(0) @binding(7) var<storage, read_write> vsgls: array<VsglRaw>;
@group(0) @binding(8) var<storage, read_write> shadow_candidates: array<vec4f>;
@group(0) @binding(9) var<storage, read> pyramid: array<f32>;
@group(0) @binding(10) var<storage, read> level_offsets: array<u32>;

fn texel_count() -> u32 {
    return params.rsm_size * params.rsm_size;
}

// Slot of the run that starts at sorted position p of cluster k: runs at multiples of PART
// first, then one per cluster for a run at its unaligned start.
fn run_slot(p: u32, k: u32) -> u32 {
    if (p % PART == 0u) {
        return p / PART;
    }
    return (texel_count() + PART - 1u) / PART + k;
}

fn chains() -> u32 {
    return select(5u, 6u, params.planes == 1u);
}

@compute @workgroup_size(WORKGROUP, 1, 1)
fn parts(@builtin(global_invocation_id) gid: vec3u) {
    let m = texel_count();
    let p = gid.x;
    if (p >= m) {
        return;
    }
    let k = keys[p];
    if (k >= params.count || (p % PART != 0u && p > 0u && keys[p - 1u] == k)) {
        return;
    }
    var sums: array<vec4f, 7>;
    for (var r = 0u; r < PARTIAL_ROWS; r++) {
        sums[r] = vec4f(0.0);
    }
    var q = p;
    loop {
        let texel = texels[q];
        for (var c = 0u; c < chains(); c++) {
            sums[c] += moments[c * params.chain_len + texel];
        }
        let w = moments[texel].w;
        let xy = vec2f(f32(texel % params.rsm_size) + 0.5, f32(texel / params.rsm_size) + 0.5);
        sums[6] += vec4f(w * xy, 1.0, 0.0);
        q += 1u;
        if (q >= m || q % PART == 0u || keys[q] != k) {
            break;
        }
    }
    let slot = run_slot(p, k);
    for (var r = 0u; r < PARTIAL_ROWS; r++) {
        partials[slot * PARTIAL_ROWS + r] = sums[r];
    }
}

// First sorted position whose key is ≥ k.
fn lower_bound(k: u32) -> u32 {
    var lo = 0u;
    var hi = texel_count();
    while (lo < hi) {
        let mid = (lo + hi) / 2u;
        if (keys[mid] < k) {
            lo = mid + 1u;
        } else {
            hi = mid;
        }
    }
    return lo;
}

// Run r (0, 1, …) of the cluster that spans [start, end): its first sorted position.
fn run_start(start: u32, r: u32) -> u32 {
    if (r == 0u) {
        return start;
    }
    return (start / PART + r) * PART;
}

fn run_count(start: u32, end: u32) -> u32 {
    if (end <= start) {
        return 0u;
    }
    return (end - 1u) / PART - start / PART + 1u;
}

// C candidate texels of the cluster drawn by w (stratified, one shift per VSGL), written as
// vsgl_gen.wgsl's write_shadow_candidates writes them: (y, footprint variance), (normal,
// diffuse power over w), so the shading pass reads them alike.
fn write_shadow_candidates(k: u32, start: u32, end: u32, total_w: f32, fallback: vec3f) {
    let c = params.shadow_candidates;
    let h = pcg_hash(k ^ pcg_hash(params.seed + 0x85ebca6bu));
    let shift = unit_float(h);
    let runs = run_count(start, end);
    for (var j = 0u; j < c; j++) {
        let goal = (f32(j) + shift) / f32(c) * total_w;
        // The run that holds the goal, then the texel within it.
        var acc = 0.0;
        var r = 0u;
        for (; r + 1u < runs; r++) {
            let w_run = partials[run_slot(run_start(start, r), k) * PARTIAL_ROWS].w;
            if (acc + w_run > goal) {
                break;
            }
            acc += w_run;
        }
        let first = run_start(start, r);
        let last = min(run_start(start, r + 1u), end);
        var texel = texels[last - 1u];
        for (var q = first; q < last; q++) {
            let w = moments[texels[q]].w;
            if (acc + w > goal && w > 0.0) {
                texel = texels[q];
                break;
            }
            acc += w;
        }
        let t = texel;
        let l = params.chain_len;
        var f = vec4f(0.0);
        if (params.planes == 1u) {
            f = moments[5u * l + t];
        }
        let moments_here = ClusterMoments(moments[t], vec4f(0.0), moments[2u * l + t], moments[3u * l + t], moments[4u * l + t], f);
        // Drawn by w, the density of importance="rsm" (the only one k-means clusters by).
        let candidate = shadow_candidate_from_texel(moments_here, params.planes == 1u, moments[t].w, fallback, params.light_offset);
        shadow_candidates[2u * (k * c + j)] = candidate.point;
        shadow_candidates[2u * (k * c + j) + 1u] = candidate.normal;
    }
}

@compute @workgroup_size(WORKGROUP, 1, 1)
fn clusters(@builtin(global_invocation_id) gid: vec3u) {
    let k = gid.x;
    if (k >= params.count) {
        return;
    }
    let start = lower_bound(k);
    let end = lower_bound(k + 1u);
    var s: array<vec4f, 7>;
    for (var r = 0u; r < PARTIAL_ROWS; r++) {
        s[r] = vec4f(0.0);
    }
    let runs = run_count(start, end);
    for (var r = 0u; r < runs; r++) {
        let slot = run_slot(run_start(start, r), k);
        for (var row = 0u; row < PARTIAL_ROWS; row++) {
            s[row] += partials[slot * PARTIAL_ROWS + row];
        }
    }
    let a = s[0];
    let e = s[4];
    let count = s[6].z;
    let centre = centres[k];
    var out: VsglRaw;
    out.diffuse_axis = vec3f(0.0, 0.0, 1.0);
    out.specular_axis = vec3f(0.0, 0.0, 1.0);
    next_centres[k] = centre;
    if (a.w > 0.0) {
        // Exact totals (the sums themselves): no estimator density to divide by.
        out = vsgl_from_cluster_moments(ClusterMoments(a, s[1], s[2], s[3], e, s[5]), 1.0, params.planes == 1u, params.light_offset);
        // Lloyd's update: the w-weighted mean of the cluster's texels in its clustering space.
        if (params.space == 0u) {
            next_centres[k] = vec4f(s[6].xy / a.w, 0.0, 0.0);
        } else {
            next_centres[k] = vec4f(e.xyz / a.w, 0.0);
        }
    }
    // The size of a cluster of `count` texels as a mip level (0: a single texel, which the
    // shading pass then shades as that texel's patch, as kernel="node" does).
    out.level = 0.5 * log2(max(count, 1.0));
    out.pdf = centre.w;
    out.texels = count;
    let total = pyramid[level_offsets[params.levels - 1u]];
    out.mass = select(0.0, a.w / total, total > 0.0);
    var shadow_target = out.mean;
    if (params.space == 0u) {
        out.center = centre.xy;
        // The surface point of the centre's texel when it is the cluster's own (lit) texel.
        let texel = min(vec2u(max(centre.xy, vec2f(0.0))), vec2u(params.rsm_size - 1u));
        let index = texel.y * params.rsm_size + texel.x;
        let w = moments[index].w;
        if (w > 0.0 && start < end) {
            shadow_target = kmeans_texel_point(1u, index, params.rsm_size, params.chain_len) + params.light_offset;
        }
    } else {
        out.center = select(vec2f(0.0), s[6].xy / a.w, a.w > 0.0);
        if (start < end) {
            shadow_target = centre.xyz + params.light_offset;
        }
    }
    out.shadow_target = shadow_target;
    if (params.shadow_candidates > 0u) {
        if (start < end && a.w > 0.0) {
            write_shadow_candidates(k, start, end, a.w, shadow_target);
        } else {
            for (var j = 0u; j < 2u * params.shadow_candidates; j++) {
                shadow_candidates[2u * k * params.shadow_candidates + j] = vec4f(0.0);
            }
        }
    }
    vsgls[k] = out;
}
