// VSGL shading (compute) [Tok15 §3.2, Eq. 5; Tok16s §4]: per pixel and VSGL, the incoming
// radiance SG of each lobe, then diffuse (cosine pulled out, or the accurate clamped-cosine
// option) and GGX specular by the SG–ASG product integral. With interleave k, the pixel at
// (x, y) evaluates only VSGLs j ≡ (y mod k)·k + (x mod k) (mod k²) and scales by k²
// [interleaved sampling, Keller & Heidrich 2001; Tok15 §5]; the denoise pass recombines them.
// Visibility is not evaluated (visibility = "none").
#include "common/constants.wgsl"
#include "common/math.wgsl"
#include "common/sg.wgsl"
#include "common/vsgl.wgsl"
#include "common/vsgl_record.wgsl"
#include "common/frame.wgsl"
#include "common/gbuffer.wgsl"
#include "common/plan.wgsl"

struct ShadeParams {
    // This dispatch shades VSGLs first … first + count − 1 (first is a multiple of k²).
    count: u32,
    interleave: u32,
    // 0 = the papers' cosine-pulled-out form with A ≈ 2π/λ, 1 = accurate clamped cosine,
    // 2 = SG product integral with the Lambert SG (the 2015 two-VSGL poster).
    diffuse_mode: u32,
    first: u32,
}

const WORKGROUP: u32 = 8u;

@group(0) @binding(0) var<uniform> frame: FrameUniforms;
@group(1) @binding(0) var<uniform> params: ShadeParams;
@group(1) @binding(1) var<storage, read> vsgls: array<VsglRaw>;
@group(1) @binding(2) var<storage, read> gbuf_position: array<vec4f>;
@group(1) @binding(3) var<storage, read> gbuf_normal: array<vec4f>;
@group(1) @binding(4) var<storage, read> gbuf_geo_normal: array<vec4f>;
@group(1) @binding(5) var<storage, read> gbuf_base_color: array<vec4f>;
@group(1) @binding(6) var<storage, read_write> indirect_diffuse: array<vec4f>;
@group(1) @binding(7) var<storage, read_write> indirect_specular: array<vec4f>;

fn diffuse_over_rd(radiance: Sg, n: vec3f) -> f32 {
    if (params.diffuse_mode == 1u) {
        return vsgl_diffuse_accurate(radiance, n);
    }
    if (params.diffuse_mode == 2u) {
        return vsgl_diffuse_sg_product(radiance, n);
    }
    return vsgl_diffuse_approx(radiance, n);
}

@compute @workgroup_size(WORKGROUP, WORKGROUP, 1)
fn main(@builtin(global_invocation_id) gid: vec3u) {
    if (gid.x >= frame.size.x || gid.y >= frame.size.y) {
        return;
    }
    let index = gid.y * frame.size.x + gid.x;
    let pos = gbuf_position[index];
    if (pos.w == GBUFFER_BACKGROUND) {
        return;
    }
    let p = pos.xyz;
    let n = gbuf_normal[index].xyz;
    let alpha = ggx_alpha_from_roughness(gbuf_normal[index].w);
    let metallic = gbuf_geo_normal[index].w;
    let base = gbuf_base_color[index].rgb;
    let rd = gbuffer_diffuse_reflectance(base, metallic);
    let rs = gbuffer_specular_reflectance(base, metallic, gbuf_base_color[index].w);
    let v = -p / max(length(p), FLT_MIN);
    let k = params.interleave;
    let stride = k * k;
    let first = params.first + (gid.y % k) * k + (gid.x % k);
    let end = params.first + params.count;
    var diffuse = vec3f(0.0);
    var specular = vec3f(0.0);
    for (var j = first; j < end; j += stride) {
        let light = vsgls[j];
        let position = VsglPosition(light.mean, light.variance);
        // Each lobe: radiance SG per unit power (amplitude 1/A(λ)), times its rgb power. A lobe
        // without power (vsgl2's records carry one lobe each; metal clusters have no diffuse
        // lobe) is skipped: it would add exactly 0. The test is uniform over the dispatch.
        if (any(light.diffuse_power > vec3f(0.0))) {
            let lobe_d = Sg(light.diffuse_axis, light.diffuse_sharpness, 1.0 / sg_integral(light.diffuse_sharpness));
            let in_d = vsgl_incoming_radiance(lobe_d, position, p);
            diffuse += light.diffuse_power * diffuse_over_rd(in_d, n);
            if (HAS_SPECULAR) {
                specular += light.diffuse_power * vsgl_specular(in_d, n, v, alpha);
            }
        }
        // Without specular materials no record has specular power (and R_s = 0 here).
        if (HAS_SPECULAR && any(light.specular_power > vec3f(0.0))) {
            let lobe_s = Sg(light.specular_axis, light.specular_sharpness, 1.0 / sg_integral(light.specular_sharpness));
            let in_s = vsgl_incoming_radiance(lobe_s, position, p);
            diffuse += light.specular_power * diffuse_over_rd(in_s, n);
            specular += light.specular_power * vsgl_specular(in_s, n, v, alpha);
        }
    }
    let scale = f32(stride);
    indirect_diffuse[index] += vec4f(min(rd * diffuse * scale, vec3f(FLT_MAX)), 0.0);
    if (HAS_SPECULAR) {
        indirect_specular[index] += vec4f(min(rs * specular * scale, vec3f(FLT_MAX)), 0.0);
    }
}
