//! Families of the lobe constructors of `wgsl/common/sg.wgsl`: the Toksvig mean direction and its
//! inverse, lambert_lobe_sg, ggx_ndf_sg_sharpness, ggx_lobe_sg.

use super::error_model::{dot_scale, floor_tiny, floor_unit, rel_sg_integral, sens_sg_integral};
use super::grids::{
    a, alphas, axes, logspace, out3, rec, tilt, v3, COSINES, GRAZING_COSINES, SHARPNESS
};
use super::{check, scalar_family, Family, FLT_MIN, ULP};
use crate::verify::harness::{HarnessFunction as F, Input, Output64};
use crate::verify::oracle;
use glam::DVec3;

/// sg_toksvig_mean_direction: λ + 1 (½), λ/(λ + 1) (2.5), × axis (½) → 3.5 ULP → 4.
/// sg_from_toksvig_mean_direction: r = length(ξ̄) (dot ¾ + sqrt 4.5 → 5.25 ULP) feeds 1 − r, whose
/// condition number is r/(1 − r) = λ: the rounded r lies in r(1 ± 5.25 ULP), and the bound evaluates
/// λ(r') = min(r'/(1 − r'), TOKSVIG_SHARPNESS_MAX) over that interval (so the clamp, and r' ≥ 1, are
/// exact), plus 3 ULP (subtraction, division). amplitude 1/A(λ): A's bound, the division, and the
/// same interval of λ through A. axis: safe_normalize (6 ULP).
fn toksvig_interval(r: f64, rel: f64) -> (f64, f64) {
    let lam = |r: f64| (r / (1.0 - r).max(FLT_MIN)).min(oracle::TOKSVIG_SHARPNESS_MAX);
    (lam(r * (1.0 - rel)), lam(r * (1.0 + rel)))
}
pub(super) fn toksvig_sharpness_bound(r: f64, rel_r: f64, lambda: f64) -> f64 {
    let (lo, hi) = toksvig_interval(r, rel_r);
    (hi - lambda).max(lambda - lo) + 3.0 * ULP * lambda + FLT_MIN
}
pub(super) fn toksvig_amplitude_bound(r: f64, rel_r: f64, lambda: f64, amplitude: f64) -> f64 {
    let (lo, hi) = toksvig_interval(r, rel_r);
    let inv_a = |l: f64| 1.0 / oracle::sg_integral(l);
    (inv_a(hi) - amplitude).abs().max((amplitude - inv_a(lo)).abs())
        + amplitude * (rel_sg_integral(lambda) + 2.5 * ULP + sens_sg_integral(lambda) * 3.0 * ULP)
}

/// ggx_lobe_sg at a VPL: c = ω'·n errs by δc = 1.5 ULP·Σ|ω'ᵢnᵢ| (absolute), so a grazing cosine has
/// condition number Σ|ω'ᵢnᵢ|/|c|. sharpness λh/max(4|c|, λh/SG_SHARPNESS_MAX) is evaluated over
/// c ± δc (clamp included), plus λh's 3.5 ULP and the division's 2.5. amplitude: as for the Toksvig
/// lobe, over the same interval. axis: 2c·n − ω' errs by ≤ 3δc + 2 ULP, then safe_normalize 6 ULP.
fn ggx_lobe_sg_interval(i: &Input) -> (f64, f64, f64) {
    let (n, w, alpha) = (v3(i, 0), v3(i, 3), a(i, 6));
    let c = w.dot(n).abs();
    let dc = 1.5 * ULP * dot_scale(w, n);
    let lh = oracle::ggx_ndf_sg_sharpness(alpha);
    let lam = |c: f64| lh / (4.0 * c.max(0.0)).max(lh / oracle::SG_SHARPNESS_MAX);
    (lam(c + dc), lam(c - dc), lh)
}
fn bound_ggx_lobe_sg_sharpness(i: &Input, r: &Output64) -> f64 {
    let (lo, hi, _) = ggx_lobe_sg_interval(i);
    (hi - r[3]).max(r[3] - lo) + 6.5 * ULP * r[3]
}
fn bound_ggx_lobe_sg_amplitude(i: &Input, r: &Output64) -> f64 {
    let (lo, hi, _) = ggx_lobe_sg_interval(i);
    let inv_a = |l: f64| 1.0 / oracle::sg_integral(l);
    (inv_a(hi) - r[4]).abs().max((r[4] - inv_a(lo)).abs())
        + r[4] * (rel_sg_integral(r[3]) + 2.5 * ULP + sens_sg_integral(r[3]) * 6.5 * ULP)
}
fn bound_ggx_lobe_sg_axis(i: &Input, _: &Output64) -> f64 {
    ULP * (8.0 + 4.5 * dot_scale(v3(i, 3), v3(i, 0)))
}

pub(super) fn lobe_families(f: &mut Vec<Family>) {
    let mut ins = Vec::new();
    for ax in axes() {
        for &l in SHARPNESS.iter().chain(&[1e12, 1e30]) {
            ins.push(rec(&[ax.x, ax.y, ax.z, l]));
        }
    }
    f.push(Family {
        function: F::SgToksvigMeanDirection,
        name: "λ = 0…1e30",
        inputs: ins,
        checks: vec![check("vector", 0..3, floor_tiny, |_, r| 4.0 * ULP * out3(r, 0).length())],
    });
    let (mut broad, mut sharp) = (Vec::new(), Vec::new());
    for ax in axes() {
        for &l in &SHARPNESS {
            let m = oracle::sg_toksvig_mean_direction(ax, l);
            (if l <= 1e3 { &mut broad } else { &mut sharp }).push(rec(&[m.x, m.y, m.z]));
        }
        // mixtures of two lobes (r smaller than each lobe's)
        for t in [0.1, 1.0, 2.5] {
            let m = 0.5 * (oracle::sg_toksvig_mean_direction(ax, 30.0) + oracle::sg_toksvig_mean_direction(tilt(ax, t, 1.0), 30.0));
            broad.push(rec(&[m.x, m.y, m.z]));
        }
        for r in [1.0 - 3e-7, 1.0 - 1.2e-7, 1.0 - 6e-8, 1.0, 1.0 + 1.2e-7] {
            sharp.push(rec(&[ax.x * r, ax.y * r, ax.z * r]));
        }
    }
    broad.push(rec(&[0.0, 0.0, 0.0]));
    for (name, ins) in [("r = λ/(λ+1), λ <= 1e3, mixtures, r = 0", broad), ("λ > 1e3, 1 − r down to 0 (clamp 1e5)", sharp)] {
        f.push(Family {
            function: F::SgFromToksvigMeanDirection,
            name,
            inputs: ins,
            checks: vec![
                check("axis", 0..3, floor_unit, |_, _| 6.0 * ULP),
                check("sharpness", 3..4, floor_tiny, |i, r| toksvig_sharpness_bound(v3(i, 0).length(), 5.25 * ULP, r[3])),
                check("amplitude", 4..5, floor_tiny, |i, r| toksvig_amplitude_bound(v3(i, 0).length(), 5.25 * ULP, r[3], r[4])),
            ],
        });
    }
    // lambert_lobe_sg: the axis is copied (exact); the sharpness is the f32 literal of the oracle's
    // f64 constant (½ ULP); amplitude 1/A(λd): A's bound + division + the constant through A.
    let ins: Vec<Input> = axes().iter().chain(&[DVec3::X]).map(|n| rec(&[n.x, n.y, n.z])).collect();
    f.push(Family {
        function: F::LambertLobeSg,
        name: "normals",
        inputs: ins,
        checks: vec![
            check("axis", 0..3, floor_unit, |_, _| 0.0),
            check("sharpness", 3..4, floor_tiny, |_, r| 0.5 * ULP * r[3]),
            check("amplitude", 4..5, floor_tiny, |_, r| r[4] * (rel_sg_integral(r[3]) + 2.5 * ULP + 0.5 * ULP * sens_sg_integral(r[3]))),
        ],
    });
    // ggx_ndf_sg_sharpness: α² (½), 2/· (2.5), the clamp constant (½) → 3.5 ULP.
    let mut al = vec![0.0, 1e-30, 1e-8, 3e-5, 4.4e-5, 4.5e-5];
    al.extend(logspace(1e-4, 1.0, 80));
    al.extend([2.0, 1e10]);
    f.push(scalar_family(F::GgxNdfSgSharpness, "α = 0…1 (clamp at α² = 2e-9), 2, 1e10", &al, floor_tiny, |_, r| 3.5 * ULP * r[0]));
    // ggx_lobe_sg by incidence.
    let lobe = |cosines: &[f64]| {
        let mut ins = Vec::new();
        for n in axes() {
            for (j, &c) in cosines.iter().enumerate() {
                let w = tilt(n, c.clamp(-1.0, 1.0).acos(), 0.9 * j as f64 + 0.1);
                for al in alphas().into_iter().chain([0.0]) {
                    ins.push(rec(&[n.x, n.y, n.z, w.x, w.y, w.z, al]));
                }
            }
        }
        ins
    };
    let below: Vec<f64> = [-1.0, -0.5, -0.01].to_vec();
    for (name, cos) in [("ω'·n 0.01…1", COSINES.to_vec()), ("grazing ω'·n <= 3e-3 (incl. 0)", GRAZING_COSINES.to_vec()), ("ω' below the surface", below)] {
        f.push(Family {
            function: F::GgxLobeSg,
            name,
            inputs: lobe(&cos),
            checks: vec![
                check("axis", 0..3, floor_unit, bound_ggx_lobe_sg_axis),
                check("sharpness", 3..4, floor_tiny, bound_ggx_lobe_sg_sharpness),
                check("amplitude", 4..5, floor_tiny, bound_ggx_lobe_sg_amplitude),
            ],
        });
    }
}
