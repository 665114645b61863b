// vsgl:include-only — declares group 2 of the virtual-light shading passes (vpl_shading,
//   vsgl_shading) and needs `frame: FrameUniforms` declared by the including shader.
//
// `visibility=` of a virtual light seen from a receiver, shared by both shading passes
// (methods/visibility.rs binds group 2): "none" compiles everything here out (both overrides
// false, placeholders bound); "raytrace" casts one shadow ray through the scene's BVH
// (shadow_ray.wgsl); "ism" looks the receiver up in the light's imperfect shadow map
// (ism_lookup.wgsl; map j belongs to light j of the shaded buffer).
#include "common/bvh.wgsl"
#include "common/shadow_ray.wgsl"
#include "common/ism_lookup.wgsl"

// visibility="raytrace": the scene's BVH and the camera's triangle ids (the receiver's own
// triangle is skipped by its shadow rays). Placeholders otherwise.
override VISIBILITY_TRACED: bool = false;
@group(2) @binding(0) var<storage, read> bvh_nodes: array<BvhNode>;
@group(2) @binding(1) var<storage, read> bvh_triangle_ids: array<u32>;
@group(2) @binding(2) var visibility_ids: texture_2d<u32>;
// visibility="ism": one imperfect shadow map per light of the buffer (passes/ism.wgsl built them
// just before this pass) and how to read them. Placeholders otherwise.
override VISIBILITY_ISM: bool = false;
@group(2) @binding(3) var<storage, read> ism_atlas: array<u32>;
@group(2) @binding(4) var<uniform> ism_lookup: IsmLookup;
// visibility="raytrace": the BVH's triangle corners (the upload's raster vertices). A
// placeholder otherwise.
@group(2) @binding(5) var<storage, read> triangle_corners: array<TriangleCorner>;
// The other pages of the BVH's nodes and corners (common/bvh.wgsl); placeholders likewise.
@group(2) @binding(6) var<storage, read> bvh_nodes_1: array<BvhNode>;
@group(2) @binding(7) var<storage, read> bvh_nodes_2: array<BvhNode>;
@group(2) @binding(8) var<storage, read> bvh_nodes_3: array<BvhNode>;
@group(2) @binding(9) var<storage, read> triangle_corners_1: array<TriangleCorner>;
@group(2) @binding(10) var<storage, read> triangle_corners_2: array<TriangleCorner>;
@group(2) @binding(11) var<storage, read> triangle_corners_3: array<TriangleCorner>;

// What the visibility of a receiver needs besides its position and shading normal.
struct ShadowReceiver {
    // Geometric normal (rays leave along it) and the receiver's own triangle (never hit).
    ng: vec3f,
    own_triangle: u32,
}

// The receiver at `pixel` (G-buffer geometric normal `geo_normal`); read only for "raytrace".
fn shadow_receiver(has_surface: bool, geo_normal: vec3f, pixel: vec2u) -> ShadowReceiver {
    var out = ShadowReceiver(vec3f(0.0, 0.0, 1.0), BVH_NO_TRIANGLE);
    if (VISIBILITY_TRACED && has_surface) {
        out.ng = geo_normal;
        out.own_triangle = textureLoad(visibility_ids, vec2i(pixel), 0).r - 1u;
    }
    return out;
}

// How much of light `light_index` (at `light_position`) reaches the receiver at p (shading
// normal n): 1 without visibility, 0 or 1 by a shadow ray, the lit fraction of its map by ISM.
fn light_visibility(p: vec3f, n: vec3f, rcv: ShadowReceiver, light_index: u32, light_position: vec3f) -> f32 {
    if (VISIBILITY_TRACED) {
        return select(0.0, 1.0, virtual_light_visible(p, rcv.ng, rcv.own_triangle, light_position, frame.view_origin.xyz, frame.scene_extent));
    }
    if (VISIBILITY_ISM) {
        return ism_visibility(light_index, p - light_position, n);
    }
    return 1.0;
}
