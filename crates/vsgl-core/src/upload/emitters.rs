//! Emissive triangles as area lights: the table the path tracer samples emitters from.
//!
//! Each triangle whose material emits (glTF `emissiveFactor` × `KHR_materials_emissive_strength`
//! > 0) is a one-sided Lambertian emitter of radiance L_e on the side its vertex normals point
//! to (the side a glTF file shades as its front; docs/scenes.md, "Emission"). Its power is
//! Φ = π · A · (L_r + L_g + L_b): a Lambertian surface's exitance is π L_e. Emitters are drawn
//! in proportion to that power, then uniformly over the triangle's area, so the density of a
//! point z on triangle i is p_i / A_i with p_i = Φ_i / ΣΦ (`EmitterRaw::probability`).
//!
//! The emissive texture multiplies L_e at the sampled point and is not in Φ: texels are at most
//! 1, so the factor's power bounds the textured one and every point that emits keeps a density
//! above zero (the estimator stays unbiased, only less well matched to dark texels).

use super::VertexRaw;
use crate::scene::Material;

/// One emissive triangle (16 bytes; `EmitterRaw` in `wgsl/passes/pathtrace.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct EmitterRaw {
    /// Index of the triangle in the upload's index buffer (three indices per triangle).
    pub triangle: u32,
    /// World-space area.
    pub area: f32,
    /// Σ of `probability` up to and including this row (the last row holds exactly 1): a
    /// uniform u picks the first row whose `cdf` exceeds it.
    pub cdf: f32,
    /// Φ_i / ΣΦ: how often this triangle is drawn.
    pub probability: f32,
}
const _: () = assert!(std::mem::size_of::<EmitterRaw>() == 16);

/// The scene's emitters and their total power (rgb summed, in the scene's units).
#[derive(Clone, Debug, Default)]
pub struct EmitterTable {
    pub rows: Vec<EmitterRaw>,
    pub total_power: f64,
}

/// The emitter table of an upload's triangles (`indices`: three per triangle into `vertices`,
/// `triangle_materials`: one material index per triangle). Triangles of zero area or of a
/// material that does not emit are left out.
pub fn emitter_table(vertices: &[VertexRaw], indices: &[u32], triangle_materials: &[u32], materials: &[Material]) -> EmitterTable {
    let mut rows = Vec::new();
    let mut powers = Vec::new();
    for (t, &m) in triangle_materials.iter().enumerate() {
        let Some(material) = materials.get(m as usize).filter(|m| m.has_emission()) else { continue };
        let corner = |k: usize| {
            let v = indices.get(3 * t + k).and_then(|&i| vertices.get(i as usize)).map_or([0.0; 3], |v| v.position);
            glam::DVec3::new(v[0] as f64, v[1] as f64, v[2] as f64)
        };
        let (a, b, c) = (corner(0), corner(1), corner(2));
        let area = 0.5 * (b - a).cross(c - a).length();
        let radiance: f64 = material.emissive.iter().map(|&e| e.max(0.0) as f64).sum();
        let power = std::f64::consts::PI * area * radiance;
        if !(power > 0.0 && power.is_finite()) {
            continue;
        }
        rows.push(EmitterRaw { triangle: t as u32, area: area as f32, cdf: 0.0, probability: 0.0 });
        powers.push(power);
    }
    let total_power: f64 = powers.iter().sum();
    let mut running = 0.0;
    for (row, power) in rows.iter_mut().zip(&powers) {
        running += power;
        row.probability = (power / total_power) as f32;
        row.cdf = (running / total_power) as f32;
    }
    if let Some(last) = rows.last_mut() {
        // Rounding must not leave a gap above the last row that a u near 1 could fall into.
        last.cdf = 1.0;
    }
    EmitterTable { rows, total_power }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn vertex(p: [f32; 3]) -> VertexRaw {
        VertexRaw { position: p, _pad0: 0.0, normal: [0.0, 1.0, 0.0], _pad1: 0.0, tangent: [1.0, 0.0, 0.0, 1.0], uv: [0.0; 2], _pad2: [0.0; 2] }
    }

    fn glowing(l: [f32; 3]) -> Material {
        Material { emissive: l, ..Material::lambertian("glow", [0.5; 3]) }
    }

    #[test]
    fn emitters_are_drawn_by_power_and_dark_or_flat_triangles_are_left_out() {
        // Triangle 0: area 0.5, L = 1+1+1; triangle 1: dark; triangle 2: area 2, L = 2 (red only);
        // triangle 3: zero area.
        let vertices = [
            vertex([0.0, 0.0, 0.0]), vertex([1.0, 0.0, 0.0]), vertex([0.0, 0.0, 1.0]),
            vertex([0.0, 0.0, 2.0]), vertex([2.0, 0.0, 0.0]), vertex([4.0, 0.0, 0.0]),
        ];
        let indices = [0, 1, 2, 0, 1, 2, 0, 3, 4, 0, 4, 5];
        let materials = [glowing([1.0; 3]), Material::lambertian("dark", [0.5; 3]), glowing([2.0, 0.0, 0.0])];
        let table = emitter_table(&vertices, &indices, &[0, 1, 2, 2], &materials);
        let pi = std::f64::consts::PI;
        assert!((table.total_power - pi * (0.5 * 3.0 + 2.0 * 2.0)).abs() < 1e-12, "{}", table.total_power);
        assert_eq!(table.rows.iter().map(|r| r.triangle).collect::<Vec<_>>(), vec![0, 2]);
        assert_eq!(table.rows[0].area, 0.5);
        assert_eq!(table.rows[1].area, 2.0);
        assert!((table.rows[0].probability as f64 - 1.5 / 5.5).abs() < 1e-7);
        assert!((table.rows[0].cdf as f64 - 1.5 / 5.5).abs() < 1e-7);
        assert_eq!(table.rows[1].cdf, 1.0);
    }

    #[test]
    fn a_scene_without_emission_has_an_empty_table() {
        let vertices = [vertex([0.0; 3]), vertex([1.0, 0.0, 0.0]), vertex([0.0, 0.0, 1.0])];
        let table = emitter_table(&vertices, &[0, 1, 2], &[0], &[Material::lambertian("dark", [0.5; 3])]);
        assert!(table.rows.is_empty());
        assert_eq!(table.total_power, 0.0);
    }
}
