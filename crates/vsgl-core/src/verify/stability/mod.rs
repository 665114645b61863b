//! The stability suite: every WGSL function of `wgsl/common/{math,sg,ggx,vsgl}.wgsl`, evaluated in
//! f32 on the GPU through [`crate::verify::harness`] and in f64 by its oracle twin on the *same* f32
//! inputs, over case families that include the extremes (sharpness 1e-6…1e9,
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
//! [`run`] returns the table; `crates/vsgl-core/tests/stability.rs` asserts that every row passes, and
//! `python -m vsgl stability` prints it. docs/numerics.md ("Stability suite") lists every bound
//! with its justification and the measured errors.
//!
//! Files: `grids.rs` (input records and case grids), `error_model.rs` (the error-model building
//! blocks and the floors), and the families by topic, in the order [`families`] runs them:
//! `math.rs`, `sg.rs`, `lobes.rs`, `asg.rs`, `ggx.rs`, `vsgl.rs`.

use crate::error::Result;
use crate::gpu::Gpu;
use crate::verify::harness::{Harness, HarnessFunction as F, Input, Output, Output64};
use std::ops::Range;

mod asg;
mod error_model;
mod ggx;
mod grids;
mod lobes;
mod math;
mod sg;
mod vsgl;

use asg::asg_families;
use ggx::ggx_families;
use grids::rec;
use lobes::lobe_families;
use math::math_families;
use sg::sg_families;
use vsgl::{tangent_plane_families, vsgl_families};

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
    tangent_plane_families(&mut f);
    f
}

#[cfg(test)]
mod tests {
    use super::grids::{FAR_ANGLES, GRAZING_COSINES, INTENSITIES, NEAR_ANGLES, ROUGHNESS, SHARPNESS};
    use super::*;
    use crate::verify::harness::OUTPUT_WIDTH;
    use std::f64::consts::PI;

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
