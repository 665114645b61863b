// Path-traced one-bounce ground truth (compute). From each pixel's G-buffer point p, directions
// are sampled by the BRDF, the bounce point x is found by ray tracing the BVH, and x's direct
// light from every light (shadow ray) is reflected at x and then at p:
//   L_ind(p, v) = ∫ f_p(l, v) ⟨n_p, l⟩ L_o(x(l), −l) dl,
//   L_o(x, ω) = Σ_lights f_x(l_x, ω) ⟨n_x, l_x⟩ e(x) V(x, light), e = I·color·cone(l_x)/d²
//   (spot; cone = 1 for a point light) or E·color (directional),
// the quantity the VPL `reference` discretizes (common/vpl.wgsl), with exact visibility.
//
// Estimator (one-sample MIS over the two lobes [Veach 1997, §9.2.4], i.e. sampling the mixture):
// choose the specular lobe with probability c_s = ΣRs / (ΣRd + ΣRs), else the diffuse lobe;
// sample l from that lobe (GGX VNDF or cosine); weigh by the mixture pdf
//   p(l) = (1 − c_s) cosθ/π + c_s G1(v) D(h) / (4 n·v)
// so each sample F = f(l, v) ⟨n, l⟩ L_o / p(l) is unbiased whichever lobe drew it. The diffuse
// and specular parts of F (f = Rd/π + Rs·f_GGX) are accumulated separately for the
// indirect_diffuse / indirect_specular AOVs; their sum's sample variance gives the error.
//
// Accumulation is progressive: each dispatch adds `batch_samples` samples per pixel. A thread
// keeps a running mean and M2 in registers (Welford 1962) and merges them into the stored ones
// with Chan, Golub & LeVeque 1979 (the pairwise update), so the variance never comes from
// E[x²] − E[x]², which cancels (DESIGN.md, Numerics).
//
// Entry points: `indirect` (one batch), `direct` (the pixel's direct light with shadow rays, for
// the `direct` AOV of this method) and `resolve` (standard error of the mean, per channel).
#include "common/constants.wgsl"
#include "common/frame.wgsl"
#include "common/gbuffer.wgsl"
#include "common/ggx.wgsl"
#include "common/math.wgsl"
#include "common/sampling.wgsl"
#include "common/bvh.wgsl"
#include "common/material_eval.wgsl"

const WORKGROUP: u32 = 8u;
// Ray origins are moved off their surface along the geometric normal by this fraction of the
// point's coordinate magnitude (relative to the frame origin, where f32 rounding is ~6e-8 of
// it): about 170 ulps, and never less than RAY_OFFSET_RELATIVE × RAY_OFFSET_EXTENT_FRACTION of
// the scene's size. The surface's own triangle is also skipped, so the offset only has to
// clear rounding on neighbouring triangles. No fixed world length (DESIGN.md, Numerics).
const RAY_OFFSET_RELATIVE: f32 = 1.0e-5;
const RAY_OFFSET_EXTENT_FRACTION: f32 = 1.0e-2;
// Bounce rays end after this many scene diagonals (every scene point lies within one).
const RAY_T_MAX_EXTENTS: f32 = 4.0;

struct PathParams {
    seed: u32,
    // Samples per pixel accumulated before this dispatch (for `resolve`: all of them).
    sample_offset: u32,
    batch_samples: u32,
    _pad0: u32,
}

@group(0) @binding(0) var<uniform> frame: FrameUniforms;
@group(0) @binding(1) var<uniform> params: PathParams;
@group(0) @binding(2) var<storage, read> bvh_nodes: array<BvhNode>;
@group(0) @binding(3) var<storage, read> bvh_triangles: array<BvhTriangle>;
@group(0) @binding(4) var<storage, read> vertices: array<VertexRaw>;
@group(0) @binding(5) var<storage, read> indices: array<u32>;
@group(0) @binding(6) var<storage, read> triangle_materials: array<u32>;
@group(0) @binding(7) var<storage, read> materials: array<MaterialRaw>;
@group(0) @binding(8) var<storage, read> lights: array<LightRaw>;
@group(0) @binding(9) var<storage, read> gbuf_position: array<vec4f>;
@group(0) @binding(10) var<storage, read> gbuf_normal: array<vec4f>;
@group(0) @binding(11) var<storage, read> gbuf_geo_normal: array<vec4f>;
@group(0) @binding(12) var<storage, read> gbuf_base_color: array<vec4f>;
// The visibility pass's triangle ids (id + 1; 0 = background): the pixel's own triangle.
@group(0) @binding(13) var visibility: texture_2d<u32>;
@group(0) @binding(14) var color_textures: texture_2d_array<f32>;
@group(0) @binding(15) var data_textures: texture_2d_array<f32>;
@group(0) @binding(16) var texture_sampler: sampler;
// Running means of the diffuse and specular parts (rgb), and M2 of their sum (rgb).
@group(0) @binding(17) var<storage, read_write> indirect_diffuse: array<vec4f>;
@group(0) @binding(18) var<storage, read_write> indirect_specular: array<vec4f>;
@group(0) @binding(19) var<storage, read_write> indirect_m2: array<vec4f>;
@group(0) @binding(20) var<storage, read_write> direct_out: array<vec4f>;
@group(0) @binding(21) var<storage, read_write> stderr_out: array<vec4f>;

// What shading needs at a surface point.
struct Surface {
    position: vec3f,
    // Geometric normal, facing the side the point is seen from.
    ng: vec3f,
    // Shading normal on the same side.
    ns: vec3f,
    rd: vec3f,
    rs: vec3f,
    alpha: f32,
    triangle: u32,
}

// Shading happens in frame space (relative to the eye, like the G-buffer and the lights); the
// BVH and the vertex buffer are relative to the scene upload's anchor, which lies at
// frame.view_origin (the eye's offset from the anchor) subtracted: a ray enters scene space
// through to_scene, a hit comes back through the vertices minus view_origin.
fn to_scene(p: vec3f) -> vec3f {
    return p + frame.view_origin.xyz;
}

fn max_abs(p: vec3f) -> f32 {
    return max(max(abs(p.x), abs(p.y)), abs(p.z));
}

// Clears the rounding of the point in both spaces it is used in.
fn ray_offset(p: vec3f) -> f32 {
    let m = max(max_abs(p), max_abs(to_scene(p)));
    return RAY_OFFSET_RELATIVE * max(m, RAY_OFFSET_EXTENT_FRACTION * frame.scene_extent);
}

// Direct light reflected towards v at a surface point from every light, each visible through
// a shadow ray: Σ f(l, v) ⟨n, l⟩ e, with e the light's irradiance facing it (light_incidence:
// I·color·cone/d² for spot and point lights, E·color for a directional light) — the direct
// pass's formula, with a traced shadow ray in place of the shadow map.
fn lights_radiance(s: Surface, v: vec3f) -> vec3f {
    var radiance = vec3f(0.0);
    let origin = s.position + s.ng * ray_offset(s.position);
    for (var i = 0u; i < frame.light_count; i++) {
        let light = lights[i];
        let inc = light_incidence(light, s.position);
        if (all(inc.e <= vec3f(0.0))) {
            continue;
        }
        let l = inc.l;
        let n_dot_l = dot(s.ns, l);
        if (n_dot_l <= 0.0 || dot(s.ng, l) <= 0.0) {
            continue;
        }
        var shadow: Ray;
        if (light.kind == LIGHT_KIND_DIRECTIONAL) {
            // The light is at infinity: the ray runs until it has left the scene (every scene
            // point lies within one diagonal of every other).
            shadow = Ray(to_scene(origin), l, RAY_T_MAX_EXTENTS * frame.scene_extent, s.triangle);
        } else {
            // From the offset origin, stopping short of the light by its own offset.
            let seg = light.position - origin;
            let seg_len = length(seg);
            shadow = Ray(to_scene(origin), seg / max(seg_len, FLT_MIN), seg_len - ray_offset(light.position), s.triangle);
        }
        if (bvh_any_hit(shadow)) {
            continue;
        }
        let brdf = s.rd * lambert_brdf_over_rd(s.ns, l) + s.rs * ggx_brdf_over_rs(s.ns, l, v, s.alpha);
        radiance += brdf * inc.e * n_dot_l;
    }
    return min(radiance, vec3f(FLT_MAX));
}

fn lerp_bary3(a: vec3f, b: vec3f, c: vec3f, w: vec2f) -> vec3f {
    return a + w.x * (b - a) + w.y * (c - a);
}

// The surface a bounce ray hit: position from the barycentrics (not origin + t·dir, which
// carries the ray's rounding), normals facing the ray's origin, and the glTF material (with its
// textures at the finest level: a path tracer integrates texture detail itself).
fn hit_surface(dir: vec3f, hit: RayHit) -> Surface {
    let tri = hit.triangle;
    var a = vertices[indices[3u * tri]];
    var b = vertices[indices[3u * tri + 1u]];
    var c = vertices[indices[3u * tri + 2u]];
    // Back to frame space.
    a.position -= frame.view_origin.xyz;
    b.position -= frame.view_origin.xyz;
    c.position -= frame.view_origin.xyz;
    let w = hit.bary;
    let position = lerp_bary3(a.position, b.position, c.position, w);
    var ng = safe_normalize(cross(b.position - a.position, c.position - a.position), -dir);
    if (dot(ng, dir) > 0.0) {
        ng = -ng;
    }
    var ns = safe_normalize(lerp_bary3(a.normal, b.normal, c.normal, w), ng);
    if (dot(ns, ng) < 0.0) {
        ns = -ns;
    }
    let material = materials[triangle_materials[tri]];
    // The finest mip: a bounce ray's footprint is not tracked.
    let uv = a.uv + w.x * (b.uv - a.uv) + w.y * (c.uv - a.uv);
    let sm = evaluate_material(material, uv, 0.0, ns, lerp_bary3(a.tangent.xyz, b.tangent.xyz, c.tangent.xyz, w), a.tangent.w);
    ns = sm.ns;
    // As in the material pass: a shading normal facing away from the viewer (here the bounce
    // ray's origin) falls back to the geometric normal.
    if (dot(ns, -dir) <= 0.0) {
        ns = ng;
    }
    return Surface(position, ng, ns, gbuffer_diffuse_reflectance(sm.base, sm.metallic),
                   gbuffer_specular_reflectance(sm.base, sm.metallic, material.specular_factor),
                   ggx_alpha_from_roughness(sm.roughness), tri);
}

// The G-buffer surface of a pixel (which must not be background).
fn pixel_surface(pixel: vec2u, index: u32) -> Surface {
    let pos = gbuf_position[index];
    let nr = gbuf_normal[index];
    let gm = gbuf_geo_normal[index];
    let base = gbuf_base_color[index].rgb;
    let tri = textureLoad(visibility, vec2i(pixel), 0).r - 1u;
    return Surface(pos.xyz, gm.xyz, nr.xyz, gbuffer_diffuse_reflectance(base, gm.w),
                   gbuffer_specular_reflectance(base, gm.w, gbuf_base_color[index].w), ggx_alpha_from_roughness(nr.w), tri);
}

// Radiance arriving at `s` from direction l: the direct light reflected by the first surface
// hit towards s (zero on a miss: there is no environment light).
fn incoming_radiance(s: Surface, l: vec3f) -> vec3f {
    let origin = s.position + s.ng * ray_offset(s.position);
    let hit = bvh_closest_hit(Ray(to_scene(origin), l, RAY_T_MAX_EXTENTS * frame.scene_extent, s.triangle));
    if (hit.triangle == BVH_NO_TRIANGLE) {
        return vec3f(0.0);
    }
    return lights_radiance(hit_surface(l, hit), -l);
}

@compute @workgroup_size(WORKGROUP, WORKGROUP, 1)
fn indirect(@builtin(global_invocation_id) gid: vec3u) {
    if (gid.x >= frame.size.x || gid.y >= frame.size.y) {
        return;
    }
    let index = gid.y * frame.size.x + gid.x;
    if (gbuf_position[index].w == GBUFFER_BACKGROUND) {
        indirect_diffuse[index] = vec4f(0.0);
        indirect_specular[index] = vec4f(0.0);
        indirect_m2[index] = vec4f(0.0);
        return;
    }
    let s = pixel_surface(gid.xy, index);
    let p = s.position;
    let n = s.ns;
    let v = -p / max(length(p), FLT_MIN);
    let basis = orthonormal_basis(n);
    // v in the frame (x, y, n): transpose(basis)·v.
    let v_local = v * basis;
    let weight_d = s.rd.r + s.rd.g + s.rd.b;
    let weight_s = s.rs.r + s.rs.g + s.rs.b;
    let c_s = select(0.0, weight_s / (weight_d + weight_s), weight_d + weight_s > 0.0);

    var mean = vec3f(0.0);
    var m2 = vec3f(0.0);
    var sum_d = vec3f(0.0);
    var sum_s = vec3f(0.0);
    for (var k = 0u; k < params.batch_samples; k++) {
        var rng = rng_init(index, params.sample_offset + k, params.seed);
        let u_lobe = rng_uniform(&rng);
        let u1 = rng_uniform(&rng);
        let u2 = rng_uniform(&rng);
        var l_local: vec3f;
        if (u_lobe < c_s) {
            let h = sample_ggx_vndf(v_local, s.alpha, u1, u2);
            l_local = 2.0 * dot(v_local, h) * h - v_local;
        } else {
            l_local = sample_cosine_hemisphere(u1, u2);
        }
        let l = safe_normalize(basis * l_local, n);
        var x_d = vec3f(0.0);
        var x_s = vec3f(0.0);
        let cos_l = dot(n, l);
        if (cos_l > 0.0 && dot(s.ng, l) > 0.0) {
            let pdf = (1.0 - c_s) * cosine_hemisphere_pdf(cos_l) + c_s * ggx_vndf_reflection_pdf(n, v, l, s.alpha);
            if (pdf > 0.0) {
                let li = incoming_radiance(s, l);
                if (any(li > vec3f(0.0))) {
                    let w = li * (cos_l / pdf);
                    x_d = min(s.rd * INV_PI * w, vec3f(FLT_MAX));
                    x_s = min(s.rs * ggx_brdf_over_rs(n, l, v, s.alpha) * w, vec3f(FLT_MAX));
                }
            }
        }
        // Welford's running mean and sum of squared deviations of the sample total.
        let x = x_d + x_s;
        let delta = x - mean;
        mean += delta / f32(k + 1u);
        m2 += delta * (x - mean);
        sum_d += x_d;
        sum_s += x_s;
    }
    let n_b = f32(params.batch_samples);
    let mean_d = sum_d / n_b;
    let mean_s = sum_s / n_b;
    if (params.sample_offset == 0u) {
        indirect_diffuse[index] = vec4f(mean_d, 0.0);
        indirect_specular[index] = vec4f(mean_s, 0.0);
        indirect_m2[index] = vec4f(min(m2, vec3f(FLT_MAX)), 0.0);
        return;
    }
    // Chan et al. 1979: merge (n_a, mean_a, M2_a) with (n_b, mean_b, M2_b).
    let n_a = f32(params.sample_offset);
    let f = n_b / (n_a + n_b);
    let old_d = indirect_diffuse[index].rgb;
    let old_s = indirect_specular[index].rgb;
    let delta = mean - (old_d + old_s);
    indirect_diffuse[index] = vec4f(old_d + (mean_d - old_d) * f, 0.0);
    indirect_specular[index] = vec4f(old_s + (mean_s - old_s) * f, 0.0);
    let m2_new = indirect_m2[index].rgb + m2 + delta * delta * (n_a * f);
    indirect_m2[index] = vec4f(min(m2_new, vec3f(FLT_MAX)), 0.0);
}

@compute @workgroup_size(WORKGROUP, WORKGROUP, 1)
fn direct(@builtin(global_invocation_id) gid: vec3u) {
    if (gid.x >= frame.size.x || gid.y >= frame.size.y) {
        return;
    }
    let index = gid.y * frame.size.x + gid.x;
    if (gbuf_position[index].w == GBUFFER_BACKGROUND) {
        direct_out[index] = vec4f(0.0, 0.0, 0.0, 1.0);
        return;
    }
    let s = pixel_surface(gid.xy, index);
    let v = -s.position / max(length(s.position), FLT_MIN);
    direct_out[index] = vec4f(lights_radiance(s, v), 1.0);
}

// Standard error of the mean per channel: √(M2 / ((N − 1) N)). One sample carries no variance
// estimate; with N = 1 the AOV holds |x|, the one-sample estimate of √E[x²] ≥ σ.
@compute @workgroup_size(WORKGROUP, WORKGROUP, 1)
fn resolve(@builtin(global_invocation_id) gid: vec3u) {
    if (gid.x >= frame.size.x || gid.y >= frame.size.y) {
        return;
    }
    let index = gid.y * frame.size.x + gid.x;
    let n = f32(params.sample_offset);
    var err: vec3f;
    if (params.sample_offset < 2u) {
        err = abs(indirect_diffuse[index].rgb + indirect_specular[index].rgb);
    } else {
        err = sqrt(max(indirect_m2[index].rgb, vec3f(0.0)) / ((n - 1.0) * n));
    }
    stderr_out[index] = vec4f(min(err, vec3f(FLT_MAX)), 0.0);
}
