// The uniform grid over k-means centres that the nearest-centre search walks (shared by
// passes/kmeans_grid.wgsl, which builds it, and passes/kmeans_assign.wgsl, which reads it).
// Centres are sorted by cell (passes/radix_sort.wgsl), so each cell is a run [start, end) of
// the sorted centre ids. In "kmeans2d" the space is the RSM's texel square and z is 0.
// vsgl:include-only (validated inside the shaders that include it)

struct KmeansGrid {
    origin: vec3f,
    // Side of a cell (cubic cells).
    cell: f32,
    dims: vec3u,
    cells: u32,
}

// The cell holding p, clamped into the grid (a point outside it belongs to the nearest cell:
// the search's ring bound stays conservative, kmeans_assign.wgsl).
fn kmeans_cell_of(grid: KmeansGrid, p: vec3f) -> vec3i {
    let c = vec3i(floor((p - grid.origin) / grid.cell));
    return clamp(c, vec3i(0), vec3i(grid.dims) - vec3i(1));
}

fn kmeans_cell_index(grid: KmeansGrid, c: vec3i) -> u32 {
    let u = vec3u(c);
    return (u.z * grid.dims.y + u.y) * grid.dims.x + u.x;
}
