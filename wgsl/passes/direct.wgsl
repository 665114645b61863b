// Direct lighting from spot, point and directional lights in compute: Lambert + GGX/Smith
// (Fresnel = 1), KHR_lights_punctual units and falloff (light_incidence in common/frame.wgsl),
// with a 3×3 PCF shadow map lookup: the spot light's perspective map, the point light's cube
// face that sees the point, the directional light's orthographic map over the scene. An emitter
// light (a cluster of emissive triangles, LIGHT_KIND_EMITTER) is shadowed by its cube like a
// point light, and its light is summed over its quadrature points (emitter_radiance).
#include "common/constants.wgsl"
#include "common/frame.wgsl"
#include "common/gbuffer.wgsl"
#include "common/plan.wgsl"
#include "common/ggx.wgsl"

override SHADOWS: bool = true;
// Whether the frame has emitter lights: without, their sum is compiled out.
override HAS_EMITTER_LIGHTS: bool = true;
// Whether this pass lights with the emitter lights (their point sum; emitter_direct="points").
// False: the emitter VSGLs shade their direct light in a pass of their own, and this one leaves
// them out.
override EMITTER_POINT_SUM: bool = true;
const WORKGROUP: u32 = 8u;
// Shadow-map normal offset in shadow texels: (SHADOW_NORMAL_OFFSET_TEXELS +
// SHADOW_SLOPE_OFFSET_TEXELS·sinθ) texel footprints at the receiver's distance from the light
// (θ: angle between the geometric normal and the light), so it scales with the scene (no fixed
// world length). Why the slope term: the 3×3 taps are bilinear comparisons, so they reach
// texel centres up to 2 texels (width t) away from the receiver's projection, where a plane
// tilted by θ lies t·tanθ deeper per texel; a receiver lifted by δ along its normal is δ/cosθ
// nearer to the light than the plane under it, so it is lit by all taps when δ > 2t·sinθ.
// 1.5 + sinθ ≥ 2 sinθ + 0.5 for every θ: half a texel to spare for depth rounding, and the
// 1.5 texels of before at normal incidence. (With 1.5 alone a plane lit at 60° lost up to 7%
// of its light to self-shadowing taps, at 80° 16%.)
const SHADOW_NORMAL_OFFSET_TEXELS: f32 = 1.5;
const SHADOW_SLOPE_OFFSET_TEXELS: f32 = 1.0;

@group(0) @binding(0) var<uniform> frame: FrameUniforms;
@group(1) @binding(0) var<storage, read> lights: array<LightRaw>;
@group(1) @binding(1) var shadow_maps: texture_depth_2d_array;
@group(1) @binding(2) var shadow_sampler: sampler_comparison;
@group(1) @binding(3) var<storage, read> gbuf_position: array<vec4f>;
@group(1) @binding(4) var<storage, read> gbuf_normal: array<vec4f>;
@group(1) @binding(5) var<storage, read> gbuf_geo_normal: array<vec4f>;
@group(1) @binding(6) var<storage, read> gbuf_base_color: array<vec4f>;
@group(1) @binding(7) var<storage, read_write> direct_out: array<vec4f>;

// The points each emitter light's direct light is summed over (upload/emitters.rs,
// POINTS_PER_LIGHT per light from light `first_light` on): position relative to the frame
// origin, and in w the point's share of the light's intensity.
struct EmitterQuadrature {
    first_light: u32,
    points_per_light: u32,
    _pad0: u32,
    _pad1: u32,
    points: array<vec4f>,
}
@group(1) @binding(8) var<storage, read> emitter_quadrature: EmitterQuadrature;

// World size of a shadow texel at the receiver (distance `dist` from the light): perspective
// maps grow with the distance, the directional light's orthographic map does not.
fn shadow_texel_size(light: LightRaw, dist: f32) -> f32 {
    if (light.kind == LIGHT_KIND_DIRECTIONAL) {
        return light.texel_tan;
    }
    return light.texel_tan * dist;
}

// Fraction of the 3×3 PCF footprint that sees the light (1 = lit).
fn shadow_visibility(light: LightRaw, p: vec3f, ng: vec3f, l: vec3f, dist: f32) -> f32 {
    let cos_ng = clamp(dot(ng, l), 0.0, 1.0);
    // A rough sinθ is enough for a bias (no cancellation concern).
    let sin_ng = sqrt(max(1.0 - cos_ng * cos_ng, 0.0));
    let offset = (SHADOW_NORMAL_OFFSET_TEXELS + SHADOW_SLOPE_OFFSET_TEXELS * sin_ng) * shadow_texel_size(light, dist);
    let q = p + ng * offset;
    var ndc: vec3f;
    var layer = light.shadow_layer;
    if (light_has_cube_faces(light)) {
        // The cube face by the dominant axis of the light-to-point vector: it is inside that
        // face's 90° frustum, so uv lies in [0, 1]².
        let d = q - light.position;
        let face = cube_face(d);
        ndc = point_shadow_ndc(light, d, face);
        layer += face;
    } else {
        let clip = light.view_proj * vec4f(q, 1.0);
        if (clip.w <= 0.0) {
            return 0.0;
        }
        ndc = clip.xyz / clip.w;
    }
    let uv = ndc.xy * vec2f(0.5, -0.5) + 0.5;
    if (any(uv < vec2f(0.0)) || any(uv > vec2f(1.0))) {
        // Outside the shadow frustum (only for cones wider than it): unshadowed.
        return 1.0;
    }
    let texel = 1.0 / frame.shadow_size;
    var sum = 0.0;
    for (var y = -1; y <= 1; y++) {
        for (var x = -1; x <= 1; x++) {
            // Reverse-Z: lit when the receiver is at least as near as the stored occluder depth.
            sum += textureSampleCompareLevel(shadow_maps, shadow_sampler, uv + vec2f(f32(x), f32(y)) * texel,
                                             layer, ndc.z);
        }
    }
    return sum / 9.0;
}

// Light reflected towards v at p from emitter light `index` (unshadowed): its patches as
// points, each a point light of its share w_k of the intensity with the emitter's cosine lobe,
//   Σ_k f(l_k, v) ⟨n, l_k⟩ w_k I color max(n_e · (−l_k), 0) / d_k²,
// a midpoint rule for the area integral of the emitted radiance [the area form of the
// rendering equation's direct term, Veach 1997 §8.1] whose error falls with the points'
// spacing squared (1.003 of the form factor under a unit square at height 1 with 64 points; the
// cluster's centre alone, a point light, 1.33).
fn emitter_radiance(light: LightRaw, index: u32, p: vec3f, n: vec3f, ng: vec3f, v: vec3f, rd: vec3f, rs: vec3f, alpha: f32) -> vec3f {
    let base = (index - emitter_quadrature.first_light) * emitter_quadrature.points_per_light;
    var radiance = vec3f(0.0);
    for (var k = 0u; k < emitter_quadrature.points_per_light; k++) {
        let point = emitter_quadrature.points[base + k];
        if (point.w <= 0.0) {
            continue;
        }
        let to_point = point.xyz - p;
        let d2 = dot(to_point, to_point);
        if (d2 <= FLT_MIN) {
            continue;
        }
        let l = to_point * inverseSqrt(d2);
        let n_dot_l = dot(n, l);
        let cos_e = dot(light.direction, -l);
        if (n_dot_l <= 0.0 || dot(ng, l) <= 0.0 || cos_e <= 0.0) {
            continue;
        }
        var brdf = rd * lambert_brdf_over_rd(n, l);
        if (HAS_SPECULAR) {
            brdf += rs * ggx_brdf_over_rs(n, l, v, alpha);
        }
        radiance += brdf * (point.w * cos_e * n_dot_l / d2);
    }
    return radiance * light.intensity * light.color;
}

@compute @workgroup_size(WORKGROUP, WORKGROUP, 1)
fn main(@builtin(global_invocation_id) gid: vec3u) {
    if (gid.x >= frame.size.x || gid.y >= frame.size.y) {
        return;
    }
    let index = gid.y * frame.size.x + gid.x;
    let pos = gbuf_position[index];
    if (pos.w == GBUFFER_BACKGROUND) {
        direct_out[index] = vec4f(0.0, 0.0, 0.0, 1.0);
        return;
    }
    let p = pos.xyz;
    let n = gbuf_normal[index].xyz;
    let roughness = gbuf_normal[index].w;
    let ng = gbuf_geo_normal[index].xyz;
    let metallic = gbuf_geo_normal[index].w;
    let base = gbuf_base_color[index].rgb;
    let rd = gbuffer_diffuse_reflectance(base, metallic);
    let rs = gbuffer_specular_reflectance(base, metallic, gbuf_base_color[index].w);
    let alpha = ggx_alpha_from_roughness(roughness);
    let v = -p / max(length(p), FLT_MIN);

    var radiance = vec3f(0.0);
    for (var i = 0u; i < frame.light_count; i++) {
        let light = lights[i];
        if (HAS_EMITTER_LIGHTS && light.kind == LIGHT_KIND_EMITTER) {
            if (!EMITTER_POINT_SUM) {
                continue;
            }
            // Shadowed by its cube as seen from its centre, lit by its points.
            let centre = light_incidence(light, p);
            var visibility = 1.0;
            if (SHADOWS && dot(ng, centre.l) > 0.0) {
                visibility = shadow_visibility(light, p, ng, centre.l, centre.dist);
            }
            if (visibility > 0.0) {
                radiance += visibility * emitter_radiance(light, i, p, n, ng, v, rd, rs, alpha);
            }
            continue;
        }
        let inc = light_incidence(light, p);
        if (all(inc.e <= vec3f(0.0))) {
            continue;
        }
        let l = inc.l;
        let n_dot_l = dot(n, l);
        if (n_dot_l <= 0.0 || dot(ng, l) <= 0.0) {
            continue;
        }
        var visibility = 1.0;
        if (SHADOWS) {
            visibility = shadow_visibility(light, p, ng, l, inc.dist);
        }
        // Irradiance on a surface facing the light (I·color·cone/d² or E·color), shadowed.
        let e = inc.e * visibility;
        var brdf = rd * lambert_brdf_over_rd(n, l);
        if (HAS_SPECULAR) {
            brdf += rs * ggx_brdf_over_rs(n, l, v, alpha);
        }
        radiance += brdf * e * n_dot_l;
    }
    direct_out[index] = vec4f(min(radiance, vec3f(FLT_MAX)), 1.0);
}
