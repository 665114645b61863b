// vsgl:include-only — the including shader declares `ism_atlas: array<u32>` (the maps built by
//   passes/ism.wgsl) and `ism_lookup: IsmLookup`.
//
// Visibility of a receiver from a virtual light through its imperfect shadow map [Ritschel et
// al. 2008 §3: a shadow-map test against the pull-push-filled point splats]: the receiver is lit
// where its distance to the light, less a bias, does not exceed the depth stored in its
// direction's texel. With `ism_pcf` = r > 0 a (2r+1)² percentage-closer filter [Reeves, Salesin
// & Cook 1987] returns the lit fraction of the texels around it, which softens the noisy depths.
#include "common/ism.wgsl"

struct IsmLookup {
    map_size: u32,
    words_per_map: u32,
    // Depth bias as a fraction of the receiver's distance to the light (`ism_bias`): the splats
    // and the pull-push averages stand for surfaces only up to a fraction of the distance.
    distance_bias: f32,
    // How far the receiver is moved off its surface towards the light's side, as a fraction of
    // its distance ("normal offset", Holbert 2011, "Saying Goodbye to Shadow Acne"): a few
    // texels' angular width (ISM_NORMAL_OFFSET_TEXELS in methods/visibility.rs), so that a
    // lifted point sees none of its own surface's splats nearer than itself in its texel, at
    // any incidence. A depth bias alone would have to grow with tan θ at grazing
    // incidence, and then let light through walls to receivers on the floor behind them.
    normal_offset: f32,
    // PCF window radius in texels (0: the receiver's texel alone; 1: 3×3).
    pcf_radius: i32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
}

// Lit fraction (0 … 1) of a receiver at `to_receiver` from the light (p − q: frame-relative
// positions differ only by the light's position) with normal n, in map `map`.
fn ism_visibility(map: u32, to_receiver: vec3f, n: vec3f) -> f32 {
    let distance = length(to_receiver);
    if (!(distance > 0.0)) {
        return 1.0;
    }
    // The side of the receiver's surface the light is on.
    let towards_light = select(n, -n, dot(n, to_receiver) > 0.0);
    let lifted = to_receiver + towards_light * (distance * ism_lookup.normal_offset);
    let lifted_distance = length(lifted);
    let size = ism_lookup.map_size;
    let centre = vec2i(ism_texel(lifted / lifted_distance, size));
    let tested = lifted_distance * (1.0 - ism_lookup.distance_bias);
    let base = map * ism_lookup.words_per_map;
    let last = i32(size) - 1;
    let radius = ism_lookup.pcf_radius;
    var lit = 0.0;
    for (var dy = -radius; dy <= radius; dy++) {
        for (var dx = -radius; dx <= radius; dx++) {
            // Clamped at the square's edges (the octahedral square's border folds onto itself,
            // so the clamped texel is a neighbour too, just not the mirrored one).
            let t = clamp(centre + vec2i(dx, dy), vec2i(0), vec2i(last));
            let key = ism_atlas[base + u32(t.y) * size + u32(t.x)];
            if (key == ISM_EMPTY || tested <= ism_key_depth(key)) {
                lit += 1.0;
            }
        }
    }
    let side = f32(2 * radius + 1);
    return lit / (side * side);
}
