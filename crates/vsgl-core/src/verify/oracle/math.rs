//! f64 twins of `wgsl/common/math.wgsl`: accurate values (the WGSL series / rational
//! approximations are checked against these).

use glam::{DMat3, DVec3};

/// Same as `EXP_ARG_MAX` in math.wgsl: arguments of exp() are capped here (exp(88) < f32 max).
pub const EXP_ARG_MAX: f64 = 88.0;
/// Same as `EXPM1_SERIES_RADIUS` in math.wgsl (the WGSL's Taylor branch; not needed in f64).
pub const EXPM1_SERIES_RADIUS: f64 = 0.5;
/// Same as `ERF_SERIES_RADIUS` in math.wgsl (the WGSL's Maclaurin branch).
pub const ERF_SERIES_RADIUS: f64 = 0.5;

/// (e^x − 1)/x, 1 at x = 0. `f64::exp_m1` is accurate to ~1 ULP everywhere, so the quotient is too.
pub fn expm1_over_x(x: f64) -> f64 {
    if x == 0.0 {
        1.0
    } else {
        expm1(x) / x
    }
}

/// e^x − 1 with the same argument cap as the WGSL.
pub fn expm1(x: f64) -> f64 {
    x.min(EXP_ARG_MAX).exp_m1()
}

/// x·sign(s) with sign(±0) = ±1 (sign bit of s).
pub fn mulsign(x: f64, s: f64) -> f64 {
    if s.is_sign_negative() {
        -x
    } else {
        x
    }
}

/// The error function to ~1e-15: erf(x) = 2/√π e^{−x²} Σ_{n≥0} 2ⁿ x^{2n+1} / (1·3·5⋯(2n+1))
/// (Abramowitz & Stegun 7.1.6; all terms positive, so no cancellation), and ±1 for |x| > 6
/// where erfc(6) = 2e-17.
pub fn erf(x: f64) -> f64 {
    let ax = x.abs();
    if ax > 6.0 {
        return mulsign(1.0, x);
    }
    let x2 = ax * ax;
    let mut term = ax;
    let mut sum = ax;
    let mut n = 0.0;
    while term > 1e-17 * sum {
        n += 1.0;
        term *= 2.0 * x2 / (2.0 * n + 1.0);
        sum += term;
    }
    mulsign(std::f64::consts::FRAC_2_SQRT_PI * (-x2).exp() * sum, x)
}

/// v/‖v‖, or `fallback` for the zero vector (and anything whose largest component is below the
/// f32 FLT_MIN that the WGSL uses as its threshold).
pub fn safe_normalize(v: DVec3, fallback: DVec3) -> DVec3 {
    let m = v.abs().max_element();
    // Written so that NaN also takes the fallback.
    if m.is_nan() || m < f32::MIN_POSITIVE as f64 {
        return fallback;
    }
    let u = v / m;
    u / u.length()
}

/// Orthonormal basis (columns x, y, z) around unit z [Duff et al. 2017, JCGT 6(1), Listing 3].
pub fn orthonormal_basis(z: DVec3) -> DMat3 {
    let s = mulsign(1.0, z.z);
    let a = -1.0 / (s + z.z);
    let b = z.x * z.y * a;
    let x = DVec3::new(1.0 + s * z.x * z.x * a, s * b, -s * z.x);
    let y = DVec3::new(b, s + z.y * z.y * a, -z.y);
    DMat3::from_cols(x, y, z)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::verify::oracle::quadrature::integrate_1d;
    use crate::verify::oracle::wgsl_text::{const_value, fractions, function_body};

    #[test]
    fn erf_matches_quadrature() {
        // erf(x) = 2/√π ∫_0^x e^{−t²} dt by composite Gauss–Legendre (exact to ~1e-15 for this
        // entire function). Tolerance 1e-14 absolute: a few ULP of values ≤ 1.
        for i in 0..=120 {
            let x = -6.0 + 0.1 * i as f64;
            let breaks: Vec<f64> = (0..=8).map(|k| x * k as f64 / 8.0).collect();
            let q = if x == 0.0 {
                0.0
            } else {
                std::f64::consts::FRAC_2_SQRT_PI * integrate_1d(|t| (-t * t).exp(), &breaks, 24)
            };
            assert!((erf(x) - q).abs() < 1e-14, "x = {x}: erf {} quadrature {q}", erf(x));
        }
        assert_eq!(erf(7.0), 1.0);
        assert_eq!(erf(-7.0), -1.0);
    }

    /// The WGSL erf, emulated in f64 with the constants and series read from math.wgsl, is within
    /// the Abramowitz–Stegun bound |ε| ≤ 1.5e-7 (plus 2e-8 for f64 vs published-digit effects),
    /// and its series branch is accurate in relative terms (≤ 5e-8 relative below 0.5).
    #[test]
    fn wgsl_erf_algorithm_is_within_published_bound() {
        let c = |n: &str| const_value("common/math.wgsl", n);
        let (p, a1, a2, a3, a4, a5) = (
            c("ERF_AS_P"),
            c("ERF_AS_A1"),
            c("ERF_AS_A2"),
            c("ERF_AS_A3"),
            c("ERF_AS_A4"),
            c("ERF_AS_A5"),
        );
        let series = fractions(&function_body("common/math.wgsl", "erf"));
        assert_eq!(
            series,
            vec![-1.0 / 3.0, 1.0 / 10.0, -1.0 / 42.0, 1.0 / 216.0, -1.0 / 1320.0],
            "erf series in math.wgsl"
        );
        let radius = c("ERF_SERIES_RADIUS");
        let emulated = |x: f64| {
            let ax = x.abs();
            if ax < radius {
                let x2 = x * x;
                let poly = series.iter().rev().fold(0.0, |acc, &k| x2 * (k + acc));
                std::f64::consts::FRAC_2_SQRT_PI * x * (1.0 + poly)
            } else {
                let t = 1.0 / (1.0 + p * ax);
                let poly = t * (a1 + t * (a2 + t * (a3 + t * (a4 + t * a5))));
                mulsign(1.0 - poly * (-ax * ax).exp(), x)
            }
        };
        let mut max_abs: f64 = 0.0;
        let mut max_rel_series: f64 = 0.0;
        for i in 1..=6000 {
            let x = i as f64 * 1e-3;
            let e = (emulated(x) - erf(x)).abs();
            max_abs = max_abs.max(e);
            if x < radius {
                max_rel_series = max_rel_series.max(e / erf(x));
            }
            assert_eq!(emulated(-x), -emulated(x));
        }
        println!("WGSL erf algorithm: max |error| {max_abs:.3e}, series branch max relative error {max_rel_series:.3e}");
        assert!(max_abs <= 1.5e-7 + 2e-8, "A&S 7.1.26 bound exceeded: {max_abs:e}");
        assert!(max_rel_series <= 5e-8, "{max_rel_series:e}");
    }

    /// The Taylor coefficients of the WGSL expm1_over_x are 1/(k+1)!, and the truncation error at
    /// the branch radius is below f32 resolution (≤ 1e-9 relative).
    #[test]
    fn wgsl_expm1_series_coefficients() {
        let coeffs = fractions(&function_body("common/math.wgsl", "expm1_over_x"));
        let expected: Vec<f64> = (2..=9).map(|k| 1.0 / (1..=k).map(|i| i as f64).product::<f64>()).collect();
        assert_eq!(coeffs.len(), expected.len(), "{coeffs:?}");
        for (c, e) in coeffs.iter().zip(&expected) {
            assert!((c - e).abs() <= 1e-16 * e.abs(), "{c} vs {e}");
        }
        let r = EXPM1_SERIES_RADIUS;
        for x in [-r, r] {
            let series = 1.0 + coeffs.iter().rev().fold(0.0, |acc, &k| x * (k + acc));
            let rel = (series - expm1_over_x(x)).abs() / expm1_over_x(x);
            assert!(rel < 1e-9, "x = {x}: truncation {rel:e}");
        }
    }

    #[test]
    fn expm1_forms_are_accurate_and_finite() {
        // Tolerances: a few f64 ULP, against the defining Taylor series for tiny x and against
        // exp(x) − 1 where that does not cancel.
        assert_eq!(expm1_over_x(0.0), 1.0);
        for x in [1e-300, 1e-12, -1e-12] {
            assert!((expm1_over_x(x) - 1.0).abs() < 1e-11);
        }
        for x in [-30.0, -2.0, 2.0, 30.0] {
            assert!((expm1(x) - (x.exp() - 1.0)).abs() <= 4.0 * f64::EPSILON * x.exp().max(1.0));
        }
        assert!(expm1(1e3).is_finite() && expm1_over_x(1e3).is_finite(), "argument cap");
        assert_eq!(expm1(-1e9), -1.0);
    }

    #[test]
    fn mulsign_and_safe_normalize() {
        assert_eq!(mulsign(2.0, -0.0), -2.0);
        assert_eq!(mulsign(2.0, 0.0), 2.0);
        assert_eq!(mulsign(-2.0, -3.0), 2.0);
        let f = DVec3::Z;
        assert_eq!(safe_normalize(DVec3::ZERO, f), f);
        let tiny = DVec3::new(3e-30, 4e-30, 0.0);
        assert!((safe_normalize(tiny, f) - DVec3::new(0.6, 0.8, 0.0)).length() < 1e-15);
        let huge = DVec3::new(3e300, 4e300, 0.0);
        assert!((safe_normalize(huge, f) - DVec3::new(0.6, 0.8, 0.0)).length() < 1e-15);
    }

    #[test]
    fn orthonormal_basis_is_orthonormal() {
        // Tolerance 1e-14: exact in real arithmetic (Duff et al.), a few ULP in f64.
        let dirs = [
            DVec3::Z,
            -DVec3::Z,
            DVec3::X,
            DVec3::new(0.3, -0.5, 0.81).normalize(),
            DVec3::new(1e-9, 0.0, -1.0).normalize(),
        ];
        for z in dirs {
            let m = orthonormal_basis(z);
            let (x, y) = (m.x_axis, m.y_axis);
            for (a, b) in [(x, y), (y, z), (z, x)] {
                assert!(a.dot(b).abs() < 1e-14, "{z}");
            }
            for v in [x, y] {
                assert!((v.length() - 1.0).abs() < 1e-14, "{z}");
            }
            assert_eq!(m.z_axis, z);
        }
    }
}
