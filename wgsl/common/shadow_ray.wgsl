// vsgl:include-only — the including shader includes common/bvh.wgsl and declares its two
//   storage arrays (bvh_nodes, bvh_triangle_ids, triangle_corners).
//
// Shadow rays between a receiver and a virtual light through the scene's BVH, for
// `visibility="raytrace"`. Points are relative to the frame origin (the eye), like the
// G-buffer and the virtual lights; the BVH is relative to the scene upload's anchor, where the
// eye is at `view_origin`, so a point enters BVH space as p + view_origin. Offsets follow the
// path tracer's rule (pathtrace.wgsl): 1e-5 of the point's coordinate magnitude in either
// space, at least 1e-7 of the scene's diagonal — no fixed world length (docs/frames.md, "Precision far from the origin").
#include "common/constants.wgsl"

const SHADOW_RAY_OFFSET_RELATIVE: f32 = 1.0e-5;
const SHADOW_RAY_OFFSET_EXTENT_FRACTION: f32 = 1.0e-2;

fn shadow_ray_max_abs(p: vec3f) -> f32 {
    return max(max(abs(p.x), abs(p.y)), abs(p.z));
}

fn shadow_ray_offset(p: vec3f, view_origin: vec3f, extent: f32) -> f32 {
    let m = max(shadow_ray_max_abs(p), shadow_ray_max_abs(p + view_origin));
    return SHADOW_RAY_OFFSET_RELATIVE * max(m, SHADOW_RAY_OFFSET_EXTENT_FRACTION * extent);
}

// Whether nothing blocks the segment from a receiver at p (geometric normal ng on the viewer's
// side, triangle `ignore`, or BVH_NO_TRIANGLE) to a virtual light at q: a ray from p moved off
// its surface, stopping short of q by q's own offset (q lies on a surface of the RSM).
fn virtual_light_visible(p: vec3f, ng: vec3f, ignore: u32, q: vec3f, view_origin: vec3f, extent: f32) -> bool {
    let origin = p + ng * shadow_ray_offset(p, view_origin, extent);
    let segment = q - origin;
    let len = length(segment);
    let t_max = len - shadow_ray_offset(q, view_origin, extent);
    if (!(t_max > 0.0)) {
        return true;
    }
    return !bvh_any_hit(Ray(origin + view_origin, segment / len, t_max, ignore));
}
