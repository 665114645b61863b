// The two lobes of one RSM texel as the VSGL moments need them [Tok15 §4.1; Tok16 §4.1]: the
// Toksvig mean directions ξ̄ of the Lambert lobe SG and of the GGX lobe SG (spherical warping
// towards the light), shared by vsgl_moments.wgsl (many VSGLs) and vsgl2_moments.wgsl (two).
#include "common/sg.wgsl"
#include "common/ggx.wgsl"
#include "common/math.wgsl"
#include "common/plan.wgsl"
#include "common/constants.wgsl"

struct RsmLobeMeans {
    diffuse: vec3f,
    specular: vec3f,
}

// `y`: texel position relative to the light; `normal`: unit; `roughness`: perceptual;
// `light_dir`: (direction, 1) for a directional light, whose light arrives from −direction at
// every texel (y is then relative to its RSM's image plane and says nothing of it); w = 0 for a
// spot or point light, lit from −y.
fn rsm_lobe_means(y: vec3f, normal: vec3f, roughness: f32, light_dir: vec4f) -> RsmLobeMeans {
    let lobe_d = lambert_lobe_sg(normal);
    var out = RsmLobeMeans(sg_toksvig_mean_direction(lobe_d.axis, lobe_d.sharpness), vec3f(0.0));
    // Without specular materials w_s = 0: the GGX lobe fit would be multiplied by 0.
    if (HAS_SPECULAR) {
        var to_light = safe_normalize(-y, normal);
        if (light_dir.w != 0.0) {
            to_light = -light_dir.xyz;
        }
        let lobe_s = ggx_lobe_sg(normal, to_light, ggx_alpha_from_roughness(roughness));
        out.specular = sg_toksvig_mean_direction(lobe_s.axis, lobe_s.sharpness);
    }
    return out;
}

// A texel is not a point but a patch of the surface. Its cross-section
// perpendicular to the light is a square of side a, a² = Δω·d² (perspective, Δω the texel's
// solid angle, as in rsm_flux.wgsl) or (2R/N)² (orthographic); on a surface tilted by θ to the
// light it is stretched by 1/cos θ along one axis. A uniform a × a/cos θ rectangle has
// positional variance (a² + a²/cos²θ)/12 (summed over its two axes), which the texel adds to
// Σw‖y‖² so that a single-texel cluster is an area light of the texel's size, not a point.
// cos θ is floored at 0.1: a grazing texel's footprint is long, but not unbounded.
const FOOTPRINT_COS_MIN: f32 = 0.1;

// `light_dir` as rsm_lobe_means takes it; `texel_footprint`: LightRsm::texel_footprint, (view
// axis, t²(2/N)²) of a perspective RSM, (0, (2R/N)²) of an orthographic one; zeros: a point.
fn rsm_texel_footprint_variance(y: vec3f, normal: vec3f, light_dir: vec4f, texel_footprint: vec4f) -> f32 {
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
    let cos_surface = max(abs(dot(normal, to_light)), FOOTPRINT_COS_MIN);
    return cross_section * (1.0 + 1.0 / (cos_surface * cos_surface)) / 12.0;
}
