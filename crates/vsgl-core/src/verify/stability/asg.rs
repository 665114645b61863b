//! Families of the ASG functions of `wgsl/common/sg.wgsl`: asg_evaluate, the SG–ASG product
//! integrals (plain and normalized), ggx_lobe_asg with the orthonormality of its frame.

use super::error_model::{fl, floor_tiny, floor_unit, perturbation};
use super::grids::{a, alphas, axes, rec, tilt, COSINES, GRAZING_COSINES, NEAR_ANGLES};
use super::{check, Check, Family, FLT_MIN, ULP};
use crate::verify::harness::{HarnessFunction as F, Input, Output64};
use crate::verify::oracle;
use glam::DVec3;
use std::f64::consts::PI;
use std::ops::Range;

/// asg_evaluate: u = ω·x, v = ω·y, ω·z (dot: 1.5 ULP backward on ω or the axes), η·u·u (1 ULP on η),
/// the sum (½), exp (its 2|X| ULP ≡ 2 ULP on the argument): c = 5 ULP per input; c₀ = 3.5 (exp's 3
/// ULP and the product). The condition number includes √(η|Xη|)·Σ|ωᵢxᵢ|/… (a sharp lobe amplifies the
/// absolute error of u) and Σ|ωᵢzᵢ|/(ω·z) near the horizon.
fn bound_asg_evaluate(i: &Input, r: &Output64) -> f64 {
    perturbation(F::AsgEvaluate, i, 0..1, 5.0, &[0, 3, 7, 11]) + 3.5 * ULP * r[0] + FLT_MIN
}

/// sg_asg_product_integral: ν = λ/2, the convolved bandwidths η·(ν/(η + ν)) (sum ½, division 2.5,
/// product ½ → 3.5 ULP) then asg_evaluate (5): c = 9 ULP per input (dη'/η' is split between η and
/// λ with weights summing to 1); c₀ = π (½) + two inverseSqrt of sums (2.5 each) + products (1) + exp
/// (3) ≈ 10. Flush-to-zero × the prefactor.
fn bound_sg_asg_product(i: &Input, r: &Output64) -> f64 {
    perturbation(F::SgAsgProductIntegral, i, 0..1, 9.0, &[0, 4, 8, 12]) + 10.0 * ULP * r[0] + FLT_MIN * (1.0 + sg_asg_prefactor(i))
}
fn sg_asg_prefactor(i: &Input) -> f64 {
    PI / ((a(i, 7) + 0.5 * a(i, 3)).max(FLT_MIN) * (a(i, 11) + 0.5 * a(i, 3)).max(FLT_MIN)).sqrt()
}
fn floor_sg_asg_product(i: &Input, _: &Output64) -> f64 {
    fl(1e-30 * sg_asg_prefactor(i))
}
/// Near the horizon the factor max(ω·z, 0) is known to ±1.5 ULP absolute: floor = the peak.
fn floor_sg_asg_product_peak(i: &Input, _: &Output64) -> f64 {
    fl(sg_asg_prefactor(i))
}
/// sg_asg_product_integral_over_asg_integral: the same c = 9; c₀ = 10 (two inverseSqrt(1 + ν/η):
/// 2.5 + ½ + 2 each, exp 3); where ν/η overflows f32 (degenerate η → 0) the GPU's 1/√(1 + ν/η) is
/// 0 and the oracle's ≤ 1/√FLT_MAX = 5.4e-20.
fn bound_sg_asg_product_over(i: &Input, r: &Output64) -> f64 {
    let nu = 0.5 * a(i, 3);
    let overflow = if nu / a(i, 7).max(FLT_MIN) > 1e37 || nu / a(i, 11).max(FLT_MIN) > 1e37 { 6e-19 } else { 0.0 };
    perturbation(F::SgAsgProductIntegralOverAsgIntegral, i, 0..1, 9.0, &[0, 4, 8, 12]) + 10.0 * ULP * r[0] + FLT_MIN + overflow
}

/// ggx_lobe_asg: c = max(ω_o·n, 0) (1.5 ULP backward), λh (3 ULP on α), c² and the clamped
/// division (3.5): c = 4 ULP per input. The frame vectors are unit: c₀ = 8 ULP absolute (the
/// normalizations' 6 and the cross products' 2); bandwidths c₀ = 4.5 ULP relative. The y axis has
/// condition number 1/sin θo (its direction is noise at normal view, where ηx = ηy makes it
/// irrelevant); the bound follows it through the perturbation.
/// The frame (x 0–2, y 4–6, z 8–10) must be orthonormal whatever the conditioning of y: residuals
/// x·y, y·z, z·x, ‖x‖² − 1, ‖y‖² − 1, ‖z‖² − 1. Each unit vector is normalized to ≤ 6 ULP, y is made
/// ⊥ z by one projection (≤ 2 ULP), x = y × z (2 ULP): each residual ≤ 2×(6 + 2) ULP; bound 16 ULP on
/// their norm. This check found two defects of the original WGSL: a skewed frame near normal view
/// (y·z = 2.3e-2 at θo ≈ 1e-7 on lavapipe; vsgl_specular 8e-7 instead of 0.9998 at the mirror
/// direction) and, with FMA contraction on an H100, a collapsed frame at ω_o = n exactly
/// (y·z = 0.99999996; vsgl_specular 1.9e-22 instead of 1.0).
pub(super) fn frame_residuals(o: &[f64]) -> Vec<f64> {
    let v = |k: usize| DVec3::new(o[k], o[k + 1], o[k + 2]);
    let (x, y, z) = (v(0), v(4), v(8));
    vec![x.dot(y), y.dot(z), z.dot(x), x.length_squared() - 1.0, y.length_squared() - 1.0, z.length_squared() - 1.0]
}

pub(super) fn bound_ggx_lobe_asg(i: &Input, r: &Output64, slots: Range<usize>, c0_abs: f64, c0_rel: f64) -> f64 {
    let norm = slots.clone().map(|j| r[j] * r[j]).sum::<f64>().sqrt();
    perturbation(F::GgxLobeAsg, i, slots, 4.0, &[0, 3]) + c0_abs * ULP + c0_rel * ULP * norm
}

pub(super) fn asg_families(f: &mut Vec<Family>) {
    let bandwidths: [f64; 9] = [0.0, 1e-6, 1.0, 10.0, 1e2, 1e4, 1e6, 1e8, 5e8];
    let (mut peak, mut horizon, mut peak_p, mut horizon_p) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let mut degenerate_p = Vec::new();
    for (zi, z) in axes().into_iter().enumerate() {
        let m = oracle::orthonormal_basis(z);
        let (x, y) = (m.x_axis, m.y_axis);
        let asg = [x.x, x.y, x.z, 0.0, y.x, y.y, y.z, 0.0, z.x, z.y, z.z];
        for (bi, &ex) in bandwidths.iter().enumerate() {
            for (bj, &ey) in bandwidths.iter().enumerate() {
                let mut rec_asg = asg;
                rec_asg[3] = ex;
                rec_asg[7] = ey;
                let mut dirs_peak = vec![z, (z + 1e-6 * x).normalize()];
                for k in [0.5f64, 1.0, 2.0, 5.0] {
                    let sx = if ex > 0.0 { (k / ex.sqrt()).min(1.5) } else { 0.7 };
                    let sy = if ey > 0.0 { (k / ey.sqrt()).min(1.5) } else { 0.7 };
                    dirs_peak.push(z * sx.cos() + x * sx.sin());
                    dirs_peak.push(z * sy.cos() + y * sy.sin());
                    dirs_peak.push((z + x * (0.6 * sx).tan() + y * (0.8 * sy).tan()).normalize());
                }
                let phi = 0.37 * (zi + bi + bj) as f64;
                let dirs_horizon: Vec<DVec3> = [0.0, 1e-6, 1e-4, -1e-6, -0.3]
                    .iter()
                    .map(|&c: &f64| z * c + (x * phi.cos() + y * phi.sin()) * (1.0 - c * c).sqrt())
                    .collect();
                for (dirs, out, out_p) in [(&dirs_peak, &mut peak, &mut peak_p), (&dirs_horizon, &mut horizon, &mut horizon_p)] {
                    for d in dirs {
                        let mut v = vec![d.x, d.y, d.z];
                        v.extend(rec_asg);
                        out.push(rec(&v));
                    }
                    for &l in &[0.0, 1e-6, 1.0, 100.0, 1e4, 1e6, 1e9] {
                        for d in dirs.iter().step_by(2) {
                            let mut v = vec![d.x, d.y, d.z, l];
                            v.extend(rec_asg);
                            // An ASG with η ≤ 1e-6 is a band, not a lobe: the tangent-plane formula
                            // does not apply and the normalized form tends to 0 (own family).
                            if ex.min(ey) <= 1e-6 {
                                degenerate_p.push(rec(&v));
                            } else {
                                out_p.push(rec(&v));
                            }
                        }
                    }
                }
            }
        }
    }
    // Floors: relative near the peak; at the horizon the factor max(ω·z, 0) is known to ±1.5 ULP
    // absolute, so errors are shown relative to the peak value (1, or the prefactor).
    for (name, ins, ins_p, horizon) in [
        ("ω near z (0…5 widths), η 0…5e8", peak, peak_p, false),
        ("ω·z = 0, ±1e-6, 1e-4, below", horizon, horizon_p, true),
    ] {
        f.push(Family {
            function: F::AsgEvaluate,
            name,
            inputs: ins,
            checks: vec![check("value", 0..1, if horizon { floor_unit } else { floor_tiny }, bound_asg_evaluate)],
        });
        f.push(Family {
            function: F::SgAsgProductIntegral,
            name,
            inputs: ins_p.clone(),
            checks: vec![check("value", 0..1, if horizon { floor_sg_asg_product_peak } else { floor_sg_asg_product }, bound_sg_asg_product)],
        });
        f.push(Family {
            function: F::SgAsgProductIntegralOverAsgIntegral,
            name,
            inputs: ins_p,
            checks: vec![check("value", 0..1, if horizon { floor_unit } else { floor_tiny }, bound_sg_asg_product_over)],
        });
    }
    let name = "degenerate η <= 1e-6 (a band, not a lobe)";
    f.push(Family {
        function: F::SgAsgProductIntegral,
        name,
        inputs: degenerate_p.clone(),
        checks: vec![check("value", 0..1, floor_sg_asg_product_peak, bound_sg_asg_product)],
    });
    f.push(Family {
        function: F::SgAsgProductIntegralOverAsgIntegral,
        name,
        inputs: degenerate_p,
        checks: vec![check("value", 0..1, floor_unit, bound_sg_asg_product_over)],
    });
    // ggx_lobe_asg by view angle.
    let views = |angles: &[f64]| {
        let mut ins = Vec::new();
        for n in axes() {
            for (j, &t) in angles.iter().enumerate() {
                let w = tilt(n, t, 0.8 * j as f64 + 0.3);
                for al in alphas().into_iter().chain([0.0]) {
                    ins.push(rec(&[n.x, n.y, n.z, w.x, w.y, w.z, al]));
                }
            }
        }
        ins
    };
    let normal_view: Vec<f64> = NEAR_ANGLES.to_vec();
    let oblique: Vec<f64> = COSINES[..8].iter().map(|c| c.acos()).collect();
    let grazing: Vec<f64> = GRAZING_COSINES.iter().map(|c| c.acos()).chain([PI / 2.0 + 0.1, 2.5]).collect();
    for (name, angles) in [("normal view (θo 0…1e-3 rad)", normal_view), ("oblique view (n·ω_o 0.01…0.99)", oblique), ("grazing n·ω_o <= 3e-3 (incl. 0), below", grazing)] {
        f.push(Family {
            function: F::GgxLobeAsg,
            name,
            inputs: views(&angles),
            checks: vec![
                check("x_axis", 0..3, floor_unit, |i, r| bound_ggx_lobe_asg(i, r, 0..3, 8.0, 0.0)),
                check("x_bandwidth", 3..4, floor_tiny, |i, r| bound_ggx_lobe_asg(i, r, 3..4, 0.0, 4.5)),
                check("y_axis", 4..7, floor_unit, |i, r| bound_ggx_lobe_asg(i, r, 4..7, 8.0, 0.0)),
                check("y_bandwidth", 7..8, floor_tiny, |i, r| bound_ggx_lobe_asg(i, r, 7..8, 0.0, 4.5)),
                check("z_axis", 8..11, floor_unit, |i, r| bound_ggx_lobe_asg(i, r, 8..11, 8.0, 0.0)),
                Check { output: "frame orthonormality", slots: 0..11, derive: Some(frame_residuals), floor: floor_unit, bound: |_, _| 16.0 * ULP },
            ],
        });
    }
}
