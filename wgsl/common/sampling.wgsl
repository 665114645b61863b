// Random numbers and BRDF sampling for the path tracer: a PCG generator, cosine-weighted
// hemisphere sampling and GGX visible-normal (VNDF) sampling with its pdf. Pure functions.
// Directions are in a local frame with the surface normal along +z (see orthonormal_basis in
// common/math.wgsl); α is the GGX roughness α = roughness² (common/ggx.wgsl).
#include "common/constants.wgsl"
#include "common/ggx.wgsl"

// ---- Random numbers -------------------------------------------------------------------------

// PCG-RXS-M-XS 32/32 [O'Neill 2014, "PCG: A Family of Simple Fast Space-Efficient Statistically
// Good Algorithms for Random Number Generation", §6.3.4], used as a hash as recommended by
// Jarzynski & Olano 2020, "Hash Functions for GPU Rendering", JCGT 9(3) ("pcg").
// The constants are the published LCG multiplier/increment and output multiplier.
fn rng_hash(x: u32) -> u32 {
    let state = x * 747796405u + 2891336453u;
    let word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// A generator state for one (pixel, sample, seed) triple. Each sample has its own stream, so an
// image depends only on the seed and the sample count, not on how samples are batched.
fn rng_init(pixel: u32, sample: u32, seed: u32) -> u32 {
    return rng_hash(pixel ^ rng_hash(sample ^ rng_hash(seed)));
}

// Next 32 random bits: advance the LCG, permute the output (PCG-RXS-M-XS).
fn rng_next(state: ptr<function, u32>) -> u32 {
    let s = *state;
    *state = s * 747796405u + 2891336453u;
    let word = ((s >> ((s >> 28u) + 4u)) ^ s) * 277803737u;
    return (word >> 22u) ^ word;
}

// Uniform in [0, 1): the top 24 bits scaled by 2^-24, so 1.0 is never returned.
fn rng_uniform(state: ptr<function, u32>) -> f32 {
    return f32(rng_next(state) >> 8u) * 5.9604644775390625e-8;
}

// ---- Cosine-weighted hemisphere ------------------------------------------------------------

// Direction with pdf cosθ/π about +z [Malley's method: uniform disk sample projected up;
// Pharr, Jakob & Humphreys, PBRT 4th ed., §A.5.3]. The disk is sampled in polar form
// r = √u1, φ = 2π u2, which is area-uniform.
fn sample_cosine_hemisphere(u1: f32, u2: f32) -> vec3f {
    let r = sqrt(u1);
    let phi = TWO_PI * u2;
    // z = √(1 − r²) = √(1 − u1): no cancellation concern, u1 is exact.
    return vec3f(r * cos(phi), r * sin(phi), sqrt(max(1.0 - u1, 0.0)));
}

fn cosine_hemisphere_pdf(cos_theta: f32) -> f32 {
    return max(cos_theta, 0.0) * INV_PI;
}

// ---- GGX visible normals [Heitz 2018] -------------------------------------------------------

// A microfacet normal h about +z distributed as the visible normals D_v(h) for the view
// direction v (unit, v.z > 0) [Heitz 2018, "Sampling the GGX Distribution of Visible Normals",
// JCGT 7(4), Listing 1]: stretch v to the hemisphere configuration (α = 1), sample the projected
// disk with the half-disk warp, project back onto the hemisphere and unstretch.
fn sample_ggx_vndf(v: vec3f, alpha: f32, u1: f32, u2: f32) -> vec3f {
    // Section 3.2: the view direction in the hemisphere configuration.
    let vh = normalize(vec3f(alpha * v.x, alpha * v.y, v.z));
    // Section 4.1: an orthonormal basis around vh (any T1 when vh = +z).
    let lensq = vh.x * vh.x + vh.y * vh.y;
    let t1 = select(vec3f(1.0, 0.0, 0.0), vec3f(-vh.y, vh.x, 0.0) * inverseSqrt(lensq), lensq > 0.0);
    let t2 = cross(vh, t1);
    // Section 4.2: a point on the projected area, uniform on the disk, then warped so the
    // lower half covers only the visible part of the ellipse.
    let r = sqrt(u1);
    let phi = TWO_PI * u2;
    let p1 = r * cos(phi);
    var p2 = r * sin(phi);
    let s = 0.5 * (1.0 + vh.z);
    p2 = (1.0 - s) * sqrt(max(1.0 - p1 * p1, 0.0)) + s * p2;
    // Section 4.3: reproject onto the hemisphere.
    let nh = p1 * t1 + p2 * t2 + sqrt(max(1.0 - p1 * p1 - p2 * p2, 0.0)) * vh;
    // Section 3.4: back to the ellipsoid configuration (the max keeps h in the upper hemisphere
    // under rounding).
    return normalize(vec3f(alpha * nh.x, alpha * nh.y, max(nh.z, 1.0e-6)));
}

// Smith G1 for GGX: 1 / (1 + Λ(v)) [Heitz 2014, Eq. 43 with Eq. 72 for Λ].
fn ggx_smith_g1(cos_theta: f32, alpha: f32) -> f32 {
    return 1.0 / (1.0 + ggx_smith_lambda(cos_theta, alpha));
}

// Pdf (solid angle) of the reflected direction l = reflect(−v, h) when h is drawn by
// sample_ggx_vndf, for unit n, v, l with n·v > 0:
//   D_v(h) = G1(v) max(0, v·h) D(h) / (n·v)                  [Heitz 2018, Eq. 3]
//   p(l) = D_v(h) / (4 v·h) = G1(v) D(h) / (4 n·v)           [Heitz 2018, Eq. 17]
// Zero when v·h ≤ 0 (such an h is never sampled). Written for any frame (not only local).
fn ggx_vndf_reflection_pdf(n: vec3f, v: vec3f, l: vec3f, alpha: f32) -> f32 {
    let n_dot_v = dot(n, v);
    if (n_dot_v <= 0.0) {
        return 0.0;
    }
    let h_sum = v + l;
    let h_len = length(h_sum);
    if (h_len <= FLT_MIN) {
        return 0.0;
    }
    let h = h_sum / h_len;
    if (dot(v, h) <= 0.0) {
        return 0.0;
    }
    let nxh = cross(n, h);
    let d = ggx_d(max(dot(n, h), 0.0), dot(nxh, nxh), alpha);
    return min(ggx_smith_g1(n_dot_v, alpha) * d / (4.0 * n_dot_v), FLT_MAX);
}
