// Numerically stable scalar primitives shared by the SG code: expm1, expm1_over_x, erf,
// mulsign, safe_normalize and an orthonormal basis. Every function is pure (arguments in,
// value out) so a test harness can call it from a compute shader.
// The f64 twin of each function is in crates/vsgl-core/src/verify/oracle/math.rs.
#include "common/constants.wgsl"

// Largest argument given to exp(): exp(88) = 1.65e38 < FLT_MAX, so nothing overflows to Inf
// (WGSL leaves overflow to Inf implementation-defined).
const EXP_ARG_MAX: f32 = 88.0;

// Below this |x|, expm1 and expm1_over_x use their Taylor series. There the truncation error
// of the 9-term series, |x|^9/10! = 5.4e-10 relative at |x| = 0.5, is below f32 rounding, while
// exp(x) − 1 would cancel: WGSL allows exp() an error of 3 + 2|x| ULP, i.e. ~5e-7 absolute
// near 1, which is ~1e-6 relative at |x| = 0.5 and grows as 1/|x| below it.
const EXPM1_SERIES_RADIUS: f32 = 0.5;

// Below this |x|, erf uses its Maclaurin series (relative error x^12/9360 = 2.6e-8 at 0.5);
// above it the Abramowitz–Stegun rational form, which is accurate in absolute terms only
// (it computes erf as 1 − small, so it loses relative accuracy as x → 0).
const ERF_SERIES_RADIUS: f32 = 0.5;
const TWO_OVER_SQRT_PI: f32 = 1.12837916709551; // 2/√π

// Abramowitz & Stegun 1964, Handbook of Mathematical Functions, Eq. 7.1.26:
// erf(x) = 1 − (a1 t + a2 t² + a3 t³ + a4 t⁴ + a5 t⁵) e^{−x²}, t = 1/(1 + p x), x ≥ 0,
// |error| ≤ 1.5e-7. The constants are the published ones.
const ERF_AS_P: f32 = 0.3275911;
const ERF_AS_A1: f32 = 0.254829592;
const ERF_AS_A2: f32 = -0.284496736;
const ERF_AS_A3: f32 = 1.421413741;
const ERF_AS_A4: f32 = -1.453152027;
const ERF_AS_A5: f32 = 1.061405429;

// (e^x − 1)/x, equal to 1 at x = 0.
// Small |x|: Taylor series Σ x^k/(k+1)! (Higham 2002, "Accuracy and Stability of Numerical
// Algorithms", §1.14.1, explains why e^x − 1 must not be formed there). We do not use
// Kahan's (u − 1)·x/log(u) trick: it needs a log accurate to a few ULP near 1, and WGSL only
// promises an absolute error of 2^-21 for log there.
fn expm1_over_x(x: f32) -> f32 {
    if (abs(x) < EXPM1_SERIES_RADIUS) {
        return 1.0 + x * (1.0 / 2.0 + x * (1.0 / 6.0 + x * (1.0 / 24.0 + x * (1.0 / 120.0
            + x * (1.0 / 720.0 + x * (1.0 / 5040.0 + x * (1.0 / 40320.0 + x * (1.0 / 362880.0))))))));
    }
    return (exp(min(x, EXP_ARG_MAX)) - 1.0) / x;
}

// e^x − 1 without cancellation for small |x| (see expm1_over_x).
fn expm1(x: f32) -> f32 {
    if (abs(x) < EXPM1_SERIES_RADIUS) {
        return x * expm1_over_x(x);
    }
    return exp(min(x, EXP_ARG_MAX)) - 1.0;
}

// x with its sign flipped where s is negative (−0 counts as negative): x·sign(s) with
// sign(0) = ±1 instead of 0, as copysign-style code needs. Bit operations only.
fn mulsign(x: f32, s: f32) -> f32 {
    return bitcast<f32>(bitcast<u32>(x) ^ (bitcast<u32>(s) & 0x80000000u));
}

// Error function. |x| < ERF_SERIES_RADIUS: Maclaurin series
// erf(x) = 2/√π Σ (−1)^k x^{2k+1} / (k! (2k+1)), six terms; otherwise Abramowitz & Stegun
// 7.1.26 (constants above), extended to x < 0 by oddness.
fn erf(x: f32) -> f32 {
    let ax = abs(x);
    if (ax < ERF_SERIES_RADIUS) {
        let x2 = x * x;
        return TWO_OVER_SQRT_PI * x * (1.0 + x2 * (-1.0 / 3.0 + x2 * (1.0 / 10.0 + x2 * (-1.0 / 42.0
            + x2 * (1.0 / 216.0 + x2 * (-1.0 / 1320.0))))));
    }
    let t = 1.0 / (1.0 + ERF_AS_P * ax);
    let poly = t * (ERF_AS_A1 + t * (ERF_AS_A2 + t * (ERF_AS_A3 + t * (ERF_AS_A4 + t * ERF_AS_A5))));
    return mulsign(1.0 - poly * exp(-ax * ax), x);
}

// v/‖v‖, or `fallback` when v is zero (or too small to have a direction in f32). v is first
// divided by its largest component so that tiny or huge vectors (e.g. λ1ξ1 + λ2ξ2 with
// λ ~ 1e-30 or 1e9) neither underflow nor overflow in dot(v, v).
fn safe_normalize(v: vec3f, fallback: vec3f) -> vec3f {
    let m = max(max(abs(v.x), abs(v.y)), abs(v.z));
    if (!(m >= FLT_MIN)) {
        return fallback;
    }
    let u = v / m;
    return u * inverseSqrt(dot(u, u));
}

// Orthonormal basis (columns x, y, z) around the unit vector z, continuous except across
// z.z = 0 where the sign flips [Duff et al. 2017, "Building an Orthonormal Basis, Revisited",
// JCGT 6(1), Listing 3]. No normalization, no branch, exact for z = ±e_z.
fn orthonormal_basis(z: vec3f) -> mat3x3f {
    let s = mulsign(1.0, z.z);
    let a = -1.0 / (s + z.z);
    let b = z.x * z.y * a;
    let x = vec3f(1.0 + s * z.x * z.x * a, s * b, -s * z.x);
    let y = vec3f(b, s + z.y * z.y * a, -z.y);
    return mat3x3f(x, y, z);
}
