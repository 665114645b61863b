// The camera side of bidirectional RSM importance (compute) [Tok15 §4.3, "a diffuse lobe
// buffer, specular lobe buffer, and position buffer are added into the G-buffer ... only
// reflectances are used as weights"]: the camera's G-buffer resampled onto a square
// power-of-two grid laid out like an RSM, so the VSGL machinery (vsgl_moments, moment_mips,
// pdf_mips, vsgl_gen) builds VSGLs of the view from it unchanged.
//
// Why it is an RSM in disguise (adjoint / importance transport): the contribution of an RSM texel
// i (a VPL of radiant intensity I_i(ω)) to pixel j is I_i(ω_ij)·f_j(ω_ji, ω_o,j)·cos_j/d². Read
// the other way round, pixel j is an emitter of "importance" with intensity
// Ψ_j(ω) = f_j(ω, ω_o,j)·cos_j(ω) — exactly a VPL of unit flux with the pixel's reflectances
// R_d, R_s, lit from the eye (the eye plays the light: the GGX lobe mirrors the view direction,
// as rsm_lobe_means does for a light at the origin; G-buffer positions are relative to the
// camera). So each grid texel gets flux 1 (one pixel), Φ·R_d = R_d, Φ·R_s = R_s, and the weight
// R_d + R_s summed over rgb, as an RSM texel gets Φ·(R_d + R_s).
//
// Grid: P×P texels (P a power of two, chosen by the caller); texel (u, v) takes the pixel under
// its centre, (⌊(u + ½)·W/P⌋, ⌊(v + ½)·H/P⌋): a stratified subsample when P < W or H, pixels
// repeated when P > W or H. Background pixels give weight 0.
#include "common/constants.wgsl"
#include "common/gbuffer.wgsl"
#include "common/plan.wgsl"

struct ViewParams {
    // Camera image size W, H and grid side P.
    width: u32,
    height: u32,
    grid: u32,
    _pad: u32,
}

const WORKGROUP: u32 = 8u;

@group(0) @binding(0) var<uniform> params: ViewParams;
@group(0) @binding(1) var<storage, read> gbuf_position: array<vec4f>;
@group(0) @binding(2) var<storage, read> gbuf_normal: array<vec4f>;
@group(0) @binding(3) var<storage, read> gbuf_geo_normal: array<vec4f>;
@group(0) @binding(4) var<storage, read> gbuf_base_color: array<vec4f>;
// The grid, in the RSM layout (gbuffer.wgsl positions and normals, rsm_flux.wgsl fluxes).
@group(0) @binding(5) var<storage, read_write> view_position: array<vec4f>;
@group(0) @binding(6) var<storage, read_write> view_normal: array<vec4f>;
@group(0) @binding(7) var<storage, read_write> view_flux_diffuse: array<vec4f>;
@group(0) @binding(8) var<storage, read_write> view_flux_specular: array<vec4f>;
@group(0) @binding(9) var<storage, read_write> view_weight: array<f32>;

@compute @workgroup_size(WORKGROUP, WORKGROUP, 1)
fn main(@builtin(global_invocation_id) gid: vec3u) {
    let p = params.grid;
    if (gid.x >= p || gid.y >= p) {
        return;
    }
    let out = gid.y * p + gid.x;
    let px = min(u32((f32(gid.x) + 0.5) * f32(params.width) / f32(p)), params.width - 1u);
    let py = min(u32((f32(gid.y) + 0.5) * f32(params.height) / f32(p)), params.height - 1u);
    let pixel = py * params.width + px;
    let pos = gbuf_position[pixel];
    if (pos.w == GBUFFER_BACKGROUND) {
        view_position[out] = vec4f(0.0, 0.0, 0.0, GBUFFER_BACKGROUND);
        view_normal[out] = vec4f(0.0, 0.0, 1.0, 1.0);
        view_flux_diffuse[out] = vec4f(0.0);
        if (HAS_SPECULAR) {
            view_flux_specular[out] = vec4f(0.0);
        }
        view_weight[out] = 0.0;
        return;
    }
    let base = gbuf_base_color[pixel];
    let metallic = gbuf_geo_normal[pixel].w;
    let rd = gbuffer_diffuse_reflectance(base.rgb, metallic);
    var rs = vec3f(0.0);
    if (HAS_SPECULAR) {
        rs = gbuffer_specular_reflectance(base.rgb, metallic, base.w);
        view_flux_specular[out] = vec4f(rs, 0.0);
    }
    let weight = rd.r + rd.g + rd.b + rs.r + rs.g + rs.b;
    view_position[out] = pos;
    view_normal[out] = gbuf_normal[pixel];
    view_flux_diffuse[out] = vec4f(rd, weight);
    view_weight[out] = weight;
}
