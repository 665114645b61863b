// LPV lookup (compute, `method="lpv"`): every pixel's diffuse indirect light from the summed
// propagation iterations [Kaplanyan & Dachsbacher 2010]. The cell's intensity I(ω) spread
// over its cross-section is the radiance L(ω) ≈ I(ω)/s² flowing along ω; the irradiance of a
// receiver with normal n is the light flowing against n, E = ∫ L(ω) max(0, −n·ω) dω, the dot
// product of L's SH with the clamped cosine about −n (common/lpv.wgsl), clamped at 0 (two bands
// ring), and the pixel reflects R_d/π·E.
// The volume is read trilinearly (cell centres, clamped to the grid's edge) at the receiver
// itself. Moving the lookup half a cell along the normal, as the injection moves the emitters,
// was measured worse on every scene tried (block error, diffuse Cornell box 1.21 against 1.05
// here; docs/methods/lpv.md, "Where the lookup reads"): it reads the cell a surface injected
// its own light into, whose lobe, pointing away, cancels the light arriving. With several
// cascades the finest that holds the point is used, blended into the next coarser one over its
// two outermost cells.
// Specular receivers get nothing: two SH bands hold no glossy light (the papers compare LPVs
// on diffuse paths only).
#include "common/constants.wgsl"
#include "common/gbuffer.wgsl"
#include "common/receiver.wgsl"
#include "common/lpv.wgsl"

const WORKGROUP: u32 = 8u;
// Cells over which a finer cascade fades into the coarser one, inside its outermost cell.
const CASCADE_BLEND_CELLS: f32 = 2.0;

struct LookupParams {
    size: vec2u,
    _pad0: u32,
    _pad1: u32,
}

@group(0) @binding(0) var<uniform> grid: LpvGrid;
@group(0) @binding(1) var<uniform> params: LookupParams;
@group(0) @binding(2) var<storage, read> total: array<vec4f>;
@group(0) @binding(3) var<storage, read> gbuf_position: array<vec4f>;
@group(0) @binding(4) var<storage, read> gbuf_normal: array<vec4f>;
@group(0) @binding(5) var<storage, read> gbuf_geo_normal: array<vec4f>;
@group(0) @binding(6) var<storage, read> gbuf_base_color: array<vec4f>;
@group(0) @binding(7) var<storage, read_write> indirect_diffuse: array<vec4f>;

// Irradiance (rgb) of cascade `c` at cell coordinates u (cell centres at +0.5) for normal n.
fn cascade_irradiance(c: u32, u: vec3f, n: vec3f) -> vec3f {
    let side = grid.side;
    let v = u - 0.5;
    let base = clamp(vec3i(floor(v)), vec3i(0), vec3i(i32(side) - 2));
    let t = clamp(v - vec3f(base), vec3f(0.0), vec3f(1.0));
    let against = sh_clamped_cosine(-n);
    var e = vec3f(0.0);
    for (var k = 0u; k < 8u; k++) {
        let o = vec3u(k & 1u, (k >> 1u) & 1u, (k >> 2u) & 1u);
        let w = select(1.0 - t.x, t.x, o.x == 1u) * select(1.0 - t.y, t.y, o.y == 1u) * select(1.0 - t.z, t.z, o.z == 1u);
        let i = lpv_cell_index(c, vec3u(base) + o, side);
        e += w * vec3f(dot(total[i], against), dot(total[i + 1u], against), dot(total[i + 2u], against));
    }
    let s = grid.cascades[c].w;
    return max(e, vec3f(0.0)) / (s * s);
}

@compute @workgroup_size(WORKGROUP, WORKGROUP, 1)
fn main(@builtin(global_invocation_id) gid: vec3u) {
    if (gid.x >= params.size.x || gid.y >= params.size.y) {
        return;
    }
    let index = gid.y * params.size.x + gid.x;
    let rcv = receiver_from_gbuffer(gbuf_position[index], gbuf_normal[index], gbuf_geo_normal[index], gbuf_base_color[index]);
    if (!rcv.has_surface || all(rcv.rd <= vec3f(0.0))) {
        return;
    }
    let side = f32(grid.side);
    var e = vec3f(0.0);
    for (var c = 0u; c < grid.cascade_count; c++) {
        let g = grid.cascades[c];
        let u = (rcv.p - g.xyz) / g.w;
        if (c == 0u) {
            e = cascade_irradiance(c, u, rcv.n);
            continue;
        }
        // Cells between the point and the cascade's nearest face.
        let inside = min(min(u.x, min(u.y, u.z)), side - max(u.x, max(u.y, u.z)));
        let w = clamp((inside - 1.0) / CASCADE_BLEND_CELLS, 0.0, 1.0);
        if (w > 0.0) {
            e = mix(e, cascade_irradiance(c, u, rcv.n), w);
        }
    }
    indirect_diffuse[index] += vec4f(min(rcv.rd * INV_PI * e, vec3f(FLT_MAX)), 0.0);
}
