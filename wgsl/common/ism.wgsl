// Imperfect shadow maps (ISMs) [Ritschel et al. 2008, "Imperfect Shadow Maps for Efficient
// Computation of Indirect Illumination", ACM TOG 27(5)]: the addressing and depth encoding that
// the build pass (passes/ism.wgsl) and the shading lookup (common/ism_lookup.wgsl) share.
//
// One map per virtual light, map_size² texels over the whole sphere of directions around the
// light (octahedral mapping, common/octahedral.wgsl: a VSGL's mean is not on a surface and its
// lobes point anywhere, so a hemisphere would not do; docs/methods/visibility.md). All maps live in one
// storage buffer: map m's words start at m·words_per_map; within a map, level 0 (map_size²
// texels) is followed by the coarser levels of the pull-push pyramid, each a quarter of the last.
//
// A texel holds the distance from the light to the nearest splatted point as a key that only
// grows as the distance shrinks: key = ~bits(distance). For positive finite f32 the bit pattern
// orders like the value (IEEE 754), so the inverted bits order the other way, an atomicMax of
// keys is an atomicMin of distances, and key 0 (what a cleared buffer holds; no finite distance
// has that key, since bits(d) ≤ 0x7F7FFFFF) means "no point landed here".
#include "common/octahedral.wgsl"

const ISM_EMPTY: u32 = 0u;

fn ism_depth_key(distance: f32) -> u32 {
    return ~bitcast<u32>(distance);
}

fn ism_key_depth(key: u32) -> f32 {
    return bitcast<f32>(~key);
}

// The level-0 texel of map_size² that the unit direction w (from the light) falls in.
fn ism_texel(w: vec3f, map_size: u32) -> vec2u {
    let uv = (octahedral_encode(w) * 0.5 + 0.5) * f32(map_size);
    return min(vec2u(max(uv, vec2f(0.0))), vec2u(map_size - 1u));
}
