//! Error-model building blocks (relative bounds, in units of 1; see the module comment of
//! [`super`]): the WGSL accuracy of exp and of the series branches, the moments, the forward
//! perturbation of the composite functions, and the denominator floors.

use super::{FLT_MIN, ULP};
use crate::verify::harness::{HarnessFunction as F, Input, Output64, INPUT_WIDTH};
use crate::verify::oracle;
use glam::DVec3;
use std::ops::Range;

/// WGSL exp(x): 3 + 2|x| ULP.
pub(super) fn rel_exp(x: f64) -> f64 {
    (3.0 + 2.0 * x.abs()) * ULP
}

/// expm1_over_x(x).
/// Series branch (|x| < ½): Horner in x with coefficients 1/(k+1)!; step k adds ≤ 2 roundings of its
/// partial sum and is damped by |x|ᵏ, so the first-order error is ≤ 2u·Σ|x|ᵏ|qₖ|/|p| ≤ 3.3u (p ≥ 0.787
/// at x = −½), the f32 coefficients add ≤ 1.65u (u = ½ ULP); truncation |x|⁹/10! ≤ 5.4e-10:
/// bound 4 ULP + 5.4e-10.
/// exp branch: (exp(x) − 1)/x; exp's error (3 + 2|x|) ULP of eˣ is amplified by the condition
/// number eˣ/|eˣ − 1| of the subtraction (≤ 2.54 at x = ½, → 1 for x ≫ 1, → 0 for x ≪ −1), plus
/// the subtraction (½) and the division (2.5 ULP) → 3.5 ULP. The argument is capped at 88 as in the
/// WGSL (and the oracle).
pub(super) fn rel_expm1_over_x(x: f64) -> f64 {
    if x.abs() < 0.5 {
        4.0 * ULP + 5.4e-10
    } else {
        let xc = x.min(88.0);
        3.5 * ULP + rel_exp(xc) * xc.exp() / xc.exp_m1().abs()
    }
}

/// expm1(x) = x·expm1_over_x(x) in the series branch (one more product: 4.5 ULP); eˣ − 1 in the
/// exp branch (the same amplified exp error, plus the subtraction: 0.5 ULP).
pub(super) fn rel_expm1(x: f64) -> f64 {
    if x.abs() < 0.5 {
        4.5 * ULP + 5.4e-10
    } else {
        let xc = x.min(88.0);
        0.5 * ULP + rel_exp(xc) * xc.exp() / xc.exp_m1().abs()
    }
}

/// sg_integral(λ) = 4π·expm1_over_x(−2λ): the f32 constant 4π and the product add 1 ULP.
pub(super) fn rel_sg_integral(lambda: f64) -> f64 {
    rel_expm1_over_x(-2.0 * lambda) + ULP
}

/// |d ln A / d ln λ| = |2λ/(e^{2λ} − 1) − 1| ≤ 1 (≈ λ for small λ, → 1 for large λ): how a relative
/// error of λ reaches A(λ).
pub(super) fn sens_sg_integral(lambda: f64) -> f64 {
    let t = 2.0 * lambda;
    if t < 1e-8 {
        lambda
    } else {
        (t / t.exp_m1() - 1.0).abs()
    }
}

/// The same divided by λ (finite as λ → 0, where it tends to 1).
pub(super) fn sens_sg_integral_over_lambda(lambda: f64) -> f64 {
    if lambda < 1e-8 {
        1.0
    } else {
        sens_sg_integral(lambda) / lambda
    }
}

/// Absolute error of the WGSL erf(x).
/// |x| < ½: Maclaurin series, relative truncation ≤ 2.7e-8 (oracle test of the coefficients);
/// Horner in x² ≤ ¼ with alternating coefficients (condition 1.18) plus 2/√π and two products:
/// ≤ 6u → 4 ULP relative with margin.
/// |x| ≥ ½: 1 − P·e^{−x²} with Abramowitz & Stegun 7.1.26, |ε| ≤ 1.5e-7 (+2e-8 for the published
/// constants rounded to f32, measured by the oracle test); the rounding of q = P·e^{−x²} = erfc(|x|)
/// is ≤ q·(exp's 3 + 2x² ULP + x²'s ½ ULP × x² + ≈ 2×4.3 ULP for the t-polynomial, whose condition
/// is ≤ 4.3 at x = ½) ≤ q·(12 + 2.5x²) ULP, and the final subtraction ½ ULP.
pub(super) fn abs_erf(x: f64) -> f64 {
    let ax = x.abs();
    if ax < 0.5 {
        (4.0 * ULP + 2.7e-8) * oracle::erf(ax)
    } else {
        let q = (1.0 - oracle::erf(ax)).max(0.0);
        1.7e-7 + ULP * (q * (12.0 + 2.5 * ax * ax) + 0.5)
    }
}

/// sg_mean_cosine(λ), relative.
/// λ < 1: the Langevin series λ·Σcₙλ²ⁿ (8 terms, alternating, condition 1.14 at λ = 1): Horner
/// ≤ 2u×1.14, the coefficients u×1.14 and the final product ½ ULP → 4 ULP; truncation 6.5e-9.
/// λ ≥ 1: (λ − 1 + (1 + λ)e)/(λ(1 − e)), e = exp(−2λ) with 3 + 4λ ULP: both numerator terms are ≥ 0
/// (no cancellation), so exp's error reaches the result weighted by the share (1+λ)e/num of the
/// numerator and e/(1 − e) of the denominator; the ~6 other roundings (2.5 ULP for the division)
/// add 5 ULP.
pub(super) fn rel_mean_cosine(x: f64) -> f64 {
    if x < 1.0 {
        4.0 * ULP + 6.5e-9
    } else {
        let e = (-2.0 * x).exp();
        let num = x - 1.0 + (1.0 + x) * e;
        ULP * (5.0 + (4.0 + 4.0 * x) * ((1.0 + x) * e / num + e / (1.0 - e)))
    }
}

/// sg_tangent_second_moment(λ) = the same series without the factor λ (4 ULP, truncation
/// 6.5e-9), or mean_cosine(λ)/λ (+2.5 ULP).
pub(super) fn rel_tangent_moment(x: f64) -> f64 {
    if x < 1.0 {
        4.0 * ULP + 6.5e-9
    } else {
        rel_mean_cosine(x) + 2.5 * ULP
    }
}

/// sg_cosine_variance(λ), relative.
/// λ < 1: 9-term series in λ² (alternating, condition 1.49): 5 ULP, truncation 1.4e-8.
/// λ ≥ 1: t₁ − t₂ with t₁ = 1/λ² (3 ULP) and t₂ = 4e/(1 − e)² whose error is exp's 3 + 4λ ULP
/// amplified by 1 + 2e/(1 − e) (the square of 1 − e) plus 4 ULP of roundings; the difference
/// cancels with condition (t₁ + t₂)/(t₁ − t₂) (6.2 at λ = 1, → 1 for large λ).
pub(super) fn rel_cosine_variance(x: f64) -> f64 {
    if x < 1.0 {
        5.0 * ULP + 1.4e-8
    } else {
        let e = (-2.0 * x).exp();
        let t1 = 1.0 / (x * x);
        let t2 = 4.0 * e / ((1.0 - e) * (1.0 - e));
        let abs = t1 * 3.5 * ULP + t2 * ((3.0 + 4.0 * x) * ULP * (1.0 + 2.0 * e / (1.0 - e)) + 4.0 * ULP);
        abs / (t1 - t2) + 0.5 * ULP
    }
}

/// Forward perturbation: Σ over the input slots of max over ± of ‖f(x with the slot moved by
/// ±c ULP) − f(x)‖ on `out` (f64 oracle). Scalars move relatively, x·(1 ± c·ULP); the components of
/// vectors (directions, positions: the 3-slot groups starting at `vectors`) move by ±c·ULP·‖v‖,
/// because the GPU's rounding of a direction or a frame built from it is absolute at the scale of
/// its length (a component of 1e-7 is not known to 1e-7 relative). For a backward error of c ULP
/// per input this is the first-order bound c·ULP·κ·|f|, κ the componentwise condition number
/// (Higham 2002, §7.2); evaluated at finite size, so clamps and branch switches count.
pub(super) fn perturbation(f: F, input: &Input, out: Range<usize>, c: f64, vectors: &[usize]) -> f64 {
    let base: [f64; INPUT_WIDTH] = input.map(|x| x as f64);
    let r0 = f.oracle64(&base);
    let mut total = 0.0;
    for k in 0..f.input_len() {
        let vector = vectors.iter().find(|&&v| (v..v + 3).contains(&k));
        let delta = match vector {
            Some(&v) => c * ULP * DVec3::new(base[v], base[v + 1], base[v + 2]).length(),
            None => c * ULP * base[k].abs(), // zero scalars are exact in f32 arithmetic
        };
        if delta == 0.0 {
            continue;
        }
        let mut worst: f64 = 0.0;
        for s in [-1.0, 1.0] {
            let mut x = base;
            x[k] += s * delta;
            let r = f.oracle64(&x);
            let d = out.clone().map(|j| (r[j] - r0[j]).powi(2)).sum::<f64>().sqrt();
            worst = worst.max(if d.is_finite() { d } else { f64::INFINITY });
        }
        total += worst;
    }
    total
}

/// Σ|aᵢbᵢ|: the scale of the rounding error of dot(a, b) (≤ 1.5 ULP × this).
pub(super) fn dot_scale(a: DVec3, b: DVec3) -> f64 {
    (a * b).abs().element_sum()
}

// Floors (all ≥ 1e-30: see the module comment).
pub(super) fn fl(x: f64) -> f64 {
    x.max(1e-30)
}
pub(super) fn floor_tiny(_: &Input, _: &Output64) -> f64 {
    1e-30
}
pub(super) fn floor_unit(_: &Input, _: &Output64) -> f64 {
    1.0
}
pub(super) fn floor_fmin(_: &Input, _: &Output64) -> f64 {
    FLT_MIN
}
