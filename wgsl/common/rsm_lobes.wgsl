// The two lobes of one RSM texel as the VSGL moments need them [Tok15 §4.1; Tok16 §4.1]: the
// Toksvig mean directions ξ̄ of the Lambert lobe SG and of the GGX lobe SG (spherical warping
// towards the light), shared by vsgl_moments.wgsl (many VSGLs) and vsgl2_moments.wgsl (two).
#include "common/sg.wgsl"
#include "common/ggx.wgsl"
#include "common/math.wgsl"
#include "common/plan.wgsl"
#include "common/constants.wgsl"
#include "common/rsm_texel.wgsl"

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

