// Light propagation volumes [Kaplanyan & Dachsbacher 2010, "Cascaded light propagation volumes
// for real-time indirect illumination", I3D; the baseline of the 2015 VSGL poster's Table 1]:
// what the injection, geometry, propagation and lookup passes share.
//
// A volume is a cubic grid of SIDE³ cells per cascade. Each cell holds the radiant intensity
// I(ω) (W/sr) of the light inside it as two-band real spherical harmonics per colour: four
// coefficients (c₀, c_x, c_y, c_z) against the orthonormal basis
//   Y₀₀ = 1/(2√π) = 0.282095,   Y₁ = √(3/(4π)) (x, y, z) = 0.488603 (x, y, z),
// so I(ω) ≈ c₀·Y₀₀ + 0.488603·(c_x, c_y, c_z)·ω, and the integral of a product of two such
// functions over the sphere is the dot product of their coefficients.
// Cells are stored cascade-major, then z, y, x; three vec4 (r, g, b) per cell.
//
// The geometry volume of each cascade has (SIDE + 1)³ cells centred on the light volume's cell
// corners [Kaplanyan & Dachsbacher 2010: offset by half a cell], one vec4 of SH per cell:
// the blocking potential B(ω) of the surfaces in it.

const SH_Y00: f32 = 0.282094792;
const SH_Y1: f32 = 0.488602512;
// The clamped cosine max(0, m·ω) projected on the basis: (π·Y₀₀, (2π/3)·Y₁·m).
const SH_COSINE_C0: f32 = 0.886226925;
const SH_COSINE_C1: f32 = 1.02332671;

// The grid of every cascade, relative to the eye (what both G-buffers' positions are relative
// to): cascades[c] = (min corner xyz, cell side w).
struct LpvGrid {
    cascades: array<vec4f, 4>,
    side: u32,
    cascade_count: u32,
    _pad0: u32,
    _pad1: u32,
}

fn sh_clamped_cosine(m: vec3f) -> vec4f {
    return vec4f(SH_COSINE_C0, SH_COSINE_C1 * m);
}

fn sh_evaluate(c: vec4f, w: vec3f) -> f32 {
    return c.x * SH_Y00 + SH_Y1 * dot(c.yzw, w);
}

fn lpv_cells_per_cascade(side: u32) -> u32 {
    return side * side * side;
}

// Index of a light-volume cell's first vec4 (red); +1 green, +2 blue.
fn lpv_cell_index(cascade: u32, cell: vec3u, side: u32) -> u32 {
    return 3u * (cascade * lpv_cells_per_cascade(side) + (cell.z * side + cell.y) * side + cell.x);
}

// Index of a geometry-volume cell (corner `corner` of the light volume, 0 … side per axis).
fn lpv_geometry_index(cascade: u32, corner: vec3u, side: u32) -> u32 {
    let s = side + 1u;
    return cascade * s * s * s + (corner.z * s + corner.y) * s + corner.x;
}
