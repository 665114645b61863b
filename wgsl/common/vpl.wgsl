// Virtual point lights (VPLs) sampled from a reflective shadow map [Dachsbacher & Stamminger
// 2005; Tokuyoshi 2015 §3.1.1]: VPL i has radiant intensity
//   I_i(ω) = Φ_i ρ(x_i, ω'_i, ω) ⟨ω, n_i⟩                        [Tok15, §3.1.1, first equation]
// split into a Lambert part (Φ R_d / π) and a GGX part (Φ R_s · D G / (4 cos cos)).
#include "common/constants.wgsl"
#include "common/ggx.wgsl"
#include "common/plan.wgsl"

// 80 bytes; the twin is `VplRaw` in crates/vsgl-core/src/passes/vpl_sample.rs.
struct Vpl {
    // Relative to the frame origin (the camera).
    position: vec3f,
    roughness: f32,
    normal: vec3f,
    _pad0: f32,
    // Φ·R_d / (N p) and Φ·R_s / (N p): the estimator weights (the RSM texel's flux times the
    // reflectances, divided by the sample count and the sampling probability).
    flux_diffuse: vec3f,
    _pad1: f32,
    flux_specular: vec3f,
    _pad2: f32,
    // Unit direction from the VPL towards the spot light (−ω'_i).
    to_light: vec3f,
    _pad3: f32,
}

struct VplRadiance {
    diffuse: vec3f,
    specular: vec3f,
}

// Reflected radiance towards `v` at a receiver (position p, normal n, reflectances rd, rs, GGX α)
// from one VPL, without visibility:
//   L = f_r(x; ω, v) ⟨n, ω⟩ I_vpl(−ω) / d²,  ω = (x_vpl − p)/d.
// `min_distance2` bounds d² from below (0 = no clamping, the unbiased default).
fn vpl_radiance(vpl: Vpl, p: vec3f, n: vec3f, v: vec3f, rd: vec3f, rs: vec3f, alpha: f32, min_distance2: f32) -> VplRadiance {
    var out = VplRadiance(vec3f(0.0), vec3f(0.0));
    let to_vpl = vpl.position - p;
    let dist2 = dot(to_vpl, to_vpl);
    // A VPL exactly at the receiver has no defined direction: it contributes nothing (the two
    // cosines vanish on the surface it lies on anyway).
    if (dist2 <= FLT_MIN) {
        return out;
    }
    let w = to_vpl * inverseSqrt(dist2);
    let cos_receiver = dot(n, w);
    let cos_vpl = -dot(vpl.normal, w);
    if (cos_receiver <= 0.0 || cos_vpl <= 0.0) {
        return out;
    }
    let alpha_vpl = ggx_alpha_from_roughness(vpl.roughness);
    // Radiant intensity of the VPL towards the receiver, per unit Φ·R: Lambert and GGX lobes.
    // HAS_SPECULAR = false: R_s = 0 at every VPL and receiver, both GGX terms are exactly 0.
    var intensity = vpl.flux_diffuse * INV_PI * cos_vpl;
    if (HAS_SPECULAR) {
        intensity += vpl.flux_specular * ggx_brdf_over_rs(vpl.normal, vpl.to_light, -w, alpha_vpl) * cos_vpl;
    }
    let e = intensity * (cos_receiver / max(dist2, min_distance2));
    out.diffuse = rd * INV_PI * e;
    if (HAS_SPECULAR) {
        out.specular = rs * ggx_brdf_over_rs(n, w, v, alpha) * e;
    }
    return out;
}
