// The patch of surface one RSM texel stands for: its positional variance (rsm_lobes.wgsl, the
// VSGL moments) and its area (the LPV geometry volume).
#include "common/constants.wgsl"

// A texel is not a point but a patch of the surface. Its cross-section
// perpendicular to the light is a square of side a, a² = Δω·d² (perspective, Δω the texel's
// solid angle, as in rsm_flux.wgsl) or (2R/N)² (orthographic); on a surface tilted by θ to the
// light it is stretched by 1/cos θ along one axis. A uniform a × a/cos θ rectangle has
// positional variance (a² + a²/cos²θ)/12 (summed over its two axes), which the texel adds to
// Σw‖y‖² so that a single-texel cluster is an area light of the texel's size, not a point.
// cos θ is floored at 0.1: a grazing texel's footprint is long, but not unbounded.
const FOOTPRINT_COS_MIN: f32 = 0.1;

// A texel's patch: its cross-section a² perpendicular to the light and the cosine between the
// surface and the light, floored at FOOTPRINT_COS_MIN.
struct TexelPatch {
    cross_section: f32,
    cos_surface: f32,
}

// `light_dir` as rsm_lobe_means takes it; `texel_footprint`: LightRsm::texel_footprint, (view
// axis, t²(2/N)²) of a perspective RSM, (0, (2R/N)²) of an orthographic one; zeros: a point.
fn rsm_texel_patch(y: vec3f, normal: vec3f, light_dir: vec4f, texel_footprint: vec4f) -> TexelPatch {
    var cross_section: f32;
    var to_light: vec3f;
    if (light_dir.w != 0.0) {
        cross_section = texel_footprint.w;
        to_light = -light_dir.xyz;
    } else {
        let d2 = dot(y, y);
        let inv_d = inverseSqrt(max(d2, FLT_MIN));
        let cos_axis = abs(dot(y, texel_footprint.xyz)) * inv_d;
        cross_section = texel_footprint.w * cos_axis * cos_axis * cos_axis * d2;
        to_light = -y * inv_d;
    }
    return TexelPatch(cross_section, max(abs(dot(normal, to_light)), FOOTPRINT_COS_MIN));
}

// The positional variance of the texel's patch (see above).
fn rsm_texel_footprint_variance(y: vec3f, normal: vec3f, light_dir: vec4f, texel_footprint: vec4f) -> f32 {
    let texel = rsm_texel_patch(y, normal, light_dir, texel_footprint);
    let cos_surface = texel.cos_surface;
    return texel.cross_section * (1.0 + 1.0 / (cos_surface * cos_surface)) / 12.0;
}

// The area of the texel's patch on the surface, a²/cos θ.
fn rsm_texel_area(y: vec3f, normal: vec3f, light_dir: vec4f, texel_footprint: vec4f) -> f32 {
    let texel = rsm_texel_patch(y, normal, light_dir, texel_footprint);
    return texel.cross_section / texel.cos_surface;
}
