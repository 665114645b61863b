// The papers' additional RSM buffers (compute) [Tok15 §4.1 and Fig. 4; Tok16 §4.1 and Fig. 4]:
// per texel, the moments whose sums over a cluster define a VSGL. Six vec4 chains, each a
// full mip chain in one buffer (chain c starts at c·chain_len; levels as in pdf_mips):
//   A = (Φ·R_d rgb, w)                 w = Φ·(R_d + R_s) summed over rgb (the paper's weight)
//   B = (Φ·R_s rgb, w_d)               w_d = Φ·R_d summed over rgb
//   C = (w_d ξ̄_d, w_s)                 ξ̄_d: Toksvig mean direction of the diffuse lobe SG
//   D = (w_s ξ̄_s, w (‖y‖² + v))        ξ̄_s: Toksvig mean direction of the GGX lobe SG;
//                                      v: the texel's own positional variance (footprint)
//   E = (w y, 0)                       y: texel position relative to the light (local origin)
//   F = (w n, w (y·n))                 n: texel normal — the cluster's mean tangent plane
//                                      (vsgl_tangent_plane_fade in vsgl.wgsl)
// Mip levels hold 2×2 averages (passes/moment_mips.wgsl), so a cluster of 4^l texels sums to
// 4^l × its level-l value [Tok15 §4.1].
#include "common/constants.wgsl"
#include "common/math.wgsl"
#include "common/sg.wgsl"
#include "common/ggx.wgsl"
#include "common/gbuffer.wgsl"
#include "common/plan.wgsl"
#include "common/rsm_lobes.wgsl"

struct MomentParams {
    rsm_size: u32,
    chain_len: u32,
    // 1: chain F exists (MomentChains::count = 6) and is written.
    planes: u32,
    _pad1: u32,
    // (direction, 1) for a directional light, 0 otherwise (rsm_lobe_means).
    light_dir: vec4f,
    // LightRsm::texel_footprint: (view axis, t²(2/N)²) of a perspective RSM; (0, (2R/N)²) of
    // an orthographic one.
    texel_footprint: vec4f,
}

const WORKGROUP: u32 = 8u;

@group(0) @binding(0) var<uniform> params: MomentParams;
@group(0) @binding(1) var<storage, read> rsm_position: array<vec4f>;
@group(0) @binding(2) var<storage, read> rsm_normal: array<vec4f>;
@group(0) @binding(3) var<storage, read> rsm_flux_diffuse: array<vec4f>;
@group(0) @binding(4) var<storage, read> rsm_flux_specular: array<vec4f>;
@group(0) @binding(5) var<storage, read_write> moments: array<vec4f>;

@compute @workgroup_size(WORKGROUP, WORKGROUP, 1)
fn main(@builtin(global_invocation_id) gid: vec3u) {
    let n = params.rsm_size;
    if (gid.x >= n || gid.y >= n) {
        return;
    }
    let i = gid.y * n + gid.x;
    let stride = params.chain_len;
    let fd = rsm_flux_diffuse[i];
    var fs = vec3f(0.0);
    if (HAS_SPECULAR) {
        fs = rsm_flux_specular[i].rgb;
    }
    let wd = fd.r + fd.g + fd.b;
    let ws = fs.r + fs.g + fs.b;
    let w = wd + ws;
    let chains = select(5u, 6u, params.planes == 1u);
    if (!(w > 0.0)) {
        for (var c = 0u; c < chains; c++) {
            moments[c * stride + i] = vec4f(0.0);
        }
        return;
    }
    let y = rsm_position[i].xyz;
    let normal = rsm_normal[i].xyz;
    let lobes = rsm_lobe_means(y, normal, rsm_normal[i].w, params.light_dir);
    let mean_d = lobes.diffuse;
    let mean_s = lobes.specular;
    moments[i] = vec4f(fd.rgb, w);
    moments[stride + i] = vec4f(fs, wd);
    moments[2u * stride + i] = vec4f(wd * mean_d, ws);
    moments[3u * stride + i] = vec4f(ws * mean_s, w * (dot(y, y) + rsm_texel_footprint_variance(y, normal, params.light_dir, params.texel_footprint)));
    moments[4u * stride + i] = vec4f(w * y, 0.0);
    if (params.planes == 1u) {
        moments[5u * stride + i] = vec4f(w * normal, w * dot(y, normal));
    }
}
