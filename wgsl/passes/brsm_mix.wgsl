// The re-weighted sampling pyramid of bidirectional RSM importance, level 0 (compute): the
// importance map q (brsm_importance.wgsl, its pyramid summed by pdf_mips) and the RSM's own
// weights w = Φ·(R_d + R_s) mixed as densities,
//   p_i = (q_i/Q + ε·w_i/W) / (1 + ε),      Q = Σ q, W = Σ w,  ε = RSM_SHARE,
// written unnormalised (without the 1/(1 + ε), which the samplers' own division by the
// pyramid's total restores). Why mix ("defensive" importance sampling, Hesterberg 1995): q is
// an SG estimate without visibility and with approximate lobes, so it can be ~0 at a texel
// that does light the view; a density that vanishes where the integrand does not is biased.
// With the mixture every texel of weight w_i > 0 keeps p_i ≥ ε/(1+ε)·w_i/W, so VPL and
// node-VSGL estimates stay unbiased and their per-sample weights are at most (1+ε)/ε times
// those of plain RSM sampling. When the view receives nothing from this RSM (Q = 0: it sees
// none of the lit surfaces' lobes) the pyramid falls back to the RSM's weights alone.
#include "common/constants.wgsl"

struct MixParams {
    rsm_size: u32,
    // Index of the top (1×1) level in both pyramids.
    top: u32,
    _pad0: u32,
    _pad1: u32,
}

// ε: the share of the RSM's own density in the mixture (1/11 ≈ 9% of the samples).
const RSM_SHARE: f32 = 0.1;
const WORKGROUP: u32 = 8u;

@group(0) @binding(0) var<uniform> params: MixParams;
// The RSM's weight pyramid (rsm_flux level 0 + pdf_mips).
@group(0) @binding(1) var<storage, read> rsm_pyramid: array<f32>;
// Level 0: q on entry, p on exit; its top holds Q (summed before this pass).
@group(0) @binding(2) var<storage, read_write> importance: array<f32>;

@compute @workgroup_size(WORKGROUP, WORKGROUP, 1)
fn main(@builtin(global_invocation_id) gid: vec3u) {
    let n = params.rsm_size;
    if (gid.x >= n || gid.y >= n) {
        return;
    }
    let i = gid.y * n + gid.x;
    let w_total = rsm_pyramid[params.top];
    let q_total = importance[params.top];
    let w = rsm_pyramid[i];
    var p = 0.0;
    if (w_total > 0.0) {
        if (q_total > 0.0) {
            p = importance[i] / q_total + RSM_SHARE * (w / w_total);
        } else {
            p = w / w_total;
        }
    }
    importance[i] = p;
}
