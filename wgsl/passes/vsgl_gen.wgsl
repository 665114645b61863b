// VSGL generation by filtered importance sampling of the mipmapped RSM (compute), one thread per
// VSGL [Tok15 §4.2; Tok16 §3–4, Algorithm 1]:
//  1. kernel centre x_i ∝ p by hierarchical sample warping (stratified: Fibonacci lattice), or
//     for sampling="metropolis" the state of Markov chain i (`samples`, written by
//     passes/metropolis_step.wgsl; ∝ p at equilibrium), with p of this frame's RSM;
//  2. kernel level l_i:
//     "density"  [Tok15 §4.2]: l = l_top − ½ log2(N p(x_i)),
//     "integral" [Tok16 Eq. 3, Algorithm 1]: solve (4^l/M) p̄(x_i, l) = K/N by bisection;
//     "node": the coarsest quadtree node on x_i's texel path whose mass
//     P_v = W_v/W is at most K/N — the 2016 rule applied to whole nodes;
//     with `coherence` c > 0 (derived for vsgl, not in the papers; docs/scenes.md, "The
//     real-scene corpus"), each kernel also shrinks until its texels' mean normal has length
//     |Σw n|/Σw ≥ c: a cluster that straddles a crease or a depth discontinuity of the RSM
//     (a corner, a helmet's brim over its face) is not one Gaussian emitter, and the light its
//     parts exchange at close range is lost when it is shaded as one;
//  3. cluster totals of every moment f from the mips read at (x_i, l_i): trilinearly as the
//     papers do (kernel_filter="trilinear"), or per level at the node holding x_i ("nodes", the
//     default; moment_bilinear says why):
//     "density"  [Tok16 Eq. 4]: ∫f g ≈ f̄(x_i, l_i) / max(N p(x_i), 1),
//     "integral" [Tok16 Eq. 5]: ∫f g ≈ f̄(x_i, l_i) / (N p̄(x_i, l_i)),
//     "node": the node's exact totals F_v/(N P_v) (moments read at the node, no filtering);
//     with f̄, p̄ in density units on the unit square (M × the texel average);
//  4. the VSGL from the moments [Tok15 §3.1; Tok16s §3]: Toksvig-merged lobes and the
//     positional Gaussian (vsgl.wgsl), and (chain F) the cluster's mean
//     tangent plane.
// The sampling density p comes from `pyramid` (2×2 sums, level 0 = per-texel weights) and the
// moments from the five (or six) chains. Usually the pyramid holds the moments' own weight w (chain A's
// .w), and the kernel mass and Eq. 5 read w̄ from chain A as the papers do. With bidirectional
// importance (`importance = 1`, brsm_mix.wgsl) the pyramid holds another density q ∝ w ×
// (view importance): centres, masses and the estimator's density then all come from q — the
// kernel mass (4^l/M)·p̄ with p̄ = M·q̄/Q, Eq. 5 as Q·f̄/(N·q̄), the node total as
// F_v/(N·Q_v/Q) — while the cluster's moments (power, lobes, positional Gaussian) still come
// from the flux chains: the same estimators with p replaced, so "node" stays unbiased.
#include "common/constants.wgsl"
#include "common/math.wgsl"
#include "common/sg.wgsl"
#include "common/vsgl.wgsl"
#include "common/vsgl_tangent_plane.wgsl"
#include "common/vsgl_record.wgsl"
#include "common/vsgl_cluster.wgsl"
#include "common/rsm_warp.wgsl"

struct GenParams {
    count: u32,
    levels: u32,
    rsm_size: u32,
    // 0 = warp random points, 1 = warp the Fibonacci lattice, 2 = the chains' `samples`.
    sampling: u32,
    seed: u32,
    // 0 = density (2015), 1 = integral (2016 bisection), 2 = quadtree node.
    kernel: u32,
    bisection_steps: u32,
    chain_len: u32,
    // Light position relative to the frame origin: moments are relative to the light.
    light_offset: vec3f,
    // K of [Tok16 §4.2] (kernel size trade-off).
    k: f32,
    // 1: the moments have chain F and the records get the cluster's tangent plane.
    planes: u32,
    // 1: `pyramid` is a density other than chain A's weight (bidirectional importance).
    importance: u32,
    // Smallest mean-normal length |Σw n|/Σw a kernel may have (0: the papers' kernels); needs
    // chain F (planes = 1).
    coherence: f32,
    // Candidate shadow targets per VSGL written to `shadow_candidates` (0: none).
    shadow_candidates: u32,
    // How the filtered kernels read a level (moment_bilinear): KERNEL_FILTER_TRILINEAR or
    // KERNEL_FILTER_NODES.
    kernel_filter: u32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
}

const WORKGROUP: u32 = 64u;
const KERNEL_FILTER_TRILINEAR: u32 = 0u;
const KERNEL_FILTER_NODES: u32 = 1u;

@group(0) @binding(0) var<uniform> params: GenParams;
@group(0) @binding(1) var<storage, read> pyramid: array<f32>;
@group(0) @binding(2) var<storage, read> level_offsets: array<u32>;
@group(0) @binding(3) var<storage, read> moments: array<vec4f>;
@group(0) @binding(4) var<storage, read_write> vsgls: array<VsglRaw>;
// sampling 2: per VSGL (continuous RSM position in texels, p); otherwise any buffer, unread.
@group(0) @binding(5) var<storage, read> samples: array<vec4f>;
// With shadow_candidates = C > 0 (visibility="raytrace" with shadow_target="resampled", or
// near_field="texels"): C texels
// of VSGL i's cluster at rows 2(i·C + j), 2(i·C + j) + 1: (its surface point relative to the
// frame origin, its footprint variance σ_t²) and (its unit normal, 0 where unknown; its diffuse
// power over the density it was drawn by). Written also for near_field="texels". A
// placeholder otherwise.
@group(0) @binding(6) var<storage, read_write> shadow_candidates: array<vec4f>;

fn moment_texel(chain: u32, level: u32, xy: vec2i) -> vec4f {
    let side = i32(params.rsm_size >> level);
    let c = clamp(xy, vec2i(0), vec2i(side - 1));
    return moments[chain * params.chain_len + level_offsets[level] + u32(c.y * side + c.x)];
}

// Read of level `level` at a continuous level-0 position `s` (texel units): bilinear, as the
// papers' trilinear mip read does (kernel_filter="trilinear"), or the level's quadtree node that
// holds `s` ("nodes"). The bilinear read blends the centre texel with up to three neighbours
// whatever the kernel's size, so a kernel of one texel is spread over about 2×2 of them, its
// mean moved by up to half a texel (into the gap, where the RSM jumps in depth): the light it
// sends to receivers a texel or two away, most of FlightHelmet's, is lost at every N
// (experiments/vsgl_defaults_on_the_corpus.md).
fn level_node(level: u32, s: vec2f) -> vec2i {
    return vec2i(vec2u(max(s, vec2f(0.0))) >> vec2u(level));
}

fn moment_bilinear(chain: u32, level: u32, s: vec2f) -> vec4f {
    if (params.kernel_filter == KERNEL_FILTER_NODES) {
        return moment_texel(chain, level, level_node(level, s));
    }
    let coord = s / f32(1u << level) - 0.5;
    let base = floor(coord);
    let f = coord - base;
    let i = vec2i(base);
    let a = mix(moment_texel(chain, level, i), moment_texel(chain, level, i + vec2i(1, 0)), f.x);
    let b = mix(moment_texel(chain, level, i + vec2i(0, 1)), moment_texel(chain, level, i + vec2i(1, 1)), f.x);
    return mix(a, b, f.y);
}

// Trilinear read at a fractional level in [0, levels − 1] (each level read by moment_bilinear).
fn moment_trilinear(chain: u32, s: vec2f, level: f32) -> vec4f {
    let top = params.levels - 1u;
    let l0 = min(u32(floor(level)), top);
    let l1 = min(l0 + 1u, top);
    let t = clamp(level - f32(l0), 0.0, 1.0);
    return mix(moment_bilinear(chain, l0, s), moment_bilinear(chain, l1, s), t);
}

// Texel average of the sampling pyramid at a level-l texel (its 2×2 sums over 4^l), clamped
// to the edge like moment_texel.
fn pdf_texel_average(level: u32, xy: vec2i) -> f32 {
    let side = i32(params.rsm_size >> level);
    let c = clamp(xy, vec2i(0), vec2i(side - 1));
    return pyramid[level_offsets[level] + u32(c.y * side + c.x)] / f32(1u << (2u * level));
}

// pdf_texel_average read as moment_trilinear reads the chains.
fn pdf_trilinear(s: vec2f, level: f32) -> f32 {
    let top = params.levels - 1u;
    let l0 = min(u32(floor(level)), top);
    let l1 = min(l0 + 1u, top);
    let t = clamp(level - f32(l0), 0.0, 1.0);
    var v = vec2f(0.0);
    for (var k = 0u; k < 2u; k++) {
        let l = select(l0, l1, k == 1u);
        if (params.kernel_filter == KERNEL_FILTER_NODES) {
            v[k] = pdf_texel_average(l, level_node(l, s));
            continue;
        }
        let coord = s / f32(1u << l) - 0.5;
        let base = floor(coord);
        let f = coord - base;
        let i = vec2i(base);
        let a = mix(pdf_texel_average(l, i), pdf_texel_average(l, i + vec2i(1, 0)), f.x);
        let b = mix(pdf_texel_average(l, i + vec2i(0, 1)), pdf_texel_average(l, i + vec2i(1, 1)), f.x);
        v[k] = mix(a, b, f.y);
    }
    return mix(v.x, v.y, t);
}

// Probability mass of the kernel at level l: (4^l/M)·p̄(x, l) = 4^l·w̄(x, l)/W with w̄ the texel
// average of the weight at that level and W the total weight (with importance: of q and Q).
fn kernel_mass(s: vec2f, level: f32, total: f32) -> f32 {
    if (params.importance == 1u) {
        return exp2(2.0 * level) * pdf_trilinear(s, level) / total;
    }
    return exp2(2.0 * level) * moment_trilinear(0u, s, level).w / total;
}

// Whether the kernel at `level` (trilinear at `s`; for "node" the node at the integer level)
// has its texels' normals coherent enough: |Σw n|/Σw ≥ c from chains F and A, divided before the
// length is taken (Σw n² overflows f32 for lights of 1e30 cd, found by the scene-level suite).
fn kernel_is_coherent(s: vec2f, level: f32, node: vec2u) -> bool {
    if (params.coherence <= 0.0 || params.planes != 1u) {
        return true;
    }
    var a: vec4f;
    var f: vec4f;
    if (params.kernel == 2u) {
        a = moment_texel(0u, u32(level), vec2i(node));
        f = moment_texel(5u, u32(level), vec2i(node));
    } else {
        a = moment_trilinear(0u, s, level);
        f = moment_trilinear(5u, s, level);
    }
    return !(a.w > 0.0) || length(f.xyz / a.w) >= params.coherence;
}

// The largest level in [0, level] whose kernel is coherent (kernel_is_coherent), by bisection:
// the normals of a kernel spread as it grows, so coherence falls with the level. Level 0 (about
// one texel) is taken whatever its coherence.
fn coherent_level(s: vec2f, level: f32) -> f32 {
    if (kernel_is_coherent(s, level, vec2u(0u))) {
        return level;
    }
    var lo = 0.0;
    var hi = level;
    for (var k = 0u; k < params.bisection_steps; k++) {
        let mid = 0.5 * (lo + hi);
        if (kernel_is_coherent(s, mid, vec2u(0u))) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    return lo;
}

// A cluster's texel-averaged moment of `chain`: "node" reads its quadtree node exactly at the
// integer `level`; the filtered kernels read trilinearly at centre `s` and the continuous level.
fn cluster_moment(chain: u32, level: f32, node: vec2u, s: vec2f) -> vec4f {
    if (params.kernel == 2u) {
        return moment_texel(chain, u32(level), vec2i(node));
    }
    return moment_trilinear(chain, s, level);
}

// Candidate shadow targets of VSGL i (experiments/corpus_shadow_targets_and_bounds.md, "Which texel the shadow ray aims
// at"): C texels of its cluster's node drawn ∝ the sampling density by warping from the node
// down (stratified over the candidates), each its surface point y = (w·y)/w and its normal
// (chain F's w·n where the chains have it, else the diffuse lobe's direction, chain C).
// The shading pass keeps one per receiver by its geometric term, so the shadow ray goes where
// the cluster's light at that receiver comes from. `upper_share`: the probability that a
// candidate is drawn from the node's parent instead (a kernel read at its nodes blends a level's
// node with its parent's, and its candidates must come from that blend, not from the parent
// alone, or those of a one-texel kernel would be its neighbours). `fallback`: the centre's
// target, for a texel the moments do not weigh.
fn write_shadow_candidates(i: u32, start_level: u32, start: vec2u, upper_share: f32, fallback: vec3f) {
    let c = params.shadow_candidates;
    let h = pcg_hash(i ^ pcg_hash(params.seed + 0x85ebca6bu));
    let shift = unit_float(h);
    for (var j = 0u; j < c; j++) {
        let u = vec2f((f32(j) + shift) / f32(c), unit_float(pcg_hash(h + j + 1u)));
        var level = start_level;
        var node = start;
        if (upper_share > 0.0 && unit_float(pcg_hash(h ^ (0x9e3779b9u * (j + 1u)))) < upper_share) {
            level += 1u;
            node = start >> vec2u(1u);
        }
        let texel = vec2i(warp_descend_from(min(u, vec2f(ONE_MINUS_ULP)), params.rsm_size, level, node).texel);
        var f = vec4f(0.0);
        if (params.planes == 1u) {
            f = moment_texel(5u, 0u, texel);
        }
        let moments_here = ClusterMoments(moment_texel(0u, 0u, texel), vec4f(0.0), moment_texel(2u, 0u, texel), moment_texel(3u, 0u, texel), moment_texel(4u, 0u, texel), f);
        let q = pyramid[u32(texel.y) * params.rsm_size + u32(texel.x)];
        let candidate = shadow_candidate_from_texel(moments_here, params.planes == 1u, q, fallback, params.light_offset);
        shadow_candidates[2u * (i * c + j)] = candidate.point;
        shadow_candidates[2u * (i * c + j) + 1u] = candidate.normal;
    }
}

@compute @workgroup_size(WORKGROUP, 1, 1)
fn main(@builtin(global_invocation_id) gid: vec3u) {
    let i = gid.x;
    if (i >= params.count) {
        return;
    }
    let n = f32(params.count);
    let m = f32(params.rsm_size * params.rsm_size);
    let top = f32(params.levels - 1u);
    let total = pyramid[level_offsets[params.levels - 1u]];
    var out: VsglRaw;
    if (!(total > 0.0)) {
        // Nothing lit: every VSGL carries no power.
        out.diffuse_axis = vec3f(0.0, 0.0, 1.0);
        out.specular_axis = vec3f(0.0, 0.0, 1.0);
        vsgls[i] = out;
        return;
    }
    var warped: WarpResult;
    if (params.sampling == 2u) {
        let at = samples[i].xy;
        let texel = min(vec2u(at), vec2u(params.rsm_size - 1u));
        warped = WarpResult(texel, at - vec2f(texel));
    } else {
        warped = warp_descend(warp_sample_point(i, params.count, params.sampling == 1u, params.seed), params.rsm_size, params.levels);
    }
    let s = vec2f(warped.texel) + warped.offset;
    let w_texel = pyramid[warped.texel.y * params.rsm_size + warped.texel.x];
    // Density of the centre on the unit square: p = M·w(texel)/W.
    let p = m * w_texel / total;

    var level: f32;
    // "node": whether to stop at a node depends on the node and its ancestors only (its mass
    // ≤ K/N, its parent's > K/N), so the stop nodes partition the RSM, the warp draws node v
    // with probability P_v, and Σ_i F_v(i)/(N P_v(i)) has expectation ΣF: unbiased, unlike
    // filtered reads, which blend neighbouring clusters. As N grows the nodes shrink to
    // single texels (VPLs with SG lobes).
    var node = warped.texel;
    if (params.kernel == 2u) {
        let target_mass = params.k / n;
        var l = params.levels - 1u;
        loop {
            node = warped.texel >> vec2u(l);
            // Still a partition with coherence: whether to stop depends on the node alone.
            if (l == 0u || (warp_weight(l, params.rsm_size, node) <= target_mass * total && kernel_is_coherent(vec2f(0.0), f32(l), node))) {
                break;
            }
            l -= 1u;
        }
        level = f32(l);
    } else if (params.kernel == 0u) {
        level = coherent_level(s, clamp(top - 0.5 * log2(max(n * p, FLT_MIN)), 0.0, top));
    } else {
        // [Tok16 Algorithm 1]: the mass grows with l, so bisect on it.
        let target_mass = params.k / n;
        var lo = 0.0;
        var hi = top;
        for (var k = 0u; k < params.bisection_steps; k++) {
            let mid = 0.5 * (lo + hi);
            if (kernel_mass(s, mid, total) < target_mass) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        level = coherent_level(s, 0.5 * (lo + hi));
    }

    let a = cluster_moment(0u, level, node, s);
    let b = cluster_moment(1u, level, node, s);
    let c = cluster_moment(2u, level, node, s);
    let d = cluster_moment(3u, level, node, s);
    let e = cluster_moment(4u, level, node, s);
    var f = vec4f(0.0);
    if (params.planes == 1u) {
        f = cluster_moment(5u, level, node, s);
    }
    // Cluster total of a texel-averaged moment f̄_texel: Eq. 5 gives W·f̄/(N·w̄); Eq. 4 gives
    // M·f̄/max(N p, 1).
    var scale: f32;
    if (params.kernel == 0u) {
        scale = m / max(n * p, 1.0);
    } else if (params.importance == 1u) {
        // Q·f̄/(N·q̄): q̄ the density's texel average over the same kernel (exact at the node).
        var q_average: f32;
        if (params.kernel == 2u) {
            q_average = pdf_texel_average(u32(level), vec2i(node));
        } else {
            q_average = pdf_trilinear(s, level);
        }
        scale = select(0.0, total / (n * q_average), q_average > 0.0);
    } else {
        scale = select(0.0, total / (n * a.w), a.w > 0.0);
    }
    out = vsgl_from_cluster_moments(ClusterMoments(a, b, c, d, e, f), scale, params.planes == 1u, params.light_offset);
    out.level = level;
    out.pdf = p;
    out.center = s;
    // The centre texel's own position y = (w·y)/w at level 0 (chains 0 and 4 hold w and w·y).
    let centre_weight = moment_texel(0u, 0u, vec2i(warped.texel)).w;
    let centre_position = moment_texel(4u, 0u, vec2i(warped.texel)).xyz / max(centre_weight, FLT_MIN);
    // (Without weight there the cluster's mean: position.mean + light_offset, as out.mean is.)
    out.shadow_target = select(out.mean, centre_position + params.light_offset, centre_weight > 0.0);
    if (params.shadow_candidates > 0u) {
        // The cluster's node: the kernel's own for "node"; for a trilinear read the node of the
        // kernel's level rounded up around the centre texel (a trilinear read at level 0.3
        // already mixes in level 1's 2×2 node, and its bilinear taps its neighbours); for a read
        // at the nodes the blend itself: the node below the level, or with probability
        // t·q̄_hi / ((1 − t)·q̄_lo + t·q̄_hi) its parent (the share of the parent in the kernel's
        // averaged moments, t the level's fraction), so candidates are drawn by the density the
        // cluster's moments weigh its texels with.
        var start_level = u32(clamp(ceil(level), 0.0, top));
        var start = warped.texel >> vec2u(start_level);
        var upper_share = 0.0;
        if (params.kernel == 2u) {
            start_level = u32(level);
            start = node;
        } else if (params.kernel_filter == KERNEL_FILTER_NODES) {
            start_level = min(u32(floor(level)), params.levels - 1u);
            start = warped.texel >> vec2u(start_level);
            let t = clamp(level - f32(start_level), 0.0, 1.0);
            if (t > 0.0 && start_level + 1u < params.levels) {
                let lower = (1.0 - t) * pdf_texel_average(start_level, vec2i(start));
                let upper = t * pdf_texel_average(start_level + 1u, vec2i(start >> vec2u(1u)));
                upper_share = select(0.0, upper / (lower + upper), lower + upper > 0.0);
            }
        }
        write_shadow_candidates(i, start_level, start, upper_share, out.shadow_target);
    }
    if (params.kernel == 2u) {
        out.mass = warp_weight(u32(level), params.rsm_size, node) / total;
    } else {
        out.mass = kernel_mass(s, level, total);
    }
    vsgls[i] = out;
}
