// LPV propagation, one iteration (compute, `method="lpv"`): every cell gathers the light its six
// face neighbours send into it [Kaplanyan & Dachsbacher 2010]. A neighbour at −d (d one of
// ±x, ±y, ±z) is a point source of intensity I(ω) (its SH); what it sends through the shared
// face leaves the destination cell through the five other faces, each subtending a solid angle
// Δω_f from the neighbour's centre: the far face (normal d, seen along d, Δω = 0.4006696846 sr)
// and the four side faces (normal s ⟂ d, seen along (d + s/2)/|d + s/2|,
// Δω = 0.4234313544 sr: the rectangle 0.5 … 1.5 along d, −0.5 … 0.5 across, at 0.5 to the side). The flux through a face, Φ_f = Δω_f · max(0, I(ω_f)), is re-emitted
// from the destination's centre as a clamped-cosine lobe about the face normal,
// Φ_f/π · max(0, n_f·ω) .
// The five solid angles add up to 2π/3, the shared face's, so propagation moves light and
// makes none: 4·0.4234313544 + 0.4006696846 = 2.0943951 sr.
// From the second iteration on (`occlude` = 1) the flux is attenuated by the geometry volume at
// the shared face's centre, T = 1 − clamp(B(−d), 0, 1): light travelling along d is stopped by
// surfaces facing −d (not on the first step, so
// surfaces do not shadow their own injected light).
// Results go to `next` (this iteration's light, what the next one propagates) and are added to
// `total` (the sum of all iterations, what the lookup reads).
#include "common/constants.wgsl"
#include "common/lpv.wgsl"

const WORKGROUP: u32 = 4u;

const FAR_FACE_SOLID_ANGLE: f32 = 0.4006696846;
const SIDE_FACE_SOLID_ANGLE: f32 = 0.4234313544;

struct PropagateParams {
    // 1: attenuate by the geometry volume.
    occlude: u32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
}

@group(0) @binding(0) var<uniform> grid: LpvGrid;
@group(0) @binding(1) var<uniform> params: PropagateParams;
@group(0) @binding(2) var<storage, read> current: array<vec4f>;
@group(0) @binding(3) var<storage, read> geometry: array<vec4f>;
@group(0) @binding(4) var<storage, read_write> next: array<vec4f>;
@group(0) @binding(5) var<storage, read_write> total: array<vec4f>;

// Direction i of +x, −x, +y, −y, +z, −z.
fn axis_direction(i: u32) -> vec3i {
    var v = vec3i(0);
    v[i / 2u] = select(1, -1, (i & 1u) == 1u);
    return v;
}

// The geometry volume of `cascade` at corner coordinates `u` (corners at whole numbers),
// trilinearly: at a face centre this is the mean of the face's four corners.
fn geometry_at(cascade: u32, u: vec3f) -> vec4f {
    let side = grid.side;
    let base = clamp(vec3i(floor(u)), vec3i(0), vec3i(i32(side) - 1));
    let t = clamp(u - vec3f(base), vec3f(0.0), vec3f(1.0));
    var sum = vec4f(0.0);
    for (var k = 0u; k < 8u; k++) {
        let o = vec3u(k & 1u, (k >> 1u) & 1u, (k >> 2u) & 1u);
        let w = select(1.0 - t.x, t.x, o.x == 1u) * select(1.0 - t.y, t.y, o.y == 1u) * select(1.0 - t.z, t.z, o.z == 1u);
        sum += w * geometry[lpv_geometry_index(cascade, vec3u(base) + o, side)];
    }
    return sum;
}

@compute @workgroup_size(WORKGROUP, WORKGROUP, WORKGROUP)
fn main(@builtin(global_invocation_id) gid: vec3u) {
    let side = grid.side;
    let cascade = gid.z / side;
    let cell = vec3u(gid.x, gid.y, gid.z % side);
    if (gid.x >= side || gid.y >= side || cascade >= grid.cascade_count) {
        return;
    }
    var gathered = array<vec4f, 3>(vec4f(0.0), vec4f(0.0), vec4f(0.0));
    for (var a = 0u; a < 6u; a++) {
        let d = axis_direction(a);
        let source = vec3i(cell) - d;
        if (any(source < vec3i(0)) || any(source >= vec3i(i32(side)))) {
            continue;
        }
        let df = vec3f(d);
        var transmittance = 1.0;
        if (params.occlude == 1u) {
            // The shared face's centre, in corner coordinates (cell centres at +0.5).
            let face = vec3f(cell) + 0.5 - 0.5 * df;
            let blocking = sh_evaluate(geometry_at(cascade, face), -df);
            transmittance = 1.0 - clamp(blocking, 0.0, 1.0);
        }
        if (transmittance <= 0.0) {
            continue;
        }
        let src = lpv_cell_index(cascade, vec3u(source), side);
        let source_sh = array<vec4f, 3>(current[src], current[src + 1u], current[src + 2u]);
        // Face 0: the far face; faces 1–4: the side faces, along the two other axes both ways.
        for (var f = 0u; f < 5u; f++) {
            var toward = df;
            var face_normal = df;
            var solid_angle = FAR_FACE_SOLID_ANGLE;
            if (f > 0u) {
                let other_axis = (a / 2u + 1u + (f - 1u) / 2u) % 3u;
                let s = vec3f(axis_direction(2u * other_axis + ((f - 1u) & 1u)));
                toward = normalize(df + 0.5 * s);
                face_normal = s;
                solid_angle = SIDE_FACE_SOLID_ANGLE;
            }
            let lobe = sh_clamped_cosine(face_normal) * (solid_angle * INV_PI * transmittance);
            for (var ch = 0u; ch < 3u; ch++) {
                gathered[ch] += lobe * max(0.0, sh_evaluate(source_sh[ch], toward));
            }
        }
    }
    let dst = lpv_cell_index(cascade, cell, side);
    for (var ch = 0u; ch < 3u; ch++) {
        next[dst + ch] = gathered[ch];
        total[dst + ch] += gathered[ch];
    }
}
