// A VSGL's mean tangent plane and the fade of its light below it: pure
// functions used by VSGL generation (the plane from the moment chain F) and shading (the fade).
#include "common/constants.wgsl"
#include "common/vsgl.wgsl"

// The cluster's mean tangent plane (derived for vsgl, not in the papers).
// Each texel j reflects only into its own hemisphere, (p − y_j)·n_j > 0. A VSGL keeps the
// weighted mean of that height, which is linear in p:
//   H(p) = E_w[(p − y)·n] = (p − μ)·N̄ + E_w[(μ − y)·n],  N̄ = Σw n/Σw,
// so two numbers per VSGL (N̄ and the offset E_w[(μ − y)·n] = μ·N̄ − Σw(y·n)/Σw) give it exactly.
// For a planar cluster H is the receiver's height above the plane; for a corner it is the mean
// of the heights above both walls, positive wherever either wall sees p from the front.
struct VsglTangentPlane {
    normal: vec3f,
    offset: f32,
}

// From the cluster sums Σw, Σw·n, Σw·(y·n) and the cluster mean μ (relative to the same local
// origin as y).
fn vsgl_tangent_plane_from_moments(sum_weight: f32, sum_weighted_normal: vec3f, sum_weighted_height: f32, mean: vec3f) -> VsglTangentPlane {
    if (!(sum_weight > 0.0)) {
        return VsglTangentPlane(vec3f(0.0), 0.0);
    }
    let normal = sum_weighted_normal / sum_weight;
    return VsglTangentPlane(normal, dot(mean, normal) - sum_weighted_height / sum_weight);
}

// Relative tolerance of H(p) = 0: H is a difference of terms of size ‖p − μ‖ and ‖μ‖ (the
// offset's cancellation), each known to a few ULP (6e-8); 1e-3 of the distance is far above that,
// and a receiver 1e-3 of the distance above a plane sees it within 0.06° of grazing, where a
// Lambertian or glossy texel sends almost nothing.
const VSGL_PLANE_TOLERANCE: f32 = 1.0e-3;

// Fraction of a VSGL's light kept at p: 0 on or below the cluster's mean tangent plane
// (H(p) ≤ τ), 1 from H(p) ≥ 2τ, linear between, with τ = VSGL_PLANE_TOLERANCE·(‖p − μ‖ + σ).
// A record without a plane (normal 0: the mode does not use it, or the normals cancel, as for a
// whole sphere) keeps everything. A lone plane therefore gets exactly 0 from its own VSGLs in
// every diffuse form, as the papers' horizon clamp gives in theirs.
fn vsgl_tangent_plane_fade(plane: VsglTangentPlane, position: VsglPosition, shading_position: vec3f) -> f32 {
    if (!any(plane.normal != vec3f(0.0))) {
        return 1.0;
    }
    let to_receiver = shading_position - position.mean;
    let height = dot(to_receiver, plane.normal) + plane.offset;
    let tolerance = VSGL_PLANE_TOLERANCE * (length(to_receiver) + sqrt(max(position.variance, 0.0)));
    if (!(tolerance > 0.0)) {
        return select(0.0, 1.0, height > 0.0);
    }
    return clamp((height - tolerance) / tolerance, 0.0, 1.0);
}
