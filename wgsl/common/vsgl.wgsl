// Virtual spherical Gaussian lights: the VSGL from summed VPL moments, its incoming-radiance SG
// at a shading point, and diffuse / specular shading by SG product integrals.
// Sources ([Tok15], [Tok15s], [Tok16s], [XSD13] as in sg.wgsl):
//   a VSGL is a radiant-intensity SG I_v(ω) = c_v G(ω; ξ_v, λ_v) [W/sr] per BRDF component
//   (diffuse, specular) and one isotropic positional Gaussian N(μ_v, σ_v²) [Tok16s §3].
// Positions: every position here is relative to a caller-chosen local origin (e.g. the light
// position), never absolute world coordinates: σ² = E[‖y‖²] − ‖μ‖² cancels catastrophically
// 1e5 m from the origin in f32 (docs/numerics.md, "VSGL variance").
// Every function is pure; the f64 twins are in crates/vsgl-core/src/verify/oracle/vsgl.rs.
#include "common/constants.wgsl"
#include "common/math.wgsl"
#include "common/sg.wgsl"
#include "common/ggx.wgsl"

// Floor of the positional variance as a fraction of the second moment E[‖y − o‖²] it is computed
// from: σ² = E[‖y − o‖²] − ‖μ − o‖² is only known to a few ULP of E[‖y − o‖²] (2^-24 = 6e-8 each,
// more after mip or tree summation), so smaller values are rounding noise, possibly negative.
// 1e-6 is ~8 ULP; it bounds σ below by 1e-3·‖y − o‖, relative to the scene's own scale.
const VSGL_VARIANCE_MIN_FRACTION: f32 = 1.0e-6;

// Positional Gaussian of a VSGL: mean μ_v (relative to the local origin) and variance σ_v².
struct VsglPosition {
    mean: vec3f,
    variance: f32,
}

// Radiant-intensity SG of a VPL cluster from its summed moments [Tok16s §3.1, §3.3; Tok15 §3.1.1]:
//   sum_weight                  = Σ Φ_j R_j                       (total reflected power, W)
//   sum_weighted_mean_direction = Σ Φ_j R_j ξ̄_j, ξ̄_j = sg_toksvig_mean_direction(lobe_j)
// ξ̄_v = (Σ Φ R ξ̄)/(Σ Φ R), ξ_v = ξ̄_v/‖ξ̄_v‖, λ_v = r/(1 − r) (sg_from_toksvig_mean_direction),
// c_v = Σ Φ R / A(λ_v), so that ∫ I_v dω = Σ Φ_j R_j exactly (energy conservation).
// The returned amplitude is c_v. A cluster without power returns amplitude 0.
fn vsgl_lobe_from_moments(sum_weight: f32, sum_weighted_mean_direction: vec3f) -> Sg {
    if (!(sum_weight > 0.0)) {
        return Sg(vec3f(0.0, 0.0, 1.0), 0.0, 0.0);
    }
    let lobe = sg_from_toksvig_mean_direction(sum_weighted_mean_direction / sum_weight);
    return Sg(lobe.axis, lobe.sharpness, min(sum_weight * lobe.amplitude, FLT_MAX));
}

// Positional Gaussian of a VPL cluster [Tok16s §3.2; Tok15 §3.1.2], weights w_j = Φ_j(R_d,j + R_s,j):
//   μ_v = Σ w y / Σ w,  σ_v² = Σ w ‖y‖² / Σ w − ‖μ_v‖²,  with y relative to the local origin.
// Clamp: σ_v² ≥ VSGL_VARIANCE_MIN_FRACTION·(Σ w ‖y‖² / Σ w) (rounding floor, see the constant).
fn vsgl_position_from_moments(sum_weight: f32, sum_weighted_position: vec3f, sum_weighted_position_len2: f32) -> VsglPosition {
    if (!(sum_weight > 0.0)) {
        return VsglPosition(vec3f(0.0), 0.0);
    }
    let inv_weight = 1.0 / sum_weight;
    let mean = sum_weighted_position * inv_weight;
    let second_moment = max(sum_weighted_position_len2 * inv_weight, 0.0);
    let variance = max(second_moment - dot(mean, mean), VSGL_VARIANCE_MIN_FRACTION * second_moment);
    return VsglPosition(mean, variance);
}

// The positional Gaussian N(μ_v, σ_v²) of a VSGL as seen from a shading point y_p [Tok15 Eq. 6]:
// on the sphere of radius d = ‖μ_v − y_p‖ around y_p it is the SG G(ω; ξ_μ, λσ) with
// ξ_μ = (μ_v − y_p)/d and λσ = d²/σ². It depends on the pair (y_p, VSGL) but not on the lobe, so
// the shading loop forms it once per pair and both lobes of the VSGL share it
// (vsgl_incoming_radiance_seen).
// Clamp: σ² is floored at d²/SG_SHARPNESS_MAX so that λσ ≤ SG_SHARPNESS_MAX (to rounding: the
// floor is d² times the constant's reciprocal, a product instead of a division), and at FLT_MIN,
// which only guards d = σ = 0. The coefficient c_v/(2πσ²) of Eq. 5 is formed from the same
// floored σ² (inv_variance), so c_in·A(λ_in) → I_v(−ξ_μ)/d² (the point-light limit) is kept
// exactly when the clamp is active.
// ξ_μ is t·(d²)^(−1/2) with the d² already formed (t = μ_v − y_p), not safe_normalize's three
// divisions by the largest component, which guard vectors whose squared length underflows: here
// d² < FLT_MIN means y_p within 1e-19 of μ_v, where λσ ≈ 0 and ξ_μ does not matter (has_axis is
// false and vsgl_incoming_radiance_seen takes −ξ_v instead).
struct VsglPositionSeen {
    // 1/σ², σ² floored as above.
    inv_variance: f32,
    // λσ = d²/σ².
    sharpness: f32,
    // ξ_μ, valid where has_axis (d² ≥ FLT_MIN); else t unnormalized (|t| < 1.1e-19).
    axis: vec3f,
    has_axis: bool,
}

fn vsgl_position_seen_from(position: VsglPosition, shading_position: vec3f) -> VsglPositionSeen {
    let to_mean = position.mean - shading_position;
    let dist2 = dot(to_mean, to_mean);
    let variance = max(max(position.variance, dist2 * (1.0 / SG_SHARPNESS_MAX)), FLT_MIN);
    let inv_variance = 1.0 / variance;
    let has_axis = dist2 >= FLT_MIN;
    return VsglPositionSeen(inv_variance, dist2 * inv_variance, to_mean * inverseSqrt(select(1.0, dist2, has_axis)), has_axis);
}

// Incoming radiance at y_p from one lobe of a VSGL as one SG [Tok15 Eq. 5; Tok16s Eq. 7], given
// the positional Gaussian as seen from y_p (vsgl_position_seen_from):
//   L_in(ω) ≈ c_v/(2πσ²)·G(ω; −ξ_v, λ_v)·G(ω; ξ_μ, λσ) = c_in G(ω; ξ_in, λ_in),
//   λ_in = ‖λσ ξ_μ − λ_v ξ_v‖, ξ_in = (λσ ξ_μ − λ_v ξ_v)/λ_in, c_in = c_v/(2πσ²)·exp(λ_in − λ_v − λσ).
// The lobe comes as (ξ_v, λ_v, c_v/(2π)): the 1/(2π) depends on the VSGL alone (the shading
// loop folds it in once per VSGL and workgroup), so the coefficient is one product with 1/σ².
// Stable form (docs/numerics.md, "Product log-amplitude"; the product of sg_product, inlined): the exponent is the log-amplitude
// −λ_v λσ ‖ξ_v + ξ_μ‖²/(λ_in + λ_v + λσ), never the difference λ_in − λ_v − λσ. ξ_in is
// v·‖v‖⁻¹ with the ‖v‖² that λ_in = ‖v‖ needs; ‖v‖² < FLT_MIN means λ_in ≈ 0, where the axis is
// sg_product's fallback: the sharper input's axis.
// The visibility V(y_p, μ_v) of [Tok15 Eq. 5] is left to the caller (multiply the amplitude).
fn vsgl_incoming_radiance_seen(lobe_axis: vec3f, lobe_sharpness: f32, amplitude_over_two_pi: f32, seen: VsglPositionSeen) -> Sg {
    let axis1 = -lobe_axis;
    let sharpness_sigma = seen.sharpness;
    // At the mean itself (d = 0) λσ = 0 and ξ_μ is irrelevant.
    let axis_mu = select(axis1, seen.axis, seen.has_axis);
    let v = lobe_sharpness * axis1 + sharpness_sigma * axis_mu;
    let v_len2 = dot(v, v);
    let sharpness = sqrt(v_len2);
    var axis = select(axis_mu, axis1, lobe_sharpness >= sharpness_sigma);
    if (v_len2 >= FLT_MIN) {
        axis = v * inverseSqrt(v_len2);
    }
    let d = axis1 - axis_mu;
    let ratio = sharpness_sigma / max(sharpness + lobe_sharpness + sharpness_sigma, FLT_MIN);
    let log_amplitude = -lobe_sharpness * ratio * dot(d, d);
    let coefficient = min(amplitude_over_two_pi * seen.inv_variance, FLT_MAX);
    return Sg(axis, sharpness, coefficient * exp(log_amplitude));
}

// Incoming radiance at shading point y_p from a VSGL lobe (ξ_v, λ_v, c_v) as one SG [Tok15 Eq. 5;
// Tok16s Eq. 7]: vsgl_incoming_radiance_seen with the positional Gaussian seen from y_p formed
// here, for callers that shade one lobe per (point, VSGL). One implementation of the formula:
// the shading loop calls the two parts itself to share the seen Gaussian between the lobes.
fn vsgl_incoming_radiance(lobe: Sg, position: VsglPosition, shading_position: vec3f) -> Sg {
    let seen = vsgl_position_seen_from(position, shading_position);
    return vsgl_incoming_radiance_seen(lobe.axis, lobe.sharpness, lobe.amplitude / TWO_PI, seen);
}

// Diffuse reflected radiance over R_d, cosine pulled out of the integral [Tok16s §4.2;
// Tok15s App. B, after Wang et al. 2009]:  L_d/R_d ≈ c_in/π · A(λ_in) · max(ξ_in·n, 0).
fn vsgl_diffuse(radiance: Sg, normal: vec3f) -> f32 {
    let cos_axis = max(dot(radiance.axis, normal), 0.0);
    return min(radiance.amplitude * INV_PI * sg_integral(radiance.sharpness) * cos_axis, FLT_MAX);
}

// The papers' cheap form [Tok16s §4.2, A(λ) ≈ 2π/λ after Iwasaki et al. 2012]:
// L_d/R_d ≈ 2c_in/λ_in · max(ξ_in·n, 0), with λ_in floored at SG_INTEGRAL_APPROX_SHARPNESS_MIN
// (sg_integral_approx) so it stays finite and ≤ the exact value at λ_in = 0.
fn vsgl_diffuse_approx(radiance: Sg, normal: vec3f) -> f32 {
    let cos_axis = max(dot(radiance.axis, normal), 0.0);
    return min(radiance.amplitude * INV_PI * sg_integral_approx(radiance.sharpness) * cos_axis, FLT_MAX);
}

// Diffuse reflected radiance over R_d with the clamped cosine kept inside the integral
// (sg_clamped_cosine_integral, derived for vsgl): L_d/R_d ≈ c_in/π · ∫ G_in max(ω·n, 0) dω.
// No light leaks from lobes below the horizon, and correct for broad lobes.
fn vsgl_diffuse_accurate(radiance: Sg, normal: vec3f) -> f32 {
    let integral = sg_clamped_cosine_integral(radiance.axis, radiance.sharpness, normal);
    return min(radiance.amplitude * INV_PI * integral, FLT_MAX);
}

// Diffuse reflected radiance over R_d as the product integral of two SGs [Tok16s §4.2 "Using
// Eq. 1 and Eq. 7"; used with few VSGLs in the 2015 poster]: the Lambert lobe replaced by
// G(ω; n, λd)/A(λd) (lambert_lobe_sg). Leaks light from lobes below the horizon.
fn vsgl_diffuse_sg_product(radiance: Sg, normal: vec3f) -> f32 {
    let lambert = lambert_lobe_sg(normal);
    let integral = sg_product_integral(radiance.axis, radiance.sharpness, lambert.axis, lambert.sharpness);
    return min(radiance.amplitude * lambert.amplitude * integral, FLT_MAX);
}

// What vsgl_specular needs of the receiver alone (unit normal n, unit view ω_o, GGX α), formed
// once per pixel by the shading loop instead of once per (pixel, VSGL) pair: n·ω_o, the view's
// Smith Λ(ω_o) [Heitz 2014, Eq. 99] and the GGX lobe's ASG at y_p [Tok16s §4.2; ggx_lobe_asg].
struct VsglSpecularReceiver {
    n: vec3f,
    w_o: vec3f,
    alpha: f32,
    n_dot_v: f32,
    lambda_v: f32,
    asg: Asg,
}

fn vsgl_specular_receiver_from(normal: vec3f, w_o: vec3f, alpha: f32) -> VsglSpecularReceiver {
    let n_dot_v = dot(normal, w_o);
    return VsglSpecularReceiver(normal, w_o, alpha, n_dot_v, ggx_smith_lambda(n_dot_v, alpha), ggx_lobe_asg(normal, w_o, alpha));
}

// Specular reflected radiance over R_s for the GGX BRDF (Fresnel = 1) [Tok16s §4.2 boxed;
// Tok15s App. B]:
//   L_s ≈ π c_in C(ξ_in) Ĝ(ξ_in; x, y, z, ηxν/(ηx+ν), ηyν/(ηy+ν)) / √((ηx+ν)(ηy+ν)), ν = λ_in/2,
// with ρ_s max(ω·n,0) ≈ C(ω)·Ĝ(ω) and Ĝ the GGX lobe ASG at y_p (ggx_lobe_asg). For GGX,
// ρ_s cos = R_s D G2/(4 n·ω_o) and D = D(n)·D/D(n) with D(n) = 1/(πα²), so
//   C(ω) = R_s G2(ω, ω_o)/(4πα² n·ω_o).
// Since √(ηx ηy) = λh/(8 n·ω_o) = 1/(4α² n·ω_o), C = R_s G2 √(ηx ηy)/π, and the boxed formula
// equals R_s G2 · sg_asg_product_integral_over_asg_integral — the form used here: identical
// while no bandwidth is clamped, and it keeps the lobe's energy (→ c_in R_s G2 for a broad
// light) when ggx_lobe_asg clamps ηy at grazing view, where C's 1/(n·ω_o) would blow up.
// Zero when the light axis or the view is below the surface (G2 → 0 there continuously).
// G2 = 1/(1 + Λ(ξ_in) + Λ(ω_o)) [Heitz 2014, Eq. 99], the height-correlated Smith G2 as
// ggx_smith_g2 forms it, with Λ(ω_o) from the receiver.
// Accuracy (oracle test vsgl_specular_vs_quadrature, against the exact GGX integral): exact in
// the point-light limit (< 1e-3); for extended lights +0…+21% (α = 0.05…0.2), because the SG
// NDF G(h; n, 2/α²) has GGX's peak and projected area but a wider core and no long tails.
fn vsgl_specular_with_receiver(radiance: Sg, receiver: VsglSpecularReceiver) -> f32 {
    let n_dot_l = dot(receiver.n, radiance.axis);
    if (n_dot_l <= 0.0 || receiver.n_dot_v <= 0.0) {
        return 0.0;
    }
    let g2 = 1.0 / (1.0 + ggx_smith_lambda(n_dot_l, receiver.alpha) + receiver.lambda_v);
    let lobe = sg_asg_product_integral_over_asg_integral(radiance.axis, radiance.sharpness, receiver.asg);
    return min(radiance.amplitude * g2 * lobe, FLT_MAX);
}

// vsgl_specular_with_receiver for one (receiver, radiance SG) pair, the receiver formed here. The
// test below the surface comes first so that callers that shade per pair do not build the ASG
// for lights behind it (the result is the same: 0).
fn vsgl_specular(radiance: Sg, normal: vec3f, w_o: vec3f, alpha: f32) -> f32 {
    if (dot(normal, radiance.axis) <= 0.0 || dot(normal, w_o) <= 0.0) {
        return 0.0;
    }
    return vsgl_specular_with_receiver(radiance, vsgl_specular_receiver_from(normal, w_o, alpha));
}

// Bounds of α² in the filtered NDF of vsgl_specular_accurate. MIN: GGX_ALPHA_MIN², so √det Σ'
// ≥ 1e-8 and (n·h)⁴(…)² stay inside f32 (ggx_d's own smallest α). MAX: the widening stops at
// α'² = 1, where GGX is D = 1/π for every microfacet normal of the hemisphere; beyond it the
// linearized Jacobian (valid for lights narrower than the lobe) would move the mass to grazing
// microfacets and send the result to 0 as λ → 0, whereas the exact value tends to c_in times the
// directional albedo. (An α given above 1 is kept: the cap is max(α², 1).)
const VSGL_FILTERED_ALPHA2_MIN: f32 = 1.0e-8;
const VSGL_FILTERED_ALPHA2_MAX: f32 = 1.0;
// Largest 1/‖ξ + ω_o‖ in vsgl_specular_accurate, so ‖m‖ = tan θ_d·‖n × e_∥‖ ≤ 2·5e8 = 1e9 and the
// squares of B's entries (≤ ~1e36) stay finite in f32. It binds only for ξ within 2e-9 of −ω_o
// (both on the horizon), where B's large eigenvalue ~‖m‖² is capped anyway (‖m‖²/(2λh_n⁴) ≥ 1e18/
// 2e9 ≫ max(α², 1) for λ ≤ SG_SHARPNESS_MAX), and b₋ = det B/b₊ → h_n² + (h₂ × m̂₂)² does not
// depend on ‖m‖ (found by the stability suite: ξ = −ω_o on the horizon overflowed to FLT_MAX).
const VSGL_FILTERED_INV_HALF_LENGTH_MAX: f32 = 5.0e8;

// Specular reflected radiance over R_s for the GGX BRDF (Fresnel = 1), the accurate SG lighting
// (lighting="accurate", after the filtered-NDF idea of Tokuyoshi et al. 2024, "Hierarchical
// Light Sampling with Accurate Spherical Gaussian Lighting"; the formulas below are derived for
// vsgl, the paper is not in seeds):
//   L_s ≈ c_in A(λ) D'(h) G2'(ξ, ω_o)/(4 n·ω_o),   h = (ξ + ω_o)/‖ξ + ω_o‖,
// D' = GGX with the slope covariance widened by the light's spread, Σ' = α²I + (2/λ)JJᵀ, and G2'
// the height-correlated Smith G2 of that widened microsurface (filtered_alpha_along).
// Derivation. ∫ c G(ω) f(ω, ω_o)(n·ω) dω = c ∫ G(ω) D(h(ω)) G2/(4 n·ω_o) dω; G2/(4 n·ω_o) varies
// slowly and is taken at ω = ξ. Change variables to the slope s = h_t/h_n of h (t, b tangent):
// dω = |∂ω/∂s| d²s, and D(h) = p(s)/h_n⁴ with p the slope density (D(m)(n·m)dω_m = p(s)d²s,
// dω_m = h_n³ d²s). For a sharp light, G(ω(s))|∂ω/∂s| = A(λ) k(s), k the density of the slope of
// h when ω ~ G/A: a normal density around s(ξ) with covariance (1/λ)JJᵀ, J = ∂s/∂ω at ξ (the SG
// is a normal density of tangent variance 1/λ per axis). So the integral is
// c A(λ) ∫ k(s) p(s)/h_n⁴ d²s ≈ c A(λ)/h_n(ξ)⁴ · (p ⊛ N(0, JJᵀ/λ))(s(ξ)): with the slope density
// read as a normal one of covariance α²/2·I (the matching behind λh = 2/α², ggx_ndf_sg_sharpness)
// the convolution has covariance ½(α²I + (2/λ)JJᵀ) = ½Σ', and it is put back into GGX form:
//   D'(h) = 1/(π √det Σ' (h_n² + h₂ᵀΣ'⁻¹h₂)²),  h₂ = (h·t, h·b)
// (the anisotropic GGX NDF with slope covariance Σ', normalized for any SPD Σ'; Σ' = α²I gives
// ggx_d). As λ → ∞, Σ' → α²I and the form is the exact point-light value c A(λ) f (n·ξ).
// The Jacobian. h = u/‖u‖, u = ξ + ω_o. Moving ξ by a tangent vector δ moves h by
// (I − hhᵀ)δ/‖u‖, ‖u‖ = 2 h·ω_o: a move e_∥ within the plane of incidence moves h by e_∥/2
// (its projection onto h's tangent plane has length h·ξ = h·ω_o), a move e_⊥ across it by
// e_⊥/(2 h·ω_o) (|∂h/∂ω| = 1/(4 h·ω_o), the Jacobian of the half vector). The slope map moves by
// ∂s = (T − s nᵀ)∂h/h_n, whose value on a unit e ⊥ h is the tangent part of n × (e × h)/h_n²,
// and e × h maps e_∥ ↦ ±e_⊥, e_⊥ ↦ ±e_∥. Summing the two outer products, with
// (n×e_⊥)(n×e_⊥)ᵀ + (n×e_∥)(n×e_∥)ᵀ = (n×)(I − hhᵀ)(n×)ᵀ = Π − (n×h)(n×h)ᵀ and
// 1/(h·ω_o)² − 1 = tan²θ_d = ‖ξ − ω_o‖²/‖ξ + ω_o‖², e_∥ = (ξ − ω_o)/‖ξ − ω_o‖:
//   JJᵀ = B/(4h_n⁴),  B = Π − (n×h)(n×h)ᵀ + mmᵀ,  m = n × (ξ − ω_o)/‖u‖,
// and in tangent coordinates (n×h has coordinates (−h_b, h_t)) B = h_n²I + h₂h₂ᵀ + m₂m₂ᵀ: a sum
// of positive terms, no cancellation, and no frame of the plane of incidence is needed (at
// ξ = ω_o, m = 0 and B = h_n²I + h₂h₂ᵀ, isotropic in the sphere as it must be). The oracle test
// filtered_slope_covariance_is_the_reflection_jacobian checks it against finite differences.
// det B = h_n⁴ + h_n²(‖h₂‖² + ‖m₂‖²) + (h₂ × m₂)² (= h_n²/(h·ω_o)², positive terms again).
// Cap (VSGL_FILTERED_ALPHA2_MAX): in the eigenbasis of B, σ± = min(α² + b±/(2λh_n⁴), max(α², 1)).
// Masking. D' is the NDF of a (rougher) microsurface, and only with that surface's own masking G1'
// does it keep the projected-area identity ∫ D'(m) G1'(ω_o, m) max(ω_o·m, 0) dm = n·ω_o; with the
// unwidened G2 a broad light at grazing view came out up to 10× too bright (n·ω_o = 0.05, λ ≤ 30,
// measured by the oracle test). So G2' uses Smith Λ with α(ω)² = ω̂₂ᵀΣ'ω̂₂; as λ → ∞ it is G2.
// Accuracy against the exact GGX integral (oracle test vsgl_specular_accurate_vs_quadrature, α
// 0.05…0.5, view angles 0…1.52 rad): see docs/methods/vsgl.md "SG lighting" for the table.
// Zero when the light axis or the view is below the surface (as vsgl_specular).
fn vsgl_specular_accurate(radiance: Sg, normal: vec3f, w_o: vec3f, alpha: f32) -> f32 {
    return vsgl_specular_filtered(radiance, normal, w_o, alpha).x;
}

// vsgl_specular_accurate's value (x) and the receiver's share of the widened lobe (y), α/α' with
// α'⁴ = σ₊σ₋ = det Σ' (the widened lobe's geometric-mean roughness): 1 for a point light, → 0 when
// the light's spread dominates. vsgl_specular_blend weights the two forms by it. (0, 1) below the
// surface.
fn vsgl_specular_filtered(radiance: Sg, normal: vec3f, w_o: vec3f, alpha: f32) -> vec2f {
    let n_dot_l = dot(normal, radiance.axis);
    let n_dot_v = dot(normal, w_o);
    if (n_dot_l <= 0.0 || n_dot_v <= 0.0) {
        return vec2f(0.0, 1.0);
    }
    let u = radiance.axis + w_o;
    let u_len2 = dot(u, u);
    let h = safe_normalize(u, normal);
    let frame = orthonormal_basis(normal);
    let h_n = dot(h, normal);
    let h2 = vec2f(dot(h, frame[0]), dot(h, frame[1]));
    let m_full = cross(normal, radiance.axis - w_o) * min(inverseSqrt(max(u_len2, FLT_MIN)), VSGL_FILTERED_INV_HALF_LENGTH_MAX);
    let m2 = vec2f(dot(m_full, frame[0]), dot(m_full, frame[1]));
    let h_n2 = h_n * h_n;
    let b_tt = h_n2 + h2.x * h2.x + m2.x * m2.x;
    let b_bb = h_n2 + h2.y * h2.y + m2.y * m2.y;
    let b_tb = h2.x * h2.y + m2.x * m2.y;
    let cross2 = h2.x * m2.y - h2.y * m2.x;
    let det_b = h_n2 * h_n2 + h_n2 * (dot(h2, h2) + dot(m2, m2)) + cross2 * cross2;
    let half_diff = 0.5 * (b_tt - b_bb);
    let b_plus = 0.5 * (b_tt + b_bb) + sqrt(half_diff * half_diff + b_tb * b_tb);
    let b_minus = det_b / max(b_plus, FLT_MIN);
    // Eigenvector of b₊: the larger of the two (equivalent) forms; B ∝ I leaves any direction.
    let v1 = vec2f(b_tb, b_plus - b_tt);
    let v2 = vec2f(b_plus - b_bb, b_tb);
    let n1 = dot(v1, v1);
    let n2 = dot(v2, v2);
    var e = vec2f(1.0, 0.0);
    if (max(n1, n2) > FLT_MIN) {
        e = select(v2 * inverseSqrt(n2), v1 * inverseSqrt(n1), n1 >= n2);
    }
    let a2 = max(alpha * alpha, VSGL_FILTERED_ALPHA2_MIN);
    let cap = max(a2, VSGL_FILTERED_ALPHA2_MAX);
    // b/(2λh_n⁴), formed as min(b, cap·den)/den so it stays finite for λ → 0 or h_n → 0.
    let den = max(2.0 * radiance.sharpness * h_n2 * h_n2, FLT_MIN);
    let s_plus = min(a2 + min(b_plus, cap * den) / den, cap);
    let s_minus = min(a2 + min(b_minus, cap * den) / den, cap);
    let y_plus = dot(h2, e);
    let y_minus = h2.y * e.x - h2.x * e.y;
    let q = h_n2 + y_plus * y_plus / s_plus + y_minus * y_minus / s_minus;
    let d = 1.0 / (PI * sqrt(s_plus * s_minus) * q * q);
    // G2' of the widened microsurface: Smith Λ with α(ω)² = ω̂₂ᵀΣ'ω̂₂ along each direction's
    // azimuth — the α of anisotropic GGX's Λ [Heitz 2014, §5.3: α_φ² = α_x²cos²φ + α_y²sin²φ, the
    // same quadratic form]. At ω = n the azimuth is undefined and Λ = 0 whatever α: α is kept.
    var alpha_lv = vec2f(alpha);
    for (var k = 0; k < 2; k++) {
        let w = select(w_o, radiance.axis, k == 0);
        let w2 = vec2f(dot(w, frame[0]), dot(w, frame[1]));
        let len2 = dot(w2, w2);
        if (len2 > FLT_MIN) {
            let wp = dot(w2, e);
            let wm = w2.y * e.x - w2.x * e.y;
            alpha_lv[k] = sqrt((s_plus * wp * wp + s_minus * wm * wm) / len2);
        }
    }
    let g2 = 1.0 / (1.0 + ggx_smith_lambda(n_dot_l, alpha_lv.x) + ggx_smith_lambda(n_dot_v, alpha_lv.y));
    let value = min(radiance.amplitude * sg_integral(radiance.sharpness) * d * g2 / (4.0 * n_dot_v), FLT_MAX);
    // σ± ≥ a2 (the widening is ≥ 0), so the share is ≤ 1; one inverseSqrt per σ keeps σ₊σ₋ in range.
    let receiver_share = min(sqrt(a2 * inverseSqrt(s_plus) * inverseSqrt(s_minus)), 1.0);
    return vec2f(value, receiver_share);
}

// Specular reflected radiance over R_s, lighting="blend": the filtered-NDF form
// (vsgl_specular_accurate) and the papers' SG–ASG product (vsgl_specular) weighted by the
// receiver's share w = α/α' of the filtered lobe (vsgl_specular_filtered):
//   L_s ≈ w·L_filtered + (1 − w)·L_ASG.
// Why: each form fails where the other holds. The filtered form is exact for a point light and
// good while the light is narrower than the lobe (w → 1), but over-lights a sharp receiver under a
// broad light; the ASG product is good there (both lobes near-Gaussian, w → 0) but, being a
// small-angle warp of the NDF, loses 27–63% of a rough lobe's light from the hemisphere
// (α ≥ 0.5, even for point lights). w is a measured choice, not a derivation: over light axes on
// the whole hemisphere (oracle test specular_forms_over_the_hemisphere) its summed L1 error is
// 0.68× the better single form's (4.85 against 7.10); docs/methods/vsgl.md, "SG lighting", has the
// table.
fn vsgl_specular_blend(radiance: Sg, normal: vec3f, w_o: vec3f, alpha: f32) -> f32 {
    if (dot(normal, radiance.axis) <= 0.0 || dot(normal, w_o) <= 0.0) {
        return 0.0;
    }
    return vsgl_specular_blend_with_receiver(radiance, vsgl_specular_receiver_from(normal, w_o, alpha));
}

// vsgl_specular_blend with the receiver formed once per pixel (vsgl_specular_receiver_from); the
// ASG product is skipped where the filtered form has all the weight.
fn vsgl_specular_blend_with_receiver(radiance: Sg, receiver: VsglSpecularReceiver) -> f32 {
    let filtered = vsgl_specular_filtered(radiance, receiver.n, receiver.w_o, receiver.alpha);
    if (filtered.y >= 1.0) {
        return filtered.x;
    }
    return filtered.y * filtered.x + (1.0 - filtered.y) * vsgl_specular_with_receiver(radiance, receiver);
}
