//! Wall time of the BVH build (the ray tracer's, `upload/bvh.rs`) on one thread and on all of
//! rayon's, over a field of tessellated spheres (what a large scene's many small objects look
//! like to the SAH), and its size per triangle. The two builds are checked to be the same bytes.
//!
//!     cargo run --release -p vsgl-core --example bvh_build_time -- --triangles 400000,1600000 --samples 3
//!
//! Threads: `RAYON_NUM_THREADS` (default: one per core). Prints a Markdown table: median and
//! extremes over `--samples` builds of each, alternating one thread and many.

use std::time::Instant;
use vsgl_core::upload::bvh::{Bvh, Triangle};

/// `count` spheres of `2·stacks·slices` triangles each on a square grid in the y = 0 plane.
fn sphere_field(triangles: usize) -> Vec<Triangle> {
    let (stacks, slices) = (16usize, 32usize);
    let per_sphere = 2 * stacks * slices;
    let spheres = triangles.div_ceil(per_sphere).max(1);
    let side = (spheres as f64).sqrt().ceil() as usize;
    let point = |c: [f64; 3], r: f64, i: usize, j: usize| {
        let theta = std::f64::consts::PI * i as f64 / stacks as f64;
        let phi = 2.0 * std::f64::consts::PI * j as f64 / slices as f64;
        [(c[0] + r * theta.sin() * phi.cos()) as f32, (c[1] + r * theta.cos()) as f32, (c[2] + r * theta.sin() * phi.sin()) as f32]
    };
    let mut out = Vec::with_capacity(spheres * per_sphere);
    for s in 0..spheres {
        let c = [(s % side) as f64 * 2.5, 1.0, (s / side) as f64 * 2.5];
        for i in 0..stacks {
            for j in 0..slices {
                let (a, b) = (point(c, 1.0, i, j), point(c, 1.0, i + 1, j));
                let (cc, d) = (point(c, 1.0, i + 1, j + 1), point(c, 1.0, i, j + 1));
                out.push([a, b, cc]);
                out.push([a, cc, d]);
            }
        }
    }
    out.truncate(triangles);
    out
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let arg = |name: &str, default: &str| {
        args.iter().position(|a| a == name).and_then(|i| args.get(i + 1)).cloned().unwrap_or_else(|| default.to_string())
    };
    let sizes: Vec<usize> = arg("--triangles", "100000,400000").split(',').map(|s| s.parse().expect("--triangles: integers")).collect();
    let samples: usize = arg("--samples", "3").parse().expect("--samples: an integer");
    println!("threads: {}", rayon::current_num_threads());
    println!("| triangles | one thread ms (median, min–max) | {} threads ms | speed-up | bytes per triangle | depth |", rayon::current_num_threads());
    println!("|---|---|---|---|---|---|");
    for &n in &sizes {
        let tris = sphere_field(n);
        let (mut one, mut many) = (Vec::new(), Vec::new());
        let mut last = None;
        for _ in 0..samples {
            let t = Instant::now();
            let a = Bvh::build_with(&tris, usize::MAX);
            one.push(t.elapsed().as_secs_f64() * 1e3);
            let t = Instant::now();
            let b = Bvh::build(&tris);
            many.push(t.elapsed().as_secs_f64() * 1e3);
            assert!(a.nodes == b.nodes && a.triangle_ids == b.triangle_ids, "the parallel build must be the one-thread build's bytes");
            last = Some(b);
        }
        let b = last.expect("at least one sample");
        let bytes = (b.node_bytes().len() + b.triangle_id_bytes().len()) as f64 / tris.len() as f64;
        let (lo1, hi1) = (one.iter().cloned().fold(f64::INFINITY, f64::min), one.iter().cloned().fold(0.0, f64::max));
        let (lo2, hi2) = (many.iter().cloned().fold(f64::INFINITY, f64::min), many.iter().cloned().fold(0.0, f64::max));
        let (m1, m2) = (median(one), median(many));
        println!("| {} | {m1:.0} ({lo1:.0}–{hi1:.0}) | {m2:.0} ({lo2:.0}–{hi2:.0}) | {:.2}x | {bytes:.1} | {} |", tris.len(), m1 / m2, b.depth);
    }
}
