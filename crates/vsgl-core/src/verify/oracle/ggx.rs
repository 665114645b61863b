//! f64 twins of `wgsl/common/ggx.wgsl`: the GGX (Trowbridge–Reitz) BRDF with height-correlated
//! Smith masking-shadowing and Fresnel = 1, and the Lambert BRDF. Same guards as the WGSL
//! (FLT_MIN floors, FLT_MAX caps of f32), which are no-ops for valid inputs.

use glam::DVec3;
use std::f64::consts::{FRAC_1_PI, PI};

const FLT_MIN: f64 = f32::MIN_POSITIVE as f64;
const FLT_MAX: f64 = f32::MAX as f64;

/// Same as `GGX_ALPHA_MIN` in ggx.wgsl.
pub const GGX_ALPHA_MIN: f64 = 1.0e-4;

/// α = roughness², floored at GGX_ALPHA_MIN.
pub fn ggx_alpha_from_roughness(roughness: f64) -> f64 {
    (roughness * roughness).max(GGX_ALPHA_MIN)
}

/// GGX normal distribution D(h) = α² / (π (α² cos²θ + sin²θ)²) [Walter et al. 2007, Eq. 33],
/// from n·h and ‖n × h‖² = sin²θ.
pub fn ggx_d(n_dot_h: f64, n_cross_h_len2: f64, alpha: f64) -> f64 {
    let a2 = alpha * alpha;
    let t = a2 * n_dot_h * n_dot_h + n_cross_h_len2;
    (a2 / (PI * t * t).max(FLT_MIN)).min(FLT_MAX)
}

/// Smith Λ for GGX [Heitz 2014, Eq. 72]: (−1 + √(1 + α² tan²θ))/2, in the form
/// α²tan²θ / (2(1 + √(1 + α²tan²θ))) (the same algebra as the WGSL; checked against the
/// defining form in the tests).
pub fn ggx_smith_lambda(cos_theta: f64, alpha: f64) -> f64 {
    let c2 = (cos_theta * cos_theta).max(FLT_MIN);
    let a2t2 = alpha * alpha * (1.0 - c2).max(0.0) / c2;
    a2t2 / (2.0 * (1.0 + (1.0 + a2t2).sqrt()))
}

/// Height-correlated Smith G2 [Heitz 2014, Eq. 99].
pub fn ggx_smith_g2(n_dot_l: f64, n_dot_v: f64, alpha: f64) -> f64 {
    1.0 / (1.0 + ggx_smith_lambda(n_dot_l, alpha) + ggx_smith_lambda(n_dot_v, alpha))
}

/// D·G2 / (4 n·l n·v) for unit n, l (to light), v (to eye); 0 below the surface.
pub fn ggx_brdf_over_rs(n: DVec3, l: DVec3, v: DVec3, alpha: f64) -> f64 {
    let n_dot_l = n.dot(l);
    let n_dot_v = n.dot(v);
    if n_dot_l <= 0.0 || n_dot_v <= 0.0 {
        return 0.0;
    }
    let h_sum = l + v;
    let h_len = h_sum.length();
    if h_len <= FLT_MIN {
        return 0.0;
    }
    let h = h_sum / h_len;
    let d = ggx_d(n.dot(h).max(0.0), n.cross(h).length_squared(), alpha);
    let g = ggx_smith_g2(n_dot_l, n_dot_v, alpha);
    (d * g / (4.0 * n_dot_l * n_dot_v)).min(FLT_MAX)
}

/// Lambert BRDF without Rd: 1/π above the surface.
pub fn lambert_brdf_over_rd(n: DVec3, l: DVec3) -> f64 {
    if n.dot(l) > 0.0 {
        FRAC_1_PI
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::verify::oracle::quadrature::integrate_sphere;
    use std::f64::consts::FRAC_PI_2;

    #[test]
    fn ggx_d_is_normalized() {
        // ∫ D(h) (n·h) dh = 1 over the hemisphere [Walter et al. 2007]. The rule is centred on n
        // at the lobe scale α with a θ break at π/2; the integrand is smooth on every panel, so the
        // quadrature is accurate to ~1e-12. Tolerance 1e-9.
        let n = DVec3::Z;
        for alpha in [GGX_ALPHA_MIN, 1e-3, 1e-2, 0.1, 0.5, 1.0] {
            let q = integrate_sphere(n, alpha, 8, &[FRAC_PI_2], |h| {
                let c = h.dot(n);
                if c <= 0.0 {
                    0.0
                } else {
                    ggx_d(c, n.cross(h).length_squared(), alpha) * c
                }
            });
            println!("GGX D normalization, α = {alpha:e}: ∫D(n·h)dh − 1 = {:.2e}", q - 1.0);
            assert!((q - 1.0).abs() < 1e-9, "α {alpha}: {q}");
        }
    }

    #[test]
    fn smith_lambda_matches_defining_form() {
        // Heitz 2014 Eq. 72 evaluated directly; it cancels only for α tanθ ≪ 1e-4, so compare in
        // the well-conditioned range with tolerance 1e-12 relative.
        for alpha in [0.05f64, 0.3, 1.0] {
            for c in [0.05, 0.3, 0.7, 0.95] {
                let tan2 = (1.0 - c * c) / (c * c);
                let direct = 0.5 * (-1.0 + (1.0 + alpha * alpha * tan2).sqrt());
                let l = ggx_smith_lambda(c, alpha);
                assert!((l - direct).abs() <= 1e-12 * direct, "α {alpha} c {c}: {l} vs {direct}");
            }
        }
        assert_eq!(ggx_smith_lambda(1.0, 0.5), 0.0);
        assert_eq!(ggx_smith_g2(1.0, 1.0, 0.5), 1.0);
        assert!(ggx_smith_lambda(1e-6, 0.5).is_finite());
    }

    #[test]
    fn brdf_is_reciprocal_and_energy_bounded() {
        let n = DVec3::Z;
        let l = DVec3::new(0.3, 0.2, 0.9).normalize();
        let v = DVec3::new(-0.5, 0.1, 0.6).normalize();
        for alpha in [0.01, 0.2, 0.9] {
            let a = ggx_brdf_over_rs(n, l, v, alpha);
            let b = ggx_brdf_over_rs(n, v, l, alpha);
            assert!((a - b).abs() <= 1e-14 * a, "reciprocity");
        }
        // Directional albedo ∫ f (n·l) dl ≤ 1 (G2 ≤ 1 only removes energy); for a smooth surface at
        // normal incidence it approaches 1 (G2 → 1). The rule is centred on the mirror direction
        // with the lobe scale 2α; tolerance 1e-6 on the bound (quadrature accuracy).
        for (alpha, cos_v) in [(0.02f64, 1.0f64), (0.2, 0.8), (0.6, 0.4), (1.0, 0.9)] {
            let v = DVec3::new((1.0 - cos_v * cos_v).sqrt(), 0.0, cos_v);
            let mirror = 2.0 * cos_v * n - v;
            let albedo = integrate_sphere(mirror, 2.0 * alpha, 256, &[FRAC_PI_2], |l| {
                ggx_brdf_over_rs(n, l, v, alpha) * l.dot(n).max(0.0)
            });
            println!("GGX directional albedo α = {alpha}, n·v = {cos_v}: {albedo:.6}");
            assert!(albedo <= 1.0 + 1e-6, "α {alpha}: {albedo}");
            if alpha <= 0.02 {
                assert!(albedo > 0.99, "α {alpha}: {albedo}");
            }
        }
        let lambert = integrate_sphere(n, 1.0, 64, &[FRAC_PI_2], |l| lambert_brdf_over_rd(n, l) * l.dot(n).max(0.0));
        assert!((lambert - 1.0).abs() < 1e-12, "{lambert}");
    }
}
