// Geometry-aware denoising of interleaved indirect light (compute) [Tok15 §5: 17×17 filter for
// 8×8 interleaving; Laine et al. 2007], as two separable cross-bilateral passes: along x, then
// along y, each over offsets −k … k (k = the interleave factor), the two ends at half weight. The
// x pass averages the k column residues of the interleaving pattern and the y pass the k row
// residues, so every interleaved subset of VSGLs enters with equal weight on a flat surface —
// like the (2k)² window it replaces, at 4k + 2 instead of 4k² taps. Taps are weighted by their
// distances to each other's tangent planes and by normal similarity so light does not bleed
// across edges. Diffuse light is demodulated by R_d in the x pass and remodulated in the y pass,
// so texture detail is kept.
//
// With denoise_form="exchange" each pass conserves the light it filters (docs/methods/vsgl.md, "A
// denoiser that keeps the light"); the default gather only nearly. A normalised gather,
// out_p = Σ_q w_pq x_q / Σ_q w_pq, moves light wherever the neighbourhoods differ: a pixel at a
// crease or a silhouette has few accepted taps, so its value reaches its neighbours with a small
// share of theirs, and where the light is brightest
// exactly there (near-field light at creases, FlightHelmet's) the image lost 27% of its diffuse
// light while the weights were the centre's alone (each tap's distance to the centre's tangent
// plane); with weights symmetric in the pair, w_pq = w_qp, it loses 5%. An exchange loses none:
//     E'_p = E_p + Σ_q h_q w_pq m_q (E_q − E_p) / max(A_p, A_q),   A_p = Σ_q h_q w_pq m_q,
// with m the light's "mass" per pixel (R_d per channel for the demodulated diffuse irradiance E,
// 1 for specular) and h the taps' half weights at ±k: each exchange p ↔ q moves as much light
// into p as out of q, so Σ_p m_p E_p is the same after the pass, and each E'_p is a convex
// combination of its taps (Σ_q h_q w_pq m_q / max(A_p, A_q) ≤ 1). On a flat surface (every A
// the same) it is the normalised gather Σ_q h_q w_pq m_q E_q / A_p.
#include "common/constants.wgsl"
#include "common/frame.wgsl"
#include "common/gbuffer.wgsl"
#include "common/plan.wgsl"

struct DenoiseParams {
    radius: i32,
    // 0: along x, input modulated, output demodulated; 1: along y, demodulated → modulated.
    direction: u32,
    // 1: exchanges normalised by max(A_p, A_q), which keep the light (denoise_form="exchange");
    // 0: by A_p alone, the normalised gather Σ_q h w m E / A_p ("gather").
    keep_light: u32,
    _pad: u32,
}

// A workgroup filters TILE consecutive pixels along the filter's axis. Its threads first copy the
// span its exchanges reach into workgroup memory (TILE + 4·radius pixels, radius ≤ MAX_RADIUS =
// the largest interleave: the taps of the taps, for their A), demodulated once per pixel, then
// compute A of the TILE + 2·radius pixels the taps reach, then filter.
const TILE: u32 = 64u;
const MAX_RADIUS: u32 = 16u;
const SPAN: u32 = TILE + 4u * MAX_RADIUS;

// Distance of a tap from a pixel's tangent plane, relative to the pixel's depth, at which its
// weight falls to e^-1. A plane distance (not a depth difference) keeps surfaces seen at
// grazing angles, whose depth changes fast across the screen, filtered.
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
// normal, R_d (the diffuse irradiance's mass), the diffuse irradiance (demodulated in the x pass)
// and specular; and for the inner TILE + 2r entries their (A_d (rgb), A_s).
var<workgroup> span_position: array<vec4f, SPAN>;
var<workgroup> span_normal: array<vec3f, SPAN>;
var<workgroup> span_rd: array<vec3f, SPAN>;
var<workgroup> span_diffuse: array<vec3f, SPAN>;
var<workgroup> span_specular: array<vec3f, SPAN>;
var<workgroup> span_capacity: array<vec4f, SPAN>;

// The symmetric weight of span entries a and b (both lit, neither background): each one's
// distance to the other's tangent plane over PLANE_SIGMA × its depth, and their normals' cosine.
fn pair_weight(a: u32, b: u32) -> f32 {
    let pa = span_position[a];
    let pb = span_position[b];
    let na = span_normal[a];
    let nb = span_normal[b];
    let dab = dot(na, pb.xyz - pa.xyz) / (PLANE_SIGMA * pa.w);
    let dba = dot(nb, pa.xyz - pb.xyz) / (PLANE_SIGMA * pb.w);
    return exp(-0.5 * (dab * dab + dba * dba)) * pow(max(dot(na, nb), 0.0), NORMAL_POWER);
}

// Tap t of −r … r: the two ends share one interleaving residue, so each weighs half.
fn tap_share(t: i32, r: i32) -> f32 {
    return select(1.0, 0.5, t == -r || t == r);
}

// Workgroup (a, b): pixels a·TILE … a·TILE + TILE − 1 along the filter's axis, line b across it.
@compute @workgroup_size(TILE, 1, 1)
fn main(@builtin(workgroup_id) wg: vec3u, @builtin(local_invocation_index) local: u32) {
    let size = vec2i(frame.size);
    let along_x = params.direction == 0u;
    let step = select(vec2i(0, 1), vec2i(1, 0), along_x);
    let demodulate_input = along_x;
    let r = params.radius;
    let ru = u32(r);
    let first = vec2i(select(vec2u(wg.y, wg.x * TILE), vec2u(wg.x * TILE, wg.y), along_x)) - 2 * r * step;
    // Copy the span [first, first + TILE + 4r) along the axis; every thread takes part, so the
    // barriers below are reached uniformly.
    for (var s = local; s < TILE + 4u * ru; s += TILE) {
        let q = first + i32(s) * step;
        var position = vec4f(0.0, 0.0, 0.0, GBUFFER_BACKGROUND);
        if (q.x >= 0 && q.y >= 0 && q.x < size.x && q.y < size.y) {
            let j = u32(q.y * size.x + q.x);
            position = gbuf_position[j];
            if (position.w != GBUFFER_BACKGROUND) {
                span_normal[s] = gbuf_normal[j].xyz;
                let rd = rd_at(j);
                span_rd[s] = rd;
                var d = in_diffuse[j].rgb;
                if (demodulate_input) {
                    d = d / rd;
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
    // A of the entries r … TILE + 3r − 1 (the pixels the centres' taps reach) for the exchange,
    // which divides by max(A_p, A_q); the gather needs the centres' own, 2r … TILE + 2r − 1.
    let exchange = params.keep_light == 1u;
    let capacity_first = select(2u * ru, ru, exchange);
    let capacity_end = select(TILE + 2u * ru, TILE + 3u * ru, exchange);
    for (var s = local + capacity_first; s < capacity_end; s += TILE) {
        var capacity = vec4f(0.0);
        if (span_position[s].w != GBUFFER_BACKGROUND) {
            for (var t = -r; t <= r; t++) {
                let q = u32(i32(s) + t);
                if (span_position[q].w == GBUFFER_BACKGROUND) {
                    continue;
                }
                let w = tap_share(t, r) * select(pair_weight(s, q), 1.0, t == 0);
                capacity += w * vec4f(span_rd[q], 1.0);
            }
        }
        span_capacity[s] = capacity;
    }
    workgroupBarrier();

    let xy = first + (i32(local) + 2 * r) * step;
    if (xy.x >= size.x || xy.y >= size.y) {
        return;
    }
    let index = u32(xy.y * size.x + xy.x);
    let centre = local + 2u * ru;
    if (span_position[centre].w == GBUFFER_BACKGROUND) {
        out_diffuse[index] = vec4f(0.0);
        if (HAS_SPECULAR) {
            out_specular[index] = vec4f(0.0);
        }
        return;
    }
    let e = span_diffuse[centre];
    let sp = span_specular[centre];
    let a = span_capacity[centre];
    var flow_d = vec3f(0.0);
    var flow_s = vec3f(0.0);
    for (var t = -r; t <= r; t++) {
        let q = u32(i32(centre) + t);
        if (t == 0 || span_position[q].w == GBUFFER_BACKGROUND) {
            continue;
        }
        let w = tap_share(t, r) * pair_weight(centre, q);
        // m_q/max(A_p, A_q) per channel; A_q ≥ m_q (its own tap) > 0, so no division by zero.
        // The gather divides by A_p alone (≥ m_p > 0).
        let n = select(a, max(a, span_capacity[q]), exchange);
        flow_d += w * span_rd[q] / n.rgb * (span_diffuse[q] - e);
        if (HAS_SPECULAR) {
            flow_s += w / n.w * (span_specular[q] - sp);
        }
    }
    var out_d = e + flow_d;
    if (!demodulate_input) {
        out_d = out_d * span_rd[centre];
    }
    out_diffuse[index] = vec4f(out_d, 0.0);
    if (HAS_SPECULAR) {
        out_specular[index] = vec4f(sp + flow_s, 0.0);
    }
}
