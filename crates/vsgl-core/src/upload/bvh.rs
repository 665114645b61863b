//! A bounding volume hierarchy over the scene's triangles, built on the CPU and flattened for
//! the compute-shader ray tracer of `method="pathtrace"` (`wgsl/common/bvh.wgsl`).
//!
//! Builder: top-down binned SAH [Wald 2007, "On fast Construction of SAH-based Bounding Volume
//! Hierarchies", §3: centroid bins, cost `A_L·N_L + A_R·N_R`], over all three axes, with an
//! object-median fallback that bounds the depth by [`BVH_MAX_DEPTH`] (the GPU traversal stack).
//! Subtrees of at least [`PARALLEL_MIN_PRIMS`] triangles are built on rayon's threads (Wald
//! 2007, §4: the two halves of a split are independent) and spliced in the order one thread
//! would have laid them out, so the hierarchy is the same bytes on any number of threads.
//! No BVH crate is used: `bvh` 0.13 needs Rust 1.90 and nalgebra, `obvhs` 0.4 a second glam
//! (≥ 0.33 beside the workspace's 0.30) and Rust 1.88, both above this workspace's 1.87.
//!
//! GPU layout: 32-byte nodes (bounds + two words) and, in leaf order, the index of each scene
//! triangle (4 bytes: the `indices` / `triangle_materials` numbering of
//! [`crate::upload::GpuScene`]). The traversal reads a triangle's corners from the upload's
//! raster vertices (`GpuScene::raster_vertices`, three 16-byte corners a triangle in scene
//! order), which the rasteriser needs anyway, so the BVH adds its nodes and 4 bytes a triangle
//! to the upload (about 34 bytes a triangle) instead of a second 48-byte copy of every triangle.
//! Bounds are min/max of the very f32 vertices the GPU intersects, so they contain them exactly.

use crate::scene::Scene;
use glam::DVec3;

/// Marks a leaf in [`BvhNodeRaw::b`]; the low bits are then the triangle count.
pub const BVH_LEAF: u32 = 0x8000_0000;
/// Deepest node level (root = 0). The WGSL traversal stack has this many entries; the builder
/// switches to median splits where SAH splits could exceed it.
pub const BVH_MAX_DEPTH: usize = 64;
/// Largest leaf the SAH may choose; larger sets are always split.
pub const BVH_MAX_LEAF: usize = 4;
/// Centroid bins per axis (Wald 2007 uses 16–32; 16 is within 1% of the full sweep there).
const SAH_BINS: usize = 16;
/// Subtrees with at least this many triangles build their two halves in parallel; below it one
/// thread builds the whole subtree (splitting smaller ones costs more than it saves).
pub const PARALLEL_MIN_PRIMS: usize = 1 << 14;
/// Cost of a box test relative to a triangle test, in the SAH leaf-or-split decision.
const SAH_TRAVERSAL_COST: f64 = 1.0;

/// One node (32 bytes): inner nodes have `a`, `b` = left, right child index; leaves have
/// `a` = first slot of [`Bvh::triangle_ids`] and `b` = [`BVH_LEAF`] | count.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct BvhNodeRaw {
    pub min: [f32; 3],
    pub a: u32,
    pub max: [f32; 3],
    pub b: u32,
}
const _: () = assert!(std::mem::size_of::<BvhNodeRaw>() == 32);

pub type Triangle = [[f32; 3]; 3];

/// The flattened hierarchy. Node 0 is the root; an empty scene has one leaf with no triangles
/// (and a zero box, so the GPU sees only finite numbers).
#[derive(Clone, Debug)]
pub struct Bvh {
    pub nodes: Vec<BvhNodeRaw>,
    /// The scene triangle index of each leaf slot: leaf `n` holds
    /// `triangle_ids[n.a .. n.a + count]`.
    pub triangle_ids: Vec<u32>,
    /// Deepest level reached (root = 0).
    pub depth: usize,
}

#[derive(Clone, Copy, Debug)]
struct Aabb {
    min: [f32; 3],
    max: [f32; 3],
}

impl Aabb {
    const EMPTY: Aabb = Aabb { min: [f32::INFINITY; 3], max: [f32::NEG_INFINITY; 3] };
    fn grow_point(&mut self, p: [f32; 3]) {
        self.grow(&Aabb { min: p, max: p });
    }
    fn grow(&mut self, o: &Aabb) {
        for k in 0..3 {
            self.min[k] = self.min[k].min(o.min[k]);
            self.max[k] = self.max[k].max(o.max[k]);
        }
    }
    fn is_empty(&self) -> bool {
        (0..3).any(|k| self.min[k] > self.max[k])
    }
    /// Half the surface area (the SAH only needs ratios), in f64.
    fn half_area(&self) -> f64 {
        if self.is_empty() {
            return 0.0;
        }
        let d = [0, 1, 2].map(|k| self.max[k] as f64 - self.min[k] as f64);
        d[0] * d[1] + d[1] * d[2] + d[2] * d[0]
    }
}

struct Prim {
    bounds: Aabb,
    centroid: [f64; 3],
    index: u32,
}

/// Smallest `d` with `2^d >= x` (x ≥ 1).
fn ceil_log2(x: usize) -> usize {
    (usize::BITS - (x.max(1) - 1).leading_zeros()) as usize
}

impl Bvh {
    /// Builds the hierarchy over `triangles` (indices into the slice become the triangle ids).
    pub fn build(triangles: &[Triangle]) -> Self {
        Self::build_with(triangles, PARALLEL_MIN_PRIMS)
    }

    /// [`Self::build`] with subtrees of at least `parallel_min` triangles split across threads
    /// (`usize::MAX`: one thread). The result does not depend on it.
    pub fn build_with(triangles: &[Triangle], parallel_min: usize) -> Self {
        use rayon::prelude::*;
        let mut prims: Vec<Prim> = triangles
            .par_iter()
            .enumerate()
            .map(|(i, t)| {
                let mut b = Aabb::EMPTY;
                for v in t {
                    b.grow_point(*v);
                }
                let centroid = [0, 1, 2].map(|k| 0.5 * (b.min[k] as f64 + b.max[k] as f64));
                Prim { bounds: b, centroid, index: i as u32 }
            })
            .collect();
        let (nodes, depth) = if prims.is_empty() {
            (vec![BvhNodeRaw { min: [0.0; 3], a: 0, max: [0.0; 3], b: BVH_LEAF }], 0)
        } else {
            let info = NodeInfo::of(&prims, true);
            build_subtree(&mut prims, info, 0, 0, parallel_min.max(2))
        };
        let triangle_ids = prims.par_iter().map(|p| p.index).collect();
        Self { nodes, triangle_ids, depth }
    }

    /// The node array as bytes for a storage buffer.
    pub fn node_bytes(&self) -> &[u8] {
        bytemuck::cast_slice(&self.nodes)
    }

    /// The leaf-ordered triangle ids as bytes for a storage buffer (one zero id when there are
    /// none, as wgpu rejects empty bindings; no leaf refers to it).
    pub fn triangle_id_bytes(&self) -> Vec<u8> {
        if self.triangle_ids.is_empty() {
            vec![0u8; std::mem::size_of::<u32>()]
        } else {
            bytemuck::cast_slice(&self.triangle_ids).to_vec()
        }
    }

    /// Closest hit along `origin + t·dir`, `0 < t < t_max`: (t, triangle id), over the
    /// `triangles` the hierarchy was built on. CPU twin of `bvh_closest_hit` for tests (f64
    /// Möller–Trumbore, same node layout and order).
    pub fn closest_hit(&self, triangles: &[Triangle], origin: [f64; 3], dir: [f64; 3], t_max: f64) -> Option<(f64, u32)> {
        let mut best: Option<(f64, u32)> = None;
        let mut stack = vec![0usize];
        while let Some(i) = stack.pop() {
            let n = &self.nodes[i];
            let limit = best.map_or(t_max, |b| b.0);
            if !ray_box(origin, dir, n, limit) {
                continue;
            }
            if n.b & BVH_LEAF != 0 {
                let count = (n.b & !BVH_LEAF) as usize;
                for &id in &self.triangle_ids[n.a as usize..n.a as usize + count] {
                    if let Some(d) = ray_triangle(origin, dir, triangles[id as usize]) {
                        if d < best.map_or(t_max, |b| b.0) {
                            best = Some((d, id));
                        }
                    }
                }
            } else {
                stack.push(n.b as usize);
                stack.push(n.a as usize);
            }
        }
        best
    }
}

/// A node's primitive bounds and centroid bounds ([min, max] per axis), which its parent's
/// bins already hold (the union of the bins on each side of the split), so a level costs one
/// binning pass and one partition over its primitives [Wald 2007, §3.2] instead of separate
/// passes for the bounds, the centroid bounds and each axis. Min and max are exact, so these
/// are the very numbers passes over the primitives would give.
#[derive(Clone, Copy, Debug)]
struct NodeInfo {
    bounds: Aabb,
    cbounds: CentroidBounds,
}

type CentroidBounds = [[f64; 3]; 2];
const CENTROID_BOUNDS_EMPTY: CentroidBounds = [[f64::INFINITY; 3], [f64::NEG_INFINITY; 3]];

/// `a` grown to hold the centroid bounds `b` (a point c is [c, c]).
fn grow_centroid_bounds(a: &mut CentroidBounds, b_min: &[f64; 3], b_max: &[f64; 3]) {
    for k in 0..3 {
        a[0][k] = a[0][k].min(b_min[k]);
        a[1][k] = a[1][k].max(b_max[k]);
    }
}

impl NodeInfo {
    const EMPTY: NodeInfo = NodeInfo { bounds: Aabb::EMPTY, cbounds: CENTROID_BOUNDS_EMPTY };
    fn add(&mut self, p: &Prim) {
        self.bounds.grow(&p.bounds);
        grow_centroid_bounds(&mut self.cbounds, &p.centroid, &p.centroid);
    }
    fn merge(&mut self, o: &NodeInfo) {
        self.bounds.grow(&o.bounds);
        grow_centroid_bounds(&mut self.cbounds, &o.cbounds[0], &o.cbounds[1]);
    }
    /// One pass over `prims` (on all threads when `parallel`: min and max do not depend on the
    /// order partial results merge in).
    fn of(prims: &[Prim], parallel: bool) -> NodeInfo {
        let add = |mut info: NodeInfo, p: &Prim| {
            info.add(p);
            info
        };
        if !parallel {
            return prims.iter().fold(NodeInfo::EMPTY, add);
        }
        use rayon::prelude::*;
        prims.par_iter().fold(|| NodeInfo::EMPTY, add).reduce(
            || NodeInfo::EMPTY,
            |mut a, b| {
                a.merge(&b);
                a
            },
        )
    }
}

/// How a node splits: the primitives left of the split come first in its slice.
struct Split {
    left_count: usize,
    left: NodeInfo,
    right: NodeInfo,
}

/// The subtree over `prims` (the slice starting at triangle `first` of the leaf order), its
/// root at level `level`: its nodes with the root first and child indices into this vector,
/// laid out as one thread's work list lays them out (a node's two children side by side when
/// it is split, then the left child's subtree, then the right's), and its deepest level.
fn build_subtree(prims: &mut [Prim], info: NodeInfo, first: usize, level: usize, parallel_min: usize) -> (Vec<BvhNodeRaw>, usize) {
    if prims.len() < parallel_min {
        return build_sequential(prims, info, first, level);
    }
    let bounds = info.bounds;
    let Some(split) = choose_split(prims, &info, level, true) else {
        let leaf = BvhNodeRaw { min: bounds.min, a: first as u32, max: bounds.max, b: BVH_LEAF | prims.len() as u32 };
        return (vec![leaf], level);
    };
    let left_count = split.left_count;
    let (left, right) = prims.split_at_mut(left_count);
    let ((l, l_depth), (r, r_depth)) = rayon::join(
        || build_subtree(left, split.left, first, level + 1, parallel_min),
        || build_subtree(right, split.right, first + left_count, level + 1, parallel_min),
    );
    // [root, left root, right root, below the left root, below the right root]: a child's
    // index i > 0 into its own vector moves to 3 + (i - 1) (+ the left's rest, on the right).
    let mut nodes = Vec::with_capacity(l.len() + r.len() + 1);
    nodes.push(BvhNodeRaw { min: bounds.min, a: 1, max: bounds.max, b: 2 });
    let shift = |n: &BvhNodeRaw, base: u32| {
        if n.b & BVH_LEAF != 0 {
            *n
        } else {
            BvhNodeRaw { a: n.a - 1 + base, b: n.b - 1 + base, ..*n }
        }
    };
    let (l_base, r_base) = (3, 3 + (l.len() - 1) as u32);
    nodes.push(shift(&l[0], l_base));
    nodes.push(shift(&r[0], r_base));
    nodes.extend(l[1..].iter().map(|n| shift(n, l_base)));
    nodes.extend(r[1..].iter().map(|n| shift(n, r_base)));
    (nodes, l_depth.max(r_depth))
}

/// [`build_subtree`] on one thread, with an explicit work list (no recursion limit).
fn build_sequential(prims: &mut [Prim], info: NodeInfo, first: usize, level: usize) -> (Vec<BvhNodeRaw>, usize) {
    let empty = BvhNodeRaw { min: [0.0; 3], a: 0, max: [0.0; 3], b: BVH_LEAF };
    let mut nodes: Vec<BvhNodeRaw> = Vec::with_capacity(2 * prims.len().max(1));
    nodes.push(empty);
    let mut depth = level;
    // (node, first prim in `prims`, prim count, level, the node's bounds)
    let mut work = vec![(0usize, 0usize, prims.len(), level, info)];
    while let Some((node, start, count, lvl, info)) = work.pop() {
        depth = depth.max(lvl);
        let slice = &mut prims[start..start + count];
        let bounds = info.bounds;
        match choose_split(slice, &info, lvl, false) {
            None => {
                nodes[node] = BvhNodeRaw { min: bounds.min, a: (first + start) as u32, max: bounds.max, b: BVH_LEAF | count as u32 };
            }
            Some(split) => {
                let l = nodes.len();
                nodes.push(empty);
                nodes.push(empty);
                nodes[node] = BvhNodeRaw { min: bounds.min, a: l as u32, max: bounds.max, b: (l + 1) as u32 };
                // Right first so the left subtree is laid out right after its parent.
                work.push((l + 1, start + split.left_count, count - split.left_count, lvl + 1, split.right));
                work.push((l, start, split.left_count, lvl + 1, split.left));
            }
        }
    }
    (nodes, depth)
}

/// Where to split a node's primitives (partitioned in place, the left ones first) and the two
/// children's bounds, or `None` for a leaf. `info`: the node's bounds and centroid bounds.
/// `parallel`: bin on all threads (the top levels, which one thread would otherwise scan alone;
/// bounds and counts are min/max and integer sums, so the order of partial results cannot
/// change them).
fn choose_split(prims: &mut [Prim], info: &NodeInfo, level: usize, parallel: bool) -> Option<Split> {
    let n = prims.len();
    if n <= 1 {
        return None;
    }
    // Depth guard: a balanced subtree of the rest needs ceil(log2(n / leaf)) more levels.
    let must_balance = level + ceil_log2(n.div_ceil(BVH_MAX_LEAF)) + 1 >= BVH_MAX_DEPTH;
    let cbounds = info.cbounds;
    let extent = [0, 1, 2].map(|k| cbounds[1][k] - cbounds[0][k]);
    let widest = (0..3).max_by(|&a, &b| extent[a].total_cmp(&extent[b])).unwrap_or(0);
    if !must_balance {
        let binning = Binning::new(&cbounds);
        let bins = bin_prims(prims, &binning, parallel);
        // (cost, axis, bin boundary): left = bins [0, boundary).
        let mut best: Option<(f64, usize, usize)> = None;
        for axis in 0..3 {
            if !binning.used[axis] {
                continue;
            }
            let axis_bins = &bins.bins[axis];
            // Sweep from the right for suffix areas, then from the left.
            let mut right_area = [0.0f64; SAH_BINS];
            let mut right_count = [0usize; SAH_BINS];
            let mut acc = Aabb::EMPTY;
            let mut cnt = 0;
            // An empty bin changes neither side, so the areas are computed only past full ones
            // (small nodes have mostly empty bins), and a boundary after an empty bin costs what
            // the one before it did, which the strict `<` below already kept.
            let mut area = 0.0;
            for i in (1..SAH_BINS).rev() {
                if axis_bins[i].count > 0 {
                    acc.grow(&axis_bins[i].bounds);
                    cnt += axis_bins[i].count;
                    area = acc.half_area();
                }
                right_area[i] = area;
                right_count[i] = cnt;
            }
            let mut acc = Aabb::EMPTY;
            let mut cnt = 0;
            for i in 1..SAH_BINS {
                if axis_bins[i - 1].count == 0 {
                    continue;
                }
                acc.grow(&axis_bins[i - 1].bounds);
                cnt += axis_bins[i - 1].count;
                if right_count[i] == 0 {
                    continue;
                }
                let cost = acc.half_area() * cnt as f64 + right_area[i] * right_count[i] as f64;
                if best.is_none_or(|b| cost < b.0) {
                    best = Some((cost, axis, i));
                }
            }
        }
        let parent_area = info.bounds.half_area();
        if let Some((cost, axis, boundary)) = best {
            // SAH: split when C_trav + cost/A ≤ n (relative to one triangle test).
            let leaf_cost = n as f64;
            let split_cost = SAH_TRAVERSAL_COST + if parent_area > 0.0 { cost / parent_area } else { n as f64 };
            if n <= BVH_MAX_LEAF && split_cost >= leaf_cost {
                return None;
            }
            let left_count = partition(prims, |p| binning.bin(axis, p.centroid[axis]) < boundary);
            if left_count > 0 && left_count < n {
                // The children's bounds: the union of the bins on each side, or a pass over each.
                let (l, r) = prims.split_at(left_count);
                let left = bins.info(axis, 0..boundary).unwrap_or_else(|| NodeInfo::of(l, false));
                let right = bins.info(axis, boundary..SAH_BINS).unwrap_or_else(|| NodeInfo::of(r, false));
                return Some(Split { left_count, left, right });
            }
        } else if n <= BVH_MAX_LEAF {
            return None;
        }
    }
    // Object median along the widest centroid axis (also when every centroid coincides).
    let mid = n / 2;
    prims.select_nth_unstable_by(mid, |a, b| a.centroid[widest].total_cmp(&b.centroid[widest]));
    let (left, right) = prims.split_at(mid);
    Some(Split { left_count: mid, left: NodeInfo::of(left, parallel), right: NodeInfo::of(right, parallel) })
}

/// Which centroid bin a coordinate falls in, per axis: [`SAH_BINS`] equal bins over the node's
/// centroid bounds; axes where every centroid coincides are not binned.
struct Binning {
    lo: [f64; 3],
    scale: [f64; 3],
    used: [bool; 3],
}

impl Binning {
    fn new(cbounds: &[[f64; 3]; 2]) -> Self {
        let extent = [0, 1, 2].map(|k| cbounds[1][k] - cbounds[0][k]);
        Binning {
            lo: cbounds[0],
            scale: extent.map(|e| if e > 0.0 { SAH_BINS as f64 / e } else { 0.0 }),
            used: extent.map(|e| e > 0.0),
        }
    }
    fn bin(&self, axis: usize, c: f64) -> usize {
        (((c - self.lo[axis]) * self.scale[axis]) as usize).min(SAH_BINS - 1)
    }
}

/// One bin: its primitives' count and bounds.
#[derive(Clone, Copy)]
struct Bin {
    bounds: Aabb,
    count: usize,
}

/// Nodes of at least this many primitives also keep each bin's centroid bounds, from which the
/// children's come; smaller ones (whose primitives are in cache) take them in a pass over each
/// child, which costs less than clearing and merging 48 more bins per node.
const BIN_CENTROIDS_MIN_PRIMS: usize = 256;

/// The bins of every binned axis, and with [`BIN_CENTROIDS_MIN_PRIMS`] or more primitives each
/// bin's centroid bounds ([axis · SAH_BINS + bin]; empty otherwise).
#[derive(Clone)]
struct Bins {
    bins: [[Bin; SAH_BINS]; 3],
    centroids: Vec<CentroidBounds>,
}

impl Bins {
    fn new(with_centroids: bool) -> Self {
        Bins {
            bins: [[Bin { bounds: Aabb::EMPTY, count: 0 }; SAH_BINS]; 3],
            centroids: if with_centroids { vec![CENTROID_BOUNDS_EMPTY; 3 * SAH_BINS] } else { Vec::new() },
        }
    }
    fn add(&mut self, binning: &Binning, p: &Prim) {
        for axis in 0..3 {
            if binning.used[axis] {
                let i = binning.bin(axis, p.centroid[axis]);
                let b = &mut self.bins[axis][i];
                b.bounds.grow(&p.bounds);
                b.count += 1;
                if let Some(c) = self.centroids.get_mut(axis * SAH_BINS + i) {
                    grow_centroid_bounds(c, &p.centroid, &p.centroid);
                }
            }
        }
    }
    fn merge(&mut self, o: &Bins) {
        for (xs, ys) in self.bins.iter_mut().zip(o.bins.iter()) {
            for (x, y) in xs.iter_mut().zip(ys.iter()) {
                x.bounds.grow(&y.bounds);
                x.count += y.count;
            }
        }
        for (x, y) in self.centroids.iter_mut().zip(o.centroids.iter()) {
            grow_centroid_bounds(x, &y[0], &y[1]);
        }
    }
    /// The bounds of the primitives in bins `range` of `axis`, if the centroids were kept.
    fn info(&self, axis: usize, range: std::ops::Range<usize>) -> Option<NodeInfo> {
        if self.centroids.is_empty() {
            return None;
        }
        let mut info = NodeInfo::EMPTY;
        for i in range {
            let c = &self.centroids[axis * SAH_BINS + i];
            info.merge(&NodeInfo { bounds: self.bins[axis][i].bounds, cbounds: *c });
        }
        Some(info)
    }
}

/// Each bin's bounds and count of `prims` on every binned axis, in one pass. (The partial bins
/// are boxed: a fold moves its accumulator at every primitive.)
fn bin_prims(prims: &[Prim], binning: &Binning, parallel: bool) -> Box<Bins> {
    let with_centroids = prims.len() >= BIN_CENTROIDS_MIN_PRIMS;
    if !parallel {
        let mut bins = Box::new(Bins::new(with_centroids));
        for p in prims {
            bins.add(binning, p);
        }
        return bins;
    }
    use rayon::prelude::*;
    prims
        .par_iter()
        .fold(
            || Box::new(Bins::new(with_centroids)),
            |mut bins, p| {
                bins.add(binning, p);
                bins
            },
        )
        .reduce(
            || Box::new(Bins::new(with_centroids)),
            |mut a, b| {
                a.merge(&b);
                a
            },
        )
}

/// Stable-enough in-place partition; returns how many satisfy `pred` (moved to the front).
fn partition(prims: &mut [Prim], pred: impl Fn(&Prim) -> bool) -> usize {
    let mut i = 0;
    for j in 0..prims.len() {
        if pred(&prims[j]) {
            prims.swap(i, j);
            i += 1;
        }
    }
    i
}

/// Slab test [Kay & Kajiya 1986] in f64 for the CPU twin.
fn ray_box(o: [f64; 3], d: [f64; 3], n: &BvhNodeRaw, t_max: f64) -> bool {
    let (mut t0, mut t1) = (0.0f64, t_max);
    for k in 0..3 {
        let inv = 1.0 / d[k];
        let mut a = (n.min[k] as f64 - o[k]) * inv;
        let mut b = (n.max[k] as f64 - o[k]) * inv;
        if a > b {
            std::mem::swap(&mut a, &mut b);
        }
        // NaN (0·∞ for a ray in a slab plane) leaves the bounds unchanged.
        if a > t0 {
            t0 = a;
        }
        if b < t1 {
            t1 = b;
        }
    }
    t0 <= t1
}

/// Möller & Trumbore 1997 in f64, no culling; `t > 0`.
pub fn ray_triangle(o: [f64; 3], d: [f64; 3], t: Triangle) -> Option<f64> {
    let v = |p: [f32; 3]| DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64);
    let (v0, v1, v2) = (v(t[0]), v(t[1]), v(t[2]));
    let (o, d) = (DVec3::from(o), DVec3::from(d));
    let e1 = v1 - v0;
    let e2 = v2 - v0;
    let p = d.cross(e2);
    let det = e1.dot(p);
    if det.abs() <= 1e-300 {
        return None;
    }
    let inv = 1.0 / det;
    let s = o - v0;
    let u = s.dot(p) * inv;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let q = s.cross(e1);
    let w = d.dot(q) * inv;
    if w < 0.0 || u + w > 1.0 {
        return None;
    }
    let dist = e2.dot(q) * inv;
    (dist > 0.0).then_some(dist)
}

/// The scene's triangles relative to `origin`, in the order and f32 rounding of
/// [`crate::upload::GpuScene::upload`] (node, primitive, index triple), so triangle `i` here is
/// triangle `i` of the GPU scene's `indices` and `triangle_materials`.
pub fn scene_triangles(scene: &Scene, origin: DVec3) -> Vec<Triangle> {
    let mut out = Vec::new();
    for (ni, node) in scene.nodes.iter().enumerate() {
        let Some(mi) = node.mesh else { continue };
        let Some(mesh) = scene.meshes.get(mi) else { continue };
        let world = scene.world_transform(ni);
        for prim in &mesh.primitives {
            let verts: Vec<[f32; 3]> = prim
                .positions
                .iter()
                .map(|p| (world.transform_point3(DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64)) - origin).as_vec3().to_array())
                .collect();
            for tri in prim.indices.chunks_exact(3) {
                let get = |i: u32| verts.get(i as usize).copied().unwrap_or([0.0; 3]);
                out.push([get(tri[0]), get(tri[1]), get(tri[2])]);
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::SplitMix64;

    /// xorshift64*: a dependency-free deterministic generator for the tests.

    fn random_soup(rng: &mut SplitMix64, n: usize, scale: f64, offset: f64) -> Vec<Triangle> {
        (0..n)
            .map(|_| {
                let c = [rng.range(-scale, scale) + offset, rng.range(-scale, scale), rng.range(-scale, scale)];
                let size = scale * 0.3 * rng.next_f64();
                [0, 1, 2].map(|_| [0, 1, 2].map(|k| (c[k] + rng.range(-size, size)) as f32))
            })
            .collect()
    }

    fn brute_force(tris: &[Triangle], o: [f64; 3], d: [f64; 3]) -> Option<(f64, u32)> {
        let mut best: Option<(f64, u32)> = None;
        for (i, t) in tris.iter().enumerate() {
            if let Some(dist) = ray_triangle(o, d, *t) {
                if best.is_none_or(|b| dist < b.0) {
                    best = Some((dist, i as u32));
                }
            }
        }
        best
    }

    fn check_structure(bvh: &Bvh, tris: &[Triangle]) {
        // Every triangle exactly once, every box contains its children / triangles.
        let mut seen = vec![0u32; tris.len()];
        for &id in &bvh.triangle_ids {
            seen[id as usize] += 1;
        }
        assert!(seen.iter().all(|&c| c == 1), "every triangle must be in exactly one leaf");
        let contains = |outer: &BvhNodeRaw, p: [f32; 3]| (0..3).all(|k| outer.min[k] <= p[k] && p[k] <= outer.max[k]);
        let mut reached = 0usize;
        let mut stack = vec![(0usize, 0usize)];
        while let Some((i, level)) = stack.pop() {
            assert!(level <= BVH_MAX_DEPTH);
            let n = bvh.nodes[i];
            if n.b & BVH_LEAF != 0 {
                let count = (n.b & !BVH_LEAF) as usize;
                reached += count;
                let mut tight = Aabb::EMPTY;
                for &id in &bvh.triangle_ids[n.a as usize..n.a as usize + count] {
                    for v in tris[id as usize] {
                        assert!(contains(&n, v), "leaf {i} must contain its triangles");
                        tight.grow_point(v);
                    }
                }
                // Tight: the builder carries children's bounds down from the bins, and a wrong
                // carry that still contains everything would only cost speed.
                if count > 0 {
                    assert_eq!((n.min, n.max), (tight.min, tight.max), "leaf {i} must be its triangles' bounds");
                }
            } else {
                let mut tight = Aabb::EMPTY;
                for c in [n.a as usize, n.b as usize] {
                    let child = bvh.nodes[c];
                    assert!(contains(&n, child.min) && contains(&n, child.max), "node {i} must contain child {c}");
                    tight.grow(&Aabb { min: child.min, max: child.max });
                    stack.push((c, level + 1));
                }
                assert_eq!((n.min, n.max), (tight.min, tight.max), "node {i} must be its children's bounds");
            }
        }
        assert_eq!(reached, tris.len());
    }

    #[test]
    fn parallel_builds_lay_out_the_same_bytes_as_one_thread() {
        let mut rng = SplitMix64(0x51_7CC1_B727_220A);
        let soup = random_soup(&mut rng, 3000, 1.0, 0.0);
        let same = vec![[[0.5f32, 0.5, 0.5], [0.5, 0.5, 0.6], [0.5, 0.6, 0.5]]; 300];
        // Subtrees split across threads also sum their bins on several threads.
        let large = random_soup(&mut rng, 2 * PARALLEL_MIN_PRIMS + 5, 1.0, 0.0);
        for tris in [soup, same, large] {
            let one = Bvh::build_with(&tris, usize::MAX);
            check_structure(&one, &tris);
            // Down to splitting every node of two or more triangles across threads.
            for parallel_min in [2, 7, 64, 1000] {
                let many = Bvh::build_with(&tris, parallel_min);
                assert_eq!(many.nodes, one.nodes, "parallel_min {parallel_min}: nodes");
                assert_eq!(many.triangle_ids, one.triangle_ids, "parallel_min {parallel_min}: triangles");
                assert_eq!(many.depth, one.depth);
            }
        }
    }

    #[test]
    fn bvh_closest_hit_matches_brute_force_on_random_rays() {
        let mut rng = SplitMix64(0x9E37_79B9_7F4A_7C15);
        // Near the origin and far from it (1e5 m: the f32 spacing there is ~8 mm).
        for (offset, scale) in [(0.0, 1.0), (1.0e5, 50.0)] {
            let tris = random_soup(&mut rng, 2000, scale, offset);
            let bvh = Bvh::build(&tris);
            check_structure(&bvh, &tris);
            let mut hits = 0;
            for _ in 0..3000 {
                let o = [rng.range(-1.5 * scale, 1.5 * scale) + offset, rng.range(-1.5 * scale, 1.5 * scale), rng.range(-1.5 * scale, 1.5 * scale)];
                let d = rng.unit_vector().to_array();
                let want = brute_force(&tris, o, d);
                let got = bvh.closest_hit(&tris, o, d, f64::INFINITY);
                match (want, got) {
                    (None, None) => {}
                    (Some(w), Some(g)) => {
                        hits += 1;
                        // Equal distances can come from two triangles: compare t, then the id.
                        assert!((w.0 - g.0).abs() <= 1e-12 * w.0.max(1.0), "t: brute {w:?} bvh {g:?}");
                        if (w.0 - g.0).abs() > 0.0 {
                            assert_eq!(w.1, g.1);
                        }
                    }
                    _ => panic!("brute force {want:?} vs bvh {got:?} for o={o:?} d={d:?}"),
                }
            }
            assert!(hits > 300, "the random rays must hit often enough to test something ({hits})");
        }
    }

    #[test]
    fn bvh_respects_t_max() {
        let tris = vec![[[-1.0, -1.0, 2.0], [1.0, -1.0, 2.0], [0.0, 1.0, 2.0]]];
        let bvh = Bvh::build(&tris);
        assert_eq!(bvh.closest_hit(&tris, [0.0; 3], [0.0, 0.0, 1.0], 3.0).map(|h| h.1), Some(0));
        assert_eq!(bvh.closest_hit(&tris, [0.0; 3], [0.0, 0.0, 1.0], 1.5), None);
        assert_eq!(bvh.closest_hit(&tris, [0.0; 3], [0.0, 0.0, -1.0], 10.0), None);
    }

    #[test]
    fn bvh_degenerate_inputs_stay_within_the_stack_depth() {
        // Identical triangles (zero centroid extent), a long coplanar strip, and none at all.
        let same = vec![[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]; 1000];
        let bvh = Bvh::build(&same);
        check_structure(&bvh, &same);
        assert!(bvh.depth <= BVH_MAX_DEPTH);
        assert_eq!(bvh.closest_hit(&same, [0.2, 0.2, -1.0], [0.0, 0.0, 1.0], 10.0).map(|h| h.0), Some(1.0));
        // Exponentially spaced triangles: SAH alone would build a deep, list-like tree.
        let strip: Vec<Triangle> = (0..3000)
            .map(|i| {
                let x = 1.01f32.powi(i);
                [[x, 0.0, 0.0], [x * 1.001, 0.0, 0.0], [x, 1.0, 0.0]]
            })
            .collect();
        let bvh = Bvh::build(&strip);
        check_structure(&bvh, &strip);
        assert!(bvh.depth <= BVH_MAX_DEPTH, "depth {}", bvh.depth);
        let empty = Bvh::build(&[]);
        assert_eq!(empty.nodes.len(), 1);
        assert_eq!(empty.closest_hit(&[], [0.0; 3], [0.0, 0.0, 1.0], 1e30), None);
        assert_eq!(empty.triangle_id_bytes().len(), 4);
    }

    #[test]
    fn scene_triangles_follow_the_upload_order() {
        let mut scene = crate::scene::builtin::cornell_box();
        let origin = DVec3::new(0.25, 1.0, 3.0);
        let tris = scene_triangles(&scene, origin);
        assert_eq!(tris.len(), scene.stats().triangles);
        // Moving the origin moves every vertex by the same f64 offset before rounding.
        let shifted = scene_triangles(&scene, origin + DVec3::X);
        assert!((tris[0][0][0] - shifted[0][0][0] - 1.0).abs() < 1e-5);
        scene.lights.clear();
        assert_eq!(scene_triangles(&scene, origin).len(), tris.len());
    }
}
