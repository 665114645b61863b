//! The light propagation volumes of `method="lpv"` [Kaplanyan & Dachsbacher 2010]: where each
//! cascade's grid lies (placed on the CPU, in f64, once per frame) and the volumes' buffers.
//! The layout (cells, SH coefficients) is written in `wgsl/common/lpv.wgsl`.

use crate::gpu::Recorder;
use glam::DVec3;

/// Most cascades (`LpvGrid::cascades` in the shaders has four entries).
pub const MAX_CASCADES: u32 = 4;
/// Bytes per light-volume cell: two SH bands (four f32) for each of r, g, b.
pub const LIGHT_CELL_BYTES: u64 = 48;
/// Bytes per geometry-volume cell: two SH bands of blocking potential.
pub const GEOMETRY_CELL_BYTES: u64 = 16;

/// `LpvGrid` of `wgsl/common/lpv.wgsl`: each cascade's min corner (relative to the eye) and
/// cell side.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub struct LpvGridRaw {
    pub cascades: [[f32; 4]; 4],
    pub side: u32,
    pub cascade_count: u32,
    pub _pad: [u32; 2],
}

/// Empty cells below the scene's bounds in cascade 0: one, plus (√5 − 1)/4, a fraction that no
/// simple ratio of the bounds maps onto a cell boundary.
pub const LOW_MARGIN_CELLS: f64 = 1.309_016_994_374_947_4;
/// Empty cells above them.
pub const HIGH_MARGIN_CELLS: f64 = 1.25;

/// One cascade in world space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cascade {
    pub min: DVec3,
    pub cell: f64,
}

/// The cascades' grids for a scene whose bounds are `anchor ± half_size`, seen from `eye`.
///
/// Cascade 0 holds the whole scene: a cube over the bounds' largest side with more than one
/// empty cell on every side, so that injection (half a cell along the normal) and the lookup's
/// trilinear reads at walls on the bounds stay inside. The margins are unequal and not whole
/// or half cells ([`LOW_MARGIN_CELLS`], [`HIGH_MARGIN_CELLS`]): with whole-cell margins the
/// centre plane of a symmetric scene and the quarter planes of many lie exactly on cell
/// boundaries, where a texel's cell is decided by rounding, so scaling or moving the scene
/// moved light from cell to cell (the scene stability suite saw 0.4–11% on the furnished room
/// and the atrium). Each further cascade has half the side of the one
/// before, the same cell count, and is centred on the eye [Kaplanyan & Dachsbacher 2010:
/// nested grids around the viewer], snapped to its own cells (counted from cascade 0's corner) (so a moving camera does not make
/// the injected light swim) and kept inside cascade 0.
pub fn place_cascades(anchor: DVec3, half_size: DVec3, eye: DVec3, side: u32, count: u32) -> Vec<Cascade> {
    let n = side as f64;
    // A scene without extent (a point) still gets a grid of positive size.
    let largest = (2.0 * half_size.max_element()).max(f64::MIN_POSITIVE.sqrt());
    let outer = largest * n / (n - LOW_MARGIN_CELLS - HIGH_MARGIN_CELLS);
    let outer_min = anchor - DVec3::splat(largest / 2.0 + LOW_MARGIN_CELLS * outer / n);
    let mut cascades = vec![Cascade { min: outer_min, cell: outer / n }];
    for c in 1..count {
        let extent = outer / f64::from(1u32 << c);
        let cell = extent / n;
        // Whole cells from cascade 0's corner, so the grid stays on its lattice when clamped.
        let free_cells = n * f64::from(1u32 << c) - n;
        let steps = ((eye - DVec3::splat(extent / 2.0) - outer_min) / cell).round().clamp(DVec3::ZERO, DVec3::splat(free_cells));
        cascades.push(Cascade { min: outer_min + steps * cell, cell });
    }
    cascades
}

/// The cascades as the shaders read them, relative to the frame origin `origin`.
pub fn grid_raw(cascades: &[Cascade], origin: DVec3, side: u32) -> LpvGridRaw {
    let mut raw = LpvGridRaw { cascades: [[0.0; 4]; 4], side, cascade_count: cascades.len() as u32, _pad: [0; 2] };
    for (slot, c) in raw.cascades.iter_mut().zip(cascades) {
        let m = (c.min - origin).as_vec3();
        *slot = [m.x, m.y, m.z, c.cell as f32];
    }
    raw
}

/// The buffers of one frame's volumes.
pub struct LpvVolumes {
    /// The injected light (iteration 0), then the ping-pong partner of `next`.
    pub current: wgpu::Buffer,
    pub next: wgpu::Buffer,
    /// The sum over all iterations: what the lookup reads.
    pub total: wgpu::Buffer,
    /// The geometry volume, or a 16-byte placeholder when nothing is occluded.
    pub geometry: wgpu::Buffer,
    /// Cells per side of one cascade, and cascades.
    pub side: u32,
    pub cascades: u32,
}

impl LpvVolumes {
    /// Zeroed volumes for `cascades` grids of `side`³ cells; `occlusion`: with a geometry volume.
    pub fn new(rec: &mut Recorder<'_>, side: u32, cascades: u32, occlusion: bool) -> Self {
        let light = Self::light_bytes(side, cascades);
        Self {
            current: rec.storage("lpv_light_volume_a_buffer", light),
            next: rec.storage_written("lpv_light_volume_b_buffer", light),
            total: rec.storage_written("lpv_light_volume_total_buffer", light),
            geometry: rec.storage("lpv_geometry_volume_buffer", if occlusion { Self::geometry_bytes(side, cascades) } else { 16 }),
            side,
            cascades,
        }
    }

    /// Bytes of one light volume over all cascades.
    pub fn light_bytes(side: u32, cascades: u32) -> u64 {
        let s = side as u64;
        s * s * s * cascades as u64 * LIGHT_CELL_BYTES
    }

    /// Bytes of the geometry volume over all cascades ((side + 1)³ cells each).
    pub fn geometry_bytes(side: u32, cascades: u32) -> u64 {
        let s = side as u64 + 1;
        s * s * s * cascades as u64 * GEOMETRY_CELL_BYTES
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cascade_zero_holds_the_scene_with_a_cell_to_spare_and_finer_ones_nest_inside_it() {
        let (anchor, half) = (DVec3::new(1.0, 2.0, 3.0), DVec3::new(2.0, 1.0, 0.5));
        let c = place_cascades(anchor, half, DVec3::new(2.5, 2.0, 3.0), 32, 3);
        assert_eq!(c.len(), 3);
        // 4 units over the cells the margins leave.
        assert!((c[0].cell - 4.0 / (32.0 - LOW_MARGIN_CELLS - HIGH_MARGIN_CELLS)).abs() < 1e-12);
        // Along the largest side (x) the margin below is exactly LOW_MARGIN_CELLS.
        assert!(((anchor.x - half.x - c[0].min.x) / c[0].cell - LOW_MARGIN_CELLS).abs() < 1e-9);
        let outer_max = c[0].min + DVec3::splat(32.0 * c[0].cell);
        assert!((anchor - half - c[0].min).min_element() >= c[0].cell - 1e-12);
        assert!((outer_max - (anchor + half)).min_element() >= c[0].cell - 1e-12);
        for k in 1..3 {
            assert!((c[k].cell - c[0].cell / f64::from(1u32 << k)).abs() < 1e-12);
            let max = c[k].min + DVec3::splat(32.0 * c[k].cell);
            assert!((c[k].min - c[0].min).min_element() >= -1e-12 && (outer_max - max).min_element() >= -1e-12, "cascade {k} leaves cascade 0");
            // On its own cell lattice from cascade 0's corner.
            let lattice = (c[k].min - c[0].min) / c[k].cell;
            assert!((lattice - lattice.round()).abs().max_element() < 1e-9);
        }
    }
}
