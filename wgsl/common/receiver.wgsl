// The receiving surface a shading pass evaluates at one pixel, from the camera G-buffer (the
// including shader declares the bindings gbuf_position, gbuf_normal, gbuf_geo_normal and
// gbuf_base_color). Pixels outside the image or without a surface get has_surface = false and
// harmless values, so every thread of a workgroup can still take part in its barriers.
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

fn load_receiver(index: u32, inside: bool) -> Receiver {
    var r = Receiver(vec3f(0.0), vec3f(0.0, 0.0, 1.0), vec3f(0.0, 0.0, 1.0), vec3f(0.0), vec3f(0.0), 1.0, false);
    if (!inside) {
        return r;
    }
    let pos = gbuf_position[index];
    if (pos.w == GBUFFER_BACKGROUND) {
        return r;
    }
    r.has_surface = true;
    r.p = pos.xyz;
    r.n = gbuf_normal[index].xyz;
    r.alpha = ggx_alpha_from_roughness(gbuf_normal[index].w);
    let metallic = gbuf_geo_normal[index].w;
    let base = gbuf_base_color[index].rgb;
    r.rd = gbuffer_diffuse_reflectance(base, metallic);
    r.rs = gbuffer_specular_reflectance(base, metallic, gbuf_base_color[index].w);
    r.v = -r.p / max(length(r.p), FLT_MIN);
    return r;
}
