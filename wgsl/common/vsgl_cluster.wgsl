// A VSGL from its cluster's moment sums, and a candidate shadow target from its texel's
// moments: shared by the generation of the sampled kernels (passes/vsgl_gen.wgsl) and of
// k-means (passes/kmeans_sums.wgsl), so both turn moments into records by the same formulas
// [Tok15 §3.1; Tok16 Appendix B; Tok16s §3]. The chains are those of passes/vsgl_moments.wgsl.
// vsgl:include-only (validated inside the shaders that include it)
#include "common/constants.wgsl"
#include "common/math.wgsl"
#include "common/sg.wgsl"
#include "common/vsgl.wgsl"
#include "common/vsgl_tangent_plane.wgsl"
#include "common/vsgl_record.wgsl"

// The chain values of one cluster: sums over its texels, or averages at one mip level (any
// common multiple of the sums: only their ratios enter, and `power_scale` turns a.rgb and b.rgb
// into the cluster's powers). f is read only when `planes`.
struct ClusterMoments {
    a: vec4f,
    b: vec4f,
    c: vec4f,
    d: vec4f,
    e: vec4f,
    f: vec4f,
}

// Toksvig-merged lobes, the positional Gaussian (relative to the light, moved by
// `light_offset` to the frame's origin), powers and, with `planes`, the mean tangent plane; the
// other fields of the record are left zero for the caller.
fn vsgl_from_cluster_moments(m: ClusterMoments, power_scale: f32, planes: bool, light_offset: vec3f) -> VsglRaw {
    var out: VsglRaw;
    let lobe_d = sg_from_toksvig_mean_direction(m.c.xyz / max(m.b.w, FLT_MIN));
    let lobe_s = sg_from_toksvig_mean_direction(m.d.xyz / max(m.c.w, FLT_MIN));
    let position = vsgl_position_from_moments(m.a.w, m.e.xyz, m.d.w);
    if (planes && m.a.w > 0.0) {
        let plane = vsgl_tangent_plane_from_moments(m.a.w, m.f.xyz, m.f.w, position.mean);
        out.plane_normal = plane.normal;
        out.plane_offset = plane.offset;
    }
    out.mean = position.mean + light_offset;
    out.variance = position.variance;
    out.diffuse_axis = lobe_d.axis;
    out.diffuse_sharpness = lobe_d.sharpness;
    out.diffuse_power = min(m.a.rgb * power_scale, vec3f(FLT_MAX));
    out.specular_axis = lobe_s.axis;
    out.specular_sharpness = lobe_s.sharpness;
    out.specular_power = min(m.b.rgb * power_scale, vec3f(FLT_MAX));
    return out;
}

// One candidate shadow target as the shading pass reads it, two vec4f rows: (y, the texel's
// footprint variance), (its normal, its diffuse power over q, the density it was drawn by:
// self-normalised in shading). `texel` holds the texel's own chain values (level 0); a texel
// without weight gives `fallback` and no light.
struct ShadowCandidate {
    point: vec4f,
    normal: vec4f,
}

fn shadow_candidate_from_texel(texel: ClusterMoments, planes: bool, q: f32, fallback: vec3f, light_offset: vec3f) -> ShadowCandidate {
    let a = texel.a;
    let w = a.w;
    var y = fallback;
    var normal = vec3f(0.0);
    var footprint = 0.0;
    var diffuse_share = 0.0;
    if (w > 0.0) {
        let y_light = texel.e.xyz / w;
        y = y_light + light_offset;
        var direction = texel.c.xyz;
        if (planes) {
            direction = texel.f.xyz;
        }
        normal = safe_normalize(direction, vec3f(0.0));
        // Chain D's w·(y·y + σ_t²) less y·y: the texel's own footprint variance.
        footprint = max(texel.d.w / w - dot(y_light, y_light), 0.0);
        diffuse_share = select(0.0, (a.r + a.g + a.b) / q, q > 0.0);
    }
    return ShadowCandidate(vec4f(y, footprint), vec4f(normal, diffuse_share));
}
