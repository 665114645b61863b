//! The scene as a point set, for imperfect shadow maps (`visibility="ism"`): points
//! spread over the triangles in proportion to their area [Ritschel et al. 2008, "Imperfect
//! Shadow Maps", §3.1: the scene's surfaces as uniformly distributed points], generated once per
//! scene upload on the CPU (in f64) and kept with it like the BVH; moved geometry re-uploads
//! the scene and so regenerates them.
//!
//! Deterministic and stratified: point i sits at the area-CDF position u_i = (i + ½)/N of the
//! triangles laid end to end (systematic sampling: a triangle of area a gets a·N/A points, ±1),
//! and inside its triangle at the barycentric warp of (f, g) [Osada et al. 2002, "Shape
//! Distributions", §4.2: P = (1 − √f)A + √f(1 − g)B + √f·g·C is uniform over the triangle for
//! uniform (f, g)], where f is u_i's position within the triangle's stretch of the CDF (so the
//! triangle's points are stratified in f) and g = frac(i·φ⁻¹) the golden-ratio sequence (so they
//! spread in the other direction too). Every `stride`-th point from any start is then again
//! spread over the whole scene, which is how the maps pick their subsets (passes/ism.wgsl).

use super::bvh::Triangle;
use glam::DVec3;

/// One point per 16 bytes (`vec4f` in WGSL: position relative to the upload anchor, w = 0).
pub const POINT_BYTES: u64 = 16;

/// The fractional part of i/φ: the golden-ratio (Kronecker) sequence, the 1-D sequence with the
/// most even gaps [Weyl 1916; Knuth, TAOCP vol. 3 §6.4, Fibonacci hashing].
fn golden_fraction(i: u64) -> f64 {
    const INV_GOLDEN: f64 = 0.618_033_988_749_894_8;
    (i as f64 * INV_GOLDEN).fract()
}

/// `count` points over `triangles` (positions as the triangles have them), as vec4 rows; empty
/// when the triangles have no area.
pub fn surface_points(triangles: &[Triangle], count: u32) -> Vec<[f32; 4]> {
    let corner = |t: &Triangle, k: usize| DVec3::new(t[k][0] as f64, t[k][1] as f64, t[k][2] as f64);
    let areas: Vec<f64> = triangles
        .iter()
        .map(|t| {
            let (a, b, c) = (corner(t, 0), corner(t, 1), corner(t, 2));
            let area = 0.5 * (b - a).cross(c - a).length();
            if area.is_finite() { area } else { 0.0 }
        })
        .collect();
    let total: f64 = areas.iter().sum();
    if count == 0 || !(total > 0.0) || !total.is_finite() {
        return Vec::new();
    }
    let n = count as u64;
    let mut points = Vec::with_capacity(count as usize);
    // Walk the triangles and the sorted CDF positions together: `before` is the area of the
    // triangles before triangle `t`.
    let (mut t, mut before) = (0usize, 0.0f64);
    for i in 0..n {
        let u = (i as f64 + 0.5) / n as f64 * total;
        while t + 1 < triangles.len() && (areas[t] == 0.0 || before + areas[t] <= u) {
            before += areas[t];
            t += 1;
        }
        let f = if areas[t] > 0.0 { ((u - before) / areas[t]).clamp(0.0, 1.0) } else { 0.5 };
        let g = golden_fraction(i);
        let s = f.sqrt();
        let (a, b, c) = (corner(&triangles[t], 0), corner(&triangles[t], 1), corner(&triangles[t], 2));
        let p = a * (1.0 - s) + b * (s * (1.0 - g)) + c * (s * g);
        points.push([p.x as f32, p.y as f32, p.z as f32, 0.0]);
    }
    points
}

#[cfg(test)]
mod tests {
    use super::*;

    fn quad(x0: f32, x1: f32) -> [Triangle; 2] {
        [[[x0, 0.0, 0.0], [x1, 0.0, 0.0], [x1, 1.0, 0.0]], [[x0, 0.0, 0.0], [x1, 1.0, 0.0], [x0, 1.0, 0.0]]]
    }

    #[test]
    fn points_follow_the_area_and_stay_on_their_triangles() {
        // A 1×1 square and a 3×1 one: three times the area, three times the points (±1 each).
        let mut tris = quad(0.0, 1.0).to_vec();
        tris.extend(quad(2.0, 5.0));
        let points = surface_points(&tris, 4000);
        assert_eq!(points.len(), 4000);
        let small = points.iter().filter(|p| p[0] <= 1.0).count();
        let large = points.iter().filter(|p| p[0] >= 2.0).count();
        assert_eq!(small + large, 4000, "every point lies on one of the squares");
        assert!((small as i64 - 1000).abs() <= 2, "{small}");
        for p in &points {
            assert!(p[1] >= 0.0 && p[1] <= 1.0 && p[2] == 0.0, "{p:?}");
        }
        // Stratified: every 0.25×0.25 cell of the small square gets its share (62.5) within 25%.
        let mut cells = [0u32; 16];
        for p in points.iter().filter(|p| p[0] <= 1.0) {
            let (cx, cy) = (((p[0] * 4.0) as usize).min(3), ((p[1] * 4.0) as usize).min(3));
            cells[cy * 4 + cx] += 1;
        }
        for c in cells {
            assert!((c as f64 - 62.5).abs() <= 0.25 * 62.5, "{cells:?}");
        }
    }

    #[test]
    fn points_are_deterministic_and_every_stride_covers_the_scene() {
        let tris = [quad(0.0, 1.0), quad(2.0, 3.0)].concat();
        assert_eq!(surface_points(&tris, 512), surface_points(&tris, 512));
        // The subset a map takes (every 8th point from any start) still covers both squares evenly.
        let points = surface_points(&tris, 512);
        for start in 0..8 {
            let subset: Vec<_> = points.iter().skip(start).step_by(8).collect();
            let left = subset.iter().filter(|p| p[0] <= 1.0).count();
            assert!((left as i64 - 32).abs() <= 1, "start {start}: {left} of {}", subset.len());
        }
    }

    #[test]
    fn degenerate_triangles_get_no_points() {
        let flat: Triangle = [[0.0; 3], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]];
        assert!(surface_points(&[flat], 100).is_empty());
        let mut tris = vec![flat];
        tris.extend(quad(0.0, 1.0));
        tris.push(flat);
        let points = surface_points(&tris, 100);
        assert_eq!(points.len(), 100);
        assert!(points.iter().all(|p| p[1] >= 0.0 && p[1] <= 1.0 && p[0] >= 0.0 && p[0] <= 1.0));
    }
}
