// The grid that makes k-means' nearest-centre search fast (compute) — our stand-in for the
// 2016 paper's binary radix tree over the centres [Tok16 Appendix D]: a uniform grid of about
// TARGET_CENTRES_PER_CELL centres a cell. Two entry points:
//   cells:  one workgroup; the centres' bounds (kmeans3d) or the RSM square (kmeans2d), the
//           grid's cell size and dimensions, and each centre's cell as a sort key;
//   ranges: after the centres are sorted by cell, each cell's run [start, end) of them.
#include "common/constants.wgsl"
#include "common/kmeans_grid.wgsl"

struct GridParams {
    // Number of centres N.
    count: u32,
    rsm_size: u32,
    // 0: "kmeans2d" (RSM texel coordinates), 1: "kmeans3d" (world positions).
    space: u32,
    _pad: u32,
}

const WORKGROUP: u32 = 256u;
// Cells per axis at most: 256² in 2D, 64³ in 3D (the keys then fit 16 and 18 bits).
const MAX_DIM_2D: u32 = 256u;
const MAX_DIM_3D: u32 = 64u;
const TARGET_CENTRES_PER_CELL: f32 = 2.0;

@group(0) @binding(0) var<uniform> params: GridParams;
@group(0) @binding(1) var<storage, read> centres: array<vec4f>;
@group(0) @binding(2) var<storage, read_write> grid: KmeansGrid;
@group(0) @binding(3) var<storage, read_write> keys: array<u32>;
@group(0) @binding(4) var<storage, read_write> values: array<u32>;
@group(0) @binding(5) var<storage, read_write> ranges: array<vec2u>;

var<workgroup> lows: array<vec3f, WORKGROUP>;
var<workgroup> highs: array<vec3f, WORKGROUP>;
var<workgroup> shared_grid: KmeansGrid;

// Cubic cells of side h so that the box holds about `target` cells, whatever its dimension: a
// flat box (a wall's centres) is gridded in its plane, a thin one along its line.
fn cell_side(extent: vec3f, target_cells: f32) -> f32 {
    let e = vec3f(max(max(extent.x, extent.y), extent.z), 0.0, min(min(extent.x, extent.y), extent.z));
    let middle = extent.x + extent.y + extent.z - e.x - e.z;
    let h3 = pow(e.x * middle * e.z / target_cells, 1.0 / 3.0);
    if (h3 > 0.0 && h3 <= e.z) {
        return h3;
    }
    let h2 = sqrt(e.x * middle / target_cells);
    if (h2 > 0.0 && h2 <= middle) {
        return h2;
    }
    return e.x / target_cells;
}

@compute @workgroup_size(WORKGROUP, 1, 1)
fn cells(@builtin(local_invocation_index) t: u32) {
    var lo = vec3f(FLT_MAX);
    var hi = vec3f(-FLT_MAX);
    for (var i = t; i < params.count; i += WORKGROUP) {
        let p = centres[i].xyz;
        lo = min(lo, p);
        hi = max(hi, p);
    }
    lows[t] = lo;
    highs[t] = hi;
    workgroupBarrier();
    for (var step = WORKGROUP / 2u; step > 0u; step /= 2u) {
        if (t < step) {
            lows[t] = min(lows[t], lows[t + step]);
            highs[t] = max(highs[t], highs[t + step]);
        }
        workgroupBarrier();
    }
    if (t == 0u) {
        let target_cells = max(f32(params.count) / TARGET_CENTRES_PER_CELL, 1.0);
        var g: KmeansGrid;
        if (params.space == 0u) {
            let side = clamp(u32(ceil(sqrt(target_cells))), 1u, MAX_DIM_2D);
            g.origin = vec3f(0.0);
            g.cell = f32(params.rsm_size) / f32(side);
            g.dims = vec3u(side, side, 1u);
        } else {
            let extent = max(highs[0] - lows[0], vec3f(0.0));
            let largest = max(max(extent.x, extent.y), extent.z);
            var h = cell_side(extent, target_cells);
            // At most MAX_DIM_3D cells along any axis; one cell where every centre coincides.
            h = max(h, largest / f32(MAX_DIM_3D));
            if (!(h > 0.0) || h > FLT_MAX) {
                h = 1.0;
            }
            g.origin = lows[0];
            g.cell = h;
            g.dims = clamp(vec3u(ceil(extent / h)), vec3u(1u), vec3u(MAX_DIM_3D));
        }
        g.cells = g.dims.x * g.dims.y * g.dims.z;
        grid = g;
        shared_grid = g;
    }
    workgroupBarrier();
    let g = shared_grid;
    for (var i = t; i < params.count; i += WORKGROUP) {
        keys[i] = kmeans_cell_index(g, kmeans_cell_of(g, centres[i].xyz));
        values[i] = i;
    }
}

// One thread per sorted centre: the first of a cell's run writes its start, the last its end
// (`ranges` starts zeroed: an empty cell is [0, 0)).
@compute @workgroup_size(WORKGROUP, 1, 1)
fn ranges_of_cells(@builtin(global_invocation_id) gid: vec3u) {
    let i = gid.x;
    if (i >= params.count) {
        return;
    }
    let key = keys[i];
    if (i == 0u || keys[i - 1u] != key) {
        ranges[key].x = i;
    }
    if (i + 1u == params.count || keys[i + 1u] != key) {
        ranges[key].y = i + 1u;
    }
}
