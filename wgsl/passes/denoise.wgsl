// Geometry-aware denoising of interleaved indirect light (compute) [Tok15 §5: 17×17 filter for
// 8×8 interleaving; Laine et al. 2007], as two separable cross-bilateral passes: along x, then
// along y, each over offsets −k … k−1 (k = the interleave factor). The x pass averages the k
// column residues of the interleaving pattern and the y pass the k row residues, so every
// interleaved subset of VSGLs enters with equal weight on a flat surface — like the (2k)² window
// it replaces, at 4k instead of 4k² taps. (An odd 17-tap window counts one residue 3 times and
// the others twice, leaving a period-k pattern on flat walls.) Taps are weighted by the distance
// to the centre pixel's tangent plane and by normal similarity so light does not bleed across
// edges. Diffuse light is demodulated by R_d in the x pass and remodulated in the y pass, so
// texture detail is kept.
#include "common/constants.wgsl"
#include "common/frame.wgsl"
#include "common/gbuffer.wgsl"
#include "common/plan.wgsl"

struct DenoiseParams {
    radius: i32,
    // 0: along x, input modulated, output demodulated; 1: along y, demodulated → modulated.
    direction: u32,
    _pad1: u32,
    _pad2: u32,
}

const WORKGROUP: u32 = 8u;
// Distance of a tap from the centre pixel's tangent plane, relative to the centre's depth, at
// which its weight falls to e^-1. A plane distance (not a depth difference) keeps surfaces seen
// at grazing angles, whose depth changes fast across the screen, filtered.
const PLANE_SIGMA: f32 = 0.02;
// Exponent on the normal cosine: taps whose normals differ by 15° weigh about 0.3.
const NORMAL_POWER: f32 = 32.0;
// Keeps demodulation finite on black surfaces (their indirect diffuse is 0 anyway).
const ALBEDO_FLOOR: f32 = 1.0e-4;

@group(0) @binding(0) var<uniform> frame: FrameUniforms;
@group(1) @binding(0) var<uniform> params: DenoiseParams;
@group(1) @binding(1) var<storage, read> gbuf_position: array<vec4f>;
@group(1) @binding(2) var<storage, read> gbuf_normal: array<vec4f>;
@group(1) @binding(3) var<storage, read> gbuf_geo_normal: array<vec4f>;
@group(1) @binding(4) var<storage, read> gbuf_base_color: array<vec4f>;
@group(1) @binding(5) var<storage, read> in_diffuse: array<vec4f>;
@group(1) @binding(6) var<storage, read> in_specular: array<vec4f>;
@group(1) @binding(7) var<storage, read_write> out_diffuse: array<vec4f>;
@group(1) @binding(8) var<storage, read_write> out_specular: array<vec4f>;

fn rd_at(i: u32) -> vec3f {
    return max(gbuffer_diffuse_reflectance(gbuf_base_color[i].rgb, gbuf_geo_normal[i].w), vec3f(ALBEDO_FLOOR));
}

@compute @workgroup_size(WORKGROUP, WORKGROUP, 1)
fn main(@builtin(global_invocation_id) gid: vec3u) {
    let size = vec2i(frame.size);
    let xy = vec2i(gid.xy);
    if (xy.x >= size.x || xy.y >= size.y) {
        return;
    }
    let index = u32(xy.y * size.x + xy.x);
    let pos = gbuf_position[index];
    if (pos.w == GBUFFER_BACKGROUND) {
        out_diffuse[index] = vec4f(0.0);
        if (HAS_SPECULAR) {
            out_specular[index] = vec4f(0.0);
        }
        return;
    }
    let depth = pos.w;
    let n = gbuf_normal[index].xyz;
    let step = select(vec2i(0, 1), vec2i(1, 0), params.direction == 0u);
    let demodulate_input = params.direction == 0u;
    var sum_d = vec3f(0.0);
    var sum_s = vec3f(0.0);
    var sum_w = 0.0;
    let r = params.radius;
    for (var t = -r; t < r; t++) {
        let q = xy + t * step;
        if (q.x < 0 || q.y < 0 || q.x >= size.x || q.y >= size.y) {
            continue;
        }
        let j = u32(q.y * size.x + q.x);
        let qp = gbuf_position[j];
        if (qp.w == GBUFFER_BACKGROUND) {
            continue;
        }
        let dz = dot(n, qp.xyz - pos.xyz) / (PLANE_SIGMA * depth);
        let cos_n = max(dot(n, gbuf_normal[j].xyz), 0.0);
        let w = exp(-dz * dz) * pow(cos_n, NORMAL_POWER);
        var d = in_diffuse[j].rgb;
        if (demodulate_input) {
            d = d / rd_at(j);
        }
        sum_d += w * d;
        if (HAS_SPECULAR) {
            sum_s += w * in_specular[j].rgb;
        }
        sum_w += w;
    }
    // The centre tap (offset 0 is inside −k … k−1) always has weight 1, so sum_w ≥ 1.
    var out_d = sum_d / sum_w;
    if (!demodulate_input) {
        out_d = out_d * rd_at(index);
    }
    out_diffuse[index] = vec4f(out_d, 0.0);
    if (HAS_SPECULAR) {
        out_specular[index] = vec4f(sum_s / sum_w, 0.0);
    }
}
