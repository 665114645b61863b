// The interleaved importance map recombined (compute), for importance_interleave = k > 1: each
// lit RSM texel gets the mean of the interleaved estimates (brsm_importance.wgsl) over the k×k
// window of texels around it, lit ones only.
//
// Why: with k > 1 texel (x, y) evaluates only the view VSGLs of its class c = (y mod k)·k +
// (x mod k) (1/k² of them, scaled by k²). Where a few view VSGLs dominate a texel's importance
// (sharp glossy lobes, a caustic's receivers), most classes miss them: neighbouring texels then
// get importances 0 and k²× the full one in a k-periodic pattern, and texels whose class missed
// are sampled through the defensive mixture only, with per-VPL weights up to 11× the plain RSM
// ones — measured on the caustics ring close-up (vpl, N = 1024), relRMSE 0.03 at k = 1 became
// 1.4 at k = 4 without this pass. Any k consecutive texels along an axis hold every residue
// mod k, so a k×k window holds one texel of every class: the window's mean is Σ over classes of
// (1/k²)·(k²·class sum) = every view VSGL evaluated once, at positions at most k texels apart —
// the full importance, blurred over k texels, as interleaved sampling's own reconstruction
// [Keller & Heidrich 2001; Tok15 §5] recombines the classes with a small filter. The window is
// shifted at the RSM's borders to stay k×k inside it. Unlit texels (RSM weight 0) are left out
// of the mean and stay 0, so nothing unlit gains probability (it would be wasted, not biased).
// Any q is a valid importance here (brsm_mix.wgsl mixes in the RSM's own density), so this
// filter changes variance only, never the estimators' expectations.
#include "common/constants.wgsl"

struct FilterParams {
    rsm_size: u32,
    // Interleave tile side k (> 1).
    interleave: u32,
    _pad0: u32,
    _pad1: u32,
}

const WORKGROUP: u32 = 8u;

@group(0) @binding(0) var<uniform> params: FilterParams;
// The RSM's weight pyramid (level 0: w per texel; w > 0 ⇔ the texel reflects light).
@group(0) @binding(1) var<storage, read> rsm_pyramid: array<f32>;
// The interleaved importance estimates, one per texel.
@group(0) @binding(2) var<storage, read> interleaved: array<f32>;
// Level 0 of the importance pyramid: the recombined q per texel.
@group(0) @binding(3) var<storage, read_write> importance: array<f32>;

@compute @workgroup_size(WORKGROUP, WORKGROUP, 1)
fn main(@builtin(global_invocation_id) gid: vec3u) {
    let n = params.rsm_size;
    if (gid.x >= n || gid.y >= n) {
        return;
    }
    let i = gid.y * n + gid.x;
    if (!(rsm_pyramid[i] > 0.0)) {
        importance[i] = 0.0;
        return;
    }
    let k = params.interleave;
    // The k×k window around the texel (k/2 before it), moved inside the RSM at its borders.
    let start = min(vec2u(max(vec2i(gid.xy) - vec2i(i32(k / 2u)), vec2i(0))), vec2u(n - k));
    var sum = 0.0;
    var count = 0u;
    for (var dy = 0u; dy < k; dy++) {
        for (var dx = 0u; dx < k; dx++) {
            let j = (start.y + dy) * n + start.x + dx;
            if (rsm_pyramid[j] > 0.0) {
                sum += interleaved[j];
                count += 1u;
            }
        }
    }
    // count ≥ 1: the texel itself is lit and inside its window. Each term is finite (≤ FLT_MAX
    // by brsm_importance's clamp); the mean of k² of them stays finite unless they overflow
    // together, which the clamp below keeps from making the pyramid's total infinite.
    importance[i] = min(sum / f32(count), FLT_MAX);
}
