//! f64 twins of `wgsl/common/vsgl.wgsl`: the VSGL from summed moments, the incoming-radiance SG
//! at a shading point, and diffuse/specular shading ([Tok15] §3, [Tok16s] §3–4).
//! Positions are relative to a caller-chosen local origin, exactly as in the WGSL.

use glam::DVec3;
use std::f64::consts::{FRAC_1_PI, PI};

use super::ggx::{ggx_smith_g2, ggx_smith_lambda};
use super::math::safe_normalize;
use super::sg::{
    ggx_lobe_asg, lambert_lobe_sg, sg_asg_product_integral_over_asg_integral, sg_clamped_cosine_integral, sg_from_toksvig_mean_direction,
    sg_integral, sg_integral_approx, sg_product, sg_product_integral, Sg, SG_SHARPNESS_MAX,
};

const FLT_MIN: f64 = f32::MIN_POSITIVE as f64;
const FLT_MAX: f64 = f32::MAX as f64;

/// Same as `VSGL_VARIANCE_MIN_FRACTION` in vsgl.wgsl: σ² ≥ this × E[‖y − o‖²] (f32 rounding floor).
pub const VSGL_VARIANCE_MIN_FRACTION: f64 = 1.0e-6;

/// Positional Gaussian N(mean, variance·I) of a VSGL, mean relative to the local origin.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VsglPosition {
    pub mean: DVec3,
    pub variance: f64,
}

/// I_v(ω) = c_v G(ω; ξ_v, λ_v) from Σ Φ R and Σ Φ R ξ̄ [Tok16s §3.1]; c_v = Σ Φ R / A(λ_v).
pub fn vsgl_lobe_from_moments(sum_weight: f64, sum_weighted_mean_direction: DVec3) -> Sg {
    if sum_weight.is_nan() || sum_weight <= 0.0 {
        return Sg {
            axis: DVec3::Z,
            sharpness: 0.0,
            amplitude: 0.0,
        };
    }
    let lobe = sg_from_toksvig_mean_direction(sum_weighted_mean_direction / sum_weight);
    Sg {
        amplitude: (sum_weight * lobe.amplitude).min(FLT_MAX),
        ..lobe
    }
}

/// μ_v = Σwy/Σw, σ_v² = Σw‖y‖²/Σw − ‖μ_v‖² ≥ VSGL_VARIANCE_MIN_FRACTION·Σw‖y‖²/Σw [Tok16s §3.2].
pub fn vsgl_position_from_moments(sum_weight: f64, sum_weighted_position: DVec3, sum_weighted_position_len2: f64) -> VsglPosition {
    if sum_weight.is_nan() || sum_weight <= 0.0 {
        return VsglPosition {
            mean: DVec3::ZERO,
            variance: 0.0,
        };
    }
    let mean = sum_weighted_position / sum_weight;
    let second_moment = (sum_weighted_position_len2 / sum_weight).max(0.0);
    let variance = (second_moment - mean.length_squared()).max(VSGL_VARIANCE_MIN_FRACTION * second_moment);
    VsglPosition { mean, variance }
}

/// L_in(ω) ≈ c_v/(2πσ²) G(ω; −ξ_v, λ_v) G(ω; ξ_μ, λσ) = c_in G(ω; ξ_in, λ_in) [Tok15 Eq. 5;
/// Tok16s Eq. 7], σ² floored at d²/SG_SHARPNESS_MAX (and FLT_MIN), log-amplitude from sg_product.
pub fn vsgl_incoming_radiance(lobe: Sg, position: VsglPosition, shading_position: DVec3) -> Sg {
    let to_mean = position.mean - shading_position;
    let dist2 = to_mean.length_squared();
    let variance = position.variance.max(dist2 / SG_SHARPNESS_MAX).max(FLT_MIN);
    let sharpness_sigma = dist2 / variance;
    let axis_mu = safe_normalize(to_mean, -lobe.axis);
    let p = sg_product(-lobe.axis, lobe.sharpness, axis_mu, sharpness_sigma);
    let coefficient = (lobe.amplitude / (2.0 * PI * variance)).min(FLT_MAX);
    Sg {
        axis: p.axis,
        sharpness: p.sharpness,
        amplitude: coefficient * p.log_amplitude.exp(),
    }
}

/// The positional Gaussian N(μ_v, σ_v²) seen from y_p [Tok15 Eq. 6]: the SG G(ω; ξ_μ, λσ) on the
/// sphere of radius d = ‖μ_v − y_p‖, ξ_μ = (μ_v − y_p)/d, λσ = d²/σ², with σ² floored at
/// d²/SG_SHARPNESS_MAX (and FLT_MIN) as in vsgl.wgsl, and 1/σ² of the same floored σ².
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VsglPositionSeen {
    pub inv_variance: f64,
    pub sharpness: f64,
    /// ξ_μ where `has_axis` (d² ≥ FLT_MIN, the f32 test of vsgl.wgsl); μ_v − y_p otherwise
    /// (shorter than 1.1e-19: the direction is undefined there and unused).
    pub axis: DVec3,
    pub has_axis: bool,
}

/// `vsgl_position_seen_from` (vsgl.wgsl): Eq. 6 of [Tok15] at y_p.
pub fn vsgl_position_seen_from(position: VsglPosition, shading_position: DVec3) -> VsglPositionSeen {
    let t = position.mean - shading_position;
    let d2 = t.length_squared();
    let variance = position.variance.max(d2 / SG_SHARPNESS_MAX).max(FLT_MIN);
    let has_axis = d2 >= FLT_MIN;
    VsglPositionSeen {
        inv_variance: 1.0 / variance,
        sharpness: d2 / variance,
        axis: if has_axis { t / d2.sqrt() } else { t },
        has_axis,
    }
}

/// `vsgl_incoming_radiance_seen` (vsgl.wgsl): [Tok15 Eq. 5] with the seen Gaussian given,
/// L_in = (c_v/2π)·(1/σ²)·G(ω; −ξ_v, λ_v)·G(ω; ξ_μ, λσ) as one SG (the product by sg_product);
/// the lobe's amplitude is given as c_v/(2π). At d = 0 (no axis) ξ_μ is taken as −ξ_v.
pub fn vsgl_incoming_radiance_seen(lobe_axis: DVec3, lobe_sharpness: f64, amplitude_over_two_pi: f64, seen: VsglPositionSeen) -> Sg {
    let toward = -lobe_axis;
    let axis_mu = if seen.has_axis { seen.axis } else { toward };
    let p = sg_product(toward, lobe_sharpness, axis_mu, seen.sharpness);
    let coefficient = (amplitude_over_two_pi * seen.inv_variance).min(FLT_MAX);
    Sg {
        axis: p.axis,
        sharpness: p.sharpness,
        amplitude: coefficient * p.log_amplitude.exp(),
    }
}

/// L_d/R_d ≈ c_in/π·A(λ_in)·max(ξ_in·n, 0) [Tok16s §4.2].
pub fn vsgl_diffuse(radiance: Sg, normal: DVec3) -> f64 {
    (radiance.amplitude * FRAC_1_PI * sg_integral(radiance.sharpness) * radiance.axis.dot(normal).max(0.0)).min(FLT_MAX)
}

/// L_d/R_d ≈ 2c_in/max(λ_in, ½)·max(ξ_in·n, 0) [Tok16s §4.2, A ≈ 2π/λ].
pub fn vsgl_diffuse_approx(radiance: Sg, normal: DVec3) -> f64 {
    (radiance.amplitude * FRAC_1_PI * sg_integral_approx(radiance.sharpness) * radiance.axis.dot(normal).max(0.0)).min(FLT_MAX)
}

/// L_d/R_d ≈ c_in/π·∫G_in max(ω·n, 0) dω (sg_clamped_cosine_integral).
pub fn vsgl_diffuse_accurate(radiance: Sg, normal: DVec3) -> f64 {
    (radiance.amplitude * FRAC_1_PI * sg_clamped_cosine_integral(radiance.axis, radiance.sharpness, normal)).min(FLT_MAX)
}

/// L_d/R_d ≈ c_in ∫ G_in G(ω; n, λd)/A(λd) dω [Tok16s §4.2 with Eq. 1].
pub fn vsgl_diffuse_sg_product(radiance: Sg, normal: DVec3) -> f64 {
    let lambert = lambert_lobe_sg(normal);
    (radiance.amplitude * lambert.amplitude * sg_product_integral(radiance.axis, radiance.sharpness, lambert.axis, lambert.sharpness))
        .min(FLT_MAX)
}

/// L_s/R_s ≈ c_in·G2(ξ_in, ω_o)·sg_asg_product_integral_over_asg_integral(ξ_in, λ_in, ggx_lobe_asg)
/// [Tok16s §4.2 boxed, in the clamp-safe form derived in vsgl.wgsl]; 0 below the surface.
pub fn vsgl_specular(radiance: Sg, normal: DVec3, w_o: DVec3, alpha: f64) -> f64 {
    let n_dot_l = normal.dot(radiance.axis);
    let n_dot_v = normal.dot(w_o);
    if n_dot_l <= 0.0 || n_dot_v <= 0.0 {
        return 0.0;
    }
    let asg = ggx_lobe_asg(normal, w_o, alpha);
    let g2 = ggx_smith_g2(n_dot_l, n_dot_v, alpha);
    (radiance.amplitude * g2 * sg_asg_product_integral_over_asg_integral(radiance.axis, radiance.sharpness, asg)).min(FLT_MAX)
}

/// What the specular form needs of the receiver alone (`VsglSpecularReceiver` in vsgl.wgsl):
/// n·ω_o, the view's Smith Λ(ω_o) [Heitz 2014, Eq. 99] and the GGX lobe ASG [Tok16s §4.2].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VsglSpecularReceiver {
    pub normal: DVec3,
    pub w_o: DVec3,
    pub alpha: f64,
    pub n_dot_v: f64,
    pub lambda_v: f64,
    pub asg: super::sg::Asg,
}

/// `vsgl_specular_receiver_from` (vsgl.wgsl).
pub fn vsgl_specular_receiver_from(normal: DVec3, w_o: DVec3, alpha: f64) -> VsglSpecularReceiver {
    let n_dot_v = normal.dot(w_o);
    VsglSpecularReceiver {
        normal,
        w_o,
        alpha,
        n_dot_v,
        lambda_v: ggx_smith_lambda(n_dot_v, alpha),
        asg: ggx_lobe_asg(normal, w_o, alpha),
    }
}

/// `vsgl_specular_with_receiver` (vsgl.wgsl): L_s/R_s ≈ c_in·G2·(SG–ASG product over the ASG's
/// integral) [Tok16s §4.2 boxed], G2 = 1/(1 + Λ(ξ_in) + Λ(ω_o)) the height-correlated Smith
/// masking-shadowing [Heitz 2014, Eq. 99]; 0 when the light axis or the view is below the surface.
pub fn vsgl_specular_with_receiver(radiance: Sg, receiver: &VsglSpecularReceiver) -> f64 {
    let n_dot_l = receiver.normal.dot(radiance.axis);
    if n_dot_l <= 0.0 || receiver.n_dot_v <= 0.0 {
        return 0.0;
    }
    let g2 = 1.0 / (1.0 + ggx_smith_lambda(n_dot_l, receiver.alpha) + receiver.lambda_v);
    (radiance.amplitude * g2 * sg_asg_product_integral_over_asg_integral(radiance.axis, radiance.sharpness, receiver.asg)).min(FLT_MAX)
}

/// Same as `VSGL_FILTERED_ALPHA2_MIN` in vsgl.wgsl: α² ≥ GGX_ALPHA_MIN² in the filtered NDF.
pub const VSGL_FILTERED_ALPHA2_MIN: f64 = 1.0e-8;
/// Same as `VSGL_FILTERED_ALPHA2_MAX` in vsgl.wgsl: the widening stops at α'² = 1 (D = 1/π).
pub const VSGL_FILTERED_ALPHA2_MAX: f64 = 1.0;
/// Same as `VSGL_FILTERED_INV_HALF_LENGTH_MAX` in vsgl.wgsl: 1/‖ξ + ω_o‖ ≤ 5e8 (‖m‖ ≤ 1e9).
pub const VSGL_FILTERED_INV_HALF_LENGTH_MAX: f64 = 5.0e8;

/// The widened slope covariance Σ' = α²I + (2/λ)JJᵀ of `vsgl_specular_accurate`, in the tangent
/// frame (t, b) = orthonormal_basis(n), as its eigen-decomposition: (σ₊, σ₋, unit eigenvector of
/// σ₊), each σ capped at max(α², VSGL_FILTERED_ALPHA2_MAX). Also returns h and its tangent part.
/// (The derivation is in vsgl.wgsl.)
pub fn vsgl_filtered_slope_covariance(sharpness: f64, normal: DVec3, w_in: DVec3, w_o: DVec3, alpha: f64) -> (f64, f64, [f64; 2], DVec3) {
    let u = w_in + w_o;
    let u_len2 = u.length_squared();
    let h = safe_normalize(u, normal);
    let frame = super::math::orthonormal_basis(normal);
    let (t, b) = (frame.x_axis, frame.y_axis);
    let h_n = h.dot(normal);
    let (h_t, h_b) = (h.dot(t), h.dot(b));
    let m = normal.cross(w_in - w_o) * (1.0 / u_len2.max(FLT_MIN).sqrt()).min(VSGL_FILTERED_INV_HALF_LENGTH_MAX);
    let (m_t, m_b) = (m.dot(t), m.dot(b));
    let h_n2 = h_n * h_n;
    // B = h_n² I + h₂h₂ᵀ + m₂m₂ᵀ
    let b_tt = h_n2 + h_t * h_t + m_t * m_t;
    let b_bb = h_n2 + h_b * h_b + m_b * m_b;
    let b_tb = h_t * h_b + m_t * m_b;
    let cross = h_t * m_b - h_b * m_t;
    let det = h_n2 * h_n2 + h_n2 * (h_t * h_t + h_b * h_b + m_t * m_t + m_b * m_b) + cross * cross;
    let half_diff = 0.5 * (b_tt - b_bb);
    let b_plus = 0.5 * (b_tt + b_bb) + (half_diff * half_diff + b_tb * b_tb).sqrt();
    let b_minus = det / b_plus.max(FLT_MIN);
    let v1 = [b_tb, b_plus - b_tt];
    let v2 = [b_plus - b_bb, b_tb];
    let n1 = v1[0] * v1[0] + v1[1] * v1[1];
    let n2 = v2[0] * v2[0] + v2[1] * v2[1];
    let (v, nv) = if n1 >= n2 { (v1, n1) } else { (v2, n2) };
    let e = if nv > FLT_MIN { [v[0] / nv.sqrt(), v[1] / nv.sqrt()] } else { [1.0, 0.0] };
    let a2 = (alpha * alpha).max(VSGL_FILTERED_ALPHA2_MIN);
    let cap = a2.max(VSGL_FILTERED_ALPHA2_MAX);
    let den = (2.0 * sharpness * h_n2 * h_n2).max(FLT_MIN);
    let widen = |bi: f64| (a2 + bi.min(cap * den) / den).min(cap);
    (widen(b_plus), widen(b_minus), e, DVec3::new(h_t, h_b, h_n))
}

/// L_s/R_s ≈ c_in A(λ_in) D'(h) G2'(ξ_in, ω_o)/(4 n·ω_o), D' the GGX NDF with the widened slope
/// covariance of [`vsgl_filtered_slope_covariance`] and G2' its Smith masking (α(ω)² = ω̂₂ᵀΣ'ω̂₂)
/// (vsgl.wgsl derives both); 0 below the surface.
pub fn vsgl_specular_accurate(radiance: Sg, normal: DVec3, w_o: DVec3, alpha: f64) -> f64 {
    vsgl_specular_filtered(radiance, normal, w_o, alpha).0
}

/// [`vsgl_specular_accurate`]'s value and the receiver's share α/α' of the widened lobe,
/// α'⁴ = σ₊σ₋ (vsgl.wgsl); (0, 1) below the surface.
pub fn vsgl_specular_filtered(radiance: Sg, normal: DVec3, w_o: DVec3, alpha: f64) -> (f64, f64) {
    let n_dot_l = normal.dot(radiance.axis);
    let n_dot_v = normal.dot(w_o);
    if n_dot_l <= 0.0 || n_dot_v <= 0.0 {
        return (0.0, 1.0);
    }
    let (s_plus, s_minus, e, h) = vsgl_filtered_slope_covariance(radiance.sharpness, normal, radiance.axis, w_o, alpha);
    let y_plus = h.x * e[0] + h.y * e[1];
    let y_minus = h.y * e[0] - h.x * e[1];
    let q = h.z * h.z + y_plus * y_plus / s_plus + y_minus * y_minus / s_minus;
    let d = 1.0 / (PI * (s_plus * s_minus).sqrt() * q * q);
    // Smith masking of the widened microsurface: Λ with α(ω)² = ω̂₂ᵀΣ'ω̂₂ along ω's azimuth.
    let frame = super::math::orthonormal_basis(normal);
    let alpha_along = |w: DVec3| {
        let (wt, wb) = (w.dot(frame.x_axis), w.dot(frame.y_axis));
        let len2 = wt * wt + wb * wb;
        if len2 <= FLT_MIN {
            return alpha;
        }
        let (yp, ym) = (wt * e[0] + wb * e[1], wb * e[0] - wt * e[1]);
        ((s_plus * yp * yp + s_minus * ym * ym) / len2).sqrt()
    };
    let g2 = 1.0 / (1.0 + ggx_smith_lambda(n_dot_l, alpha_along(radiance.axis)) + ggx_smith_lambda(n_dot_v, alpha_along(w_o)));
    let value = (radiance.amplitude * sg_integral(radiance.sharpness) * d * g2 / (4.0 * n_dot_v)).min(FLT_MAX);
    let a2 = (alpha * alpha).max(VSGL_FILTERED_ALPHA2_MIN);
    (value, (a2 / (s_plus * s_minus).sqrt()).sqrt().min(1.0))
}

/// lighting="blend": w·[`vsgl_specular_accurate`] + (1 − w)·[`vsgl_specular`], w = α/α' the
/// receiver's share of the widened lobe (vsgl.wgsl says why); 0 below the surface.
pub fn vsgl_specular_blend(radiance: Sg, normal: DVec3, w_o: DVec3, alpha: f64) -> f64 {
    if normal.dot(radiance.axis) <= 0.0 || normal.dot(w_o) <= 0.0 {
        return 0.0;
    }
    vsgl_specular_blend_with_receiver(radiance, &vsgl_specular_receiver_from(normal, w_o, alpha))
}

/// [`vsgl_specular_blend`] with the receiver formed once per pixel, as the shading loop calls it.
pub fn vsgl_specular_blend_with_receiver(radiance: Sg, receiver: &VsglSpecularReceiver) -> f64 {
    let (filtered, share) = vsgl_specular_filtered(radiance, receiver.normal, receiver.w_o, receiver.alpha);
    if share >= 1.0 {
        return filtered;
    }
    share * filtered + (1.0 - share) * vsgl_specular_with_receiver(radiance, receiver)
}

/// Same as `VSGL_PLANE_TOLERANCE` in vsgl_tangent_plane.wgsl.
pub const VSGL_PLANE_TOLERANCE: f64 = 1.0e-3;

/// A VSGL's mean tangent plane (derived for vsgl): the weighted mean height
/// H(p) = E_w[(p − y)·n] = (p − μ)·N̄ + offset, N̄ = Σw n/Σw, offset = μ·N̄ − Σw(y·n)/Σw.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VsglTangentPlane {
    pub normal: DVec3,
    pub offset: f64,
}

/// The plane from the cluster sums Σw, Σw·n, Σw·(y·n) and the cluster mean μ (all relative to
/// one local origin); no plane (N̄ = 0) without weight.
pub fn vsgl_tangent_plane_from_moments(sum_weight: f64, sum_weighted_normal: DVec3, sum_weighted_height: f64, mean: DVec3) -> VsglTangentPlane {
    if sum_weight.is_nan() || sum_weight <= 0.0 {
        return VsglTangentPlane { normal: DVec3::ZERO, offset: 0.0 };
    }
    let normal = sum_weighted_normal / sum_weight;
    VsglTangentPlane { normal, offset: mean.dot(normal) - sum_weighted_height / sum_weight }
}

/// Fraction of a VSGL's light kept at p: 0 for H(p) ≤ τ, 1 from 2τ, linear between,
/// τ = VSGL_PLANE_TOLERANCE·(‖p − μ‖ + σ); 1 without a plane (N̄ = 0).
pub fn vsgl_tangent_plane_fade(plane: VsglTangentPlane, position: VsglPosition, shading_position: DVec3) -> f64 {
    if plane.normal == DVec3::ZERO {
        return 1.0;
    }
    let to_receiver = shading_position - position.mean;
    let height = to_receiver.dot(plane.normal) + plane.offset;
    let tolerance = VSGL_PLANE_TOLERANCE * (to_receiver.length() + position.variance.max(0.0).sqrt());
    if !(tolerance > 0.0) {
        return if height > 0.0 { 1.0 } else { 0.0 };
    }
    ((height - tolerance) / tolerance).clamp(0.0, 1.0)
}

#[cfg(test)]
#[path = "vsgl_tests.rs"]
mod tests;
