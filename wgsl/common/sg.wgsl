// Spherical Gaussians (SGs), anisotropic spherical Gaussians (ASGs) and the SG/ASG forms of the
// Lambert and GGX reflection lobes used by VSGLs.
//   SG:  G(ω; ξ, λ) = exp(−½λ‖ω − ξ‖²) = exp(λ(ω·ξ − 1)), axis ξ (unit), sharpness λ ≥ 0.
//   ASG: Ĝ(ω) = max(ω·z, 0)·exp(−ηx(ω·x)² − ηy(ω·y)²), orthonormal frame (x, y, z).
// Sources:
//   [Tok15]  Tokuyoshi 2015, "Virtual Spherical Gaussian Lights for Real-time Glossy Indirect
//            Illumination", CGF 34(7)            (docs/README.md, "Papers")
//   [Tok15s] its supplemental material, App. A–B
//   [Tok16s] supplement of Tokuyoshi 2016, "Modified Filtered Importance Sampling for Virtual
//            Spherical Gaussian Lights", §2–4
//   [XSD13]  Xu et al. 2013, "Anisotropic Spherical Gaussians", ACM TOG 32(6)
// Every function is pure. The f64 twin of each one is in crates/vsgl-core/src/verify/oracle/sg.rs,
// and docs/numerics.md lists every clamp below with its reason.
#include "common/constants.wgsl"
#include "common/math.wgsl"

// Largest SG sharpness anywhere (NDF, warped lobes, λσ of a VSGL). An f32 unit vector is
// rounded to ~2^-24 per component, so −½λ‖ω − ξ‖² carries an absolute error of about
// λ‖ω − ξ‖·1e-7 = √λ·1e-7 at one standard deviation (‖ω − ξ‖ = 1/√λ): 0.3% at λ = 1e9, 3% at
// 1e11. 1e9 is also above every sharpness valid inputs produce at normal incidence
// (λh = 2/α² ≤ 2e8 at GGX_ALPHA_MIN), so it only bites at grazing angles and for
// VSGLs whose variance is below 1e-9 of the squared distance.
const SG_SHARPNESS_MAX: f32 = 1.0e9;

// The cheap integral A(λ) ≈ 2π/λ [IDN12 via Tok16s §4.2] exceeds the exact A(0) = 4π below
// λ = ½; flooring λ there keeps it ≤ 4π (the integral of 1 over the sphere) and finite at 0.
const SG_INTEGRAL_APPROX_SHARPNESS_MIN: f32 = 0.5;

// Below this sharpness the vMF moments (sg_mean_cosine, sg_tangent_second_moment,
// sg_cosine_variance) use their Maclaurin series: the closed forms cancel there
// (coth λ − 1/λ loses ~3/λ² of its digits). Truncation errors at λ = 1 are listed per function.
const SG_MOMENT_SERIES_RADIUS: f32 = 1.0;

// Sharpness λd of the normalized SG that replaces the Lambert lobe max(ω·n,0)/π
// [Tok16s Eq. 1; Tok15s Eq. A.1: "λd ≈ 2, obtained by the least square method"]. The
// least-squares optimum of ∫(max(ω·n,0)/π − G/A(λ))² dω over the sphere is λ = 2.2925, which the
// papers round to 2; the oracle test lambert_lobe_sg_quality recomputes it. Relative L2 error
// 0.187 (0.208 at λ = 2); 9.2% of the lobe's energy lies below the horizon (11.9% at λ = 2).
const LAMBERT_LOBE_SG_SHARPNESS: f32 = 2.2925;

// Largest sharpness recovered from a Toksvig mean direction, λ = r/(1 − r). In f32, r < 1 is
// rounded to ~6e-8 (one ULP below 1) plus a few ULP from the averaging, so the relative error
// of λ is about λ·1.2e-7: 1.2% at 1e5, and r rounds to 1 (λ = ∞) from λ ≈ 1.7e7 on.
// The clamped lobe is still 1/√1e5 ≈ 3e-3 rad wide (a few pixels at 1080p, 60° field of view).
const TOKSVIG_SHARPNESS_MAX: f32 = 1.0e5;

// Largest ASG bandwidth: the counterpart of SG_SHARPNESS_MAX, since an SG is
// exp(−(λ/2)‖ω − ξ‖²), i.e. η = λ/2 in ASG terms.
const ASG_BANDWIDTH_MAX: f32 = 0.5 * SG_SHARPNESS_MAX;

// Below this sin²θo = ‖n × ω_o‖² (θo < 1e-6 rad) ggx_lobe_asg takes the fixed frame around its
// axis: the GGX lobe is isotropic there to f32 precision (ηy/ηx − 1 = tan²θo < 1e-12), while
// n × ω_o is rounding noise (~1e-7 per component) whose direction means nothing. A ratio of unit
// vectors, so no world-unit epsilon.
const ASG_ISOTROPIC_SIN2_MAX: f32 = 1.0e-12;

const INV_SQRT_TWO: f32 = 0.707106781186548;     // 1/√2
const INV_SQRT_TWO_PI: f32 = 0.398942280401433;  // 1/√(2π)

// A scaled SG, amplitude·G(ω; axis, sharpness). The lobe functions below return normalized
// SGs (amplitude = 1/A(λ)); a VSGL lobe carries the radiant intensity c_v; an incoming
// radiance SG carries c_in.
struct Sg {
    axis: vec3f,
    sharpness: f32,
    amplitude: f32,
}

// G(ω; ξ1, λ1)·G(ω; ξ2, λ2) = exp(log_amplitude)·G(ω; axis, sharpness). The amplitude stays in
// log form (≤ 0) so callers can fold it with other factors without under/overflow.
struct SgProduct {
    axis: vec3f,
    sharpness: f32,
    log_amplitude: f32,
}

// ASG frame and bandwidths [XSD13]: Ĝ(ω) = max(ω·z, 0)·exp(−ηx(ω·x)² − ηy(ω·y)²).
struct Asg {
    x_axis: vec3f,
    x_bandwidth: f32,
    y_axis: vec3f,
    y_bandwidth: f32,
    z_axis: vec3f,
}

// SG value [Tok16s §2; Tok15 §2.2]: G(ω; ξ, λ) = exp(−½λ‖ω − ξ‖²).
// The ‖ω − ξ‖² form keeps digits near the axis: ω·ξ − 1 rounds to 0 below ~3e-4 rad
// (√(2·2^-24)), while d = ω − ξ is a difference of nearby floats and exact (Sterbenz).
fn sg_evaluate(dir: vec3f, axis: vec3f, sharpness: f32) -> f32 {
    let d = dir - axis;
    return exp(-0.5 * sharpness * dot(d, d));
}

// SG integral [Tok16s §2]: A(λ) = ∫ G dω = 2π(1 − e^{−2λ})/λ.
// Stable form: 2π(1 − e^{−2λ})/λ = 4π·(e^{−2λ} − 1)/(−2λ) = 4π·expm1_over_x(−2λ): equal to 4π
// at λ = 0, no cancellation for small λ (1 − e^{−2λ} loses all digits below λ ~ 1e-8 in f32),
// 2π/λ for large λ (e^{−2λ} underflows to 0, harmlessly).
fn sg_integral(sharpness: f32) -> f32 {
    return 2.0 * TWO_PI * expm1_over_x(-2.0 * sharpness);
}

// Approximate SG integral A(λ) ≈ 2π/λ for λ not small [Tok16s §4.2 citing Iwasaki et al. 2012],
// with λ floored at SG_INTEGRAL_APPROX_SHARPNESS_MIN (= ½, where 2π/λ reaches A(0) = 4π).
fn sg_integral_approx(sharpness: f32) -> f32 {
    return TWO_PI / max(sharpness, SG_INTEGRAL_APPROX_SHARPNESS_MIN);
}

// Product of two SGs [Tok15 Eq. 5; Tok16s Eq. 7]:
//   G(ω; ξ1, λ1)·G(ω; ξ2, λ2) = exp(λm − λ1 − λ2)·G(ω; ξm, λm),
//   v = λ1ξ1 + λ2ξ2, λm = ‖v‖, ξm = v/λm,
// because λ1(ω·ξ1 − 1) + λ2(ω·ξ2 − 1) = ω·v − λ1 − λ2 = λm(ω·ξm − 1) + (λm − λ1 − λ2).
// Log-amplitude: λm − λ1 − λ2 is a difference of large numbers (for λ ~ 1e6 its f32 error is
// ~0.1 in the exponent). Multiply and divide by λm + λ1 + λ2:
//   λm² − (λ1 + λ2)² = (λ1² + λ2² + 2λ1λ2 ξ1·ξ2) − (λ1² + λ2² + 2λ1λ2)
//                    = −2λ1λ2(1 − ξ1·ξ2) = −λ1λ2‖ξ1 − ξ2‖²      (‖ξ1 − ξ2‖² = 2 − 2ξ1·ξ2),
//   λm − λ1 − λ2 = (λm² − (λ1 + λ2)²)/(λm + λ1 + λ2) = −λ1λ2‖ξ1 − ξ2‖²/(λm + λ1 + λ2).
// Every term is ≥ 0, so nothing cancels; it is evaluated as −λ1·(λ2/(λm + λ1 + λ2))·‖ξ1 − ξ2‖²
// so that λ1λ2 cannot overflow (the ratio is ≤ 1). When λm = 0 (equal opposite lobes, or both
// λ = 0) the product is constant and the axis, returned as the sharper input's, is irrelevant.
fn sg_product(axis1: vec3f, sharpness1: f32, axis2: vec3f, sharpness2: f32) -> SgProduct {
    let v = sharpness1 * axis1 + sharpness2 * axis2;
    let sharpness = length(v);
    let axis = safe_normalize(v, select(axis2, axis1, sharpness1 >= sharpness2));
    let d = axis1 - axis2;
    let ratio = sharpness2 / max(sharpness + sharpness1 + sharpness2, FLT_MIN);
    return SgProduct(axis, sharpness, -sharpness1 * ratio * dot(d, d));
}

// Product integral of two SGs: ∫ G1 G2 dω = exp(λm − λ1 − λ2)·A(λm) (sg_product, sg_integral).
fn sg_product_integral(axis1: vec3f, sharpness1: f32, axis2: vec3f, sharpness2: f32) -> f32 {
    let p = sg_product(axis1, sharpness1, axis2, sharpness2);
    return exp(p.log_amplitude) * sg_integral(p.sharpness);
}

// Mean cosine E[ω·ξ] of the vMF distribution G/A: the Langevin function L(λ) = coth λ − 1/λ
// [Mardia & Jupp 2000, "Directional Statistics", §9.3.2 (mean resultant length, p = 3)].
// λ < 1: Maclaurin series Σ 2^{2n} B_{2n} λ^{2n−1}/(2n)!, n ≤ 8 (truncation 6.5e-9 relative at λ = 1).
// λ ≥ 1: L = (λ − 1 + (1 + λ)e^{−2λ}) / (λ(1 − e^{−2λ})), whose numerator terms are both ≥ 0.
fn sg_mean_cosine(sharpness: f32) -> f32 {
    let x = sharpness;
    if (x < SG_MOMENT_SERIES_RADIUS) {
        let x2 = x * x;
        return x * (1.0 / 3.0 + x2 * (-1.0 / 45.0 + x2 * (2.0 / 945.0 + x2 * (-1.0 / 4725.0
            + x2 * (2.0 / 93555.0 + x2 * (-1382.0 / 638512875.0 + x2 * (4.0 / 18243225.0
            + x2 * (-3617.0 / 162820783125.0))))))));
    }
    let e = exp(-2.0 * x);
    return (x - 1.0 + (1.0 + x) * e) / (x * (1.0 - e)); // 1 − e ≥ 1 − e^{-2}: no cancellation
}

// Second moment E[(ω·t)²] of the vMF distribution along a unit t ⊥ ξ: L(λ)/λ
// (from E[(ω·ξ)²] = 1 − 2L/λ and E[(ω·t)²] = (1 − E[(ω·ξ)²])/2). Series below λ = 1 is the
// Langevin series divided by λ (1/3 at λ = 0).
fn sg_tangent_second_moment(sharpness: f32) -> f32 {
    let x = sharpness;
    if (x < SG_MOMENT_SERIES_RADIUS) {
        let x2 = x * x;
        return 1.0 / 3.0 + x2 * (-1.0 / 45.0 + x2 * (2.0 / 945.0 + x2 * (-1.0 / 4725.0
            + x2 * (2.0 / 93555.0 + x2 * (-1382.0 / 638512875.0 + x2 * (4.0 / 18243225.0
            + x2 * (-3617.0 / 162820783125.0)))))));
    }
    return sg_mean_cosine(x) / x;
}

// Variance Var[ω·ξ] of the vMF distribution: 1/λ² − 1/sinh²λ [Mardia & Jupp 2000, §9.3.2;
// it equals 1 − 2L/λ − L², which cancels to 1/λ² for large λ and must not be used].
// λ < 1: series Σ (2n − 1) 2^{2n} B_{2n} λ^{2n−2}/(2n)!, n ≤ 9 (truncation 1.4e-8 relative at λ = 1).
// λ ≥ 1: 1/λ² − 4e^{−2λ}/(1 − e^{−2λ})² (loses at most ~2 bits, at λ = 1).
fn sg_cosine_variance(sharpness: f32) -> f32 {
    let x = sharpness;
    if (x < SG_MOMENT_SERIES_RADIUS) {
        let x2 = x * x;
        return 1.0 / 3.0 + x2 * (-1.0 / 15.0 + x2 * (2.0 / 189.0 + x2 * (-1.0 / 675.0
            + x2 * (2.0 / 10395.0 + x2 * (-1382.0 / 58046625.0 + x2 * (4.0 / 1403325.0
            + x2 * (-3617.0 / 10854718875.0 + x2 * (87734.0 / 2292899734125.0))))))));
    }
    let e = exp(-2.0 * x);
    let one_minus_e = 1.0 - e; // ≥ 1 − e^{-2}: no cancellation
    return 1.0 / (x * x) - 4.0 * e / (one_minus_e * one_minus_e);
}

// ∫ G(ω; ξ, λ) max(ω·n, 0) dω: the clamped-cosine product integral, the "accurate" diffuse
// option (the papers pull the cosine out instead: vsgl_diffuse, [Tok16s §4.2]).
// Source: derived for vsgl (docs/numerics.md §"Clamped cosine"); not in the papers.
//  1. ∫ G max(ω·n, 0) dω = A(λ)·E[max(t, 0)], t = ω·n, ω ~ vMF(ξ, λ) = G/A.
//  2. Odd part, exact: E[max(t,0)] − E[max(−t,0)] = E[t] = c·L(λ), c = ξ·n.
//  3. t is replaced by a normal variable with t's exact mean m = cL and variance
//     s² = c²·Var[ω·ξ] + (1 − c²)·L/λ. For a normal, E[max(t,0)] = mΦ(m/s) + sφ(m/s)
//     = m/2 + [½m·erf(m/(s√2)) + sφ(m/s)]: the bracket is the even part.
//  4. The even part is scaled by k(λ) so that it is exact at c = ±1, where
//     ½E[|ω·ξ|] = ε1(2 − (1 + λ)ε1)/(4ε2), ε1 = expm1_over_x(−λ), ε2 = expm1_over_x(−2λ)
//     (from ∫ G max(±ω·ξ, 0) dω = 2π(λ − 1 + e^{−λ})/λ² and 2πe^{−λ}(1 − (1 + λ)e^{−λ})/λ²).
//     k → 1.0854 as λ → 0, where the result is then exact (π), and k → 1 for large λ.
// Measured against quadrature (oracle test sg_clamped_cosine_integral_vs_quadrature): the
// error is below 0.9% of A(λ) for all λ and c, and below 1e-3·A(λ) for λ ≥ 30.
// Φ uses erf (Abramowitz–Stegun, |error| ≤ 1.5e-7 absolute); the result is floored at 0 because
// for c → −1, large λ the two terms of mΦ + sφ cancel to ~0.
fn sg_clamped_cosine_integral(axis: vec3f, sharpness: f32, normal: vec3f) -> f32 {
    let c = clamp(dot(axis, normal), -1.0, 1.0);
    let mean_cos = sg_mean_cosine(sharpness);
    let var_axial = sg_cosine_variance(sharpness);
    let var_tangent = sg_tangent_second_moment(sharpness);
    // k(λ): exact even part at c = 1 over the normal model's even part at c = 1.
    let e1 = expm1_over_x(-sharpness);
    let e2 = expm1_over_x(-2.0 * sharpness);
    let even_exact = e1 * (2.0 - (1.0 + sharpness) * e1) / (4.0 * e2);
    let s1 = sqrt(max(var_axial, FLT_MIN));
    let z1 = mean_cos / s1;
    let even_model1 = 0.5 * mean_cos * erf(z1 * INV_SQRT_TWO) + s1 * INV_SQRT_TWO_PI * exp(-0.5 * z1 * z1);
    let k = even_exact / max(even_model1, FLT_MIN);
    // Normal model at c.
    let m = c * mean_cos;
    let s = sqrt(max(c * c * var_axial + (1.0 - c * c) * var_tangent, FLT_MIN)); // 1 − c² ≥ 0: clamped c
    let z = m / s;
    let even_model = 0.5 * m * erf(z * INV_SQRT_TWO) + s * INV_SQRT_TWO_PI * exp(-0.5 * z * z);
    return sg_integral(sharpness) * max(0.5 * m + k * even_model, 0.0);
}

// Toksvig mean direction of a normalized SG [Tok16s §3.1; Tok15 §3.1.1, after Toksvig 2005]:
// ξ̄ = λ/(λ + 1)·ξ. The inverse is sg_from_toksvig_mean_direction.
fn sg_toksvig_mean_direction(axis: vec3f, sharpness: f32) -> vec3f {
    return (sharpness / (sharpness + 1.0)) * axis;
}

// Normalized SG from a (weighted average of) Toksvig mean direction(s) [Tok16s §3.1]:
// ξ = ξ̄/‖ξ̄‖, λ = r/(1 − r), r = ‖ξ̄‖; amplitude 1/A(λ).
// Clamp: λ ≤ TOKSVIG_SHARPNESS_MAX (as r → 1, 1 − r is pure rounding noise in f32; r ≥ 1 from
// rounding also lands there). r = 0 gives λ = 0, a constant lobe whose axis (+z) is irrelevant.
fn sg_from_toksvig_mean_direction(mean_direction: vec3f) -> Sg {
    let r = length(mean_direction);
    let sharpness = min(r / max(1.0 - r, FLT_MIN), TOKSVIG_SHARPNESS_MAX);
    let axis = safe_normalize(mean_direction, vec3f(0.0, 0.0, 1.0));
    return Sg(axis, sharpness, 1.0 / sg_integral(sharpness));
}

// Lambert lobe as a normalized SG [Tok16s Eq. 1; Tok15s Eq. A.1]:
// ρd max(ω·n, 0) = Rd max(ω·n, 0)/π ≈ Rd·G(ω; n, λd)/A(λd), λd = LAMBERT_LOBE_SG_SHARPNESS.
fn lambert_lobe_sg(normal: vec3f) -> Sg {
    return Sg(normal, LAMBERT_LOBE_SG_SHARPNESS, 1.0 / sg_integral(LAMBERT_LOBE_SG_SHARPNESS));
}

// Gain that normalizes the Lambert lobe's SG over the texel's own hemisphere instead of the
// sphere (VSGLs lost 9% of the diffuse light at every N). The papers' lobe
// G(ω; n, λd)/A(λd) [Tok16s Eq. 1] has the integral of ρd max(ω·n, 0) over the *sphere*, but the
// fraction e^{−λd}/(1 + e^{−λd}) of it (9.2% at λd = 2.2925) lies below the texel's plane, where
// a Lambertian texel emits nothing and no receiver of its light lies: that power is lost.
// Normalizing over the upper hemisphere, A_hemi(λ) = 2π(1 − e^{−λ})/λ against
// A(λ) = 2π(1 − e^{−2λ})/λ, multiplies the lobe by A(λd)/A_hemi(λd) = 1 + e^{−λd}
// (for λd = LAMBERT_LOBE_SG_SHARPNESS; tests/test_vsgl.py checks the digits).
const LAMBERT_LOBE_HEMISPHERE_GAIN: f32 = 1.1010136;

// Relative RMS difference over the hemisphere between that hemisphere-normalized Lambert SG and
// max(cos θ, 0)/π (numerical quadrature, tests/test_vsgl.py recomputes it): the SG is 14% too
// high at the normal, 27% too low at 60° and 0.037 instead of 0 at the horizon.
const LAMBERT_LOBE_SG_SHAPE_ERROR: f32 = 0.1562;

// Sharpness of the SG that replaces the peak-normalized NDF [Tok16s §2.1; Tok15s App. A]:
// D(h)/D(n) ≈ G(h; n, λh), λh = 2/α² (Beckmann and GGX). Clamp: α² is floored so that
// λh ≤ SG_SHARPNESS_MAX (and α = 0 stays finite).
fn ggx_ndf_sg_sharpness(alpha: f32) -> f32 {
    return 2.0 / max(alpha * alpha, 2.0 / SG_SHARPNESS_MAX);
}

// GGX specular lobe at a VPL as a normalized SG, by spherical warping [Tok16s §2.1 and Eq. 2;
// Tok15s App. A; after Wang et al. 2009]: ξs = 2(ω'·n)n − ω' (ω' toward the light),
// λs = λh/(4|ω'·n|); Rs·G(ω; ξs, λs)/A(λs) ≈ ρs(ω', ω) max(ω·n, 0).
// ([Tok16s] writes |ξs·n|: the same number, reflection keeps the normal component.)
// Clamp: at grazing incidence |ω'·n| → 0 and λs → ∞; the denominator is floored at
// λh/SG_SHARPNESS_MAX so λs ≤ SG_SHARPNESS_MAX, without forming Inf.
fn ggx_lobe_sg(normal: vec3f, w_in: vec3f, alpha: f32) -> Sg {
    let c = dot(w_in, normal);
    let axis = safe_normalize(2.0 * c * normal - w_in, normal);
    let sharpness_h = ggx_ndf_sg_sharpness(alpha);
    let sharpness = sharpness_h / max(4.0 * abs(c), sharpness_h / SG_SHARPNESS_MAX);
    return Sg(axis, sharpness, 1.0 / sg_integral(sharpness));
}

// ASG value [XSD13; Tok16s §4.2]: Ĝ(ω) = max(ω·z, 0)·exp(−ηx(ω·x)² − ηy(ω·y)²).
fn asg_evaluate(dir: vec3f, asg: Asg) -> f32 {
    let u = dot(dir, asg.x_axis);
    let v = dot(dir, asg.y_axis);
    return max(dot(dir, asg.z_axis), 0.0) * exp(-asg.x_bandwidth * u * u - asg.y_bandwidth * v * v);
}

// GGX lobe at a shading point as an ASG [Tok16s §4.2 / Tok15s App. B, following XSD13's
// warping of the NDF]; ω_o = view direction (toward the eye, the papers' ω_p).
// Derivation (spherical warping, as for ggx_lobe_sg but per axis): the NDF is
// D(h)/D(n) ≈ exp(−½λh δ²) for a tilt δ of h away from n. At the mirror configuration h = n,
// ω = 2(h·ω_o)h − ω_o = ξz. Tilting h by δ within the plane of incidence turns ω by 2δ;
// tilting it by δ perpendicular to that plane turns ω by 2δ(ω_o·n) (h·ω_o is unchanged to
// first order, so ω moves by 2(ω_o·n)·δ). Hence, in ω around ξz:
//   ηx = λh/8                 along x, in the plane of incidence,
//   ηy = λh/(8(ω_o·n)²)       along y = n × ω_o (normalized), perpendicular to it.
// Check: √(ηx·ηy) = λh/(8|ω_o·n|) = λs/2, the isotropic warp of ggx_lobe_sg.
// Clamp: ηy ≤ ASG_BANDWIDTH_MAX at grazing view (denominator floored, no Inf). At normal
// incidence n × ω_o = 0 and ηx = ηy, so any frame around ξz is right.
// Stable frame (both defects below were found by the stability suite, docs/numerics.md):
//  - n × ω_o carries an absolute rounding error of ~1 ULP per component, so near normal view
//    (‖n × ω_o‖ = sin θo → 0) its direction is noise of relative size ULP/sin θo, including a
//    component along z: measured y·z = −2.6e-2 at θo = 3e-7 rad, which for ηy ~ 1e7 moves the
//    lobe's peak off its own axis. One Gram–Schmidt step against z makes y ⊥ z to rounding; the
//    remaining error of y within the tangent plane only matters through ηy − ηx = ηx tan²θo,
//    which vanishes with it. (y − (y·z)z = y exactly in real arithmetic: n × ω_o ⊥ z.)
//  - at ω_o = n exactly, n × ω_o is 0 only without FMA contraction; on an NVIDIA H100 it is
//    rounding noise that can point along z, and the projection then leaves noise (measured
//    y·z = 0.99999996, vsgl_specular 1.9e-22 instead of 1.0). Below ASG_ISOTROPIC_SIN2_MAX the
//    fixed basis around z is used instead (exact there: the lobe is isotropic).
fn ggx_lobe_asg(normal: vec3f, w_o: vec3f, alpha: f32) -> Asg {
    let c = max(dot(w_o, normal), 0.0);
    let z = safe_normalize(2.0 * c * normal - w_o, normal);
    let y_raw = cross(normal, w_o);
    let y_fixed = orthonormal_basis(z)[1];
    var y = y_fixed;
    if (dot(y_raw, y_raw) >= ASG_ISOTROPIC_SIN2_MAX) {
        y = safe_normalize(y_raw - dot(y_raw, z) * z, y_fixed);
    }
    let x = cross(y, z);
    let sharpness_h = ggx_ndf_sg_sharpness(alpha);
    let eta_x = min(0.125 * sharpness_h, ASG_BANDWIDTH_MAX);
    let eta_y = sharpness_h / max(8.0 * c * c, sharpness_h / ASG_BANDWIDTH_MAX);
    return Asg(x, eta_x, y, eta_y, z);
}

// SG–ASG product integral [XSD13 (SG–ASG convolution); Tok16s §4.2 boxed; Tok15s App. B]:
//   ∫ G(ω; ξ, λ) Ĝ(ω) dω ≈ π/√((ηx + ν)(ηy + ν)) · Ĝ(ξ; x, y, z, ηxν/(ηx + ν), ηyν/(ηy + ν)),
//   ν = λ/2 (both lobes as Gaussians in the tangent plane; accurate for sharp lobes).
// ηxν/(ηx + ν) is formed as ηx·(ν/(ηx + ν)) and the square root per factor, so nothing
// overflows at η, ν ~ 1e9.
fn sg_asg_product_integral(sg_axis: vec3f, sg_sharpness: f32, asg: Asg) -> f32 {
    let nu = 0.5 * sg_sharpness;
    let sx = max(asg.x_bandwidth + nu, FLT_MIN);
    let sy = max(asg.y_bandwidth + nu, FLT_MIN);
    let convolved = Asg(asg.x_axis, asg.x_bandwidth * (nu / sx), asg.y_axis, asg.y_bandwidth * (nu / sy), asg.z_axis);
    return PI * inverseSqrt(sx) * inverseSqrt(sy) * asg_evaluate(sg_axis, convolved);
}

// The same product integral divided by the tangent-plane ASG integral π/√(ηx·ηy):
//   Ĝ(ξ; …, ηxν/(ηx + ν), ηyν/(ηy + ν)) / √((1 + ν/ηx)(1 + ν/ηy)).
// This is the SG–ASG product for a normalized ASG lobe; vsgl_specular uses it so that a
// clamped bandwidth cannot change the lobe's energy. Bandwidths are floored at FLT_MIN.
fn sg_asg_product_integral_over_asg_integral(sg_axis: vec3f, sg_sharpness: f32, asg: Asg) -> f32 {
    let nu = 0.5 * sg_sharpness;
    let ex = max(asg.x_bandwidth, FLT_MIN);
    let ey = max(asg.y_bandwidth, FLT_MIN);
    let convolved = Asg(asg.x_axis, ex * (nu / (ex + nu)), asg.y_axis, ey * (nu / (ey + nu)), asg.z_axis);
    return inverseSqrt(1.0 + nu / ex) * inverseSqrt(1.0 + nu / ey) * asg_evaluate(sg_axis, convolved);
}
