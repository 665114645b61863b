// One Metropolis–Hastings step per Markov chain per frame (compute), one thread per chain:
// temporally coherent RSM sampling for `sampling="metropolis"` in the spirit of Barák, Bittner
// and Havran 2013 ("Temporally coherent adaptive sampling for imperfect shadow maps"), which
// Tok16 §6 compares against. Each virtual light of an RSM view is one chain; the chains live in
// a buffer the renderer keeps from frame to frame (methods/metropolis.rs).
//
// Target: the density the hierarchical warp samples, on the unit square of the RSM,
//     p(s) = M·w(texel(s))/W     (w: level 0 of `pyramid`, W: its total, M: texel count;
//                                 rsm_warp.wgsl),
// so at equilibrium a chain state is distributed like a warped sample and the estimators that
// divide by N·p (VPLs: Φ·R/(N p); VSGL kernels [Tok16 Eq. 4–5]) keep their expectations.
// `pyramid` is the one those estimators read: the RSM's weights w_i = Φ·(R_d + R_s), or with
// importance="brsm" the re-weighted pyramid of brsm_mix.wgsl, whose level 0 holds
//     π_i = q_i/Q + ε·w_i/W     (q: the importance map, ε = 0.1; total Π = 1 + ε, or 1 with
//                                 Q = 0, when π_i = w_i/W),
// so the target is p(s) = M·π_i/Π = M·(q_i/Q + ε·w_i/W)/(1 + ε): the same density the warp
// draws brsm samples from and that vpl_sample / vsgl_gen divide by. Why the three must agree:
// a VPL's estimate is E_x[f(x)/(N·p̂(x))] with x the chain state and p̂ the density divided by;
// if x ~ p at equilibrium this is ∫f/N·(p/p̂), unbiased only if p̂ = p wherever f ≠ 0 (and p > 0
// there: π_i ≥ ε·w_i/W > 0 at every texel that reflects light). Targeting w while dividing by
// π would weight texel i by (w_i/W)/(π_i/Π) — biased towards texels the view ignores. Below,
// target_density, the acceptance ratio p(y)/p(x) (Π cancels) and the warp of the jumps all
// read `pyramid`, so they follow π. The target must also stay fixed from frame to frame while
// the chains run: methods/metropolis.rs seeds the view's VSGLs with the chains' first seed.
//
// State: the chain's point on a surface, in world space (relative to a fixed origin of the
// chain buffer), so it stays put when the light moves. Each frame the point is reprojected into
// the current RSM view; it has target density 0 there (and the chain restarts with a fresh draw
// from the warp, an exact sample of p) when it falls outside the RSM, behind the view, onto a
// texel of weight 0, or off the surface the texel sees (farther than one texel footprint from
// the plane of that texel: the surface moved, or something now occludes the point).
// chain_space="rsm" keeps the continuous RSM position instead (it moves with the light's
// view; density 0 only on a texel of weight 0).
//
// The step, from x (the reprojected state, p(x) > 0), with a proposal kernel that is a fixed
// mixture of two kernels, each of which keeps p invariant on its own (detailed balance), so
// the mixture does too:
//  - with probability 1 − JUMP: a local random walk y = x + r·(2u − 1), u uniform in [0,1)²,
//    r = params.radius texels. The proposal density is symmetric, q(y|x) = q(x|y) = 1/(2r)²,
//    so the Metropolis–Hastings ratio p(y)q(x|y) / (p(x)q(y|x)) reduces to p(y)/p(x):
//    accept with probability min(1, p(y)/p(x)). This is the coherent move: a chain moves at
//    most r texels, and not at all when rejected (then its light stays exactly where it was).
//  - with probability JUMP: an independence proposal from the warp itself, q(y|x) = p(y): the
//    ratio p(y)p(x) / (p(x)p(y)) = 1, always accepted. It lets chains cross regions of zero
//    density the random walk cannot (two lit patches), i.e. makes the chain ergodic.
// Random numbers come from the frame's seed and the chain's index (PCG hash): a given seed
// sequence gives the same chains.
#include "common/constants.wgsl"
#include "common/rsm_warp.wgsl"

struct StepParams {
    // Chains of this view (its share of num_lights).
    count: u32,
    // Chains [0, kept) continue from their stored state; [kept, count) start from the warp.
    kept: u32,
    rsm_size: u32,
    levels: u32,
    seed: u32,
    // 1: start chains from the Fibonacci lattice (stratified) rather than random points.
    stratified: u32,
    // 1: orthographic view (a directional light).
    orthographic: u32,
    // Probability of the independence (warp) move, [0, 1].
    jump: f32,
    // The view's image-plane axes and ray origin, as FrameUniforms has them (right and up
    // scaled by tan(fov/2) or the half-width), the origin relative to the chains' origin.
    right: vec3f,
    // Random-walk half-width r in texels.
    radius: f32,
    up: vec3f,
    // 1: chain_space="rsm": a state is (s.x, s.y, 0, 1), the continuous RSM position, kept
    // as is from frame to frame (no reprojection, no surface test).
    rsm_space: u32,
    forward: vec3f,
    _pad1: f32,
    view_origin: vec3f,
    _pad2: f32,
}

const WORKGROUP: u32 = 64u;

@group(0) @binding(0) var<uniform> params: StepParams;
// The target's weight pyramid (2×2 sums; the RSM's own or brsm's re-weighted one).
@group(0) @binding(1) var<storage, read> pyramid: array<f32>;
@group(0) @binding(2) var<storage, read> level_offsets: array<u32>;
// RSM positions relative to the view origin, and geometric normals.
@group(0) @binding(3) var<storage, read> rsm_position: array<vec4f>;
@group(0) @binding(4) var<storage, read> rsm_geo_normal: array<vec4f>;
// Per chain: world position relative to the chains' origin, w = 1 when the chain has a state.
@group(0) @binding(5) var<storage, read_write> chains: array<vec4f>;
// Per chain, for the sampling passes: (s.x, s.y) the continuous RSM position in texels, p(s).
@group(0) @binding(6) var<storage, read_write> samples: array<vec4f>;

// Target density on the unit square at the continuous texel position s; 0 outside the RSM.
fn target_density(s: vec2f) -> f32 {
    let n = f32(params.rsm_size);
    if (!(all(s >= vec2f(0.0)) && all(s < vec2f(n)))) {
        return 0.0;
    }
    let t = vec2u(s);
    let total = pyramid[level_offsets[params.levels - 1u]];
    return select(0.0, n * n * pyramid[t.y * params.rsm_size + t.x] / total, total > 0.0);
}

// The ray through continuous texel position s (frame.wgsl's view_ndc / camera_ray /
// view_ray_origin with the pixel centre at texel + 0.5): origin relative to the view origin,
// and direction (not normalised).
fn view_ndc_at(s: vec2f) -> vec2f {
    let n = f32(params.rsm_size);
    return vec2f(2.0 * s.x / n - 1.0, 1.0 - 2.0 * s.y / n);
}

// The inverse: the continuous texel position of a point d relative to the view origin, and
// the world width of a texel there (the same-surface tolerance). Negative width: behind.
struct Projected {
    s: vec2f,
    footprint: f32,
}

fn project(d: vec3f) -> Projected {
    let n = f32(params.rsm_size);
    var ndc: vec2f;
    var footprint: f32;
    if (params.orthographic != 0u) {
        ndc = vec2f(dot(d, params.right) / dot(params.right, params.right), dot(d, params.up) / dot(params.up, params.up));
        footprint = 2.0 * length(params.right) / n;
    } else {
        // right and up are perpendicular to the unit forward: d = t·(forward + ndc.x·right +
        // ndc.y·up) with t = d·forward.
        let t = dot(d, params.forward);
        if (!(t > 0.0)) {
            return Projected(vec2f(-1.0), -1.0);
        }
        ndc = vec2f(dot(d, params.right) / (t * dot(params.right, params.right)), dot(d, params.up) / (t * dot(params.up, params.up)));
        footprint = 2.0 * length(params.right) * t / n;
    }
    return Projected(vec2f(0.5 * (ndc.x + 1.0) * n, 0.5 * (1.0 - ndc.y) * n), footprint);
}

// The surface point the view sees at continuous position s, on the plane of s's texel
// (position and geometric normal of the RSM texel), relative to the view origin.
fn surface_point(s: vec2f) -> vec3f {
    let t = vec2u(s);
    let texel = t.y * params.rsm_size + t.x;
    let p0 = rsm_position[texel].xyz;
    let ng = rsm_geo_normal[texel].xyz;
    let ndc = view_ndc_at(s);
    var o = vec3f(0.0);
    var dir = params.forward + ndc.x * params.right + ndc.y * params.up;
    if (params.orthographic != 0u) {
        o = ndc.x * params.right + ndc.y * params.up;
        dir = params.forward;
    }
    let denom = dot(dir, ng);
    if (abs(denom) <= FLT_MIN) {
        return p0;
    }
    return o + dir * (dot(p0 - o, ng) / denom);
}

// Where a stored state lands in this frame's RSM and its target density there (0: restart).
struct Reprojected {
    s: vec2f,
    p: f32,
}

fn reproject(state: vec4f) -> Reprojected {
    if (state.w != 1.0) {
        return Reprojected(vec2f(0.0), 0.0);
    }
    if (params.rsm_space != 0u) {
        return Reprojected(state.xy, target_density(state.xy));
    }
    let d = state.xyz - params.view_origin;
    let proj = project(d);
    let p = target_density(proj.s);
    if (!(proj.footprint > 0.0) || !(p > 0.0)) {
        return Reprojected(proj.s, 0.0);
    }
    let t = vec2u(proj.s);
    let texel = t.y * params.rsm_size + t.x;
    let plane_distance = abs(dot(d - rsm_position[texel].xyz, rsm_geo_normal[texel].xyz));
    return Reprojected(proj.s, select(0.0, p, plane_distance <= proj.footprint));
}

// Uniform float i of chain `chain` in this frame (independent streams per seed and chain).
fn step_random(chain: u32, i: u32) -> f32 {
    return unit_float(pcg_hash(pcg_hash(pcg_hash(params.seed ^ 0x85ebca6bu) + chain) + i));
}

@compute @workgroup_size(WORKGROUP, 1, 1)
fn main(@builtin(global_invocation_id) gid: vec3u) {
    let i = gid.x;
    if (i >= params.count) {
        return;
    }
    let total = pyramid[level_offsets[params.levels - 1u]];
    var state = chains[i];
    if (!(total > 0.0)) {
        // Nothing lit (the view is then skipped; kept for safety): keep the state.
        samples[i] = vec4f(0.0);
        return;
    }
    var current = Reprojected(vec2f(0.0), 0.0);
    if (i < params.kept) {
        current = reproject(state);
    }
    var s = current.s;
    var moved = false;
    if (!(current.p > 0.0)) {
        // A new chain, or a state of density 0: any proposal is accepted (p(x) = 0), so draw
        // it from the warp: an exact sample of p.
        let w = warp_descend(warp_sample_point(i, params.count, params.stratified == 1u, params.seed), params.rsm_size, params.levels);
        s = vec2f(w.texel) + w.offset;
        moved = true;
    } else if (step_random(i, 0u) < params.jump) {
        // Independence proposal q = p: always accepted (ratio 1).
        let u = vec2f(step_random(i, 1u), step_random(i, 2u));
        let w = warp_descend(u, params.rsm_size, params.levels);
        s = vec2f(w.texel) + w.offset;
        moved = true;
    } else {
        // Symmetric random walk: accept with min(1, p(y)/p(x)), as u·p(x) < p(y).
        let y = current.s + params.radius * (2.0 * vec2f(step_random(i, 3u), step_random(i, 4u)) - 1.0);
        let p_y = target_density(y);
        if (step_random(i, 5u) * current.p < p_y) {
            s = y;
            moved = true;
        }
    }
    let n = f32(params.rsm_size);
    s = clamp(s, vec2f(0.0), vec2f(n * ONE_MINUS_ULP));
    if (moved) {
        // The new state's world point; a rejected move keeps the stored point bit for bit.
        if (params.rsm_space != 0u) {
            state = vec4f(s, 0.0, 1.0);
        } else {
            state = vec4f(surface_point(s) + params.view_origin, 1.0);
        }
        chains[i] = state;
    }
    samples[i] = vec4f(s, target_density(s), 0.0);
}
