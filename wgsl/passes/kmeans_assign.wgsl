// k-means assignment (compute), one thread per RSM texel [Tok16 Appendix D]: every lit texel
// (w > 0) goes to its nearest centre — in texel coordinates ("kmeans2d") or world positions
// ("kmeans3d") — found by walking the centre grid (kmeans_grid.wgsl) in rings of cells around
// the texel's own until no unvisited cell can hold a nearer centre. Ties go to the lower centre
// id, as a brute-force argmin would. The output is a (cluster id, texel) pair to sort; unlit
// texels get the key N, which sorts after every cluster.
//
// Ring bound: a centre in a cell at Chebyshev ring r ≥ 1 around the texel's cell is at least
// (r − 1)·h away (h the cell side; also for a texel outside the grid, whose cell is clamped),
// so once the best squared distance is below ((r − 1)·h)² ring r and beyond are left out.
#include "common/constants.wgsl"
#include "common/kmeans_grid.wgsl"
#include "common/kmeans_space.wgsl"

struct AssignParams {
    // Number of centres N (also the key of unlit texels).
    count: u32,
    rsm_size: u32,
    space: u32,
    chain_len: u32,
}

const WORKGROUP: u32 = 64u;

@group(0) @binding(0) var<uniform> params: AssignParams;
@group(0) @binding(1) var<storage, read> moments: array<vec4f>;
@group(0) @binding(2) var<storage, read> centres: array<vec4f>;
@group(0) @binding(3) var<storage, read> grid: KmeansGrid;
// Centre ids sorted by cell, and each cell's run of them.
@group(0) @binding(4) var<storage, read> sorted_centres: array<u32>;
@group(0) @binding(5) var<storage, read> ranges: array<vec2u>;
@group(0) @binding(6) var<storage, read_write> keys: array<u32>;
@group(0) @binding(7) var<storage, read_write> values: array<u32>;

struct Nearest {
    id: u32,
    distance2: f32,
}

// A cell's box grown by this fraction of its side before the pruning test below, so rounding in
// its corners (and a centre that the clamp of the grid's last cell holds a rounding past its
// box) never skips a cell that holds a centre as near as the best.
const CELL_MARGIN: f32 = 1.0e-4;

fn visit_cell(g: KmeansGrid, cell: vec3i, p: vec3f, best: ptr<function, Nearest>) {
    // Skips a cell whose box lies farther than the best centre so far: no centre in it can be
    // nearer, nor as near (exact, ties included). Without it each texel read every centre of the
    // first two rings (27 cells in 3D); with it a model of this search reads 3.3–6× fewer
    // bytes than a binary radix tree's search (experiments/kmeans_generation_cost.md).
    let margin = CELL_MARGIN * g.cell;
    let lo = g.origin + vec3f(cell) * g.cell - margin;
    let gap = max(max(lo - p, p - (lo + g.cell + 2.0 * margin)), vec3f(0.0));
    if (dot(gap, gap) > (*best).distance2) {
        return;
    }
    let run = ranges[kmeans_cell_index(g, cell)];
    for (var k = run.x; k < run.y; k++) {
        let id = sorted_centres[k];
        let d = centres[id].xyz - p;
        let d2 = dot(d, d);
        if (d2 < (*best).distance2 || (d2 == (*best).distance2 && id < (*best).id)) {
            *best = Nearest(id, d2);
        }
    }
}

@compute @workgroup_size(WORKGROUP, 1, 1)
fn main(@builtin(global_invocation_id) gid: vec3u) {
    let texels = params.rsm_size * params.rsm_size;
    let i = gid.x;
    if (i >= texels) {
        return;
    }
    values[i] = i;
    if (!(moments[i].w > 0.0)) {
        keys[i] = params.count;
        return;
    }
    let g = grid;
    let p = kmeans_texel_point(params.space, i, params.rsm_size, params.chain_len);
    let home = kmeans_cell_of(g, p);
    var best = Nearest(params.count, FLT_MAX);
    let rings = i32(max(max(g.dims.x, g.dims.y), g.dims.z));
    let low = -home;
    let high = vec3i(g.dims) - vec3i(1) - home;
    for (var r = 0; r < rings; r++) {
        if (r >= 1) {
            let bound = f32(r - 1) * g.cell;
            if (best.distance2 < bound * bound) {
                break;
            }
        }
        // The cells at Chebyshev distance exactly r, clipped to the grid.
        for (var dz = max(-r, low.z); dz <= min(r, high.z); dz++) {
            for (var dy = max(-r, low.y); dy <= min(r, high.y); dy++) {
                if (abs(dz) == r || abs(dy) == r) {
                    for (var dx = max(-r, low.x); dx <= min(r, high.x); dx++) {
                        visit_cell(g, home + vec3i(dx, dy, dz), p, &best);
                    }
                } else {
                    if (-r >= low.x) {
                        visit_cell(g, home + vec3i(-r, dy, dz), p, &best);
                    }
                    if (r <= high.x && r != 0) {
                        visit_cell(g, home + vec3i(r, dy, dz), p, &best);
                    }
                }
            }
        }
    }
    keys[i] = best.id;
}
