// vsgl:include-only — the including shader declares the storage arrays
//   bvh_nodes: array<BvhNode>, bvh_triangle_ids: array<u32>, triangle_corners: array<TriangleCorner>
// that crates/vsgl-core/src/upload/bvh.rs builds (node 0 is the root; the scene triangle index of
// each leaf slot, in leaf order) and the upload holds (the raster vertices: three corners a
// triangle, in scene order), and bvh_nodes_1…3 and triangle_corners_1…3: nodes and corners are
// the pages of one buffer each (STORAGE_PAGE_BYTES = 2^27 bytes, crates/vsgl-core/src/gpu/
// buffers.rs), so a scene may have more of them than one binding holds; pages past the end bind
// the first again. Reading corners through the id keeps the BVH at its nodes and 4 bytes a
// triangle, where a leaf-ordered copy of the corners took 48.
//
// Ray queries over the BVH: closest hit and any hit (shadow rays), with a fixed-size stack whose
// size is the builder's depth bound. Ray–box: slab test with Ize's conservative rounding
// [Ize 2013, "Robust BVH Ray Traversal", JCGT 2(2), §3: far distances scaled by 1 + 2γ₃].
// Ray–triangle: watertight test [Woop, Benthin & Wald 2013, "Watertight Ray/Triangle
// Intersection", JCGT 2(1), §3 and Listing 1], without culling and without the f64 fallback
// for edges hit exactly (both triangles then report the hit, which is harmless here).
#include "common/constants.wgsl"
#include "common/storage_pages.wgsl"

// 32 bytes; the twin is `BvhNodeRaw` in crates/vsgl-core/src/upload/bvh.rs.
struct BvhNode {
    min: vec3f,
    // Inner node: left child. Leaf: first triangle.
    a: u32,
    max: vec3f,
    // Inner node: right child. Leaf: BVH_LEAF | triangle count.
    b: u32,
}

// 16 bytes; the twin is `RasterVertex` in crates/vsgl-core/src/upload/mod.rs. Corner k of scene
// triangle t is triangle_corners[3t + k]; `triangle` is t.
struct TriangleCorner {
    position: vec3f,
    triangle: u32,
}

// Elements of a page: 2^27 bytes of 32-byte nodes and of 16-byte corners.
const BVH_NODE_PAGE_SHIFT: u32 = 22u;
const CORNER_PAGE_SHIFT: u32 = 23u;

// Without STORAGE_PAGED (common/storage_pages.wgsl) every index is in page 0.
fn bvh_node(i: u32) -> BvhNode {
    if (!STORAGE_PAGED || i < (1u << BVH_NODE_PAGE_SHIFT)) {
        return bvh_nodes[i];
    }
    return bvh_node_paged(i);
}

fn bvh_node_paged(i: u32) -> BvhNode {
    let j = i & ((1u << BVH_NODE_PAGE_SHIFT) - 1u);
    switch (i >> BVH_NODE_PAGE_SHIFT) {
        case 1u: {
            return bvh_nodes_1[j];
        }
        case 2u: {
            return bvh_nodes_2[j];
        }
        default: {
            return bvh_nodes_3[j];
        }
    }
}

// Corner k of scene triangle t: triangle_corner(3t + k).
fn triangle_corner(i: u32) -> vec3f {
    if (!STORAGE_PAGED || i < (1u << CORNER_PAGE_SHIFT)) {
        return triangle_corners[i].position;
    }
    return triangle_corner_paged(i);
}

fn triangle_corner_paged(i: u32) -> vec3f {
    let j = i & ((1u << CORNER_PAGE_SHIFT) - 1u);
    switch (i >> CORNER_PAGE_SHIFT) {
        case 1u: {
            return triangle_corners_1[j].position;
        }
        case 2u: {
            return triangle_corners_2[j].position;
        }
        default: {
            return triangle_corners_3[j].position;
        }
    }
}

const BVH_LEAF: u32 = 0x80000000u;
// = BVH_MAX_DEPTH in bvh.rs: the builder guarantees no deeper node, and the traversal pushes at
// most one entry per level.
const BVH_STACK_SIZE: u32 = 64u;
const BVH_NO_TRIANGLE: u32 = 0xffffffffu;
// 1 + 2γ₃ with γ_n = nε/(1 − nε), ε = 2^-24 [Ize 2013, Eq. 5]: makes the f32 slab test
// conservative, so rounding never culls a box the ray passes through.
const BVH_BOX_FAR_SCALE: f32 = 1.00000036;
// Direction components smaller than this are replaced by it (keeping the sign) before taking
// reciprocals, so the slab test sees large finite numbers instead of ∞ and never 0·∞. It is a
// direction cosine (dimensionless), not a length.
const BVH_DIR_MIN: f32 = 1.0e-20;

struct Ray {
    origin: vec3f,
    // Unit direction.
    dir: vec3f,
    // Hits count for 0 < t < t_max.
    t_max: f32,
    // A triangle id never reported (the surface the ray leaves), or BVH_NO_TRIANGLE.
    ignore: u32,
}

struct RayHit {
    t: f32,
    triangle: u32,
    // Barycentric weights of v1 and v2 (v0 gets 1 − x − y).
    bary: vec2f,
}

// Per-ray constants of the watertight test (Woop et al. 2013, §3.1): the axis kz of the largest
// direction component, the other two in an order that keeps the winding, and the shear.
struct RayShear {
    k: vec3u,
    s: vec3f,
}

fn ray_shear(dir: vec3f) -> RayShear {
    let a = abs(dir);
    var kz = 2u;
    if (a.x > a.y && a.x > a.z) {
        kz = 0u;
    } else if (a.y > a.z) {
        kz = 1u;
    }
    var kx = (kz + 1u) % 3u;
    var ky = (kx + 1u) % 3u;
    if (dir[kz] < 0.0) {
        let t = kx;
        kx = ky;
        ky = t;
    }
    let dz = dir[kz];
    return RayShear(vec3u(kx, ky, kz), vec3f(dir[kx] / dz, dir[ky] / dz, 1.0 / dz));
}

// Watertight ray/triangle test (Woop et al. 2013, Listing 1). Returns t (< 0 on a miss, or if
// not closer than t_max) and the barycentric weights of v1, v2.
fn ray_triangle_watertight(origin: vec3f, sh: RayShear, t_max: f32, v0: vec3f, v1: vec3f, v2: vec3f) -> vec3f {
    let miss = vec3f(-1.0, 0.0, 0.0);
    // Vertices relative to the origin, permuted so the ray runs along +z, then sheared.
    let a = v0 - origin;
    let b = v1 - origin;
    let c = v2 - origin;
    let ax = a[sh.k.x] - sh.s.x * a[sh.k.z];
    let ay = a[sh.k.y] - sh.s.y * a[sh.k.z];
    let bx = b[sh.k.x] - sh.s.x * b[sh.k.z];
    let by = b[sh.k.y] - sh.s.y * b[sh.k.z];
    let cx = c[sh.k.x] - sh.s.x * c[sh.k.z];
    let cy = c[sh.k.y] - sh.s.y * c[sh.k.z];
    // Scaled barycentrics: 2D edge functions in the sheared frame (U for v0, V for v1, W for v2).
    let u = cx * by - cy * bx;
    let v = ax * cy - ay * cx;
    let w = bx * ay - by * ax;
    if ((u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0)) {
        return miss;
    }
    let det = u + v + w;
    if (det == 0.0) {
        return miss;
    }
    let az = sh.s.z * a[sh.k.z];
    let bz = sh.s.z * b[sh.k.z];
    let cz = sh.s.z * c[sh.k.z];
    let t_scaled = u * az + v * bz + w * cz;
    // Sign-corrected comparisons instead of a division (Listing 1, no back-face culling).
    let t_signed = select(t_scaled, -t_scaled, det < 0.0);
    let det_abs = abs(det);
    if (t_signed <= 0.0 || t_signed >= t_max * det_abs) {
        return miss;
    }
    let inv = 1.0 / det;
    return vec3f(t_scaled * inv, v * inv, w * inv);
}

// Entry distance of the ray into the box, or −1 when it misses or enters at or beyond t_max.
fn ray_box_entry(origin: vec3f, inv_dir: vec3f, t_max: f32, bmin: vec3f, bmax: vec3f) -> f32 {
    let t0 = (bmin - origin) * inv_dir;
    let t1 = (bmax - origin) * inv_dir;
    let near = min(t0, t1);
    let far = max(t0, t1);
    let t_near = max(max(near.x, near.y), max(near.z, 0.0));
    let t_far = min(min(far.x, far.y), far.z) * BVH_BOX_FAR_SCALE;
    if (t_near > t_far || t_near >= t_max) {
        return -1.0;
    }
    return t_near;
}

fn bvh_safe_inverse(dir: vec3f) -> vec3f {
    let s = select(vec3f(1.0), vec3f(-1.0), dir < vec3f(0.0));
    let d = select(dir, s * BVH_DIR_MIN, abs(dir) < vec3f(BVH_DIR_MIN));
    return 1.0 / d;
}

// Closest hit with 0 < t < ray.t_max; triangle = BVH_NO_TRIANGLE on a miss.
fn bvh_closest_hit(ray: Ray) -> RayHit {
    var hit = RayHit(ray.t_max, BVH_NO_TRIANGLE, vec2f(0.0));
    let inv_dir = bvh_safe_inverse(ray.dir);
    let sh = ray_shear(ray.dir);
    let root = bvh_node(0u);
    if (ray_box_entry(ray.origin, inv_dir, hit.t, root.min, root.max) < 0.0) {
        return hit;
    }
    // Stack of (node, entry distance): entries are skipped when a closer hit was found since.
    var stack_node: array<u32, BVH_STACK_SIZE>;
    var stack_t: array<f32, BVH_STACK_SIZE>;
    var sp = 0u;
    var index = 0u;
    loop {
        let node = bvh_node(index);
        var descend = false;
        if ((node.b & BVH_LEAF) != 0u) {
            let count = node.b & ~BVH_LEAF;
            for (var i = 0u; i < count; i++) {
                let id = bvh_triangle_ids[node.a + i];
                if (id == ray.ignore) {
                    continue;
                }
                let c = 3u * id;
                let r = ray_triangle_watertight(ray.origin, sh, hit.t, triangle_corner(c), triangle_corner(c + 1u), triangle_corner(c + 2u));
                if (r.x > 0.0) {
                    hit = RayHit(r.x, id, r.yz);
                }
            }
        } else {
            // Test both children; go to the nearer, push the farther.
            let left = bvh_node(node.a);
            let right = bvh_node(node.b);
            let tl = ray_box_entry(ray.origin, inv_dir, hit.t, left.min, left.max);
            let tr = ray_box_entry(ray.origin, inv_dir, hit.t, right.min, right.max);
            if (tl >= 0.0 && tr >= 0.0) {
                let near_first = tl <= tr;
                index = select(node.b, node.a, near_first);
                stack_node[sp] = select(node.a, node.b, near_first);
                stack_t[sp] = max(tl, tr);
                sp += 1u;
                descend = true;
            } else if (tl >= 0.0) {
                index = node.a;
                descend = true;
            } else if (tr >= 0.0) {
                index = node.b;
                descend = true;
            }
        }
        if (!descend) {
            // Pop the next entry that can still hold a closer hit.
            var found = false;
            while (sp > 0u) {
                sp -= 1u;
                if (stack_t[sp] < hit.t) {
                    index = stack_node[sp];
                    found = true;
                    break;
                }
            }
            if (!found) {
                break;
            }
        }
    }
    return hit;
}

// Whether anything lies on the ray with 0 < t < ray.t_max (shadow rays): stops at the first hit.
fn bvh_any_hit(ray: Ray) -> bool {
    let inv_dir = bvh_safe_inverse(ray.dir);
    let sh = ray_shear(ray.dir);
    let root = bvh_node(0u);
    if (ray_box_entry(ray.origin, inv_dir, ray.t_max, root.min, root.max) < 0.0) {
        return false;
    }
    var stack_node: array<u32, BVH_STACK_SIZE>;
    var sp = 0u;
    var index = 0u;
    loop {
        let node = bvh_node(index);
        var descend = false;
        if ((node.b & BVH_LEAF) != 0u) {
            let count = node.b & ~BVH_LEAF;
            for (var i = 0u; i < count; i++) {
                let id = bvh_triangle_ids[node.a + i];
                if (id == ray.ignore) {
                    continue;
                }
                let c = 3u * id;
                if (ray_triangle_watertight(ray.origin, sh, ray.t_max, triangle_corner(c), triangle_corner(c + 1u), triangle_corner(c + 2u)).x > 0.0) {
                    return true;
                }
            }
        } else {
            let left = bvh_node(node.a);
            let right = bvh_node(node.b);
            let tl = ray_box_entry(ray.origin, inv_dir, ray.t_max, left.min, left.max);
            let tr = ray_box_entry(ray.origin, inv_dir, ray.t_max, right.min, right.max);
            if (tl >= 0.0 && tr >= 0.0) {
                index = node.a;
                stack_node[sp] = node.b;
                sp += 1u;
                descend = true;
            } else if (tl >= 0.0) {
                index = node.a;
                descend = true;
            } else if (tr >= 0.0) {
                index = node.b;
                descend = true;
            }
        }
        if (!descend) {
            if (sp == 0u) {
                break;
            }
            sp -= 1u;
            index = stack_node[sp];
        }
    }
    return false;
}
