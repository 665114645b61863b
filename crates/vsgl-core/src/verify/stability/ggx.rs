//! Families of the BRDFs of `wgsl/common/ggx.wgsl`: ggx_alpha_from_roughness, ggx_d, the Smith
//! Λ and G2, ggx_brdf_over_rs, lambert_brdf_over_rd.

use super::error_model::{dot_scale, floor_tiny, perturbation};
use super::grids::{a, alphas, axes, logspace, rec, tilt, v3, COSINES, GRAZING_COSINES};
use super::{check, scalar_family, Family, FLT_MIN, ULP};
use crate::verify::harness::{HarnessFunction as F, Input, Output64};
use crate::verify::oracle;
use std::f64::consts::PI;

/// ggx_d(n·h, ‖n×h‖², α) = α²/(π t²), t = α²(n·h)² + ‖n×h‖²: both terms ≥ 0 (the stable form; no
/// 1 − cos² cancellation), t ≤ 2 ULP, t² 4.5, π· 5, α² ½ and the division 2.5 → 8 ULP.
fn bound_ggx_d(_: &Input, r: &Output64) -> f64 {
    8.0 * ULP * r[0] + FLT_MIN
}

/// ggx_smith_lambda(cos θ, α): c² (½), 1 − c² whose condition number is c²/(1 − c²) with respect to
/// the rounding of c² (it is the input cos θ that fixes sin²θ; near normal incidence Λ ≈ 0 and G2 is
/// unaffected), /c² (2.5), α²· (1): tan term ≤ (4 + ½·c²/(1 − c²)) ULP; Λ = t/(2(1 + √(1 + t))) has
/// d ln Λ/d ln t ≤ 1 and adds 1 + t (½), sqrt (4.5), 1 + (½), the division (2.5) → 8 ULP.
pub(super) fn rel_smith_lambda(c: f64, alpha: f64) -> f64 {
    let c2 = (c * c).max(FLT_MIN);
    if alpha == 0.0 || c2 >= 1.0 {
        return 0.0; // Λ = 0 exactly on both sides
    }
    ULP * (12.0 + 0.5 * c2 / (1.0 - c2))
}
/// ggx_smith_g2 = 1/(1 + Λl + Λv): the Λ errors weighted by Λ/(1 + ΣΛ), two sums (1) and the
/// division (2.5).
fn bound_ggx_smith_g2(i: &Input, r: &Output64) -> f64 {
    let (l, v, al) = (a(i, 0), a(i, 1), a(i, 2));
    let (ll, lv) = (oracle::ggx_smith_lambda(l, al), oracle::ggx_smith_lambda(v, al));
    r[0] * ((ll * rel_smith_lambda(l, al) + lv * rel_smith_lambda(v, al)) / (1.0 + ll + lv) + 3.5 * ULP)
}

/// ggx_brdf_over_rs: h = (l + v)/‖l + v‖ (its direction errs by ~3 ULP), n·h and n × h (dots and
/// a cross: 1.5 ULP each), D (8 ULP relative, with condition ∂ln D/∂θh ≤ 2/α on the angle of h:
/// 1e4 at α = 1e-4), G2, the products and the division by 4 n·l n·v: c = 6 ULP per input, c₀ = 12.
/// The below-horizon decisions (n·l, n·v ≤ 0) are switch points, which the perturbation sees.
fn bound_ggx_brdf(i: &Input, r: &Output64) -> f64 {
    perturbation(F::GgxBrdfOverRs, i, 0..1, 6.0, &[0, 3, 6]) + 12.0 * ULP * r[0] + FLT_MIN
}

/// lambert_brdf_over_rd: 1/π (½ ULP) where n·l > 0; the decision itself can flip where
/// |n·l| ≤ 1.5 ULP·Σ|nᵢlᵢ| (then the error is 1/π).
fn bound_lambert_brdf(i: &Input, r: &Output64) -> f64 {
    let (n, l) = (v3(i, 0), v3(i, 3));
    if n.dot(l).abs() <= 1.5 * ULP * dot_scale(n, l) {
        1.0 / PI
    } else {
        0.5 * ULP * r[0]
    }
}

pub(super) fn ggx_families(f: &mut Vec<Family>) {
    // ggx_alpha_from_roughness: r² (½) and the f32 literal of GGX_ALPHA_MIN (½) → 1 ULP.
    let mut rs = vec![0.0, 1e-30, 1e-4, 3e-3, 9.99e-3, 1e-2, 1.001e-2];
    rs.extend(logspace(1e-2, 1.0, 60));
    rs.extend([2.0, 1e10]);
    f.push(scalar_family(F::GgxAlphaFromRoughness, "roughness 0…1, 2, 1e10", &rs, floor_tiny, |_, r| ULP * r[0]));
    // ggx_d from consistent (n·h, ‖n×h‖²) pairs at θh = 0, α/10…10α, and wide.
    let mut ins = Vec::new();
    for al in alphas() {
        for t in [0.0, 0.1, 0.5, 1.0, 2.0, 10.0].iter().map(|k| k * al).chain([0.3, 1.0, 1.5, PI / 2.0]) {
            ins.push(rec(&[t.cos(), t.sin().powi(2), al]));
        }
    }
    f.push(Family { function: F::GgxD, name: "θh = 0…10α and wide, α 1e-4…1", inputs: ins, checks: vec![check("value", 0..1, floor_tiny, bound_ggx_d)] });
    // ggx_smith_lambda / g2: cosines grazing…1 and below.
    let cosines: Vec<f64> = GRAZING_COSINES.iter().chain(&COSINES).copied().chain([-0.3]).collect();
    let (mut il, mut ig) = (Vec::new(), Vec::new());
    for al in alphas() {
        for &c in &cosines {
            il.push(rec(&[c, al]));
            for &c2 in cosines.iter().step_by(2) {
                ig.push(rec(&[c, c2, al]));
            }
        }
    }
    f.push(Family {
        function: F::GgxSmithLambda,
        name: "cos θ 0…1 (grazing incl.), α 1e-4…1",
        inputs: il,
        checks: vec![check("value", 0..1, floor_tiny, |i, r| rel_smith_lambda(a(i, 0), a(i, 1)) * r[0] + FLT_MIN)],
    });
    f.push(Family { function: F::GgxSmithG2, name: "n·l, n·v 0…1, α 1e-4…1", inputs: ig, checks: vec![check("value", 0..1, floor_tiny, bound_ggx_smith_g2)] });
    // ggx_brdf_over_rs: mirror configuration (h = n) and general pairs, grazing included.
    let (mut mirror, mut general, mut grazing, mut lambert) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let cos_all: Vec<f64> = GRAZING_COSINES.iter().chain(&COSINES).copied().chain([-0.2]).collect();
    for n in axes() {
        for (j, &c) in cos_all.iter().enumerate() {
            let l = tilt(n, c.clamp(-1.0, 1.0).acos(), 0.5 * j as f64);
            lambert.push(rec(&[n.x, n.y, n.z, l.x, l.y, l.z]));
            let v = 2.0 * l.dot(n) * n - l;
            for al in alphas() {
                let target = if c >= 0.01 { &mut mirror } else { &mut grazing };
                target.push(rec(&[n.x, n.y, n.z, l.x, l.y, l.z, v.x, v.y, v.z, al]));
                // h tilted by α from n (the lobe's half width)
                let h = tilt(n, al.min(1.0), 1.0 + j as f64);
                let v2 = 2.0 * l.dot(h) * h - l;
                let r = rec(&[n.x, n.y, n.z, l.x, l.y, l.z, v2.x, v2.y, v2.z, al]);
                (if c >= 0.01 && v2.dot(n) >= 0.01 { &mut mirror } else { &mut grazing }).push(r);
            }
            for (k, &c2) in cos_all.iter().enumerate().step_by(3) {
                let v = tilt(n, c2.clamp(-1.0, 1.0).acos(), 2.0 + 0.3 * k as f64);
                for al in alphas().into_iter().step_by(3) {
                    let r = rec(&[n.x, n.y, n.z, l.x, l.y, l.z, v.x, v.y, v.z, al]);
                    (if c.min(c2) >= 0.01 { &mut general } else { &mut grazing }).push(r);
                }
            }
        }
    }
    // Near grazing the BRDF does not vanish (G2 ∝ n·v cancels the 1/(n·v)) while the n·v ≤ 0 test is
    // decided at rounding level: a jump of the full value, so errors there are shown relative to
    // the value (floor = |ref|) and bounded by the perturbation, which sees the switch.
    for (name, ins) in [("near the mirror direction (θh = 0, α), n·l >= 0.01", mirror), ("general l, v (n·l, n·v >= 0.01)", general), ("n·l or n·v grazing (<= 3e-3, incl. 0) or below", grazing)] {
        f.push(Family { function: F::GgxBrdfOverRs, name, inputs: ins, checks: vec![check("value", 0..1, floor_tiny, bound_ggx_brdf)] });
    }
    f.push(Family {
        function: F::LambertBrdfOverRd,
        name: "n·l −0.2…1, grazing incl. 0",
        inputs: lambert,
        checks: vec![check("value", 0..1, |_, _| 1.0 / PI, bound_lambert_brdf)],
    });
}
