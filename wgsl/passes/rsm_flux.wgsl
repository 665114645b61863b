// Reflective shadow map flux (compute): after the material pass has resolved the light's view
// into an RSM G-buffer (positions relative to the light), give every texel the flux it
// receives and the reflected power weights Φ·R_d, Φ·R_s [Dachsbacher & Stamminger 2005].
//   Φ_texel = I · color · cone(ω) · Δω,  Δω = t² (2/N)² cos³θ
// where t = tan(half field of view), N the RSM side and θ the angle to the light axis: the solid
// angle of a texel of a perspective image plane at unit distance (area t²(2/N)², foreshortened
// by cosθ and at distance 1/cosθ). A point light has six such images (cube faces, t = 1,
// cone = 1) whose texels together cover the sphere: Σ Δω = 4π, so the flux sums to 4π·I.
// A directional light (illuminance E in lux) has one orthographic RSM whose rays are parallel
// to the light: a texel is a patch of area ΔA = (2R/N)² of the plane perpendicular to the light
// (R the half-width of the image plane), through which the flux
//   Φ_texel = E · color · ΔA
// reaches the receiver (the perpendicular cross-section, not the receiver's foreshortened area:
// no cos θ_receiver term, as no 1/cos appears in the perspective case either). The RSM covers the
// scene's bounding sphere, so the flux sums to E·(cross-section of the lit geometry).
#include "common/constants.wgsl"
#include "common/frame.wgsl"
#include "common/gbuffer.wgsl"
#include "common/plan.wgsl"

// SAMPLING_WEIGHTS = false: the method samples nothing from the RSM (`vsgl2` sums it, the
// reference takes every texel), so no level 0 of the weight pyramid is written.
override SAMPLING_WEIGHTS: bool = true;

const WORKGROUP: u32 = 8u;

@group(0) @binding(0) var<uniform> view: FrameUniforms;
@group(1) @binding(0) var<storage, read> light: LightRaw;
@group(1) @binding(1) var<storage, read> rsm_position: array<vec4f>;
@group(1) @binding(2) var<storage, read> rsm_geo_normal: array<vec4f>;
@group(1) @binding(3) var<storage, read> rsm_base_color: array<vec4f>;
// Φ·R_d (rgb), w = Φ·(R_d + R_s) summed over rgb: the sampling weight.
@group(1) @binding(4) var<storage, read_write> rsm_flux_diffuse: array<vec4f>;
// Φ·R_s (rgb), w unused.
@group(1) @binding(5) var<storage, read_write> rsm_flux_specular: array<vec4f>;
// Level 0 of the sampling-weight pyramid.
@group(1) @binding(6) var<storage, read_write> pdf_level0: array<f32>;

// Φ_texel of a perspective RSM (spot light, point light cube face): see the top.
fn perspective_texel_flux(xy: vec2u, n: u32) -> vec3f {
    // The texel's ray, unnormalised: forward + ndc.x·right·t + ndc.y·up·t; cosθ = 1/‖ray‖.
    let pixel = vec2f(xy) + 0.5;
    let ndc = vec2f(2.0 * pixel.x / f32(n) - 1.0, 1.0 - 2.0 * pixel.y / f32(n));
    let ray = view.cam_forward.xyz + ndc.x * view.cam_right.xyz + ndc.y * view.cam_up.xyz;
    let inv_len = inverseSqrt(dot(ray, ray));
    let cos_theta = dot(ray, view.cam_forward.xyz) * inv_len;
    let tan2 = dot(view.cam_up.xyz, view.cam_up.xyz);
    let texel = 2.0 / f32(n);
    let solid_angle = tan2 * texel * texel * cos_theta * cos_theta * cos_theta;
    let to_light = -ray * inv_len;
    // A point light's RSM is one of its six 90° cube faces (t = 1): no cone; an emitter
    // cluster's cube faces take its cosine lobe.
    return light.intensity * light.color * light_lobe(light, to_light) * solid_angle;
}

@compute @workgroup_size(WORKGROUP, WORKGROUP, 1)
fn main(@builtin(global_invocation_id) gid: vec3u) {
    let n = view.size.x;
    if (gid.x >= n || gid.y >= n) {
        return;
    }
    let index = gid.y * n + gid.x;
    let pos = rsm_position[index];
    if (pos.w == GBUFFER_BACKGROUND) {
        rsm_flux_diffuse[index] = vec4f(0.0);
        if (HAS_SPECULAR) {
            rsm_flux_specular[index] = vec4f(0.0);
        }
        if (SAMPLING_WEIGHTS) {
            pdf_level0[index] = 0.0;
        }
        return;
    }
    var flux: vec3f;
    if (view.orthographic != 0u) {
        // cam_right, cam_up: the image plane's half-widths R; the texel is (2R/N)² of it.
        let texel = 2.0 / f32(n);
        let area = length(view.cam_right.xyz) * length(view.cam_up.xyz) * texel * texel;
        flux = light.intensity * light.color * area;
    } else {
        flux = perspective_texel_flux(gid.xy, n);
    }
    let base = rsm_base_color[index].rgb;
    let metallic = rsm_geo_normal[index].w;
    let fd = flux * gbuffer_diffuse_reflectance(base, metallic);
    var fs = vec3f(0.0);
    if (HAS_SPECULAR) {
        fs = flux * gbuffer_specular_reflectance(base, metallic, rsm_base_color[index].w);
        rsm_flux_specular[index] = vec4f(fs, 0.0);
    }
    let weight = fd.r + fd.g + fd.b + fs.r + fs.g + fs.b;
    rsm_flux_diffuse[index] = vec4f(fd, weight);
    if (SAMPLING_WEIGHTS) {
        pdf_level0[index] = weight;
    }
}
