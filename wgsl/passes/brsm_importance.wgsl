// The importance map of bidirectional RSM importance (compute) [Tok15 §4.3, Fig. 6: "VSGLs are
// also used for the importance estimation"]: for every RSM texel i, an estimate of what it adds
// to the image, from the view's VSGLs (brsm_view_gbuffer.wgsl → vsgl_gen.wgsl).
//
// What is evaluated (derived for vsgl from the adjoint reading in brsm_view_gbuffer.wgsl): texel i is a
// VPL of radiant intensity I_i(ω) = Φ_i [R_d,i/π + R_s,i f_s,i(ω_l, ω)/R_s,i] cos_i(ω); its
// contribution to the image, summed over pixels j and rgb, is
//   q_i = Σ_j I_i(ω_ij) Ψ_j(ω_ji)/d_ij²,   Ψ_j(ω) = f_j(ω, ω_o,j) cos_j(ω),
// and by reciprocity (f_i(ω_l, ω) = f_i(ω, ω_l)) this is texel i *shaded* by the view's
// importance emitters Ψ_j with its own BRDF, "viewed" from the light direction ω_l:
//   q_i = Σ_rgb [ Φ R_d,i · (1/π)∫ L_Ψ(ω) cos_i dω  +  Φ R_s,i · ∫ L_Ψ(ω) f_s,i(ω, ω_l)/R_s,i cos_i dω ],
// L_Ψ the incoming "importance radiance" at y_i. The view's VSGLs approximate the Ψ_j as SG
// emitters (their powers are the summed pixel reflectances), so each lobe's incoming SG is
// vsgl_incoming_radiance (Tok15 Eq. 5), the diffuse integral vsgl_diffuse_accurate (clamped
// cosine kept inside: no leak from below the texel's horizon) and the specular one
// vsgl_specular with ω_o = ω_l (the SG–ASG product with the texel's GGX lobe). No visibility
// (the papers' "4096 VSGLs without shadow maps"), so q_i overestimates occluded texels; the
// sampling density stays a valid one (brsm_mix.wgsl mixes in the RSM's own weights), so this
// costs variance only, never bias.
//
// Interleaved (`importance_interleave` = k > 1; the importance map was 91% of a lavapipe frame
// at 2048 view VSGLs, and Tok15 Table 1's 0.79 ms for it implies a reduced rate): texel (x, y)
// belongs to class c = (y mod k)·k + (x mod k) and evaluates only the view VSGLs j ≡ c (mod k²),
// scaled by k² — the pattern of the shading passes' `interleave` (common/interleave.wgsl), with
// the same deinterleaved workgroups, so one tile load of a class's VSGLs serves WORKGROUP²
// texels. The view VSGLs' indices follow a stratified lattice over the view, so each class's
// subset is a coarser stratified sample of the same view and k²·Σ_{j≡c} estimates Σ_j (exact in
// expectation if the classes were random subsets). The scale cancels in q_i/Q (brsm_mix.wgsl)
// and is kept so that the map stays an estimate of q. Whatever the estimate, the mixture keeps
// every lit texel samplable, so the VPL and node-VSGL estimators stay unbiased; the cost is a
// k-periodic pattern in q (variance, and for the filtered kernels, which assume f/q smooth over
// a kernel, bias), which brsm_importance_filter.wgsl removes by recombining the classes over
// k×k windows (why it is needed is measured there). With k > 1 this pass writes a scratch
// buffer the filter reads; k = 1 is the plain mapping, bit for bit, straight into the pyramid.
#include "common/constants.wgsl"
#include "common/math.wgsl"
#include "common/sg.wgsl"
#include "common/ggx.wgsl"
#include "common/vsgl.wgsl"
#include "common/vsgl_record.wgsl"
#include "common/frame.wgsl"
#include "common/gbuffer.wgsl"
#include "common/plan.wgsl"
#include "common/interleave.wgsl"

struct ImportanceParams {
    rsm_size: u32,
    // View VSGLs.
    count: u32,
    // Interleave tile side k (1: every view VSGL at every texel).
    interleave: u32,
    _pad0: u32,
}

const WORKGROUP: u32 = 8u;
const TILE: u32 = 64u; // = WORKGROUP², one view VSGL of the class loaded per thread

@group(0) @binding(0) var<uniform> params: ImportanceParams;
@group(0) @binding(1) var<storage, read> light: LightRaw;
@group(0) @binding(2) var<storage, read> rsm_position: array<vec4f>;
@group(0) @binding(3) var<storage, read> rsm_normal: array<vec4f>;
@group(0) @binding(4) var<storage, read> rsm_flux_diffuse: array<vec4f>;
@group(0) @binding(5) var<storage, read> rsm_flux_specular: array<vec4f>;
@group(0) @binding(6) var<storage, read> view_vsgls: array<VsglRaw>;
// Level 0 of the importance pyramid (k = 1) or the interleaved estimates (k > 1): q_i per texel.
@group(0) @binding(7) var<storage, read_write> importance: array<f32>;

var<workgroup> tile: array<VsglRaw, TILE>;

@compute @workgroup_size(WORKGROUP, WORKGROUP, 1)
fn main(@builtin(workgroup_id) wg: vec3u, @builtin(local_invocation_id) lid: vec3u, @builtin(local_invocation_index) local: u32) {
    let n_side = params.rsm_size;
    let k = params.interleave;
    let stride = k * k;
    let ip = interleaved_pixel(wg, lid, vec2u(n_side), k, WORKGROUP);
    let inside = ip.pixel.x < n_side && ip.pixel.y < n_side;
    let i = ip.pixel.y * n_side + ip.pixel.x;
    var lit = false;
    var y = vec3f(0.0);
    var normal = vec3f(0.0, 0.0, 1.0);
    var alpha = 1.0;
    var to_light = vec3f(0.0, 0.0, 1.0);
    var fd = vec3f(0.0);
    var fs = vec3f(0.0);
    if (inside) {
        let pos = rsm_position[i];
        fd = rsm_flux_diffuse[i].rgb;
        if (HAS_SPECULAR) {
            fs = rsm_flux_specular[i].rgb;
        }
        lit = pos.w != GBUFFER_BACKGROUND && (fd.r + fd.g + fd.b + fs.r + fs.g + fs.b) > 0.0;
        // RSM positions are relative to the RSM's origin, `light.position` (relative to the
        // frame origin, as the view VSGLs are): vpl_sample.wgsl's write_vpl.
        y = pos.xyz + light.position;
        let nr = rsm_normal[i];
        normal = nr.xyz;
        alpha = ggx_alpha_from_roughness(nr.w);
        to_light = safe_normalize(-pos.xyz, normal);
        if (light.kind == LIGHT_KIND_DIRECTIONAL) {
            to_light = -light.direction;
        }
    }
    var diffuse = vec3f(0.0);
    var specular = vec3f(0.0);
    // The class's view VSGLs are class_index + m·k², m = 0 … class_count − 1 (the same for the
    // whole workgroup). Every thread takes part in the tile loads and barriers, lit or not.
    let class_count = class_light_count(ip.class_index, params.count, k);
    for (var tile_start = 0u; tile_start < class_count; tile_start += TILE) {
        let m = tile_start + local;
        if (m < class_count) {
            tile[local] = view_vsgls[ip.class_index + m * stride];
        }
        workgroupBarrier();
        let n_tile = min(TILE, class_count - tile_start);
        if (lit) {
            for (var t = 0u; t < n_tile; t++) {
                let v = tile[t];
                let position = VsglPosition(v.mean, v.variance);
                // Each lobe: incoming SG per unit power times its rgb power, as vsgl_shading.wgsl
                // shades the light's VSGLs with the default lambert_lobe="hemisphere".
                if (any(v.diffuse_power > vec3f(0.0))) {
                    let in_d = vsgl_incoming_radiance(vsgl_record_diffuse_lobe(v, LAMBERT_LOBE_HEMISPHERE_GAIN), position, y);
                    diffuse += v.diffuse_power * vsgl_diffuse_accurate(in_d, normal);
                    if (HAS_SPECULAR) {
                        specular += v.diffuse_power * vsgl_specular(in_d, normal, to_light, alpha);
                    }
                }
                if (HAS_SPECULAR && any(v.specular_power > vec3f(0.0))) {
                    let in_s = vsgl_incoming_radiance(vsgl_record_specular_lobe(v), position, y);
                    diffuse += v.specular_power * vsgl_diffuse_accurate(in_s, normal);
                    specular += v.specular_power * vsgl_specular(in_s, normal, to_light, alpha);
                }
            }
        }
        workgroupBarrier();
    }
    if (inside) {
        let q = fd * diffuse + fs * specular;
        // Finite and ≥ 0 by construction; the clamp keeps one overflowing texel from making the
        // pyramid's total infinite. × k²: the class's share stands for all view VSGLs.
        importance[i] = select(0.0, min((q.r + q.g + q.b) * f32(stride), FLT_MAX), lit);
    }
}
