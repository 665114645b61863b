// Direct lighting from the spot lights in compute: Lambert + GGX/Smith (Fresnel = 1), the
// glTF cone falloff and inverse-square law, with a 3×3 PCF shadow map lookup.
#include "common/constants.wgsl"
#include "common/frame.wgsl"
#include "common/gbuffer.wgsl"
#include "common/plan.wgsl"
#include "common/ggx.wgsl"

override SHADOWS: bool = true;
const WORKGROUP: u32 = 8u;
// Shadow-map normal offset in shadow texels. The offset is this many texel footprints at the
// receiver's distance from the light, so it scales with the scene (no fixed world length).
const SHADOW_NORMAL_OFFSET_TEXELS: f32 = 1.5;

@group(0) @binding(0) var<uniform> frame: FrameUniforms;
@group(1) @binding(0) var<storage, read> lights: array<LightRaw>;
@group(1) @binding(1) var shadow_maps: texture_depth_2d_array;
@group(1) @binding(2) var shadow_sampler: sampler_comparison;
@group(1) @binding(3) var<storage, read> gbuf_position: array<vec4f>;
@group(1) @binding(4) var<storage, read> gbuf_normal: array<vec4f>;
@group(1) @binding(5) var<storage, read> gbuf_geo_normal: array<vec4f>;
@group(1) @binding(6) var<storage, read> gbuf_base_color: array<vec4f>;
@group(1) @binding(7) var<storage, read_write> direct_out: array<vec4f>;

// Fraction of the 3×3 PCF footprint that sees the light (1 = lit).
fn shadow_visibility(light: LightRaw, p: vec3f, ng: vec3f, dist: f32) -> f32 {
    let offset = SHADOW_NORMAL_OFFSET_TEXELS * light.texel_tan * dist;
    let clip = light.view_proj * vec4f(p + ng * offset, 1.0);
    if (clip.w <= 0.0) {
        return 0.0;
    }
    let ndc = clip.xyz / clip.w;
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
                                             light.shadow_layer, ndc.z);
        }
    }
    return sum / 9.0;
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
        let to_light = light.position - p;
        let dist2 = dot(to_light, to_light);
        if (dist2 <= FLT_MIN) {
            continue;
        }
        let dist = sqrt(dist2);
        let l = to_light / dist;
        let n_dot_l = dot(n, l);
        if (n_dot_l <= 0.0 || dot(ng, l) <= 0.0) {
            continue;
        }
        let cone = spot_cone_attenuation(light, l);
        if (cone <= 0.0) {
            continue;
        }
        var visibility = 1.0;
        if (SHADOWS) {
            visibility = shadow_visibility(light, p, ng, dist);
        }
        // Irradiance-scaled intensity: I·color·cone/d² (candela → W/m² per unit solid angle).
        let e = light.intensity * light.color * (cone * visibility / dist2);
        var brdf = rd * lambert_brdf_over_rd(n, l);
        if (HAS_SPECULAR) {
            brdf += rs * ggx_brdf_over_rs(n, l, v, alpha);
        }
        radiance += brdf * e * n_dot_l;
    }
    direct_out[index] = vec4f(min(radiance, vec3f(FLT_MAX)), 1.0);
}
