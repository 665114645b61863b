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

// A workgroup filters TILE consecutive pixels along the filter's axis. Its threads first copy the
// span the taps reach (TILE + 2·radius pixels, radius ≤ MAX_RADIUS = the largest interleave) from
// the G-buffer into workgroup memory, demodulated once per pixel, and every tap then reads it
// there: the x pass used to read position, normal, input and (to demodulate) base colour and
// geometric normal per tap, 16 taps per pixel at k = 8. The taps and their order are unchanged,
// so the output is the same to the bit.
const TILE: u32 = 64u;
const MAX_RADIUS: u32 = 16u;
const SPAN: u32 = TILE + 2u * MAX_RADIUS;

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

// The span: position (w: depth, or GBUFFER_BACKGROUND also for pixels outside the image), shading
// normal, the input diffuse (demodulated in the x pass) and specular.
var<workgroup> span_position: array<vec4f, SPAN>;
var<workgroup> span_normal: array<vec3f, SPAN>;
var<workgroup> span_diffuse: array<vec3f, SPAN>;
var<workgroup> span_specular: array<vec3f, SPAN>;

// Workgroup (a, b): pixels a·TILE … a·TILE + TILE − 1 along the filter's axis, line b across it.
@compute @workgroup_size(TILE, 1, 1)
fn main(@builtin(workgroup_id) wg: vec3u, @builtin(local_invocation_index) local: u32) {
    let size = vec2i(frame.size);
    let along_x = params.direction == 0u;
    let step = select(vec2i(0, 1), vec2i(1, 0), along_x);
    let demodulate_input = along_x;
    let r = params.radius;
    let first = vec2i(select(vec2u(wg.y, wg.x * TILE), vec2u(wg.x * TILE, wg.y), along_x)) - r * step;
    // Copy the span [first, first + TILE + 2r) along the axis; every thread takes part, so the
    // barrier below is reached uniformly.
    for (var s = local; s < TILE + 2u * u32(r); s += TILE) {
        let q = first + i32(s) * step;
        var position = vec4f(0.0, 0.0, 0.0, GBUFFER_BACKGROUND);
        if (q.x >= 0 && q.y >= 0 && q.x < size.x && q.y < size.y) {
            let j = u32(q.y * size.x + q.x);
            position = gbuf_position[j];
            if (position.w != GBUFFER_BACKGROUND) {
                span_normal[s] = gbuf_normal[j].xyz;
                var d = in_diffuse[j].rgb;
                if (demodulate_input) {
                    d = d / rd_at(j);
                }
                span_diffuse[s] = d;
                if (HAS_SPECULAR) {
                    span_specular[s] = in_specular[j].rgb;
                }
            }
        }
        span_position[s] = position;
    }
    workgroupBarrier();

    let xy = first + (i32(local) + r) * step;
    if (xy.x >= size.x || xy.y >= size.y) {
        return;
    }
    let index = u32(xy.y * size.x + xy.x);
    let centre = local + u32(r);
    let pos = span_position[centre];
    if (pos.w == GBUFFER_BACKGROUND) {
        out_diffuse[index] = vec4f(0.0);
        if (HAS_SPECULAR) {
            out_specular[index] = vec4f(0.0);
        }
        return;
    }
    let depth = pos.w;
    let n = span_normal[centre];
    var sum_d = vec3f(0.0);
    var sum_s = vec3f(0.0);
    var sum_w = 0.0;
    // Taps −r … r − 1 of the centre are span entries local … local + 2r − 1.
    for (var t = 0u; t < 2u * u32(r); t++) {
        let qp = span_position[local + t];
        if (qp.w == GBUFFER_BACKGROUND) {
            continue;
        }
        let dz = dot(n, qp.xyz - pos.xyz) / (PLANE_SIGMA * depth);
        let cos_n = max(dot(n, span_normal[local + t]), 0.0);
        let w = exp(-dz * dz) * pow(cos_n, NORMAL_POWER);
        sum_d += w * span_diffuse[local + t];
        if (HAS_SPECULAR) {
            sum_s += w * span_specular[local + t];
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
