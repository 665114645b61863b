//! Whether a scene's surfaces lie on the boundary of their convex hull (a "convex shell": one
//! convex room seen from inside, a floor and a wall meeting in a concave corner, a single
//! plane). Then no segment between two surface points passes through another surface — the
//! segment lies inside the hull and a hull face's plane has every point on one side — so shadow
//! rays between receivers and virtual lights can never be blocked and the pass plan leaves
//! `visibility="raytrace"` out (`methods/visibility.rs`).

use super::bvh::Triangle;
use glam::DVec3;

/// Largest triangle count checked (the test is O(triangles × vertices)); larger scenes are
/// reported as not convex, which only keeps the shadow rays.
pub const MAX_TRIANGLES: usize = 4096;

/// True when every non-degenerate triangle's plane has all vertices of the scene on one side
/// (within `tolerance` × `extent`, rounding of the upload). Conservative: false when unsure.
pub fn is_convex_shell(triangles: &[Triangle], extent: f64) -> bool {
    if triangles.is_empty() || triangles.len() > MAX_TRIANGLES {
        return false;
    }
    let tolerance = 1e-6 * extent.max(f64::MIN_POSITIVE);
    let points: Vec<DVec3> = triangles.iter().flatten().map(|p| DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64)).collect();
    for t in triangles {
        let [a, b, c] = t.map(|p| DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64));
        let normal = (b - a).cross(c - a);
        let len = normal.length();
        if !(len > 0.0) || !len.is_finite() {
            continue; // degenerate: blocks nothing
        }
        let n = normal / len;
        let (mut above, mut below) = (false, false);
        for p in &points {
            let d = n.dot(*p - a);
            above |= d > tolerance;
            below |= d < -tolerance;
            if above && below {
                return false;
            }
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::is_convex_shell;

    fn quad(corners: [[f32; 3]; 4]) -> Vec<[[f32; 3]; 3]> {
        vec![[corners[0], corners[1], corners[2]], [corners[0], corners[2], corners[3]]]
    }

    #[test]
    fn rooms_corners_and_planes_are_convex_shells_and_dividers_are_not() {
        let floor = quad([[-1.0, 0.0, -1.0], [-1.0, 0.0, 1.0], [1.0, 0.0, 1.0], [1.0, 0.0, -1.0]]);
        let back = quad([[-1.0, 0.0, -1.0], [1.0, 0.0, -1.0], [1.0, 2.0, -1.0], [-1.0, 2.0, -1.0]]);
        let divider = quad([[0.0, 0.0, -1.0], [0.0, 0.0, 1.0], [0.0, 1.0, 1.0], [0.0, 1.0, -1.0]]);
        assert!(is_convex_shell(&floor, 2.0), "a plane");
        assert!(is_convex_shell(&[floor.clone(), back.clone()].concat(), 3.0), "a concave corner");
        assert!(!is_convex_shell(&[floor.clone(), divider].concat(), 3.0), "a wall splitting the floor");
        // An occluder floating in the corner breaks it.
        let block = quad([[0.2, 0.5, 0.2], [0.4, 0.5, 0.2], [0.4, 0.5, 0.4], [0.2, 0.5, 0.4]]);
        assert!(!is_convex_shell(&[floor, back, block].concat(), 3.0));
        assert!(!is_convex_shell(&[], 1.0), "nothing: no claim");
    }
}
