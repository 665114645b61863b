// Material pass: turns the visibility buffer (triangle ids) into the G-buffer in compute. It
// serves the camera and, with a light's view, the reflective shadow map (positions are then
// relative to the light, or for a directional light's orthographic view to its image plane's
// centre).
// Barycentrics come from intersecting the pixel's camera ray with the visible triangle
// (Möller & Trumbore 1997), which is exact and perspective-correct; texture LOD comes from the
// ray differentials of the neighbouring pixels (Igehy 1999), computed the same way.
#include "common/constants.wgsl"
#include "common/frame.wgsl"
#include "common/gbuffer.wgsl"
#include "common/material_eval.wgsl"
#include "common/scene_vertices.wgsl"

const WORKGROUP: u32 = 8u;

@group(0) @binding(0) var<uniform> frame: FrameUniforms;
@group(1) @binding(0) var visibility: texture_2d<u32>;
@group(1) @binding(1) var<storage, read> vertices: array<VertexRaw>;
@group(1) @binding(2) var<storage, read> indices: array<u32>;
@group(1) @binding(3) var<storage, read> triangle_materials: array<u32>;
@group(1) @binding(4) var<storage, read> materials: array<MaterialRaw>;
@group(1) @binding(5) var color_textures: texture_2d_array<f32>;
@group(1) @binding(6) var data_textures: texture_2d_array<f32>;
@group(1) @binding(7) var texture_sampler: sampler;
@group(1) @binding(8) var<storage, read_write> gbuf_position: array<vec4f>;
@group(1) @binding(9) var<storage, read_write> gbuf_normal: array<vec4f>;
@group(1) @binding(10) var<storage, read_write> gbuf_geo_normal: array<vec4f>;
@group(1) @binding(11) var<storage, read_write> gbuf_base_color: array<vec4f>;
// Emitted radiance (rgb, w = 0) for the compositing pass (aov_pack); written only by the
// camera's variant of a scene with an emissive material (HAS_EMISSION), else a placeholder.
@group(1) @binding(12) var<storage, read_write> gbuf_emission: array<vec4f>;
// The vertices' other pages (common/scene_vertices.wgsl).
@group(1) @binding(13) var<storage, read> vertices_1: array<VertexRaw>;
@group(1) @binding(14) var<storage, read> vertices_2: array<VertexRaw>;
@group(1) @binding(15) var<storage, read> vertices_3: array<VertexRaw>;

// Leave-out: false where no material emits (and always for a light's view: emissive surfaces
// do not light the scene, so the RSM never needs them).
override HAS_EMISSION: bool = true;

struct Hit {
    t: f32,
    // Barycentric weights of v1 and v2.
    b: vec2f,
}

// Ray (origin 0, unit direction d) against triangle v0 v1 v2, without culling or clamping.
fn ray_triangle(d: vec3f, v0: vec3f, v1: vec3f, v2: vec3f) -> Hit {
    let e1 = v1 - v0;
    let e2 = v2 - v0;
    let p = cross(d, e2);
    let det = dot(e1, p);
    // Edge-on triangles (|det| tiny relative to the edge lengths) cover no pixel centre in
    // exact arithmetic; fall back to the centroid rather than divide by ~0.
    if (abs(det) <= 1.0e-12 * length(e1) * length(e2)) {
        return Hit(length(v0), vec2f(1.0 / 3.0));
    }
    let inv = 1.0 / det;
    let s = -v0;
    let u = dot(s, p) * inv;
    let q = cross(s, e1);
    let v = dot(d, q) * inv;
    return Hit(dot(e2, q) * inv, vec2f(u, v));
}

fn interpolate2(a: vec2f, b: vec2f, c: vec2f, w: vec2f) -> vec2f {
    return a + w.x * (b - a) + w.y * (c - a);
}

@compute @workgroup_size(WORKGROUP, WORKGROUP, 1)
fn main(@builtin(global_invocation_id) gid: vec3u) {
    if (gid.x >= frame.size.x || gid.y >= frame.size.y) {
        return;
    }
    let pixel = gid.xy;
    let index = pixel.y * frame.size.x + pixel.x;
    let id = textureLoad(visibility, vec2i(pixel), 0).r;
    if (id == 0u) {
        gbuf_position[index] = vec4f(0.0, 0.0, 0.0, GBUFFER_BACKGROUND);
        gbuf_normal[index] = vec4f(0.0);
        gbuf_geo_normal[index] = vec4f(0.0);
        gbuf_base_color[index] = vec4f(0.0);
        if (HAS_EMISSION) {
            gbuf_emission[index] = vec4f(0.0);
        }
        return;
    }
    let tri = id - 1u;
    let i0 = indices[3u * tri];
    let i1 = indices[3u * tri + 1u];
    let i2 = indices[3u * tri + 2u];
    // Vertices relative to the view's ray origin (the camera, or the light for an RSM).
    var a = scene_vertex(i0);
    var b = scene_vertex(i1);
    var c = scene_vertex(i2);
    a.position -= frame.view_origin.xyz;
    b.position -= frame.view_origin.xyz;
    c.position -= frame.view_origin.xyz;
    let d = camera_ray(frame, vec2f(pixel) + 0.5);
    // An orthographic view's ray starts on the image plane: intersect with the triangle moved
    // by −origin (ray_triangle's ray starts at 0); the barycentrics then interpolate a, b, c,
    // so positions stay relative to view_origin.
    let o = view_ray_origin(frame, vec2f(pixel) + 0.5);
    let hit = ray_triangle(d, a.position - o, b.position - o, c.position - o);
    // The raster says the pixel centre is inside; rounding may put it a hair outside.
    var w = clamp(hit.b, vec2f(0.0), vec2f(1.0));
    if (w.x + w.y > 1.0) {
        w = w / (w.x + w.y);
    }
    let position = a.position + w.x * (b.position - a.position) + w.y * (c.position - a.position);

    // Geometric normal facing the camera; all surfaces are double-sided.
    var ng = cross(b.position - a.position, c.position - a.position);
    ng = ng / max(length(ng), FLT_MIN);
    if (dot(ng, d) > 0.0) {
        ng = -ng;
    }
    var ns = a.normal + w.x * (b.normal - a.normal) + w.y * (c.normal - a.normal);
    let ns_len = length(ns);
    ns = select(ng, ns / ns_len, ns_len > 1.0e-6);
    if (dot(ns, ng) < 0.0) {
        ns = -ns;
    }

    var uv = vec2f(0.0);
    var lod = 0.0;
    if (HAS_TEXTURES) {
        uv = interpolate2(a.uv, b.uv, c.uv, w);
        // Ray differentials: UV of the neighbouring pixels' rays on the same triangle plane.
        let px = vec2f(pixel) + vec2f(1.5, 0.5);
        let py = vec2f(pixel) + vec2f(0.5, 1.5);
        let ox = view_ray_origin(frame, px);
        let oy = view_ray_origin(frame, py);
        let hx = ray_triangle(camera_ray(frame, px), a.position - ox, b.position - ox, c.position - ox);
        let hy = ray_triangle(camera_ray(frame, py), a.position - oy, b.position - oy, c.position - oy);
        let duv_dx = interpolate2(a.uv, b.uv, c.uv, hx.b) - uv;
        let duv_dy = interpolate2(a.uv, b.uv, c.uv, hy.b) - uv;
        let footprint = max(length(duv_dx), length(duv_dy)) * f32(frame.texture_layer_size);
        lod = log2(max(footprint, 1.0e-6));
    }
    let tangent = a.tangent.xyz + w.x * (b.tangent.xyz - a.tangent.xyz) + w.y * (c.tangent.xyz - a.tangent.xyz);
    let material = materials[triangle_materials[tri]];
    let surface = evaluate_material(material, uv, lod, ns, tangent, a.tangent.w);
    ns = surface.ns;
    // A shading normal facing away from the viewer (interpolation or normal maps at
    // silhouettes) would shade a surface the camera cannot see; fall back to the geometry.
    if (dot(ns, -d) <= 0.0) {
        ns = ng;
    }
    let view_depth = dot(position, frame.cam_forward.xyz);
    gbuf_position[index] = vec4f(position, max(view_depth, FLT_MIN));
    gbuf_normal[index] = vec4f(ns, surface.roughness);
    gbuf_geo_normal[index] = vec4f(ng, surface.metallic);
    gbuf_base_color[index] = vec4f(surface.base, material.specular_factor);
    if (HAS_EMISSION) {
        gbuf_emission[index] = vec4f(material_emission(material, uv, lod), 0.0);
    }
}
