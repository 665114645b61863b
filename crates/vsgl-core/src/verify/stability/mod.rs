//! The stability suite: every WGSL function of `wgsl/common/{math,sg,ggx,vsgl}.wgsl`, evaluated in
//! f32 on the GPU through [`crate::verify::harness`] and in f64 by its oracle twin on the *same* f32
//! inputs, over case families that include the extremes of issue 3 (sharpness 1e-6…1e9,
//! roughness 1e-4…1, cosines down to 1e-6 and exactly 0, axes equal / opposite / 1e-7 rad apart,
//! variance down to 1e-12 of d² and exactly 0, positions 1e5 m from the origin relative to a
//! local origin, intensities 1e-8…1e8, zero power).
//!
//! # What is measured
//! For every output of every case: `e = ‖gpu − ref‖ / max(‖ref‖, floor)`, the Euclidean norm over
//! the output's slots (one slot for scalars, three for vectors). `floor` is stated per output and
//! tied to the function's own scale (e.g. `1e-30 × scale` where the function is accurate in
//! relative terms down to f32 underflow; the scale itself where it is accurate only in absolute
//! terms, such as unit axes or the clamped-cosine integral, which is a difference of O(A(λ))
//! terms). Every floor is at least 1e-30, so a result that underflows (± FLT_MIN) never dominates.
//! A row of the table is one (function output, case family): its `max_rel_error` is the largest
//! `e`, and it passes when no GPU output is NaN/Inf and **every case** is within its own bound,
//! `‖gpu − ref‖ ≤ bound(case)`, i.e. `worst_ratio = max ‖gpu − ref‖/bound ≤ 1`. The `bound` column is
//! the bound of the case that has the largest error, over the same denominator (so it is directly
//! comparable with `max_rel_error`).
//!
//! # How the bounds are built
//! Inputs are identical on both sides, so the difference is the GPU's own rounding (and the
//! WGSL's approximations of transcendentals). The accuracy WGSL guarantees for f32 is the model
//! (WGSL spec §"Floating Point Accuracy"; ULP = 2⁻²³ relative, [`ULP`]): `+ − ×` correctly
//! rounded (½ ULP), `x / y` 2.5 ULP, `inverseSqrt` 2 ULP, `sqrt` 4.5 ULP (inherited from
//! `1/inverseSqrt`), `exp(x)` 3 + 2|x| ULP, `dot`/`length`/`normalize`/`cross` inherited from their
//! expressions (a 3-term `dot` errs by ≤ 1.5 ULP × Σ|aᵢbᵢ|). Each bound is "a few ULP × the
//! condition number of the formula at that case":
//! - **elementary functions** (math.wgsl, SG integrals and moments, products, lobes, the BRDF
//!   factors, the VSGL moments and the diffuse forms): analytic, per case; the derivation is the
//!   comment above each `bound_*` function. Where a quantity is ill-conditioned (a grazing cosine
//!   of two f32 unit vectors, opposite lobes whose sum cancels, the variance E‖y‖² − ‖μ‖², 1 − r
//!   near the Toksvig clamp), the bound evaluates the formula over the interval the rounded
//!   quantity can take, so clamps and branch switches are accounted exactly.
//! - **composite functions** whose frames and exponents are built from many dot products
//!   (`asg_evaluate`, `ggx_lobe_asg`, the SG–ASG products, `vsgl_incoming_radiance`,
//!   `vsgl_specular`, `ggx_brdf_over_rs`): the componentwise condition number is evaluated with
//!   the f64 oracle, `P(x; c) = Σₖ max± ‖f(x with xₖ moved by ±c ULP) − f(x)‖`, for a backward
//!   error of `c` ULP per input (the longest chain of roundings any input passes through, counted
//!   in the comment of each function), plus `c₀·ULP·|f|` for the roundings after the last
//!   input-dependent step. Scalars move relatively; vector components by c ULP of the vector's
//!   length (the rounding of directions and of frames built from them is absolute). A WGSL form that is less stable than backward-stable (e.g. exp(λ(ω·ξ − 1)), or the
//!   skewed ASG frame found and fixed by this suite) exceeds such a bound by orders of magnitude.
//! - approximations that the WGSL makes on purpose are added in absolute terms: the
//!   Abramowitz–Stegun erf (|ε| ≤ 1.5e-7) and the truncation of each series (values in the WGSL
//!   comments).
//! - flush-to-zero: an intermediate that underflows may become 0 on a GPU; that costs at most
//!   `FLT_MIN` times the factor applied after it, which is added where it can occur.
//!
//! [`run`] returns the table; `tests/stability.rs` asserts that every row passes, and
//! `python -m vsgl stability` prints it. docs/numerics.md ("Stability suite") lists every bound
//! with its justification and the measured errors.

use crate::error::Result;
use crate::gpu::Gpu;
use crate::verify::harness::{Harness, HarnessFunction as F, Input, Output, Output64, INPUT_WIDTH};
use crate::verify::oracle;
use crate::rng::SplitMix64;
use glam::DVec3;
use std::f64::consts::PI;
use std::ops::Range;

/// One ULP of f32 at 1 (2⁻²³): the unit of every bound.
pub const ULP: f64 = f32::EPSILON as f64;
const FLT_MIN: f64 = f32::MIN_POSITIVE as f64;
const FLT_MAX: f64 = f32::MAX as f64;

/// `floor(input, oracle output)`: the denominator floor of the relative error.
pub type FloorFn = fn(&Input, &Output64) -> f64;
/// `bound(input, oracle output)`: the largest acceptable `‖gpu − ref‖` for that case.
pub type BoundFn = fn(&Input, &Output64) -> f64;

/// A quantity derived from a whole output record (f64 view of it), compared like an output.
pub type DeriveFn = fn(&[f64]) -> Vec<f64>;

/// One compared output of a function: its slots (or a quantity derived from the record), floor
/// and bound.
pub struct Check {
    /// Output name (`value`, `axis`, `sharpness`, …), shown as `function.output`.
    pub output: &'static str,
    pub slots: Range<usize>,
    /// When set, the compared vector is `derive(record)` instead of `record[slots]` (e.g. the
    /// orthonormality residuals of a frame).
    pub derive: Option<DeriveFn>,
    pub floor: FloorFn,
    pub bound: BoundFn,
}

/// A grid of cases for one function, with the outputs it compares.
pub struct Family {
    pub function: F,
    pub name: &'static str,
    pub inputs: Vec<Input>,
    pub checks: Vec<Check>,
}

/// One row of the stability table.
#[derive(Clone, Debug, PartialEq)]
pub struct StabilityRow {
    /// `wgsl_function.output`.
    pub function: String,
    pub family: String,
    pub cases: usize,
    /// max over cases of ‖gpu − ref‖ / max(‖ref‖, floor).
    pub max_rel_error: f64,
    /// The bound of the case that has `max_rel_error`, over the same denominator (already
    /// multiplied by the bound scale). Every case has its own bound; see `worst_ratio`.
    pub bound: f64,
    /// max over cases of ‖gpu − ref‖ / bound (≤ 1 when the row passes).
    pub worst_ratio: f64,
    /// Cases whose GPU output (or, never expected, oracle output) is NaN or ±Inf.
    pub nonfinite: usize,
    pub pass: bool,
    /// The case with the largest error/bound ratio: input, GPU and oracle outputs.
    pub worst_case: String,
}

/// Runs every family on `gpu`. `bound_scale` multiplies every bound (1 for the real suite; tests
/// use a small value to prove that the suite can fail).
pub fn run(gpu: &Gpu, bound_scale: f64) -> Result<Vec<StabilityRow>> {
    let harness = Harness::new(gpu)?;
    let mut rows = Vec::new();
    for family in families() {
        let out = harness.evaluate(gpu, family.function, &family.inputs)?;
        rows.extend(score(&family, &out, bound_scale));
    }
    Ok(rows)
}

/// Opens the adapter (`None`: the best one, or `VSGL_ADAPTER`) and runs the suite.
pub fn run_on_adapter(adapter: Option<&str>, bound_scale: f64) -> Result<Vec<StabilityRow>> {
    let gpu = Gpu::new(adapter)?;
    run(&gpu, bound_scale)
}

/// Compares GPU outputs with the oracle for every check of `family` (pure CPU; `gpu_out[i]` is the
/// GPU's output record for `family.inputs[i]`).
pub fn score(family: &Family, gpu_out: &[Output], bound_scale: f64) -> Vec<StabilityRow> {
    assert_eq!(gpu_out.len(), family.inputs.len(), "one output record per input");
    let refs: Vec<Output64> = family.inputs.iter().map(|i| family.function.oracle(i)).collect();
    let mut rows = Vec::new();
    for check in &family.checks {
        let (mut max_e, mut bound_at_max, mut worst, mut nonfinite) = (-1.0f64, 0.0f64, 0.0f64, 0usize);
        let mut worst_case = String::new();
        for ((input, g), r) in family.inputs.iter().zip(gpu_out).zip(&refs) {
            let g64: Vec<f64> = g.iter().map(|&x| x as f64).collect();
            let (gs, rs): (Vec<f64>, Vec<f64>) = match check.derive {
                Some(derive) => (derive(&g64), derive(&r[..])),
                None => (g64[check.slots.clone()].to_vec(), r[check.slots.clone()].to_vec()),
            };
            let describe = |note: &str| {
                format!(
                    "{note}input {:?} gpu {:?} oracle {:?}",
                    &input[..family.function.input_len()],
                    gs,
                    rs
                )
            };
            if gs.iter().chain(&rs).any(|x| !x.is_finite()) {
                nonfinite += 1;
                worst = f64::INFINITY;
                worst_case = describe("non-finite: ");
                continue;
            }
            let diff = gs.iter().zip(&rs).map(|(x, y)| (x - y) * (x - y)).sum::<f64>().sqrt();
            let norm = rs.iter().map(|y| y * y).sum::<f64>().sqrt();
            let den = norm.max((check.floor)(input, r)).max(f64::MIN_POSITIVE);
            let bound = (check.bound)(input, r) * bound_scale;
            let ratio = if diff == 0.0 {
                0.0
            } else if bound > 0.0 {
                diff / bound
            } else {
                f64::INFINITY
            };
            if diff / den > max_e {
                max_e = diff / den;
                bound_at_max = bound / den;
            }
            if ratio > worst || worst_case.is_empty() {
                worst = worst.max(ratio);
                worst_case = describe("");
            }
        }
        rows.push(StabilityRow {
            function: format!("{}.{}", family.function.name(), check.output),
            family: family.name.to_string(),
            cases: family.inputs.len(),
            max_rel_error: max_e.max(0.0),
            bound: bound_at_max,
            worst_ratio: worst,
            nonfinite,
            pass: nonfinite == 0 && worst <= 1.0,
            worst_case,
        });
    }
    rows
}

// ---------------------------------------------------------------------------------------------
// Input records and grids

fn rec(values: &[f64]) -> Input {
    let mut r = [0.0f32; INPUT_WIDTH];
    for (slot, x) in r.iter_mut().zip(values) {
        *slot = *x as f32;
    }
    r
}

fn a(i: &Input, k: usize) -> f64 {
    i[k] as f64
}

fn v3(i: &Input, k: usize) -> DVec3 {
    DVec3::new(a(i, k), a(i, k + 1), a(i, k + 2))
}

fn out3(o: &Output64, k: usize) -> DVec3 {
    DVec3::new(o[k], o[k + 1], o[k + 2])
}

/// `axis` turned by `angle` toward azimuth `phi` of its own frame (f64).
fn tilt(axis: DVec3, angle: f64, phi: f64) -> DVec3 {
    let m = oracle::orthonormal_basis(axis);
    (axis * angle.cos() + (m.x_axis * phi.cos() + m.y_axis * phi.sin()) * angle.sin()).normalize()
}

/// Axes: two coordinate axes (exact f32 arithmetic) and three general directions (every dot
/// product rounds).
fn axes() -> Vec<DVec3> {
    vec![
        DVec3::Z,
        -DVec3::Y,
        DVec3::new(0.3, -0.5, 0.81).normalize(),
        DVec3::new(-0.62, 0.21, -0.75).normalize(),
        DVec3::new(1.0, 1.0, 1.0).normalize(),
    ]
}

/// SG sharpness: 0, the issue's 1e-6…1e8, and SG_SHARPNESS_MAX = 1e9.
const SHARPNESS: [f64; 20] =
    [0.0, 1e-6, 1e-4, 1e-2, 0.1, 0.25, 0.5, 1.0, 2.0, 5.0, 10.0, 30.0, 100.0, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9];
/// A coarser sharpness grid for pairs.
const SHARPNESS_PAIRS: [f64; 12] = [0.0, 1e-6, 1e-3, 0.5, 1.0, 3.0, 10.0, 100.0, 1e4, 1e6, 1e8, 1e9];
/// Angles between two axes: equal, 1e-7 rad apart, …, nearly opposite, opposite.
const NEAR_ANGLES: [f64; 6] = [0.0, 1e-7, 1e-6, 1e-5, 1e-4, 1e-3];
const MID_ANGLES: [f64; 8] = [1e-2, 0.1, 0.3, 0.7, 1.2, 1.8, 2.5, 3.0];
const FAR_ANGLES: [f64; 4] = [PI - 1e-4, PI - 1e-6, PI - 1e-7, PI];
/// Cosines: exactly 0, grazing 1e-6 …, normal 1.
const GRAZING_COSINES: [f64; 6] = [0.0, 1e-6, 1e-5, 1e-4, 1e-3, 3e-3];
const COSINES: [f64; 10] = [0.01, 0.05, 0.1, 0.3, 0.5, 0.7, 0.9, 0.99, 0.9999, 1.0];
/// glTF roughness 1e-4…1 (α = max(roughness², GGX_ALPHA_MIN) as the renderer does).
const ROUGHNESS: [f64; 13] = [1e-4, 3e-4, 1e-3, 3e-3, 0.01, 0.02, 0.05, 0.1, 0.2, 0.35, 0.5, 0.75, 1.0];
/// Radiant intensities / powers, and 0.
const INTENSITIES: [f64; 6] = [0.0, 1e-8, 1e-4, 1.0, 1e4, 1e8];

fn alphas() -> Vec<f64> {
    ROUGHNESS.iter().map(|&r| oracle::ggx_alpha_from_roughness(r)).collect()
}

fn lin(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    (0..=n).map(|k| lo + (hi - lo) * k as f64 / n as f64).collect()
}

fn logspace(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    (0..=n).map(|k| (lo.ln() + (hi.ln() - lo.ln()) * k as f64 / n as f64).exp()).collect()
}

// ---------------------------------------------------------------------------------------------
// Error-model building blocks (relative bounds, in units of 1; see the module comment)

/// WGSL exp(x): 3 + 2|x| ULP.
fn rel_exp(x: f64) -> f64 {
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
fn rel_expm1_over_x(x: f64) -> f64 {
    if x.abs() < 0.5 {
        4.0 * ULP + 5.4e-10
    } else {
        let xc = x.min(88.0);
        3.5 * ULP + rel_exp(xc) * xc.exp() / xc.exp_m1().abs()
    }
}

/// expm1(x) = x·expm1_over_x(x) in the series branch (one more product: 4.5 ULP); eˣ − 1 in the
/// exp branch (the same amplified exp error, plus the subtraction: 0.5 ULP).
fn rel_expm1(x: f64) -> f64 {
    if x.abs() < 0.5 {
        4.5 * ULP + 5.4e-10
    } else {
        let xc = x.min(88.0);
        0.5 * ULP + rel_exp(xc) * xc.exp() / xc.exp_m1().abs()
    }
}

/// sg_integral(λ) = 4π·expm1_over_x(−2λ): the f32 constant 4π and the product add 1 ULP.
fn rel_sg_integral(lambda: f64) -> f64 {
    rel_expm1_over_x(-2.0 * lambda) + ULP
}

/// |d ln A / d ln λ| = |2λ/(e^{2λ} − 1) − 1| ≤ 1 (≈ λ for small λ, → 1 for large λ): how a relative
/// error of λ reaches A(λ).
fn sens_sg_integral(lambda: f64) -> f64 {
    let t = 2.0 * lambda;
    if t < 1e-8 {
        lambda
    } else {
        (t / t.exp_m1() - 1.0).abs()
    }
}

/// The same divided by λ (finite as λ → 0, where it tends to 1).
fn sens_sg_integral_over_lambda(lambda: f64) -> f64 {
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
fn abs_erf(x: f64) -> f64 {
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
fn rel_mean_cosine(x: f64) -> f64 {
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
fn rel_tangent_moment(x: f64) -> f64 {
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
fn rel_cosine_variance(x: f64) -> f64 {
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
fn perturbation(f: F, input: &Input, out: Range<usize>, c: f64, vectors: &[usize]) -> f64 {
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
fn dot_scale(a: DVec3, b: DVec3) -> f64 {
    (a * b).abs().element_sum()
}

// Floors (all ≥ 1e-30: see the module comment).
fn fl(x: f64) -> f64 {
    x.max(1e-30)
}
fn floor_tiny(_: &Input, _: &Output64) -> f64 {
    1e-30
}
fn floor_unit(_: &Input, _: &Output64) -> f64 {
    1.0
}
fn floor_fmin(_: &Input, _: &Output64) -> f64 {
    FLT_MIN
}

fn check(output: &'static str, slots: Range<usize>, floor: FloorFn, bound: BoundFn) -> Check {
    Check { output, slots, derive: None, floor, bound }
}

fn scalar_family(function: F, name: &'static str, xs: &[f64], floor: FloorFn, bound: BoundFn) -> Family {
    Family { function, name, inputs: xs.iter().map(|&x| rec(&[x])).collect(), checks: vec![check("value", 0..1, floor, bound)] }
}

// ---------------------------------------------------------------------------------------------
// The families

/// Every case family of the suite.
pub fn families() -> Vec<Family> {
    let mut f = Vec::new();
    math_families(&mut f);
    sg_families(&mut f);
    lobe_families(&mut f);
    asg_families(&mut f);
    ggx_families(&mut f);
    vsgl_families(&mut f);
    f
}

fn math_families(f: &mut Vec<Family>) {
    let mut series = lin(-0.4999, 0.4999, 120);
    for k in [1e-30, 1e-20, 1e-10, 1e-7, 1e-5, 1e-3] {
        series.extend([k, -k]);
    }
    let mut negative: Vec<f64> = logspace(0.5, 1e9, 120).into_iter().map(|x| -x).collect();
    negative.extend([-0.5000001, -1e37]);
    // Up to 1e37: WGSL specifies x/y only for |y| ≤ 2¹²⁶ = 8.5e37 (an H100 returns 0 beyond), and
    // the argument is capped at 88 anyway.
    let mut positive = logspace(0.5, 88.0, 120);
    positive.extend([0.5000001, 88.5, 100.0, 1e3, 1e9, 1e37]);
    // expm1_over_x and expm1: rel_expm1_over_x / rel_expm1 (relative; floor 1e-30, the values
    // are ≥ 1e-9 in magnitude except expm1 near 0, which is relative-accurate there too).
    for (name, xs) in [("series |x| < 1/2", &series), ("exp branch, x <= -1/2", &negative), ("exp branch, x >= 1/2 (capped at 88)", &positive)] {
        f.push(scalar_family(F::Expm1OverX, name, xs, floor_tiny, |i, r| rel_expm1_over_x(a(i, 0)) * r[0].abs() + FLT_MIN));
        f.push(scalar_family(F::Expm1, name, xs, floor_tiny, |i, r| rel_expm1(a(i, 0)) * r[0].abs() + FLT_MIN));
    }
    // mulsign: a sign-bit operation, exact (bound 0); ±0 signs count as ±1.
    let mut ins = Vec::new();
    for x in [0.0, -0.0, 1e-37, -2.5, 3e38, -1.0] {
        for s in [0.0, -0.0, 1e-30, -1e-30, 1.0, -7.0, 3e38, -3e38] {
            ins.push(rec(&[x, s]));
        }
    }
    f.push(Family { function: F::Mulsign, name: "magnitudes 0…3e38, signs ±0…±3e38", inputs: ins, checks: vec![check("value", 0..1, floor_fmin, |_, _| 0.0)] });
    // erf: series branch relative (floor 1e-30); A&S branch absolute (floor 1: the approximation
    // is absolute by construction, and |erf| ≥ 0.52 there).
    let mut xs = lin(-0.4999, 0.4999, 160);
    xs.extend([1e-30, -1e-20, 1e-7, -1e-4]);
    f.push(scalar_family(F::Erf, "series |x| < 1/2", &xs, floor_tiny, |i, _| abs_erf(a(i, 0))));
    let mut xs = lin(0.5, 6.0, 220);
    xs.extend(lin(-6.0, -0.5, 220));
    xs.extend([10.0, 100.0, 1e10, -3e38]);
    f.push(scalar_family(F::Erf, "A&S branch |x| >= 1/2", &xs, floor_unit, |i, _| abs_erf(a(i, 0))));
    // safe_normalize: v/m (2.5 ULP per component), dot (≤ 0.75 ULP on the norm), inverseSqrt
    // (2 ULP), product (½ ULP): ‖error‖ ≤ 5.75 ULP of the unit result → 6 ULP. Fallback: exact.
    let mut unit = Vec::new();
    let mut scaled = Vec::new();
    for ax in axes() {
        for (j, t) in MID_ANGLES.iter().chain(&NEAR_ANGLES).enumerate() {
            let w = tilt(ax, *t, 0.3 + j as f64);
            unit.push(rec(&[w.x, w.y, w.z, 0.0, 0.0, 1.0]));
            for m in [2e-37, 1e-20, 1e-3, 7.0, 1e20, 1e37] {
                // components below FLT_MIN would be flushed to zero on some GPUs: keep them ≥ 0
                // or ≥ 1e-37 in magnitude
                let v = w * m;
                let v = DVec3::select(v.abs().cmplt(DVec3::splat(1.2e-37)), DVec3::ZERO, v);
                scaled.push(rec(&[v.x, v.y, v.z, 0.0, 0.0, 1.0]));
            }
        }
    }
    let fallback = vec![rec(&[0.0, 0.0, 0.0, 0.0, 1.0, 0.0]), rec(&[-0.0, 0.0, 0.0, 0.6, 0.8, 0.0])];
    for (name, ins) in [("unit vectors", unit), ("magnitudes 1e-37…1e37", scaled), ("zero vector (fallback)", fallback)] {
        f.push(Family { function: F::SafeNormalize, name, inputs: ins, checks: vec![check("vector", 0..3, floor_unit, |_, _| 6.0 * ULP)] });
    }
    // orthonormal_basis: a = −1/(s + z.z) (s + z.z ≥ 1: no cancellation; 3 ULP), b = z.x·z.y·a
    // (4 ULP, |b| ≤ ½), x = (1 + s·z.x²·a, s·b, −s·z.x): the first component is a sum of terms ≤ 1
    // (5.5 ULP absolute), the second 2 ULP absolute → ‖error‖ ≤ 6 ULP; same for y; z is copied.
    let mut ins = Vec::new();
    for ax in axes().into_iter().chain([-DVec3::Z, DVec3::X]) {
        for (j, t) in NEAR_ANGLES.iter().chain(&MID_ANGLES).chain(&FAR_ANGLES).enumerate() {
            for phi in [0.0, 1.1, 2.0, 3.5, 5.0] {
                let w = tilt(ax, *t, phi + j as f64);
                ins.push(rec(&[w.x, w.y, w.z]));
            }
        }
    }
    for t in [PI / 2.0 - 1e-7, PI / 2.0, PI / 2.0 + 1e-7] {
        for phi in lin(0.0, 6.0, 12) {
            let w = DVec3::new(t.sin() * phi.cos(), t.sin() * phi.sin(), t.cos());
            ins.push(rec(&[w.x, w.y, w.z]));
        }
    }
    f.push(Family {
        function: F::OrthonormalBasis,
        name: "z over the sphere, poles ±1e-7, seam z.z = 0",
        inputs: ins,
        checks: vec![
            check("x", 0..3, floor_unit, |_, _| 6.0 * ULP),
            check("y", 3..6, floor_unit, |_, _| 6.0 * ULP),
            check("z", 6..9, floor_unit, |_, _| 0.0),
        ],
    });
}

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
fn bound_sg_product_integral(i: &Input, r: &Output64) -> f64 {
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
fn clamped_cosine_abs_bound(xi: DVec3, lambda: f64, n: DVec3, value: f64) -> f64 {
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

fn sg_families(f: &mut Vec<Family>) {
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
fn toksvig_sharpness_bound(r: f64, rel_r: f64, lambda: f64) -> f64 {
    let (lo, hi) = toksvig_interval(r, rel_r);
    (hi - lambda).max(lambda - lo) + 3.0 * ULP * lambda + FLT_MIN
}
fn toksvig_amplitude_bound(r: f64, rel_r: f64, lambda: f64, amplitude: f64) -> f64 {
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

fn lobe_families(f: &mut Vec<Family>) {
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
fn frame_residuals(o: &[f64]) -> Vec<f64> {
    let v = |k: usize| DVec3::new(o[k], o[k + 1], o[k + 2]);
    let (x, y, z) = (v(0), v(4), v(8));
    vec![x.dot(y), y.dot(z), z.dot(x), x.length_squared() - 1.0, y.length_squared() - 1.0, z.length_squared() - 1.0]
}

fn bound_ggx_lobe_asg(i: &Input, r: &Output64, slots: Range<usize>, c0_abs: f64, c0_rel: f64) -> f64 {
    let norm = slots.clone().map(|j| r[j] * r[j]).sum::<f64>().sqrt();
    perturbation(F::GgxLobeAsg, i, slots, 4.0, &[0, 3]) + c0_abs * ULP + c0_rel * ULP * norm
}

fn asg_families(f: &mut Vec<Family>) {
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

/// ggx_d(n·h, ‖n×h‖², α) = α²/(π t²), t = α²(n·h)² + ‖n×h‖²: both terms ≥ 0 (the stable form; no
/// 1 − cos² cancellation), t ≤ 2 ULP, t² 4.5, π· 5, α² ½ and the division 2.5 → 8 ULP.
fn bound_ggx_d(_: &Input, r: &Output64) -> f64 {
    8.0 * ULP * r[0] + FLT_MIN
}

/// ggx_smith_lambda(cos θ, α): c² (½), 1 − c² whose condition number is c²/(1 − c²) with respect to
/// the rounding of c² (it is the input cos θ that fixes sin²θ; near normal incidence Λ ≈ 0 and G2 is
/// unaffected), /c² (2.5), α²· (1): tan term ≤ (4 + ½·c²/(1 − c²)) ULP; Λ = t/(2(1 + √(1 + t))) has
/// d ln Λ/d ln t ≤ 1 and adds 1 + t (½), sqrt (4.5), 1 + (½), the division (2.5) → 8 ULP.
fn rel_smith_lambda(c: f64, alpha: f64) -> f64 {
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

fn ggx_families(f: &mut Vec<Family>) {
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

/// vsgl_lobe_from_moments: ξ̄ = Σ/W (2.5 ULP per component) then the Toksvig inverse, so r = ‖ξ̄‖
/// errs by 2.5 + 5.25 ULP and λ, the amplitude W/A(λ) (+½ ULP) follow as in
/// sg_from_toksvig_mean_direction; the axis errs by 2.5 + 6 ULP. No power (W ≤ 0): exact zeros.
fn bound_lobe_from_moments(i: &Input, r: &Output64, part: usize) -> f64 {
    let w = a(i, 0);
    if w.is_nan() || w <= 0.0 {
        return 0.0;
    }
    let rr = (v3(i, 1) / w).length();
    match part {
        0 => 8.5 * ULP,
        1 => toksvig_sharpness_bound(rr, 7.75 * ULP, r[3]),
        _ => {
            let amp = if r[4] >= FLT_MAX { r[4] } else { r[4] / w };
            w * toksvig_amplitude_bound(rr, 7.75 * ULP, r[3], amp) + 0.5 * ULP * r[4]
        }
    }
}

/// vsgl_position_from_moments: 1/W (2.5) then products (½): the mean and M₂ = Σw‖y‖²/W err by 3 ULP
/// (relative); σ² = M₂ − ‖μ‖² errs by ≤ 3.5·M₂ + 7.5·‖μ‖² ≤ 11 ULP × M₂ (absolute), i.e. its
/// condition number is M₂/σ², bounded by 1e6 through the VSGL_VARIANCE_MIN_FRACTION clamp (whose
/// own value errs by 3.5 ULP). This is why positions must be relative to a local origin: M₂/σ² is
/// (distance to the local origin / cluster radius)², 1e14 for a 1 cm cluster 1e5 m from the world
/// origin.
fn bound_position_variance(i: &Input, r: &Output64) -> f64 {
    let w = a(i, 0);
    if w.is_nan() || w <= 0.0 {
        return 0.0;
    }
    let m2 = (a(i, 4) / w).max(0.0);
    11.0 * ULP * m2 + 3.5 * ULP * r[3] + FLT_MIN
}

/// vsgl_incoming_radiance: t = μ − y_p (½ ULP), d² (1.5), the σ² clamp d²/1e9 (3), λσ = d²/σ² (2.5),
/// ξμ = normalize(t) (6), sg_product of (−ξv, λv) and (ξμ, λσ): the log-amplitude's 10.25 ULP, exp's
/// 2|ℓ| ULP; c = 20 ULP per input (the longest chain, on ℓ). c₀: the coefficient c_v/(2πσ²) (3.5) and
/// exp's 3 ULP for the amplitude, 6 ULP absolute for the axis, 5.5 ULP for λ_in. Condition numbers:
/// the product's (λv + λσ)/λ_in (a lobe pointing away from the shading point), |ℓ|, and
/// ‖μ‖/‖μ − y_p‖ (the perturbation moves μ and y_p by ULPs of their own size; the GPU's t is in fact
/// rounded relative to itself, so this part is conservative).
fn bound_incoming(i: &Input, r: &Output64, slots: Range<usize>, c0_abs: f64, c0_rel: f64) -> f64 {
    let norm = slots.clone().map(|j| r[j] * r[j]).sum::<f64>().sqrt();
    // exp(ℓ) may flush to 0 before it is multiplied by the coefficient c_v/(2πσ²)
    let flush = if slots.start == 4 { FLT_MIN * (a(i, 4) / (2.0 * PI * a(i, 8).max(FLT_MIN))).min(FLT_MAX) } else { 0.0 };
    perturbation(F::VsglIncomingRadiance, i, slots, 20.0, &[0, 5, 9]) + c0_abs * ULP + c0_rel * ULP * norm + flush + FLT_MIN
}
fn floor_incoming_amplitude(i: &Input, _: &Output64) -> f64 {
    let to_mean = v3(i, 5) - v3(i, 9);
    let var = a(i, 8).max(to_mean.length_squared() / oracle::SG_SHARPNESS_MAX).max(FLT_MIN);
    fl(1e-30 * a(i, 4) / (2.0 * PI * var))
}

/// Radiance SG inputs: slots 0–4 (axis, sharpness, amplitude c_in), normal 5–7.
fn radiance_parts(i: &Input) -> (DVec3, f64, f64, DVec3) {
    (v3(i, 0), a(i, 3), a(i, 4), v3(i, 5))
}
/// vsgl_diffuse = c·(1/π)·A(λ)·max(ξ·n, 0): A's bound, 1/π (½) and three products (1.5); the cosine
/// errs by 1.5 ULP·Σ|ξᵢnᵢ| absolute (grazing lobes: condition Σ|ξᵢnᵢ|/(ξ·n)), which also covers a
/// flipped max(·, 0) decision.
fn bound_vsgl_diffuse(i: &Input, r: &Output64) -> f64 {
    let (xi, lambda, c, n) = radiance_parts(i);
    r[0] * (rel_sg_integral(lambda) + 2.0 * ULP) + c / PI * oracle::sg_integral(lambda) * 1.5 * ULP * dot_scale(xi, n) + FLT_MIN
}
/// vsgl_diffuse_approx: the same with 2π/max(λ, ½) (3 ULP).
fn bound_vsgl_diffuse_approx(i: &Input, r: &Output64) -> f64 {
    let (xi, lambda, c, n) = radiance_parts(i);
    r[0] * 5.0 * ULP + c / PI * oracle::sg_integral_approx(lambda) * 1.5 * ULP * dot_scale(xi, n) + FLT_MIN
}
/// vsgl_diffuse_accurate = c/π·sg_clamped_cosine_integral: that bound × c/π, + 1.5 ULP.
fn bound_vsgl_diffuse_accurate(i: &Input, r: &Output64) -> f64 {
    let (xi, lambda, c, n) = radiance_parts(i);
    let value = r[0] * PI / c.max(FLT_MIN);
    c / PI * clamped_cosine_abs_bound(xi, lambda, n, value) + 1.5 * ULP * r[0]
}
/// vsgl_diffuse_sg_product = c·(1/A(λd))·sg_product_integral(ξ, λ, n, λd): that bound × c/A(λd), plus
/// 1/A(λd) (A's bound + 2.5 + ½ for the constant) and the products (1).
fn bound_vsgl_diffuse_sg_product(i: &Input, r: &Output64) -> f64 {
    let (xi, lambda, c, n) = radiance_parts(i);
    let ld = oracle::LAMBERT_LOBE_SG_SHARPNESS;
    let amp = 1.0 / oracle::sg_integral(ld);
    let inner = rec(&[xi.x, xi.y, xi.z, lambda, n.x, n.y, n.z, ld]);
    let pi_value = F::SgProductIntegral.oracle(&inner);
    c * amp * bound_sg_product_integral(&inner, &pi_value) + r[0] * (rel_sg_integral(ld) + 4.0 * ULP)
}
/// vsgl_specular: ggx_lobe_asg (4 ULP), G2 (Smith Λ's 8 ULP through α), the convolved bandwidths
/// (3.5) and exp (2): c = 10 ULP per input; c₀ = 3 (exp) + 10 (two inverseSqrt(1 + ν/η)) + 3.5 (G2's
/// sums and division) ≈ 16. Condition numbers: grazing n·l and n·v (G2 and the frame), the
/// sharpness of the convolved ASG times the frame's absolute error, |exponent|.
fn bound_vsgl_specular(i: &Input, r: &Output64) -> f64 {
    perturbation(F::VsglSpecular, i, 0..1, 10.0, &[0, 5, 8]) + 16.0 * ULP * r[0] + FLT_MIN * a(i, 4)
}

fn vsgl_families(f: &mut Vec<Family>) {
    // vsgl_lobe_from_moments: single lobes and mixtures × powers 1e-8…1e8; zero power.
    let (mut broad, mut sharp, mut zero) = (Vec::new(), Vec::new(), Vec::new());
    for ax in axes() {
        for &w in &INTENSITIES[1..] {
            for &l in &SHARPNESS {
                let m = w * oracle::sg_toksvig_mean_direction(ax, l);
                (if l <= 1e3 { &mut broad } else { &mut sharp }).push(rec(&[w, m.x, m.y, m.z]));
            }
            let m = w * 0.5 * (oracle::sg_toksvig_mean_direction(ax, 100.0) + oracle::sg_toksvig_mean_direction(tilt(ax, 0.3, 2.0), 10.0));
            broad.push(rec(&[w, m.x, m.y, m.z]));
        }
        zero.push(rec(&[0.0, 0.0, 0.0, 0.0]));
        zero.push(rec(&[0.0, ax.x, ax.y, ax.z]));
        zero.push(rec(&[-1.0, ax.x, ax.y, ax.z]));
    }
    let lobe_checks = || {
        vec![
            check("axis", 0..3, floor_unit, |i, r| bound_lobe_from_moments(i, r, 0)),
            check("sharpness", 3..4, floor_tiny, |i, r| bound_lobe_from_moments(i, r, 1)),
            check("amplitude", 4..5, floor_tiny, |i, r| bound_lobe_from_moments(i, r, 2)),
        ]
    };
    for (name, ins) in [("λ <= 1e3, power 1e-8…1e8", broad), ("λ > 1e3 (Toksvig clamp), power 1e-8…1e8", sharp), ("zero power", zero)] {
        f.push(Family { function: F::VsglLobeFromMoments, name, inputs: ins, checks: lobe_checks() });
    }
    // vsgl_position_from_moments: VPL clusters summed in f32 as a GPU would, relative to a local
    // origin (the light) — near it, and 1e5 m from the world origin — and degenerate clusters.
    let mut rng = SplitMix64(0x5eed);
    let (mut near, mut far, mut degenerate) = (Vec::new(), Vec::new(), Vec::new());
    let world = DVec3::new(1e5, -1e5, 1e5);
    for &dist in &[0.0, 0.1, 1.0, 10.0, 100.0] {
        for &radius_fraction in &[1e-6, 1e-4, 1e-2, 0.3, 1.0] {
            for &power in &INTENSITIES[1..] {
                let light = world + dist * rng.unit_vector();
                let radius = radius_fraction * dist.max(1.0);
                let (mut w, mut sy, mut sy2) = (0f32, glam::Vec3::ZERO, 0f32);
                for _ in 0..64 {
                    let p = world + radius * rng.unit_vector() * rng.next_f64().sqrt();
                    let y = (p - light).as_vec3(); // position relative to the local origin, in f32
                    let pw = (power * (0.5 + rng.next_f64())) as f32;
                    w += pw;
                    sy += pw * y;
                    sy2 += pw * y.length_squared();
                }
                let r = rec(&[w as f64, sy.x as f64, sy.y as f64, sy.z as f64, sy2 as f64]);
                (if dist <= 10.0 * radius { &mut near } else { &mut far }).push(r);
            }
        }
    }
    for &power in &INTENSITIES[1..] {
        for y in [DVec3::ZERO, DVec3::new(2.0, 0.0, 0.0), DVec3::new(1e-3, -3.0, 7.0)] {
            // every VPL at one point: σ² = 0 exactly (up to the f32 moments)
            let (w, s1, s2) = (64.0 * power, 64.0 * power * y, 64.0 * power * y.length_squared());
            degenerate.push(rec(&[w, s1.x, s1.y, s1.z, s2]));
        }
    }
    degenerate.push(rec(&[0.0, 0.0, 0.0, 0.0, 0.0]));
    degenerate.push(rec(&[0.0, 1.0, 2.0, 3.0, 4.0]));
    let pos_checks = || {
        vec![
            check("mean", 0..3, floor_tiny, |i, r| if a(i, 0) > 0.0 { 3.0 * ULP * out3(r, 0).length() } else { 0.0 }),
            check("variance", 3..4, floor_tiny, bound_position_variance),
        ]
    };
    for (name, ins) in [
        ("clusters within 10 radii of the local origin", near),
        ("clusters 1e5 m from the world origin, local origin 0.1…100 m away", far),
        ("all VPLs at one point (σ² = 0), zero power", degenerate),
    ] {
        f.push(Family { function: F::VsglPositionFromMoments, name, inputs: ins, checks: pos_checks() });
    }
    // vsgl_incoming_radiance: σ²/d² 0, 1e-12…1e3 × λv × lobe directions × intensities; the shading
    // point at the mean; positions from world coordinates 1e5 m away, relative to the light.
    let (mut toward, mut away, mut at_mean, mut offset) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let ratios = [0.0, 1e-12, 1e-9, 1e-6, 1e-3, 1.0, 1e3];
    let lambdas_v = [0.0, 1e-6, 0.5, 10.0, 1e3, 1e5];
    for (k, &mean) in [DVec3::new(0.5, -0.3, 2.0), DVec3::new(-3.0, 1.0, 0.2)].iter().enumerate() {
        let y_p = DVec3::new(0.1, 0.2, 0.0);
        let to_p = (y_p - mean).normalize(); // the VSGL lobe emits toward the shading point along +to_p
        for &ratio in &ratios {
            let var = ratio * (mean - y_p).length_squared();
            for &lv in &lambdas_v {
                for (j, t) in [0.0, 1e-7, 1e-3, 0.5, 2.0, PI].iter().enumerate() {
                    let axis = tilt(to_p, *t, 0.7 * (j + k) as f64);
                    for &c in &INTENSITIES {
                        let r = rec(&[axis.x, axis.y, axis.z, lv, c, mean.x, mean.y, mean.z, var, y_p.x, y_p.y, y_p.z]);
                        (if *t <= 0.5 { &mut toward } else { &mut away }).push(r);
                    }
                }
            }
        }
    }
    for &var in &[0.0, 1e-6, 1.0] {
        for &lv in &lambdas_v {
            for &c in &[0.0, 1.0, 1e8] {
                let m = DVec3::new(0.4, 1.5, -0.7);
                at_mean.push(rec(&[0.0, 0.0, 1.0, lv, c, m.x, m.y, m.z, var, m.x, m.y, m.z]));
            }
        }
    }
    let light = world + DVec3::new(0.3, 2.5, -0.4);
    for &(mean_w, p_w) in &[
        (world + DVec3::new(1.0, 0.0, 0.5), world + DVec3::new(-0.5, 0.1, 0.2)),
        (world + DVec3::new(0.01, 0.0, 0.0), world + DVec3::new(0.0, 0.01, 0.0)),
        (world + DVec3::new(30.0, -5.0, 2.0), world + DVec3::new(-2.0, 0.0, 0.0)),
    ] {
        let (mean, y_p) = (mean_w - light, p_w - light); // relative to the local origin, in f64
        for &ratio in &ratios {
            let var = ratio * (mean - y_p).length_squared();
            for &lv in &lambdas_v {
                let axis = tilt((y_p - mean).normalize(), 0.3, 1.0);
                for &c in &INTENSITIES {
                    offset.push(rec(&[axis.x, axis.y, axis.z, lv, c, mean.x, mean.y, mean.z, var, y_p.x, y_p.y, y_p.z]));
                }
            }
        }
    }
    let incoming_checks = || {
        vec![
            check("axis", 0..3, floor_unit, |i, r| bound_incoming(i, r, 0..3, 6.0, 0.0)),
            check("sharpness", 3..4, floor_tiny, |i, r| bound_incoming(i, r, 3..4, 0.0, 5.5)),
            check("amplitude", 4..5, floor_incoming_amplitude, |i, r| bound_incoming(i, r, 4..5, 0.0, 6.5)),
        ]
    };
    for (name, ins) in [
        ("lobe toward y_p; σ²/d² 0, 1e-12…1e3; λv 0…1e5; I 0, 1e-8…1e8", toward),
        ("lobe away from y_p (the SG product cancels), same grids", away),
        ("shading point at the mean (d = 0)", at_mean),
        ("scene 1e5 m from the origin, light as local origin", offset),
    ] {
        f.push(Family { function: F::VsglIncomingRadiance, name, inputs: ins, checks: incoming_checks() });
    }
    // Diffuse and specular shading from a radiance SG: λ_in × lobe/normal angle × c_in.
    let shade = |cosines: &[f64]| {
        let mut ins = Vec::new();
        for n in axes() {
            for &l in SHARPNESS.iter().step_by(2).chain(&[1e9]) {
                for (j, &c) in cosines.iter().enumerate() {
                    let xi = tilt(n, c.clamp(-1.0, 1.0).acos(), 0.4 + j as f64);
                    for &amp in &[0.0, 1e-8, 1.0, 1e8, 1e20] {
                        ins.push(rec(&[xi.x, xi.y, xi.z, l, amp, n.x, n.y, n.z]));
                    }
                }
            }
        }
        ins
    };
    let above = COSINES.to_vec();
    let grazing: Vec<f64> = GRAZING_COSINES.iter().flat_map(|&c| [c, -c]).collect();
    let below: Vec<f64> = [-0.01, -0.3, -1.0].to_vec();
    // Floors: relative (1e-30 of the scale c·A(λ)/π) above the horizon; the scale itself at grazing
    // and below, where the cosine is known only to ±1.5 ULP absolute.
    let relative: FloorFn = |i, _| fl(1e-30 * a(i, 4) * oracle::sg_integral(a(i, 3)) / PI);
    let absolute: FloorFn = |i, _| fl(a(i, 4) * oracle::sg_integral(a(i, 3)) / PI);
    for (name, cos, scale) in [("ξ·n 0.01…1", above, relative), ("grazing |ξ·n| <= 3e-3 (incl. 0)", grazing, absolute), ("ξ·n < 0", below, absolute)] {
        let ins = shade(&cos);
        f.push(Family { function: F::VsglDiffuse, name, inputs: ins.clone(), checks: vec![check("value", 0..1, scale, bound_vsgl_diffuse)] });
        f.push(Family {
            function: F::VsglDiffuseApprox,
            name,
            inputs: ins.clone(),
            checks: vec![check("value", 0..1, scale, bound_vsgl_diffuse_approx)],
        });
        f.push(Family {
            function: F::VsglDiffuseAccurate,
            name,
            inputs: ins.clone(),
            checks: vec![check("value", 0..1, absolute, bound_vsgl_diffuse_accurate)],
        });
        f.push(Family {
            function: F::VsglDiffuseSgProduct,
            name,
            inputs: ins,
            checks: vec![check("value", 0..1, scale, bound_vsgl_diffuse_sg_product)],
        });
    }
    // vsgl_specular: views normal…grazing × light lobes at the mirror direction and off it.
    let (mut normal_view, mut oblique, mut grazing) = (Vec::new(), Vec::new(), Vec::new());
    for n in axes() {
        for (j, &t) in NEAR_ANGLES.iter().chain(&[0.3, 1.0, 1.4]).chain(&GRAZING_COSINES.map(f64::acos)).enumerate() {
            let w_o = tilt(n, t, 0.6 * j as f64 + 0.2);
            let mirror = 2.0 * w_o.dot(n) * n - w_o;
            for al in alphas().into_iter().step_by(2) {
                for &l in &[1e-6, 1.0, 1e2, 1e4, 1e6, 1e9] {
                    for off in [0.0, 1e-7, 0.5 * al, 2.0 * al] {
                        let xi = tilt(mirror, off, 1.0 + j as f64);
                        let r = rec(&[xi.x, xi.y, xi.z, l, 1.0, n.x, n.y, n.z, w_o.x, w_o.y, w_o.z, al]);
                        if t <= 1e-3 {
                            normal_view.push(r);
                        } else if t < 1.5 {
                            oblique.push(r);
                        } else {
                            grazing.push(r);
                        }
                    }
                }
            }
        }
    }
    for (name, ins) in [
        ("normal view (θo 0…1e-3 rad)", normal_view),
        ("oblique view, light at and off the mirror direction", oblique),
        ("grazing view n·ω_o <= 3e-3 (incl. 0)", grazing),
    ] {
        f.push(Family {
            function: F::VsglSpecular,
            name,
            inputs: ins,
            checks: vec![check("value", 0..1, |i, _| fl(1e-30 * a(i, 4)), bound_vsgl_specular)],
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::verify::harness::OUTPUT_WIDTH;

    /// The oracle's own output, rounded to f32, as a stand-in for a perfect GPU.
    fn perfect(family: &Family) -> Vec<Output> {
        family
            .inputs
            .iter()
            .map(|i| {
                let r = family.function.oracle(i);
                let mut o = [0.0f32; OUTPUT_WIDTH];
                for (slot, x) in o.iter_mut().zip(r) {
                    *slot = x as f32;
                }
                o
            })
            .collect()
    }

    #[test]
    fn every_function_has_families_and_every_output_is_checked() {
        let fams = families();
        for f in F::ALL {
            let mine: Vec<&Family> = fams.iter().filter(|x| x.function == f).collect();
            assert!(!mine.is_empty(), "{} has no family", f.name());
            for fam in mine {
                let mut covered = vec![false; f.output_len()];
                for c in &fam.checks {
                    for s in c.slots.clone() {
                        covered[s] = true;
                    }
                }
                assert!(covered.iter().all(|&c| c), "{} / {}: not every output slot is checked", f.name(), fam.name);
                assert!(!fam.inputs.is_empty(), "{} / {} is empty", f.name(), fam.name);
            }
        }
    }

    /// The required extremes are in the grids.
    #[test]
    fn grids_contain_the_issue_extremes() {
        assert!(SHARPNESS.contains(&1e-6) && SHARPNESS.contains(&1e8) && SHARPNESS.contains(&0.0));
        assert!(ROUGHNESS.contains(&1e-4) && ROUGHNESS.contains(&1.0));
        assert!(GRAZING_COSINES.contains(&1e-6) && GRAZING_COSINES.contains(&0.0));
        assert!(NEAR_ANGLES.contains(&0.0) && NEAR_ANGLES.contains(&1e-7) && FAR_ANGLES.contains(&PI));
        assert!(INTENSITIES.contains(&1e-8) && INTENSITIES.contains(&1e8) && INTENSITIES.contains(&0.0));
        let fams = families();
        let names: Vec<&str> = fams.iter().map(|f| f.name).collect();
        assert!(names.iter().any(|n| n.contains("1e5 m")), "positions offset 1e5 m");
        assert!(names.iter().any(|n| n.contains("σ² = 0")), "zero variance");
        assert!(names.iter().any(|n| n.contains("zero power")), "zero power");
        assert!(names.iter().any(|n| n.contains("1e-12")), "variance 1e-12 of d²");
    }

    /// A GPU that returned the oracle's values rounded to f32 passes every row (the bounds cover
    /// one final rounding), and moving one output by far more than its bound fails that row.
    #[test]
    fn scoring_passes_exact_and_fails_wrong_outputs() {
        for fam in families() {
            let out = perfect(&fam);
            for row in score(&fam, &out, 1.0) {
                assert!(row.pass, "{} / {}: {:?}", row.function, row.family, row.worst_case);
            }
        }
        let fam = families().into_iter().find(|f| f.function == F::SgIntegral).expect("sg_integral family");
        let mut out = perfect(&fam);
        out[3][0] *= 1.001;
        let rows = score(&fam, &out, 1.0);
        assert!(!rows[0].pass && rows[0].max_rel_error > 9e-4, "{:?}", rows[0]);
        out[3][0] = f32::NAN;
        let rows = score(&fam, &out, 1.0);
        assert!(!rows[0].pass && rows[0].nonfinite == 1);
    }
}
