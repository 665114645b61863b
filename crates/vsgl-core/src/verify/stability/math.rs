//! Families of `wgsl/common/math.wgsl`: expm1_over_x, expm1, mulsign, erf, safe_normalize,
//! orthonormal_basis.

use super::error_model::{abs_erf, floor_fmin, floor_tiny, floor_unit, rel_expm1, rel_expm1_over_x};
use super::grids::{a, axes, lin, logspace, rec, tilt, FAR_ANGLES, MID_ANGLES, NEAR_ANGLES};
use super::{check, scalar_family, Family, FLT_MIN, ULP};
use crate::verify::harness::HarnessFunction as F;
use glam::DVec3;
use std::f64::consts::PI;

pub(super) fn math_families(f: &mut Vec<Family>) {
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
