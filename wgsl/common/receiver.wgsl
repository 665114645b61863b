// The receiving surface a shading pass evaluates at one pixel, from its camera G-buffer texels
// (the including pass reads them from its own bindings). Pixels outside the image or without a
// surface get has_surface = false and harmless values, so every thread of a workgroup can
// still take part in its barriers.
#include "common/constants.wgsl"
#include "common/gbuffer.wgsl"
#include "common/ggx.wgsl"

struct Receiver {
    // Position relative to the eye, shading normal, unit direction towards the eye.
    p: vec3f,
    n: vec3f,
    v: vec3f,
    // Diffuse and specular reflectances, GGX α.
    rd: vec3f,
    rs: vec3f,
    alpha: f32,
    has_surface: bool,
}

// No surface (outside the image).
fn no_receiver() -> Receiver {
    return Receiver(vec3f(0.0), vec3f(0.0, 0.0, 1.0), vec3f(0.0, 0.0, 1.0), vec3f(0.0), vec3f(0.0), 1.0, false);
}

// The receiver of one pixel's G-buffer texels (gbuf_position, gbuf_normal, gbuf_geo_normal,
// gbuf_base_color at the pixel).
fn receiver_from_gbuffer(position: vec4f, normal: vec4f, geo_normal: vec4f, base_color: vec4f) -> Receiver {
    var r = no_receiver();
    if (position.w == GBUFFER_BACKGROUND) {
        return r;
    }
    r.has_surface = true;
    r.p = position.xyz;
    r.n = normal.xyz;
    r.alpha = ggx_alpha_from_roughness(normal.w);
    let metallic = geo_normal.w;
    r.rd = gbuffer_diffuse_reflectance(base_color.rgb, metallic);
    r.rs = gbuffer_specular_reflectance(base_color.rgb, metallic, base_color.w);
    r.v = -r.p / max(length(r.p), FLT_MIN);
    return r;
}
