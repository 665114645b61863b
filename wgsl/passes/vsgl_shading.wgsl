// VSGL shading (compute) [Tok15 §3.2, Eq. 5; Tok16s §4]: per pixel and VSGL, the incoming
// radiance SG of each lobe, then diffuse (cosine pulled out, or the accurate clamped-cosine
// option) and GGX specular by the SG–ASG product integral. With interleave k, the pixel at
// (x, y) evaluates only VSGLs j ≡ (y mod k)·k + (x mod k) (mod k²) and scales by k²
// [interleaved sampling, Keller & Heidrich 2001; Tok15 §5]; the denoise pass recombines them.
// A workgroup shades pixels of one interleave class (common/interleave.wgsl), so the VSGLs it
// needs are the same for all its threads and are staged through workgroup memory in tiles of
// TILE: one device-memory load serves WORKGROUP²·PIXELS_PER_THREAD pixels, and each thread
// shades PIXELS_PER_THREAD pixels of the class per tile read. Visibility is not evaluated
// (visibility = "none"), or with `visibility="raytrace"` (VISIBILITY_TRACED) by one shadow ray
// to each VSGL's shadow target (its sampled centre texel's surface point, μ for vsgl2;
// the VSGL's lobes count only where it is visible), or with `visibility="ism"`
// (VISIBILITY_ISM) by a lookup in μ's imperfect shadow map.
#include "common/constants.wgsl"
#include "common/math.wgsl"
#include "common/sg.wgsl"
#include "common/ggx.wgsl"
#include "common/vsgl.wgsl"
#include "common/vsgl_tangent_plane.wgsl"
#include "common/vsgl_record.wgsl"
#include "common/frame.wgsl"
#include "common/gbuffer.wgsl"
#include "common/plan.wgsl"
#include "common/interleave.wgsl"
#include "common/receiver.wgsl"
#include "common/light_visibility.wgsl"
#include "common/sampling.wgsl"

struct ShadeParams {
    // This dispatch shades VSGLs first … first + count − 1 (first is a multiple of k²).
    count: u32,
    interleave: u32,
    // 0 = the papers' cosine-pulled-out form with A ≈ 2π/λ, 1 = accurate clamped cosine,
    // 2 = SG product integral with the Lambert SG (the 2015 two-VSGL poster).
    diffuse_mode: u32,
    first: u32,
    // 1 (kernel="node"): a VSGL of one RSM texel (level 0) is shaded as that texel exactly —
    // its diffuse lobe as a Lambertian point emitter, I(ω) = P_d·max(ω·n_t, 0)/π — so VSGLs
    // become VPLs as N reaches the texel count and converge with them.
    exact_texels: u32,
    // 1 (diffuse "accurate" and "sg_product", and "papers" with the method's plane_fade): the
    // diffuse term fades out below each VSGL's mean tangent plane (vsgl_tangent_plane_fade);
    // 2: the receiver's glossy reflection of the diffuse lobe fades too (emitter VSGLs, whose
    // receivers on the emitter's own plane would otherwise mirror it at zero distance).
    plane_fade: u32,
    // 0 = lighting="asg": the papers' SG–ASG specular (vsgl_specular); 1 = lighting="accurate":
    // the filtered-NDF specular (vsgl_specular_accurate); 2 = lighting="blend": the two weighted
    // by the receiver's share of the filtered lobe (vsgl_specular_blend). With 1 and 2 the host
    // also selects diffuse_mode 1.
    lighting_mode: u32,
    // 1 = lambert_lobe="hemisphere": the diffuse lobes carry LAMBERT_LOBE_HEMISPHERE_GAIN;
    // 2 = "exact_compact": that, blended with the exact Lambert emission (lambert_exact_weight);
    // 0 = "papers": the sphere-normalized lobe of [Tok16s Eq. 1].
    lambert_lobe: u32,
    // Candidate texels per VSGL in `shadow_candidates` (vsgl_gen.wgsl writes them for
    // shadow_target="resampled" with ray tracing and for near_field="texels"), 0 = none.
    shadow_candidates: u32,
    // Seed of the per-(pixel, VSGL) pick among the candidates.
    seed: u32,
    // 1 (shadow_target="resampled", with VISIBILITY_TRACED and candidates): aim each shadow
    // ray at a candidate (resampled_shadow_target).
    resample_target: u32,
    // 1 (near_field="texels"): where the receiver is inside a VSGL's positional Gaussian or
    // behind its tangent plane, its diffuse light is also estimated from the candidate texels
    // one by one (near_field_texel_irradiance).
    near_field_texels: u32,
}

const WORKGROUP: u32 = 8u;
// Below this weight (a receiver in front of the plane and beyond ~7σ of the mean) the
// near-field texel estimate is not formed: there it and the SG agree, so mixing in 2% of it
// changes no corpus scene's mean or block error in the third digit (cornell_box_original's
// block error 0.179 → 0.180 against 1e-3), while the loop ran for 20× fewer pairs (lavapipe,
// a shading-bound frame — 256², N = 2048, interleave 1 — cost 1.51× → 1.31× near_field="sg"'s
// on cornell_box).
const NEAR_FIELD_WEIGHT_MIN: f32 = 2.0e-2;
const TILE: u32 = 64u; // = WORKGROUP², one VSGL loaded per thread
// Pixels each thread shades, 1 … 4 (register blocking): each VSGL the loop reads from the tile
// serves this many (pixel, VSGL) pairs, whose receivers stay in registers. Set by the host
// (crates/vsgl-core/src/passes/vsgl_shading.rs: 2 for diffuse-only variants, 1 with specular), whose dispatch size
// depends on it; a constant of each pipeline, so the unused pixels compile out.
override PIXELS_PER_THREAD: u32;

@group(0) @binding(0) var<uniform> frame: FrameUniforms;
@group(1) @binding(0) var<uniform> params: ShadeParams;
@group(1) @binding(1) var<storage, read> vsgls: array<VsglRaw>;
@group(1) @binding(2) var<storage, read> gbuf_position: array<vec4f>;
@group(1) @binding(3) var<storage, read> gbuf_normal: array<vec4f>;
@group(1) @binding(4) var<storage, read> gbuf_geo_normal: array<vec4f>;
@group(1) @binding(5) var<storage, read> gbuf_base_color: array<vec4f>;
@group(1) @binding(6) var<storage, read_write> indirect_diffuse: array<vec4f>;
@group(1) @binding(7) var<storage, read_write> indirect_specular: array<vec4f>;
// Rows 2(v·C + j) and 2(v·C + j) + 1: candidate j's point and unit normal (0: unknown) for VSGL
// v (vsgl_gen.wgsl); read only with shadow_candidates = C > 0.
@group(1) @binding(8) var<storage, read> shadow_candidates: array<vec4f>;

// The tile keeps, per VSGL, only what the shading loop reads, in arrays of 16 bytes grouped by
// the branch that reads them, so the default diffuse path reads 48 of the record's 128 bytes:
// the loop runs once per (pixel, VSGL) pair and its shared-memory reads are per pair, while the
// tile is written once per VSGL and workgroup (WORKGROUP²·PIXELS_PER_THREAD pixels), and each
// row read is shared by the PIXELS_PER_THREAD pixels of a thread. What depends on the VSGL
// alone is formed there too (store_tile_light), once instead of once per pixel.
// Positional Gaussian (μ_v, σ_v²).
var<workgroup> tile_position: array<vec4f, TILE>;
// Diffuse lobe: (axis ξ_v, sharpness λ_v) and (rgb power, amplitude over 2π, gain/(2π A(λ_v)):
// the factor of the incoming radiance's coefficient that depends on the VSGL alone).
var<workgroup> tile_diffuse_lobe: array<vec4f, TILE>;
var<workgroup> tile_diffuse_power: array<vec4f, TILE>;
// Specular lobe, read only with HAS_SPECULAR: the same, 1/(2π A(λ)).
var<workgroup> tile_specular_lobe: array<vec4f, TILE>;
var<workgroup> tile_specular_power: array<vec4f, TILE>;
// Mean tangent plane (N̄, offset), read only with plane_fade.
var<workgroup> tile_plane: array<vec4f, TILE>;
// (shadow target, level): the target is read only with visibility, the level only by the
// exact_texels path.
var<workgroup> tile_target_level: array<vec4f, TILE>;

// Writes record `v` into tile slot `slot`, with its lobes' amplitudes: the diffuse one with
// the Lambert gain params.lambert_lobe selects (vsgl_record_diffuse_lobe), the specular one
// normalized (vsgl_record_specular_lobe). Each is exp + division + a series branch
// (sg_integral) that depends on the VSGL only; the 1/(2π) of the incoming radiance's
// coefficient (vsgl_incoming_radiance_seen) is folded in here too.
fn store_tile_light(slot: u32, v: VsglRaw) {
    let gain = select(1.0, LAMBERT_LOBE_HEMISPHERE_GAIN, params.lambert_lobe != 0u);
    let lobe_d = vsgl_record_diffuse_lobe(v, gain);
    tile_position[slot] = vec4f(v.mean, v.variance);
    tile_diffuse_lobe[slot] = vec4f(lobe_d.axis, lobe_d.sharpness);
    tile_diffuse_power[slot] = vec4f(v.diffuse_power, lobe_d.amplitude / TWO_PI);
    if (HAS_SPECULAR) {
        let lobe_s = vsgl_record_specular_lobe(v);
        tile_specular_lobe[slot] = vec4f(lobe_s.axis, lobe_s.sharpness);
        tile_specular_power[slot] = vec4f(v.specular_power, lobe_s.amplitude / TWO_PI);
    }
    tile_plane[slot] = vec4f(v.plane_normal, v.plane_offset);
    tile_target_level[slot] = vec4f(v.shadow_target, v.level);
}

// Irradiance over power at p (normal n) from a Lambertian patch at `mean` facing `axis` whose
// positional variance is σ²: the texel's radiant intensity per unit power max(−ω·axis, 0)/π
// times max(n·ω, 0)/d², with d² + 2σ² in place of d², which on the axis of a Lambertian disk of
// radius r (r² = 2σ²) is exact, Φ/(π(d² + r²)), and bounds the 1/d² spike at contacts. With
// σ² = 0 it is vpl_radiance's Lambert term (common/vpl.wgsl) without the GGX lobes, which the
// callers here do not need (the receiver's specular takes the texel's SG, see the node path).
fn lambert_patch_irradiance(mean: vec3f, axis: vec3f, variance: f32, p: vec3f, n: vec3f) -> f32 {
    let to_light = mean - p;
    let center_dist2 = dot(to_light, to_light);
    let dist2 = max(center_dist2 + 2.0 * variance, FLT_MIN);
    let l = to_light * inverseSqrt(max(center_dist2, FLT_MIN));
    return max(dot(-l, axis), 0.0) * INV_PI * max(dot(n, l), 0.0) / dist2;
}

// Weight of the exact Lambertian emission against the cluster's SG (lambert_lobe=
// "exact_compact": exact lobes as clusters shrink). The Lambert SG's shape
// differs from max(cos, 0)/π by ε = LAMBERT_LOBE_SG_SHAPE_ERROR (relative RMS over the
// hemisphere) however small the cluster, while treating the cluster as one patch at μ errs by
// about σ²/d²: equal where σ²/d² = ε, so w = ε·d²/(ε·d² + σ²) trusts the exact form where the
// cluster is compact as seen from p and the SG where it is extended. The default since
// 2026-12-01 (closer to the reference on every corpus scene and built-in); it loses to the SG
// alone where a floor cluster lights a wall at grazing angles (docs/methods/vsgl.md, "Lambert
// lobes").
fn lambert_exact_weight(mean: vec3f, variance: f32, p: vec3f) -> f32 {
    let to_light = mean - p;
    let scaled = LAMBERT_LOBE_SG_SHAPE_ERROR * dot(to_light, to_light);
    return scaled / max(scaled + variance, FLT_MIN);
}

fn diffuse_over_rd(radiance: Sg, n: vec3f) -> f32 {
    if (params.diffuse_mode == 1u) {
        return vsgl_diffuse_accurate(radiance, n);
    }
    if (params.diffuse_mode == 2u) {
        return vsgl_diffuse_sg_product(radiance, n);
    }
    return vsgl_diffuse_approx(radiance, n);
}

// The incoming radiance of a lobe (vsgl_incoming_radiance_seen) and the specular form
// (vsgl_specular_with_receiver) are those of common/vsgl.wgsl, in their split form: the
// positional Gaussian seen from p (vsgl_position_seen_from) is formed once per (pixel, VSGL)
// pair and serves both lobes, and the receiver's ASG, n·ω_o and Λ(ω_o)
// (vsgl_specular_receiver_from) once per pixel.

fn specular_over_rs(radiance: Sg, r: VsglSpecularReceiver) -> f32 {
    if (params.lighting_mode == 1u) {
        return vsgl_specular_accurate(radiance, r.n, r.w_o, r.alpha);
    }
    if (params.lighting_mode == 2u) {
        return vsgl_specular_blend_with_receiver(radiance, r);
    }
    return vsgl_specular_with_receiver(radiance, r);
}

// The workgroup's footprint in pixels of its class: PIXELS_PER_THREAD blocks of WORKGROUP²
// pixels side by side along x (crates/vsgl-core/src/passes/vsgl_shading.rs dispatches by it).
fn block_footprint() -> vec2u {
    return vec2u(WORKGROUP * PIXELS_PER_THREAD, WORKGROUP);
}

// One of a thread's pixels: what the loop reads of its receiver, kept in registers through the
// whole loop, and its sums. rd and rs are read again after the loop (write_block_pixel) instead.
struct BlockPixel {
    index: u32,
    has_surface: bool,
    p: vec3f,
    n: vec3f,
    shadowing: ShadowReceiver,
    specular_receiver: VsglSpecularReceiver,
    diffuse: vec3f,
    specular: vec3f,
}

// Pixel `slot` of thread `lid`: its pixel in block `slot` of the footprint, so for each slot
// the threads of a row read neighbouring G-buffer texels (at interleave 1).
fn block_pixel(wg: vec3u, lid: vec3u, slot: u32) -> BlockPixel {
    let k = params.interleave;
    let ip = interleaved_block_pixel(wg, vec2u(lid.x + slot * WORKGROUP, lid.y), frame.size, k, block_footprint());
    let inside = ip.pixel.x < frame.size.x && ip.pixel.y < frame.size.y;
    let index = ip.pixel.y * frame.size.x + ip.pixel.x;
    var rcv = no_receiver();
    if (inside) {
        rcv = receiver_from_gbuffer(gbuf_position[index], gbuf_normal[index], gbuf_geo_normal[index], gbuf_base_color[index]);
    }
    var geo_normal = vec3f(0.0, 0.0, 1.0);
    if (VISIBILITY_TRACED && rcv.has_surface) {
        geo_normal = gbuf_geo_normal[index].xyz;
    }
    var px: BlockPixel;
    px.index = index;
    px.has_surface = rcv.has_surface;
    px.p = rcv.p;
    px.n = rcv.n;
    px.shadowing = shadow_receiver(rcv.has_surface, geo_normal, ip.pixel);
    if (HAS_SPECULAR && rcv.has_surface) {
        px.specular_receiver = vsgl_specular_receiver_from(rcv.n, rcv.v, rcv.alpha);
    }
    px.diffuse = vec3f(0.0);
    px.specular = vec3f(0.0);
    return px;
}

// One VSGL of the tile as shade_pair reads it: read from workgroup memory once for all of a
// thread's pixels. Rows that this variant or this VSGL never reads are not read (left 0).
struct TileLight {
    // Its index in the VSGL buffer (its imperfect shadow map).
    index: u32,
    position: VsglPosition,
    diffuse_lobe: vec4f,
    diffuse_power_amplitude: vec4f,
    specular_lobe: vec4f,
    specular_power_amplitude: vec4f,
    plane: vec4f,
    target_level: vec4f,
}

fn tile_light(t: u32, index: u32) -> TileLight {
    var light: TileLight;
    light.index = index;
    let pos = tile_position[t];
    light.position = VsglPosition(pos.xyz, pos.w);
    light.diffuse_power_amplitude = tile_diffuse_power[t];
    light.diffuse_lobe = tile_diffuse_lobe[t];
    if (VISIBILITY_TRACED || params.exact_texels == 1u) {
        light.target_level = tile_target_level[t];
    }
    if (params.plane_fade >= 1u) {
        light.plane = tile_plane[t];
    }
    // Without specular materials no record has specular power (and R_s = 0 here).
    if (HAS_SPECULAR) {
        light.specular_power_amplitude = tile_specular_power[t];
        if (any(light.specular_power_amplitude.xyz > vec3f(0.0))) {
            light.specular_lobe = tile_specular_lobe[t];
        }
    }
    return light;
}

// shadow_target="resampled" (experiments/corpus_shadow_targets_and_bounds.md, "Which texel the shadow ray aims at"): one of
// VSGL v's candidate texels (drawn ∝ the sampling density, vsgl_gen.wgsl) kept with
// probability ∝ its geometric term at the receiver, max(−ω·n_y, 0)·max(ω·n, 0)/d² (resampled
// importance sampling [Talbot et al. 2005]): as the candidates grow the pick follows each
// texel's share of the cluster's light at p, so one ray's expected visibility tends to the
// cluster's light-weighted visibility there. A power-drawn target misses that the near, facing
// texels that light p are the ones p sees. `fallback` where no candidate faces p.
fn resampled_shadow_target(v: u32, pixel: u32, p: vec3f, n: vec3f, fallback: vec3f) -> vec3f {
    let c = params.shadow_candidates;
    var total = 0.0;
    var chosen = fallback;
    // One uniform number per (pixel, VSGL), consumed by reservoir sampling of the candidates.
    var state = rng_init(pixel, v, params.seed ^ 0x27d4eb2fu);
    var u = rng_uniform(&state);
    for (var j = 0u; j < c; j++) {
        let y = shadow_candidates[2u * (v * c + j)].xyz;
        let normal = shadow_candidates[2u * (v * c + j) + 1u].xyz;
        let to = y - p;
        let d2 = dot(to, to);
        let inv_d = inverseSqrt(max(d2, FLT_MIN));
        var emitter = 1.0;
        if (any(normal != vec3f(0.0))) {
            emitter = max(-dot(to, normal) * inv_d, 0.0);
        }
        let g = emitter * max(dot(to, n) * inv_d, 0.0) / max(d2, FLT_MIN);
        if (!(g > 0.0)) {
            continue;
        }
        total += g;
        // Keep candidate j with probability g/total; u is rescaled within the branch taken so
        // that one number serves every step.
        let keep = g / total;
        if (u < keep) {
            chosen = y;
            u = u / keep;
        } else {
            u = (u - keep) / (1.0 - keep);
        }
        u = min(u, 0.99999994);
    }
    return chosen;
}

// near_field="texels": the irradiance over power at p (normal n) from VSGL v's candidate texels
// as patches of their footprints (lambert_patch_irradiance, each with its own normal), their
// mean weighted by each one's diffuse power over the density it was drawn by: a C-sample
// estimate of the cluster's texels shaded one by one, which is what the Gaussian of [Tok15
// Eq. 5] stands for only when p is far from it and in front of it. `axis`: the normal of a
// candidate whose normal is unknown.
fn near_field_texel_irradiance(v: u32, p: vec3f, n: vec3f, axis: vec3f) -> f32 {
    let c = params.shadow_candidates;
    var sum = 0.0;
    var weight = 0.0;
    for (var j = 0u; j < c; j++) {
        let point = shadow_candidates[2u * (v * c + j)];
        let normal_share = shadow_candidates[2u * (v * c + j) + 1u];
        var normal = normal_share.xyz;
        if (all(normal == vec3f(0.0))) {
            normal = axis;
        }
        // Faded below the texel's own tangent plane as a cluster's light is below its mean
        // one (vsgl_tangent_plane_fade): a receiver on the plane of a lone lit quad otherwise
        // got 4e-8 of a pixel from rounding in the emitter's cosine.
        let fade = vsgl_tangent_plane_fade(VsglTangentPlane(normal, 0.0), VsglPosition(point.xyz, point.w), p);
        sum += normal_share.w * fade * lambert_patch_irradiance(point.xyz, normal, point.w, p, n);
        weight += normal_share.w;
    }
    return select(0.0, sum / weight, weight > 0.0);
}

// Adds one VSGL's light to one pixel's sums: the pair (pixel, VSGL) of the inner loop.
fn shade_pair(px: ptr<function, BlockPixel>, light: TileLight) {
    if (!(*px).has_surface) {
        return;
    }
    let p = (*px).p;
    let n = (*px).n;
    let position = light.position;
    let diffuse_power_amplitude = light.diffuse_power_amplitude;
    var diffuse_power = diffuse_power_amplitude.xyz;
    var lit = 1.0;
    if (VISIBILITY_TRACED || VISIBILITY_ISM) {
        // V(x_p, μ_v) of Tok15 Eq. 3: a shadow ray to the VSGL's shadow target (its
        // centre texel's surface point; μ for vsgl2), or the lit fraction of μ's
        // imperfect shadow map; it scales both lobes' powers.
        var shadow_target = position.mean;
        if (VISIBILITY_TRACED) {
            shadow_target = light.target_level.xyz;
            if (params.resample_target == 1u && params.shadow_candidates > 0u) {
                shadow_target = resampled_shadow_target(light.index, (*px).index, p, n, shadow_target);
            }
        }
        lit = light_visibility(p, n, (*px).shadowing, light.index, shadow_target);
        if (lit <= 0.0) {
            return;
        }
        diffuse_power *= lit;
    }
    // Texels reflect only into their own hemisphere, so nothing reaches p from below
    // the cluster's tangent plane. The diffuse forms that integrate the incoming lobe
    // over the receiver's hemisphere ("accurate", "sg_product") always need the fade;
    // the papers' form takes it with plane_fade (vsgl's default: its product axis tips
    // over the horizon of a receiver behind the cluster's plane). The specular ASG form
    // vanishes there already and is left as it is.
    var fade = 1.0;
    if (params.plane_fade >= 1u) {
        let plane = light.plane;
        fade = vsgl_tangent_plane_fade(VsglTangentPlane(plane.xyz, plane.w), position, p);
    }
    let seen = vsgl_position_seen_from(position, p);
    // Each lobe: radiance SG per unit power (amplitude 1/A(λ)), times its rgb
    // power. A lobe without power (vsgl2's records carry one lobe each; metal
    // clusters have no diffuse lobe) is skipped: it would add exactly 0.
    let has_diffuse = any(diffuse_power > vec3f(0.0));
    let lobe_d4 = light.diffuse_lobe;
    if (params.exact_texels == 1u && has_diffuse && light.target_level.w == 0.0) {
        // The texel is a patch, not a point: its positional
        // variance σ² is its footprint (vsgl_moments.wgsl).
        let texel_irradiance = lambert_patch_irradiance(position.mean, lobe_d4.xyz, position.variance, p, n);
        (*px).diffuse += diffuse_power * (texel_irradiance * INV_PI);
        if (HAS_SPECULAR) {
            // The receiver's specular keeps the texel's SG with its footprint (as
            // "exact_compact" does): a point emitter in a sharp GGX lobe is a spike
            // wherever it sits in the mirror direction. Measured on an H200 at 256²
            // (experiments/vsgl_vs_pathtracer_h200.md): node VSGLs at
            // N = 16384 gave 22.97 on caustics_ring and 0.97 on mirror_panel against
            // 0.59 and 0.10 at N = 4096, all of it in indirect_specular.
            let in_d = vsgl_incoming_radiance_seen(lobe_d4.xyz, lobe_d4.w, diffuse_power_amplitude.w, seen);
            (*px).specular += diffuse_power * specular_over_rs(in_d, (*px).specular_receiver);
        }
    } else if (has_diffuse) {
        let in_d = vsgl_incoming_radiance_seen(lobe_d4.xyz, lobe_d4.w, diffuse_power_amplitude.w, seen);
        var from_diffuse_lobe = fade * diffuse_over_rd(in_d, n);
        if (params.lambert_lobe == 2u) {
            // The receiver's specular keeps the SG: a point emitter would put a
            // spike into every glossy receiver.
            let w = lambert_exact_weight(position.mean, position.variance, p);
            // A point emitter (σ² = 0): the weight leaves the near field to the SG,
            // and d² + 2σ² would bias it low off its axis (measured: cornell_box
            // 0.061 → 0.050 at N = 4096, lit_floor_corner 0.211 → 0.186).
            // Faded like the SG: on or below the cluster's tangent plane the point's own
            // cosine is rounding noise (a lone plane lit its back by 1e-8 without it).
            let exact = fade * lambert_patch_irradiance(position.mean, lobe_d4.xyz, 0.0, p, n) * INV_PI;
            from_diffuse_lobe = mix(from_diffuse_lobe, exact, w);
        }
        if (params.near_field_texels == 1u) {
            // Inside the Gaussian (d² ≲ σ²) the SG of Eq. 5 no longer describes where the
            // light comes from, and behind the mean tangent plane the fade removes the light
            // of the cluster's texels that do face p: there its texels are taken one by one.
            let to_mean = position.mean - p;
            let d2 = dot(to_mean, to_mean);
            let near = position.variance / max(position.variance + d2, FLT_MIN);
            let w_texels = max(near, 1.0 - fade);
            if (w_texels > NEAR_FIELD_WEIGHT_MIN && params.shadow_candidates > 0u) {
                let texels = near_field_texel_irradiance(light.index, p, n, lobe_d4.xyz) * INV_PI;
                from_diffuse_lobe = mix(from_diffuse_lobe, texels, w_texels);
            }
        }
        (*px).diffuse += diffuse_power * from_diffuse_lobe;
        if (HAS_SPECULAR) {
            let glossy_fade = select(1.0, fade, params.plane_fade == 2u);
            (*px).specular += diffuse_power * (glossy_fade * specular_over_rs(in_d, (*px).specular_receiver));
        }
    }
    if (HAS_SPECULAR) {
        let specular_power_amplitude = light.specular_power_amplitude;
        let specular_power = specular_power_amplitude.xyz * lit;
        if (any(specular_power > vec3f(0.0))) {
            let lobe_s4 = light.specular_lobe;
            let in_s = vsgl_incoming_radiance_seen(lobe_s4.xyz, lobe_s4.w, specular_power_amplitude.w, seen);
            (*px).diffuse += specular_power * (fade * diffuse_over_rd(in_s, n));
            (*px).specular += specular_power * specular_over_rs(in_s, (*px).specular_receiver);
        }
    }
}

// Adds a pixel's sums, times its reflectances and the interleave's k², to the targets.
fn write_block_pixel(px: BlockPixel, stride: u32) {
    if (!px.has_surface) {
        return;
    }
    let rcv = receiver_from_gbuffer(gbuf_position[px.index], gbuf_normal[px.index], gbuf_geo_normal[px.index], gbuf_base_color[px.index]);
    let scale = f32(stride);
    indirect_diffuse[px.index] += vec4f(min(rcv.rd * px.diffuse * scale, vec3f(FLT_MAX)), 0.0);
    if (HAS_SPECULAR) {
        indirect_specular[px.index] += vec4f(min(rcv.rs * px.specular * scale, vec3f(FLT_MAX)), 0.0);
    }
}

@compute @workgroup_size(WORKGROUP, WORKGROUP, 1)
fn main(@builtin(workgroup_id) wg: vec3u, @builtin(local_invocation_id) lid: vec3u, @builtin(local_invocation_index) local: u32) {
    let k = params.interleave;
    let stride = k * k;
    // The thread's pixels. Those past PIXELS_PER_THREAD stay zero (no surface) and, like every
    // branch on the override, compile out.
    var pixel0 = block_pixel(wg, lid, 0u);
    var pixel1: BlockPixel;
    var pixel2: BlockPixel;
    var pixel3: BlockPixel;
    if (PIXELS_PER_THREAD > 1u) {
        pixel1 = block_pixel(wg, lid, 1u);
    }
    if (PIXELS_PER_THREAD > 2u) {
        pixel2 = block_pixel(wg, lid, 2u);
    }
    if (PIXELS_PER_THREAD > 3u) {
        pixel3 = block_pixel(wg, lid, 3u);
    }
    let any_surface = pixel0.has_surface || pixel1.has_surface || pixel2.has_surface || pixel3.has_surface;
    // All of the workgroup's pixels are of one class. Its VSGLs are params.first + class_index
    // + m·k², m = 0 … class_count − 1.
    let class_index = interleaved_block_pixel(wg, lid.xy, frame.size, k, block_footprint()).class_index;
    let class_first = params.first + class_index;
    let class_count = class_light_count(class_index, params.count, k);
    // Every thread takes part in the tile loads and barriers, with a surface or not.
    for (var tile_start = 0u; tile_start < class_count; tile_start += TILE) {
        let m = tile_start + local;
        if (m < class_count) {
            store_tile_light(local, vsgls[class_first + m * stride]);
        }
        workgroupBarrier();
        let n_tile = min(TILE, class_count - tile_start);
        if (any_surface) {
            // Each pixel sums the same VSGLs in the same order as with one pixel per thread.
            for (var t = 0u; t < n_tile; t++) {
                let light = tile_light(t, class_first + (tile_start + t) * stride);
                shade_pair(&pixel0, light);
                if (PIXELS_PER_THREAD > 1u) {
                    shade_pair(&pixel1, light);
                }
                if (PIXELS_PER_THREAD > 2u) {
                    shade_pair(&pixel2, light);
                }
                if (PIXELS_PER_THREAD > 3u) {
                    shade_pair(&pixel3, light);
                }
            }
        }
        workgroupBarrier();
    }
    write_block_pixel(pixel0, stride);
    write_block_pixel(pixel1, stride);
    write_block_pixel(pixel2, stride);
    write_block_pixel(pixel3, stride);
}
