//! Families of the SG functions of `wgsl/common/sg.wgsl`: sg_evaluate, sg_integral and its
//! approximation, the vMF moments, sg_product, sg_product_integral, sg_clamped_cosine_integral.

use super::error_model::{
    abs_erf, dot_scale, fl, floor_tiny, floor_unit, rel_cosine_variance, rel_exp, rel_expm1_over_x,
    rel_mean_cosine, rel_sg_integral, rel_tangent_moment, sens_sg_integral_over_lambda,
};
use super::grids::{
    a, axes, lin, logspace, rec, tilt, v3, COSINES, FAR_ANGLES, GRAZING_COSINES, MID_ANGLES,
    NEAR_ANGLES, SHARPNESS, SHARPNESS_PAIRS,
};
use super::{check, scalar_family, Family, FLT_MIN, ULP};
use crate::verify::harness::{HarnessFunction as F, Input, Output64};
use crate::verify::oracle;
use glam::DVec3;
use std::f64::consts::PI;

/// sg_evaluate: the exponent X = −½λ‖ω − ξ‖² is formed from d = ω − ξ (½ ULP per component, exact
/// when the axes are close: Sterbenz), dot(d, d) (≤ 1.5 ULP: squares are ≥ 0), and the products
/// (1 ULP): ≤ 5 ULP×|X| altogether; exp adds 3 + 2|X| ULP. Relative bound (3 + 7|X|) ULP; an
/// underflowed result may flush to 0 (+FLT_MIN). No condition number beyond |X|: the form
/// exp(λ(ω·ξ − 1)) would have 1/‖ω − ξ‖² near the axis.
fn bound_sg_evaluate(i: &Input, r: &Output64) -> f64 {
    let d = v3(i, 0) - v3(i, 3);
    let x = 0.5 * a(i, 6) * d.length_squared();
    r[0] * (3.0 + 7.0 * x) * ULP + FLT_MIN
}

/// sg_product: v = λ₁ξ₁ + λ₂ξ₂ (two products and a sum per component: ‖δv‖ ≤ ULP·(λ₁ + λ₂)).
/// The condition number of λm = ‖v‖ and of the axis v/λm is κ = (λ₁ + λ₂)/λm (opposite lobes
/// cancel). axis: ‖δ(v/|v|)‖ ≤ 2‖δv‖/λm (capped at 2, any two unit vectors), + 6 ULP for
/// safe_normalize. sharpness: ‖δv‖ + 5.5 ULP·λm (dot ¾ + sqrt 4.5 ULP); floor ULP·(λ₁ + λ₂), the
/// absolute resolution of λm. log-amplitude −λ₁·(λ₂/S)·‖ξ₁ − ξ₂‖², S = λm + λ₁ + λ₂ ≥ λ₁ + λ₂: S errs
/// by ≤ 4.25 ULP (λm's absolute error over S, and two sums), the division 2.5, ‖ξ₁ − ξ₂‖² 2.5
/// (exact differences, then squares ≥ 0), two products 1: relative 10.25 ULP → 11 ULP. No κ: every
/// term is ≥ 0 (the stable form; λm − λ₁ − λ₂ would have κ = (λ₁+λ₂)/|λm − λ₁ − λ₂|).
fn product_lambdas(i: &Input, r: &Output64) -> (f64, f64) {
    (a(i, 3) + a(i, 7), r[3])
}
fn bound_sg_product_axis(i: &Input, r: &Output64) -> f64 {
    let (sum, lm) = product_lambdas(i, r);
    let dv = ULP * sum;
    let dir = if dv == 0.0 { 0.0 } else if lm > 0.0 { (2.0 * dv / lm).min(2.0) } else { 2.0 };
    dir + 6.0 * ULP
}
fn bound_sg_product_sharpness(i: &Input, r: &Output64) -> f64 {
    let (sum, lm) = product_lambdas(i, r);
    ULP * (sum + 5.5 * lm) + FLT_MIN
}
fn bound_sg_product_log_amplitude(_: &Input, r: &Output64) -> f64 {
    11.0 * ULP * r[4].abs() + FLT_MIN
}

/// sg_product_integral = exp(ℓ)·A(λm): exp's (3 + 2|ℓ|) ULP, ℓ's 11 ULP·|ℓ|, A's own bound, and λm's
/// error reaching A with |d ln A/d ln λ| (≤ 1, ≈ λ for small λ: opposite lobes do not hurt), one
/// product. Flush-to-zero of exp(ℓ): + FLT_MIN·A(λm).
pub(super) fn bound_sg_product_integral(i: &Input, r: &Output64) -> f64 {
    let p = oracle::sg_product(v3(i, 0), a(i, 3), v3(i, 4), a(i, 7));
    let (sum, lm) = (a(i, 3) + a(i, 7), p.sharpness);
    let la = p.log_amplitude.abs();
    let rel = rel_exp(la) + 11.0 * ULP * la + rel_sg_integral(lm) + sens_sg_integral_over_lambda(lm) * ULP * (sum + 5.5 * lm) + 0.5 * ULP;
    r[0] * rel + FLT_MIN * oracle::sg_integral(lm)
}
fn floor_sg_product_integral(i: &Input, _: &Output64) -> f64 {
    fl(1e-30 * oracle::sg_integral(a(i, 3)).min(oracle::sg_integral(a(i, 7))))
}

/// sg_clamped_cosine_integral = A(λ)·max(½m + k·M, 0), m = cL, M the even part of the normal model,
/// k = (exact even part at c = 1)/(model at c = 1). Absolute error relative to A(λ) (the formula
/// cancels to ~0 for lobes below the horizon, so it is accurate only in absolute terms, as the
/// oracle's quadrature test measures it), the sum of
///  - R·(A's bound), and the error of c = ξ·n (1.5 ULP·Σ|ξᵢnᵢ|, slope ≤ 1.1);
///  - the moments: k·(|m|·(L's bound) + φ(z)·s·(½·max(Var's, T's bound) + 3 ULP)) (∂/∂s = kφ);
///  - the A&S erf: ½k|m|·|erf error at z/√2|, and k·M·(k's relative error);
///  - 12 ULP for the remaining ~20 roundings of O(1) terms (weights ≤ 0.6).
///
/// k's relative error: even_exact = ε₁(2 − (1+λ)ε₁)/(4ε₂) (2 − (1+λ)ε₁ ≥ 0.7: condition ≤ 1.9) and the
/// model at c = 1, whose erf and moments errors are weighted by their share of M₁.
fn bound_sg_clamped_cosine(i: &Input, r: &Output64) -> f64 {
    let (xi, lambda, n) = (v3(i, 0), a(i, 3), v3(i, 4));
    clamped_cosine_abs_bound(xi, lambda, n, r[0])
}
pub(super) fn clamped_cosine_abs_bound(xi: DVec3, lambda: f64, n: DVec3, value: f64) -> f64 {
    let area = oracle::sg_integral(lambda);
    let c = xi.dot(n).clamp(-1.0, 1.0);
    let l = oracle::sg_mean_cosine(lambda);
    let var = oracle::sg_cosine_variance(lambda);
    let tan = oracle::sg_tangent_second_moment(lambda);
    let phi = |z: f64| (-0.5 * z * z).exp() / (2.0 * PI).sqrt();
    let (b_l, b_v, b_t) = (rel_mean_cosine(lambda), rel_cosine_variance(lambda), rel_tangent_moment(lambda));
    let b_s = 0.5 * b_v.max(b_t) + 3.0 * ULP;
    let s1 = var.max(FLT_MIN).sqrt();
    let z1 = l / s1;
    let m1 = 0.5 * l * oracle::erf(z1 / 2f64.sqrt()) + s1 * phi(z1);
    let m = c * l;
    let s = (c * c * var + (1.0 - c * c) * tan).max(FLT_MIN).sqrt();
    let z = m / s;
    let big_m = 0.5 * m * oracle::erf(z / 2f64.sqrt()) + s * phi(z);
    let e1 = oracle::expm1_over_x(-lambda);
    let e2 = oracle::expm1_over_x(-2.0 * lambda);
    let even_exact = e1 * (2.0 - (1.0 + lambda) * e1) / (4.0 * e2);
    let k = even_exact / m1.max(FLT_MIN);
    let b_k = 1.9 * (rel_expm1_over_x(-lambda) + ULP) + rel_expm1_over_x(-2.0 * lambda) + rel_expm1_over_x(-lambda) + 3.0 * ULP
        + (0.5 * l * abs_erf(z1 / 2f64.sqrt()) + 0.5 * l * b_l + phi(z1) * s1 * b_s) / m1.max(FLT_MIN)
        + 2.5 * ULP;
    let relative_to_area = (value / area.max(FLT_MIN)) * rel_sg_integral(lambda)
        + 1.1 * 1.5 * ULP * dot_scale(xi, n)
        + k * (m.abs() * b_l + phi(z) * s * b_s)
        + 0.5 * k * m.abs() * abs_erf(z / 2f64.sqrt())
        + k * big_m * b_k
        + 12.0 * ULP;
    area * relative_to_area + FLT_MIN
}
fn floor_clamped_cosine(i: &Input, _: &Output64) -> f64 {
    oracle::sg_integral(a(i, 3))
}

pub(super) fn sg_families(f: &mut Vec<Family>) {
    // sg_evaluate: ω near ξ (equal, 1e-7 … 1e-3 rad), at 0.25…12 lobe widths, anywhere (incl.
    // opposite), for every sharpness.
    let mut near = Vec::new();
    let mut lobe = Vec::new();
    let mut far = Vec::new();
    for ax in axes() {
        for &l in &SHARPNESS {
            let push = |v: &mut Vec<Input>, t: f64, phi: f64| {
                let w = tilt(ax, t.min(PI), phi);
                v.push(rec(&[w.x, w.y, w.z, ax.x, ax.y, ax.z, l]));
            };
            for (j, &t) in NEAR_ANGLES.iter().enumerate() {
                push(&mut near, t, 0.7 * j as f64);
            }
            if l > 0.0 {
                for (j, k) in [0.25, 0.5, 1.0, 2.0, 4.0, 8.0, 12.0].iter().enumerate() {
                    push(&mut lobe, k / l.sqrt(), 1.3 * j as f64);
                }
            }
            for (j, &t) in MID_ANGLES.iter().chain(&FAR_ANGLES).enumerate() {
                push(&mut far, t, 0.9 * j as f64);
            }
        }
    }
    for (name, ins) in [("ω within 1e-3 rad of ξ (equal, 1e-7 apart…)", near), ("ω at 0.25…12 lobe widths", lobe), ("ω anywhere, incl. opposite", far)] {
        f.push(Family { function: F::SgEvaluate, name, inputs: ins, checks: vec![check("value", 0..1, floor_tiny, bound_sg_evaluate)] });
    }
    // sg_integral (relative; branch at λ = ¼) and the 2π/max(λ, ½) approximation (division 2.5 +
    // the constant ½ → 3 ULP).
    let mut small = vec![0.0, 1e-30, 1e-20, 1e-12, 1e-8, 1e-6, 1e-4];
    small.extend(lin(1e-3, 0.2499, 60));
    let mut large = lin(0.25, 3.0, 60);
    large.extend(logspace(3.0, 1e30, 80));
    for (name, xs) in [("series branch λ < 1/4 (incl. 0)", &small), ("λ >= 1/4 up to 1e30", &large)] {
        f.push(scalar_family(F::SgIntegral, name, xs, floor_tiny, |i, r| rel_sg_integral(a(i, 0)) * r[0] + FLT_MIN));
    }
    let mut all = small.clone();
    all.extend(&large);
    f.push(scalar_family(F::SgIntegralApprox, "λ = 0…1e30", &all, floor_tiny, |_, r| 3.0 * ULP * r[0]));
    // vMF moments, each branch.
    let mut small = vec![0.0, 1e-30, 1e-20, 1e-10, 1e-6, 1e-3];
    small.extend(lin(0.01, 0.9999, 100));
    let mut large = lin(1.0, 1.2, 40);
    large.extend(lin(1.2, 40.0, 100));
    large.extend(logspace(40.0, 1e12, 60));
    for (name, xs) in [("series branch λ < 1", &small), ("closed form λ >= 1", &large)] {
        f.push(scalar_family(F::SgMeanCosine, name, xs, floor_tiny, |i, r| rel_mean_cosine(a(i, 0)) * r[0].abs()));
        f.push(scalar_family(F::SgTangentSecondMoment, name, xs, floor_tiny, |i, r| rel_tangent_moment(a(i, 0)) * r[0].abs()));
        f.push(scalar_family(F::SgCosineVariance, name, xs, floor_tiny, |i, r| rel_cosine_variance(a(i, 0)) * r[0].abs()));
    }
    // sg_product and sg_product_integral: every sharpness pair × axis pairs.
    let pairs = |angles: &[f64]| {
        let mut ins = Vec::new();
        for ax in axes() {
            for (j, &t) in angles.iter().enumerate() {
                let b = tilt(ax, t, 1.3 * j as f64 + 0.2);
                for &l1 in &SHARPNESS_PAIRS {
                    for &l2 in &SHARPNESS_PAIRS {
                        ins.push(rec(&[ax.x, ax.y, ax.z, l1, b.x, b.y, b.z, l2]));
                    }
                }
            }
        }
        ins
    };
    for (name, angles) in [
        ("axes equal or 1e-7…1e-3 rad apart", &NEAR_ANGLES[..]),
        ("axes 0.01…3 rad apart", &MID_ANGLES[..]),
        ("axes opposite or nearly (π − 1e-4…π)", &FAR_ANGLES[..]),
    ] {
        let ins = pairs(angles);
        f.push(Family {
            function: F::SgProduct,
            name,
            inputs: ins.clone(),
            checks: vec![
                check("axis", 0..3, floor_unit, bound_sg_product_axis),
                check("sharpness", 3..4, |i, _| fl(ULP * (a(i, 3) + a(i, 7))), bound_sg_product_sharpness),
                check("log_amplitude", 4..5, floor_tiny, bound_sg_product_log_amplitude),
            ],
        });
        f.push(Family {
            function: F::SgProductIntegral,
            name,
            inputs: ins,
            checks: vec![check("value", 0..1, floor_sg_product_integral, bound_sg_product_integral)],
        });
    }
    // sg_clamped_cosine_integral: every sharpness × ξ·n ∈ [−1, 1], grazing included.
    let cc = |cosines: &[f64]| {
        let mut ins = Vec::new();
        for n in axes() {
            for &l in &SHARPNESS {
                for (j, &c) in cosines.iter().enumerate() {
                    let xi = tilt(n, c.clamp(-1.0, 1.0).acos(), 0.4 + j as f64);
                    ins.push(rec(&[xi.x, xi.y, xi.z, l, n.x, n.y, n.z]));
                }
            }
        }
        ins
    };
    let above: Vec<f64> = COSINES.to_vec();
    let grazing: Vec<f64> = GRAZING_COSINES.iter().flat_map(|&c| [c, -c]).collect();
    let below: Vec<f64> = COSINES.iter().map(|c| -c).collect();
    for (name, cos) in [("lobe above the horizon (ξ·n 0.01…1)", above), ("grazing (|ξ·n| <= 3e-3, incl. 0)", grazing), ("lobe below the horizon (ξ·n −1…−0.01)", below)] {
        f.push(Family {
            function: F::SgClampedCosineIntegral,
            name,
            inputs: cc(&cos),
            checks: vec![check("value", 0..1, floor_clamped_cosine, bound_sg_clamped_cosine)],
        });
    }
}
