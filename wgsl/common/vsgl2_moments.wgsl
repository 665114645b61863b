// vsgl:include-only (the includer defines the entry points)
// Two VSGLs by parallel summation (compute) [the 2015 poster "Fast indirect illumination using
// two virtual spherical Gaussian lights", Fig. 2]: one VSGL for the diffuse lobes and one for the
// specular lobes of all RSM texels (VPLs), each with its own positional Gaussian.
// Per texel (positions y relative to the light, as in vsgl_moments.wgsl), with
// w_d = Φ·R_d and w_s = Φ·R_s summed over rgb:
//   diffuse_power      = (Φ·R_d rgb, w_d (‖y‖² + v))   v: the texel's footprint variance
//   diffuse_direction  = (w_d ξ̄_d, w_d)        ξ̄_d: Toksvig mean direction of the Lambert SG
//   diffuse_position   = (w_d y, 0)
//   specular_power     = (Φ·R_s rgb, w_s (‖y‖² + v))
//   specular_direction = (w_s ξ̄_s, w_s)        ξ̄_s: Toksvig mean direction of the GGX lobe SG
//   specular_position  = (w_s y, 0)
// = 6 vec4 per texel: the poster's three RGBA32F buffers per VSGL; and one shared by both,
//   plane              = (w n, w (y·n))       w = w_d + w_s, n the texel normal
// the cluster's mean tangent plane (vsgl_tangent_plane.wgsl; the fade's height
// p·N̄ − E_w[y·n] does not depend on which weights gave μ, so one plane serves both records).
// Shared by the two implementations of the reduction (passes/vsgl2_reduce.wgsl: shared memory;
// passes/vsgl2_reduce_subgroup.wgsl: subgroup sums). Their entry points:
//   `tiles`: one 8×8 workgroup per 8×8 RSM tile (texels outside the RSM count as zero, so any
//            RSM side works) sums its tile in shared memory (a pairwise tree) and writes one
//            partial: ⌈n/8⌉² partials, 1/64 of the RSM as in the poster.
//   `merge`: one 64-thread workgroup per 256 partials (each thread adds 4 pairwise, then the same
//            tree): ⌈count/256⌉ partials. Repeated until one workgroup is left; that last
//            dispatch (`finish` = 1) also turns the total into the two VSGL records.
// Every addition is part of a pairwise tree (4-way pairwise, then binary), so the f32 rounding
// error of a total grows with log2 of the texel count, not with the count.
#include "common/constants.wgsl"
#include "common/math.wgsl"
#include "common/sg.wgsl"
#include "common/ggx.wgsl"
#include "common/vsgl.wgsl"
#include "common/vsgl_record.wgsl"
#include "common/vsgl_tangent_plane.wgsl"
#include "common/plan.wgsl"
#include "common/rsm_lobes.wgsl"

struct ReduceParams {
    rsm_size: u32,
    // `merge`: number of input partials.
    count: u32,
    // `merge`: 1 on the last dispatch (one workgroup), which writes the two VSGLs.
    finish: u32,
    _pad0: u32,
    // Light position relative to the frame origin: the moments are relative to the light.
    light_offset: vec3f,
    _pad1: f32,
    // (direction, 1) for a directional light, 0 otherwise (rsm_lobe_means).
    light_dir: vec4f,
    // LightRsm::texel_footprint (rsm_texel_footprint_variance).
    texel_footprint: vec4f,
}

struct Moments2 {
    diffuse_power: vec4f,
    diffuse_direction: vec4f,
    diffuse_position: vec4f,
    specular_power: vec4f,
    specular_direction: vec4f,
    specular_position: vec4f,
    plane: vec4f,
}

const TILE: u32 = 8u;
const GROUP: u32 = 64u;
// Partials one `merge` workgroup reduces (4 per thread).
const MERGE_SPAN: u32 = 256u;

@group(0) @binding(0) var<uniform> params: ReduceParams;
@group(0) @binding(1) var<storage, read> rsm_position: array<vec4f>;
@group(0) @binding(2) var<storage, read> rsm_normal: array<vec4f>;
@group(0) @binding(3) var<storage, read> rsm_flux_diffuse: array<vec4f>;
@group(0) @binding(4) var<storage, read> rsm_flux_specular: array<vec4f>;
@group(0) @binding(5) var<storage, read> partial_in: array<Moments2>;
@group(0) @binding(6) var<storage, read_write> partial_out: array<Moments2>;
@group(0) @binding(7) var<storage, read_write> vsgls: array<VsglRaw>;


fn moments_zero() -> Moments2 {
    return Moments2(vec4f(0.0), vec4f(0.0), vec4f(0.0), vec4f(0.0), vec4f(0.0), vec4f(0.0), vec4f(0.0));
}

fn moments_add(a: Moments2, b: Moments2) -> Moments2 {
    return Moments2(
        a.diffuse_power + b.diffuse_power,
        a.diffuse_direction + b.diffuse_direction,
        a.diffuse_position + b.diffuse_position,
        a.specular_power + b.specular_power,
        a.specular_direction + b.specular_direction,
        a.specular_position + b.specular_position,
        a.plane + b.plane,
    );
}

// The moments of RSM texel (x, y); zero outside the RSM and where no power is reflected (the
// same test as vsgl_moments.wgsl, so background texels never reach the lobe functions).
fn texel_moments(xy: vec2u) -> Moments2 {
    let n = params.rsm_size;
    if (xy.x >= n || xy.y >= n) {
        return moments_zero();
    }
    let i = xy.y * n + xy.x;
    let fd = rsm_flux_diffuse[i].rgb;
    var fs = vec3f(0.0);
    if (HAS_SPECULAR) {
        fs = rsm_flux_specular[i].rgb;
    }
    let wd = fd.r + fd.g + fd.b;
    let ws = fs.r + fs.g + fs.b;
    if (!(wd + ws > 0.0)) {
        return moments_zero();
    }
    let y = rsm_position[i].xyz;
    let normal = rsm_normal[i].xyz;
    let lobes = rsm_lobe_means(y, normal, rsm_normal[i].w, params.light_dir);
    let mean_d = lobes.diffuse;
    let mean_s = lobes.specular;
    // Each texel's own extent is part of the cluster's positional variance.
    let y2 = dot(y, y) + rsm_texel_footprint_variance(y, normal, params.light_dir, params.texel_footprint);
    return Moments2(
        vec4f(fd, wd * y2),
        vec4f(wd * mean_d, wd),
        vec4f(wd * y, 0.0),
        vec4f(fs, ws * y2),
        vec4f(ws * mean_s, ws),
        vec4f(ws * y, 0.0),
        (wd + ws) * vec4f(normal, dot(y, normal)),
    );
}

fn partial_at(i: u32) -> Moments2 {
    if (i < params.count) {
        return partial_in[i];
    }
    return moments_zero();
}

// The record of one lobe's VSGL from its summed moments; the other lobe carries no power.
fn lobe_record(power: vec4f, direction: vec4f, position_sum: vec4f, plane_sum: vec4f, plane_weight: f32) -> VsglRaw {
    var out: VsglRaw;
    let lobe = vsgl_lobe_from_moments(direction.w, direction.xyz);
    let position = vsgl_position_from_moments(direction.w, position_sum.xyz, power.w);
    // plane_sum is over all texels with w = w_d + w_s (plane_weight = Σw); the shading pass
    // reads the plane only for the forms that fade (ShadeParams.plane_fade).
    let plane = vsgl_tangent_plane_from_moments(plane_weight, plane_sum.xyz, plane_sum.w, position.mean);
    out.plane_normal = plane.normal;
    out.plane_offset = plane.offset;
    out.mean = position.mean + params.light_offset;
    // Two VSGLs stand for the whole RSM: their shadow rays keep aiming at μ (docs/methods/visibility.md).
    out.shadow_target = out.mean;
    out.variance = position.variance;
    // vsgl_lobe_from_moments: ξ̄ = Σwξ̄/Σw → (axis, λ) by sg_from_toksvig_mean_direction; a lobe
    // without power comes back as axis +z, λ = 0.
    out.diffuse_axis = lobe.axis;
    out.diffuse_sharpness = lobe.sharpness;
    out.specular_axis = vec3f(0.0, 0.0, 1.0);
    out.diffuse_power = min(power.rgb, vec3f(FLT_MAX));
    // One kernel covering the whole RSM: level log2(n), centre n/2, mass 1, no sampling pdf.
    out.level = log2(f32(params.rsm_size));
    out.pdf = 0.0;
    out.center = vec2f(0.5 * f32(params.rsm_size));
    out.mass = 1.0;
    return out;
}

// The last merge's total → record 0: the diffuse VSGL (its lobe in the diffuse fields);
// record 1: the specular VSGL (its lobe moved to the specular fields).
fn write_records(total: Moments2) {
    let plane_weight = total.diffuse_direction.w + total.specular_direction.w;
    vsgls[0] = lobe_record(total.diffuse_power, total.diffuse_direction, total.diffuse_position, total.plane, plane_weight);
    var specular = lobe_record(total.specular_power, total.specular_direction, total.specular_position, total.plane, plane_weight);
    specular.specular_axis = specular.diffuse_axis;
    specular.specular_sharpness = specular.diffuse_sharpness;
    specular.specular_power = specular.diffuse_power;
    specular.diffuse_axis = vec3f(0.0, 0.0, 1.0);
    specular.diffuse_sharpness = 0.0;
    specular.diffuse_power = vec3f(0.0);
    vsgls[1] = specular;
}

// The four partials a `merge` thread adds first (4-way pairwise).
fn merge_inputs(wid: u32, lid: u32) -> Moments2 {
    let base = wid * MERGE_SPAN + lid;
    let a = moments_add(partial_at(base), partial_at(base + GROUP));
    let b = moments_add(partial_at(base + 2u * GROUP), partial_at(base + 3u * GROUP));
    return moments_add(a, b);
}
