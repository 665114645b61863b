// GGX (Trowbridge–Reitz) microfacet BRDF with Smith masking-shadowing and Fresnel = 1, and the
// Lambert BRDF: the point-light evaluation used by the direct pass and the VPL baseline.
// Conventions (docs/scenes.md, "Materials"): α = roughness², Rs = F0, no angular Fresnel, as in the papers.
#include "common/constants.wgsl"

// Smallest α used anywhere. GGX D ∝ 1/α² at the half vector, so α = 1e-4 (roughness 0.01)
// gives D ≈ 3e7: finite in f32. Below it the lobe is narrower than an f32 direction can
// resolve near the peak, so it is a mirror for every practical purpose.
const GGX_ALPHA_MIN: f32 = 1.0e-4;

fn ggx_alpha_from_roughness(roughness: f32) -> f32 {
    return max(roughness * roughness, GGX_ALPHA_MIN);
}

// GGX normal distribution D(h) [Walter et al. 2007, Eq. 33], written with
// 1 + (α²−1)cos²θ = α²cos²θ + sin²θ and sin²θ = ‖n×h‖², which keeps digits near the peak
// where 1 − cos²θ would cancel.
fn ggx_d(n_dot_h: f32, n_cross_h_len2: f32, alpha: f32) -> f32 {
    let a2 = alpha * alpha;
    let t = a2 * n_dot_h * n_dot_h + n_cross_h_len2;
    return min(a2 / max(PI * t * t, FLT_MIN), FLT_MAX);
}

// Smith Λ for GGX [Heitz 2014, Eq. 72]: Λ = (−1 + sqrt(1 + α² tan²θ)) / 2, evaluated as
// α² tan²θ / (2 (1 + sqrt(1 + α² tan²θ))) to avoid cancellation for small α tanθ.
fn ggx_smith_lambda(cos_theta: f32, alpha: f32) -> f32 {
    let c2 = max(cos_theta * cos_theta, FLT_MIN);
    let a2t2 = alpha * alpha * max(1.0 - c2, 0.0) / c2;
    return a2t2 / (2.0 * (1.0 + sqrt(1.0 + a2t2)));
}

// Height-correlated Smith G2 [Heitz 2014, Eq. 99].
fn ggx_smith_g2(n_dot_l: f32, n_dot_v: f32, alpha: f32) -> f32 {
    return 1.0 / (1.0 + ggx_smith_lambda(n_dot_l, alpha) + ggx_smith_lambda(n_dot_v, alpha));
}

// Specular BRDF value without Rs: D·G2 / (4 n·l n·v) for unit n, l (to light), v (to eye).
// Zero when either direction is below the surface.
fn ggx_brdf_over_rs(n: vec3f, l: vec3f, v: vec3f, alpha: f32) -> f32 {
    let n_dot_l = dot(n, l);
    let n_dot_v = dot(n, v);
    if (n_dot_l <= 0.0 || n_dot_v <= 0.0) {
        return 0.0;
    }
    let h_sum = l + v;
    let h_len = length(h_sum);
    if (h_len <= FLT_MIN) {
        return 0.0;
    }
    let h = h_sum / h_len;
    let nxh = cross(n, h);
    let d = ggx_d(max(dot(n, h), 0.0), dot(nxh, nxh), alpha);
    let g = ggx_smith_g2(n_dot_l, n_dot_v, alpha);
    return min(d * g / (4.0 * n_dot_l * n_dot_v), FLT_MAX);
}

// Lambert BRDF without Rd: 1/π for directions above the surface.
fn lambert_brdf_over_rd(n: vec3f, l: vec3f) -> f32 {
    return select(0.0, INV_PI, dot(n, l) > 0.0);
}
