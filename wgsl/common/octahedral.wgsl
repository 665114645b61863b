// Octahedral mapping of the unit sphere onto the square [−1, 1]² [Praun & Hoppe 2003,
// "Spherical parametrization and remeshing", §3; the encoding of Cigolle et al. 2014, "A Survey
// of Efficient Representations for Independent Unit Vectors", JCGT 3(2), Listing 1]: the
// direction is projected onto the octahedron |x| + |y| + |z| = 1, whose upper half unfolds onto
// the diamond |u| + |v| ≤ 1 and whose lower half folds out into the four corners. One square map
// then covers the whole sphere with texels of nearly equal solid angle (within a factor of ~2
// of each other, against ~4 for a cube face's corner against its centre), with no seams
// inside the square. Imperfect shadow maps (common/ism.wgsl) use it for every virtual light.
#include "common/math.wgsl"

// The point of [−1, 1]² for the unit direction w (w need not be exactly unit: the projection
// divides by its L1 norm, so only its direction matters).
fn octahedral_encode(w: vec3f) -> vec2f {
    let l1 = max(abs(w.x) + abs(w.y) + abs(w.z), FLT_MIN);
    let p = w.xy / l1;
    if (w.z >= 0.0) {
        return p;
    }
    // Lower hemisphere: reflect across the diamond's edge into the corner of the same quadrant.
    let folded = vec2f(1.0) - abs(p.yx);
    return vec2f(mulsign(folded.x, p.x), mulsign(folded.y, p.y));
}

// The unit direction of the point e of [−1, 1]² (the inverse of octahedral_encode), for tests
// and for texel centres.
fn octahedral_decode(e: vec2f) -> vec3f {
    var w = vec3f(e, 1.0 - abs(e.x) - abs(e.y));
    if (w.z < 0.0) {
        let unfolded = vec2f(1.0) - abs(w.yx);
        w = vec3f(mulsign(unfolded.x, w.x), mulsign(unfolded.y, w.y), w.z);
    }
    return normalize(w);
}
