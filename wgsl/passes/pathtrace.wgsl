// Path-traced one-bounce ground truth (compute). From each pixel's G-buffer point p, directions
// are sampled by the BRDF, the bounce point x is found by ray tracing the BVH, and x's direct
// light from every light (shadow ray) is reflected at x and then at p:
//   L_ind(p, v) = ∫ f_p(l, v) ⟨n_p, l⟩ L_o(x(l), −l) dl,
//   L_o(x, ω) = Σ_lights f_x(l_x, ω) ⟨n_x, l_x⟩ e(x) V(x, light), e = I·color·cone(l_x)/d²
//   (spot; cone = 1 for a point light) or E·color (directional),
// the quantity the VPL `reference` discretizes (common/vpl.wgsl), with exact visibility.
//
// Estimator (one-sample MIS over the two lobes [Veach 1997, §9.2.4], i.e. sampling the mixture):
// choose the specular lobe with probability c_s = ΣRs / (ΣRd + ΣRs), else the diffuse lobe;
// sample l from that lobe (GGX VNDF or cosine); weigh by the mixture pdf
//   p(l) = (1 − c_s) cosθ/π + c_s G1(v) D(h) / (4 n·v)
// so each sample F = f(l, v) ⟨n, l⟩ L_o / p(l) is unbiased whichever lobe drew it. The diffuse
// and specular parts of F (f = Rd/π + Rs·f_GGX) are accumulated separately for the
// indirect_diffuse / indirect_specular AOVs; their sum's sample variance gives the error.
//
// Accumulation is progressive: each dispatch adds `batch_samples` samples per pixel. A thread
// keeps a running mean and M2 in registers (Welford 1962) and merges them into the stored ones
// with Chan, Golub & LeVeque 1979 (the pairwise update), so the variance never comes from
// E[x²] − E[x]², which cancels (docs/numerics.md).
//
// Bidirectional mode (`strategy="bidirectional"`, STRATEGY_BIDIRECTIONAL) adds a second strategy
// for the same paths, light tracing: photons leave a light (sampled by power, then uniformly
// over its cone or sphere, or over a disk covering the scene for a directional light), hit x,
// are reflected once by sampling x's BRDF, hit y, and are connected to the eye and splatted into
// y's pixel [Veach 1997, ch. 10: bidirectional path tracing's light-to-eye strategy]. `strategy=
// "light"` (STRATEGY_LIGHT) keeps light tracing alone, a check on the others. Light tracing finds spot → near-mirror → diffuse paths (caustics) that camera
// paths reach only by chance. Splatted paths land anywhere in a pixel, so in this mode both
// strategies estimate the radiance averaged over the pixel's area (camera rays are jittered
// over the pixel) and are combined with the balance heuristic [Veach 1997, §9.2], with
// W·H photons per camera sample:
//   w_light = N_L p_light / (N_L p_light + N_cam p_cam),   w_cam = 1 − w_light,
// p_* the densities of the path's two free vertices (x, y) per unit area under each strategy
// (mis_light_weight). The light part is accumulated per batch and its variance taken over
// batches (light_fold); `resolve` adds it to the camera part. The `direct` AOV stays the
// pixel-centre value in both modes.
//
// Emissive triangles are area lights (HAS_EMITTERS; upload/emitters.rs builds their table): a
// one-sided Lambertian emitter of radiance L_e on the side its vertex normals point to. Each
// shading point takes one emitter sample per path sample, drawn by power and then uniformly
// over the triangle's area (density p_z = p_i / A_i), with a shadow ray:
//   L ≈ f(l, v) ⟨n, l⟩ L_e(z) cos_z / |z − p|² / p_z          (next-event estimation)
// [Veach 1997, §9.1 / Pharr et al., "Sampling light sources": the area form of the rendering
// equation]. Each shading point also traces one ray drawn from its BSDF and counts the emitter
// it hits, f ⟨n, l⟩ L_e / p_bsdf; the two camera strategies are combined by the power
// heuristic over z's density per unit area, p_z against p_bsdf cos_z / |z − p|² [Veach 1997,
// §9.2.3] (emitter_camera_weight): next-event estimation wins on rough surfaces and large
// emitters, BSDF sampling in glossy lobes narrower than the emitter's solid angle. At the
// bounce point x this is the emitters' share of L_o(x) above; at the pixel centre it is their
// direct light, whose running mean (emitted_direct) `resolve` adds to the `direct` AOV.
// Photons leave emitters too, drawn by power among all lights, from a uniform point, in a
// cosine-distributed direction, so light tracing and its MIS weights cover them (the camera
// side's density of z then sums both camera strategies').
//
// Entry points: `indirect` (one batch), `direct` (the pixel's direct light with shadow rays, for
// the `direct` AOV of this method), `light_paths` and `light_fold` (bidirectional: one batch of
// photons, folded into the light part) and `resolve` (standard error of the mean, per channel).
#include "common/constants.wgsl"
#include "common/frame.wgsl"
#include "common/gbuffer.wgsl"
#include "common/ggx.wgsl"
#include "common/math.wgsl"
#include "common/sampling.wgsl"
#include "common/bvh.wgsl"
#include "common/material_eval.wgsl"
#include "common/scene_vertices.wgsl"

const WORKGROUP: u32 = 8u;
const STRATEGY_CAMERA: u32 = 0u;
const STRATEGY_BIDIRECTIONAL: u32 = 1u;
const STRATEGY_LIGHT: u32 = 2u;
// Ray origins are moved off their surface along the geometric normal by this fraction of the
// point's coordinate magnitude (relative to the frame origin, where f32 rounding is ~6e-8 of
// it): about 170 ulps, and never less than RAY_OFFSET_RELATIVE × RAY_OFFSET_EXTENT_FRACTION of
// the scene's size. The surface's own triangle is also skipped, so the offset only has to
// clear rounding on neighbouring triangles. No fixed world length (docs/frames.md, "Precision far from the origin").
const RAY_OFFSET_RELATIVE: f32 = 1.0e-5;
const RAY_OFFSET_EXTENT_FRACTION: f32 = 1.0e-2;
// Bounce rays end after this many scene diagonals (every scene point lies within one).
const RAY_T_MAX_EXTENTS: f32 = 4.0;

struct PathParams {
    seed: u32,
    // Samples per pixel accumulated before this dispatch (for `resolve`: all of them).
    sample_offset: u32,
    batch_samples: u32,
    // STRATEGY_BIDIRECTIONAL: camera and light strategies combined by MIS over pixel areas;
    // STRATEGY_LIGHT: light tracing alone; STRATEGY_CAMERA (0): camera paths only, from the
    // pixel centre's G-buffer point.
    strategy: u32,
    // The upload's emissive triangles and their total power π Σ A_i (L_r + L_g + L_b).
    emitter_count: u32,
    emitter_power: f32,
}

@group(0) @binding(0) var<uniform> frame: FrameUniforms;
@group(0) @binding(1) var<uniform> params: PathParams;
@group(0) @binding(2) var<storage, read> bvh_nodes: array<BvhNode>;
@group(0) @binding(3) var<storage, read> bvh_triangle_ids: array<u32>;
@group(0) @binding(4) var<storage, read> vertices: array<VertexRaw>;
@group(0) @binding(5) var<storage, read> indices: array<u32>;
@group(0) @binding(6) var<storage, read> triangle_materials: array<u32>;
@group(0) @binding(7) var<storage, read> materials: array<MaterialRaw>;
@group(0) @binding(8) var<storage, read> lights: array<LightRaw>;
@group(0) @binding(9) var<storage, read> gbuf_position: array<vec4f>;
@group(0) @binding(10) var<storage, read> gbuf_normal: array<vec4f>;
@group(0) @binding(11) var<storage, read> gbuf_geo_normal: array<vec4f>;
@group(0) @binding(12) var<storage, read> gbuf_base_color: array<vec4f>;
// The visibility pass's triangle ids (id + 1; 0 = background): the pixel's own triangle.
@group(0) @binding(13) var visibility: texture_2d<u32>;
@group(0) @binding(14) var color_textures: texture_2d_array<f32>;
@group(0) @binding(15) var data_textures: texture_2d_array<f32>;
@group(0) @binding(16) var texture_sampler: sampler;
// Running means of the diffuse and specular parts (rgb), and M2 of their sum (rgb).
@group(0) @binding(17) var<storage, read_write> indirect_diffuse: array<vec4f>;
@group(0) @binding(18) var<storage, read_write> indirect_specular: array<vec4f>;
@group(0) @binding(19) var<storage, read_write> indirect_m2: array<vec4f>;
@group(0) @binding(20) var<storage, read_write> direct_out: array<vec4f>;
@group(0) @binding(21) var<storage, read_write> stderr_out: array<vec4f>;
// Bidirectional mode: this batch's light-tracing splats, f32 bits added atomically (diffuse
// rgb, specular rgb, 2 unused per pixel); the light part's running means over batches (diffuse
// rgb + batch count in w, specular rgb), and its weighted M2 (rgb) and total weight (w).
// (float_sums: the name common/atomic_float.wgsl adds into.)
@group(0) @binding(22) var<storage, read_write> float_sums: array<atomic<u32>>;
@group(0) @binding(23) var<storage, read_write> light_mean: array<vec4f>;
@group(0) @binding(24) var<storage, read_write> light_m2: array<vec4f>;
// The emitter table (upload/emitters.rs) and the running mean of the emitters' direct light at
// each pixel centre (rgb).
@group(0) @binding(25) var<storage, read> emitters: array<EmitterRaw>;
@group(0) @binding(26) var<storage, read_write> emitted_direct: array<vec4f>;
// The upload's raster vertices: the BVH's triangle corners (common/bvh.wgsl).
@group(0) @binding(27) var<storage, read> triangle_corners: array<TriangleCorner>;
// The other pages of the arrays that may outgrow one binding (common/bvh.wgsl,
// common/scene_vertices.wgsl).
@group(0) @binding(28) var<storage, read> bvh_nodes_1: array<BvhNode>;
@group(0) @binding(29) var<storage, read> bvh_nodes_2: array<BvhNode>;
@group(0) @binding(30) var<storage, read> bvh_nodes_3: array<BvhNode>;
@group(0) @binding(31) var<storage, read> triangle_corners_1: array<TriangleCorner>;
@group(0) @binding(32) var<storage, read> triangle_corners_2: array<TriangleCorner>;
@group(0) @binding(33) var<storage, read> triangle_corners_3: array<TriangleCorner>;
@group(0) @binding(34) var<storage, read> vertices_1: array<VertexRaw>;
@group(0) @binding(35) var<storage, read> vertices_2: array<VertexRaw>;
@group(0) @binding(36) var<storage, read> vertices_3: array<VertexRaw>;

// Whether the upload has emissive triangles: without, no emitter code runs and no random number
// is drawn for them, so a scene without emission renders as before emitters existed.
override HAS_EMITTERS: bool = true;

struct EmitterRaw {
    triangle: u32,
    area: f32,
    // Σ probability up to and including this row (the last is 1).
    cdf: f32,
    // Φ_i / ΣΦ.
    probability: f32,
}

// What shading needs at a surface point.
struct Surface {
    position: vec3f,
    // Geometric normal, facing the side the point is seen from.
    ng: vec3f,
    // Shading normal on the same side.
    ns: vec3f,
    rd: vec3f,
    rs: vec3f,
    alpha: f32,
    triangle: u32,
}

// Shading happens in frame space (relative to the eye, like the G-buffer and the lights); the
// BVH and the vertex buffer are relative to the scene upload's anchor, which lies at
// frame.view_origin (the eye's offset from the anchor) subtracted: a ray enters scene space
// through to_scene, a hit comes back through the vertices minus view_origin.
fn to_scene(p: vec3f) -> vec3f {
    return p + frame.view_origin.xyz;
}

fn max_abs(p: vec3f) -> f32 {
    return max(max(abs(p.x), abs(p.y)), abs(p.z));
}

// Clears the rounding of the point in both spaces it is used in.
fn ray_offset(p: vec3f) -> f32 {
    let m = max(max_abs(p), max_abs(to_scene(p)));
    return RAY_OFFSET_RELATIVE * max(m, RAY_OFFSET_EXTENT_FRACTION * frame.scene_extent);
}

// The camera side of a bidirectional path's MIS weight, known when its bounce point x is shaded.
struct CameraMis {
    enabled: bool,
    // Camera strategy's density of the path's free vertices (y, x) per unit area, less the
    // factors both strategies share (see mis_light_weight).
    p_cam: f32,
    // cos_g at y towards x (a factor of the light strategy's density of y).
    cos_gy_x: f32,
}

const NO_MIS = CameraMis(false, 0.0, 0.0);

// Pdf (solid angle) of the lobe-mixture sampling of `indirect` and `light_paths` at s for the
// direction l given the other direction v: (1 − c_s) cosθ/π + c_s G1(v) D(h)/(4 n·v).
fn bsdf_pdf(s: Surface, l: vec3f, v: vec3f) -> f32 {
    let weight_d = s.rd.r + s.rd.g + s.rd.b;
    let weight_s = s.rs.r + s.rs.g + s.rs.b;
    let c_s = select(0.0, weight_s / (weight_d + weight_s), weight_d + weight_s > 0.0);
    return (1.0 - c_s) * cosine_hemisphere_pdf(dot(s.ns, l)) + c_s * ggx_vndf_reflection_pdf(s.ns, v, l, s.alpha);
}

// Draws a direction from the same mixture about s.ns for the other direction v (local frame).
fn sample_bsdf(s: Surface, v: vec3f, u_lobe: f32, u1: f32, u2: f32) -> vec3f {
    let weight_d = s.rd.r + s.rd.g + s.rd.b;
    let weight_s = s.rs.r + s.rs.g + s.rs.b;
    let c_s = select(0.0, weight_s / (weight_d + weight_s), weight_d + weight_s > 0.0);
    let basis = orthonormal_basis(s.ns);
    let v_local = v * basis;
    var l_local: vec3f;
    if (u_lobe < c_s) {
        let h = sample_ggx_vndf(v_local, s.alpha, u1, u2);
        l_local = 2.0 * dot(v_local, h) * h - v_local;
    } else {
        l_local = sample_cosine_hemisphere(u1, u2);
    }
    return safe_normalize(basis * l_local, s.ns);
}

// Radius of the disk a directional light's photons start from: it covers the sphere around the
// scene's bounds (half the diagonal) with the shadow map's 1% margin.
fn directional_disk_radius() -> f32 {
    return 0.505 * frame.scene_extent;
}

// Power a light sends out (rgb summed): what photons are drawn by. Spot: I·2π(1 − cos θ_outer)
// (the cone's falloff is applied per photon, so this bounds it); point: 4π I; directional:
// E times the photon disk's area.
fn light_power(light: LightRaw) -> f32 {
    let c = light.color.r + light.color.g + light.color.b;
    if (light.kind == LIGHT_KIND_DIRECTIONAL) {
        let r = directional_disk_radius();
        return light.intensity * c * PI * r * r;
    }
    if (light.kind == LIGHT_KIND_SPOT) {
        return light.intensity * c * TWO_PI * (1.0 - light.cos_outer);
    }
    return light.intensity * c * 2.0 * TWO_PI;
}

// Σ light_power over the frame's lights: photons pick light i with light_power(i) / this.
fn total_light_power() -> f32 {
    var total = 0.0;
    for (var k = 0u; k < frame.light_count; k++) {
        total += light_power(lights[k]);
    }
    return total;
}

// What photons are drawn from: the lights' power and the emitters' (HAS_EMITTERS).
fn photon_power_total() -> f32 {
    var total = total_light_power();
    if (HAS_EMITTERS) {
        total += params.emitter_power;
    }
    return total;
}

// The emitter row whose cdf interval holds u ∈ [0, 1) (binary search: the first cdf > u).
fn pick_emitter(u: f32) -> u32 {
    var lo = 0u;
    var hi = params.emitter_count - 1u;
    while (lo < hi) {
        let mid = (lo + hi) / 2u;
        if (u < emitters[mid].cdf) {
            hi = mid;
        } else {
            lo = mid + 1u;
        }
    }
    return lo;
}

// A point drawn on the emitters: its emitting side's normal, its radiance and its density
// per unit area over all emitters (pick probability / area).
struct EmitterPoint {
    position: vec3f,
    normal: vec3f,
    radiance: vec3f,
    pdf_area: f32,
    triangle: u32,
}

// Draws an emitter by power with u_pick, then a point uniformly over its triangle with
// (u1, u2): barycentrics (1 − √u1, √u1 (1 − u2), √u1 u2) [Pharr et al., "Sampling a triangle"].
fn sample_emitter(u_pick: f32, u1: f32, u2: f32) -> EmitterPoint {
    let e = emitters[pick_emitter(u_pick)];
    let su = sqrt(u1);
    return emitter_point(e.triangle, vec2f(su * (1.0 - u2), su * u2), e.probability / max(e.area, FLT_MIN));
}

// The point of emissive triangle `tri` at barycentrics w (of its second and third corners):
// frame-space position, the emitting side's normal (the side the vertex normals point to), the
// emitted radiance there and the given density.
fn emitter_point(tri: u32, w: vec2f, pdf_area: f32) -> EmitterPoint {
    let a = scene_vertex(indices[3u * tri]);
    let b = scene_vertex(indices[3u * tri + 1u]);
    let c = scene_vertex(indices[3u * tri + 2u]);
    let position = lerp_bary3(a.position, b.position, c.position, w) - frame.view_origin.xyz;
    let ng = safe_normalize(cross(b.position - a.position, c.position - a.position), vec3f(0.0, 1.0, 0.0));
    let normal = select(-ng, ng, dot(ng, lerp_bary3(a.normal, b.normal, c.normal, w)) >= 0.0);
    let uv = a.uv + w.x * (b.uv - a.uv) + w.y * (c.uv - a.uv);
    let radiance = material_emission(materials[triangle_materials[tri]], uv, 0.0);
    return EmitterPoint(position, normal, radiance, pdf_area, tri);
}

// The emitter point a ray along `dir` hit: its radiance towards the ray's origin (zero where the
// triangle does not emit or the ray met its back) and next-event estimation's density of it per
// unit area. That density is sample_emitter's, p_i / A_i with p_i = π A_i ΣL_e / emitter_power,
// so π ΣL_e / emitter_power with the material's emissive factor (the table's power leaves the
// texture out), and needs no lookup from triangle to table row.
fn emitter_hit(dir: vec3f, hit: RayHit) -> EmitterPoint {
    let factor = max(materials[triangle_materials[hit.triangle]].emissive, vec3f(0.0));
    var z = emitter_point(hit.triangle, hit.bary, PI * (factor.r + factor.g + factor.b) / max(params.emitter_power, FLT_MIN));
    if (dot(z.normal, dir) >= 0.0) {
        z.radiance = vec3f(0.0);
    }
    return z;
}

// MIS weight of one of the camera strategies that reach an emitter point z from a shading point:
// next-event estimation (z drawn by area, density p_z) and BSDF sampling (density
// p_bsdf · cos_z / |z − p|² per unit area of z). `p_this` is the strategy's own density, `p_other`
// the other's. Between the two, the power heuristic (exponent 2) [Veach 1997, §9.2.3]: the
// balance heuristic adds up to half the squared mean to a single sample's variance, which
// measured 20% more noise than next-event estimation alone on diffuse receivers under large
// emitters. In bidirectional mode (mis.enabled) the camera side as a whole, density
// p_cam (p_z + p_bsdf), keeps the balance heuristic against the light strategy (N_L p_light,
// mis_light_weight's densities), so the three weights of a path still sum to one with the
// light strategy's in light_paths. Written with ratios so huge or zero densities give 0 or 1,
// never NaN.
fn emitter_camera_weight(p_this: f32, p_other: f32, mis: CameraMis, p_light: f32) -> f32 {
    if (!(p_this > 0.0)) {
        return 0.0;
    }
    let ratio = min(p_other / p_this, 1.0e18);
    var weight = 1.0 / (1.0 + ratio * ratio);
    if (mis.enabled) {
        let photons_per_sample = f32(frame.size.x) * f32(frame.size.y);
        let light = min(photons_per_sample * p_light / max(mis.p_cam, FLT_MIN), FLT_MAX);
        weight /= 1.0 + light / min(p_this + p_other, FLT_MAX);
    }
    return weight;
}

// The light strategy's density of x per unit area for a photon from emitter point z (see
// light_emission_density): the emitters' share of the photons, z's area density, the cosine
// lobe's cos_z/π and the solid angle's cos_g(x)/d².
fn emitter_emission_density(z: EmitterPoint, cos_z: f32, x: Surface, l: vec3f, dist: f32) -> f32 {
    let share = params.emitter_power / max(photon_power_total(), FLT_MIN);
    return share * z.pdf_area * cos_z * INV_PI * max(dot(x.ng, l), 0.0) / max(dist * dist, FLT_MIN);
}

// Pdf (solid angle) of a photon's direction from a spot (uniform over the outer cone) or point
// light (uniform over the sphere).
fn light_direction_pdf(light: LightRaw) -> f32 {
    if (light.kind == LIGHT_KIND_SPOT) {
        return 1.0 / (TWO_PI * max(1.0 - light.cos_outer, FLT_MIN));
    }
    return 0.25 * INV_PI;
}

// The light strategy's density of x per unit area for `light` (picked with probability q):
// p_dir · cos_g(x, l)/d² for a spot or point light at distance d, cos_g(x, l)/(π R²) for a
// directional light's disk of radius R. l points from x to the light.
fn light_emission_density(light: LightRaw, q: f32, x: Surface, l: vec3f, dist: f32) -> f32 {
    let cos_x = max(dot(x.ng, l), 0.0);
    var density: f32;
    if (light.kind == LIGHT_KIND_DIRECTIONAL) {
        let r = directional_disk_radius();
        density = cos_x / (PI * r * r);
    } else {
        density = light_direction_pdf(light) * cos_x / max(dist * dist, FLT_MIN);
    }
    return q * density;
}

// Area of one pixel on the image plane at distance 1 (the camera's pixel footprint).
fn pixel_area() -> f32 {
    return 4.0 * length(frame.cam_right.xyz) * length(frame.cam_up.xyz) / (f32(frame.size.x) * f32(frame.size.y));
}

// Image-plane area per unit surface area at a point y seen from the eye (frame origin) with
// geometric normal ng: cos_g(y, eye) / (d² cos³θ_c), θ_c the angle off the camera axis.
fn image_per_surface_area(y: vec3f, ng: vec3f) -> f32 {
    let d2 = dot(y, y);
    let d = sqrt(d2);
    let cos_c = dot(y, normalize(frame.cam_forward.xyz)) / d;
    let cos_y = dot(ng, -y / d);
    return max(cos_y, 0.0) / max(d2 * cos_c * cos_c * cos_c, FLT_MIN);
}

// Balance-heuristic weight of the light strategy [Veach 1997, §9.2] with W·H photons per
// camera sample, from the two strategies' densities of the path's free vertices (y, x) per unit
// area, both divided by the factors they share (cos_g at x and at y towards each other,
// 1/|x − y|²):
//   camera: image_per_surface_area(y)/A_pixel · p_bsdf,y(y→x) · cos_g(x, y)
//   light:  light_emission_density(x) · p_bsdf,x(x→y) · cos_g(y, x)
// Written as 1/(1 + ratio) so huge or zero densities give 0 or 1, never NaN.
fn mis_light_weight(p_cam: f32, p_light: f32) -> f32 {
    if (params.strategy == STRATEGY_LIGHT) {
        return 1.0;
    }
    let photons_per_sample = f32(frame.size.x) * f32(frame.size.y);
    let a = min(photons_per_sample * p_light, FLT_MAX);
    let b = min(p_cam, FLT_MAX);
    if (!(a > 0.0)) {
        return 0.0;
    }
    return 1.0 / (1.0 + b / a);
}

// Direct light reflected towards v at a surface point from every light, each visible through
// a shadow ray: Σ f(l, v) ⟨n, l⟩ e, with e the light's irradiance facing it (light_incidence:
// I·color·cone/d² for spot and point lights, E·color for a directional light) — the direct
// pass's formula, with a traced shadow ray in place of the shadow map.
// `mis`: the camera strategy's side of the MIS weight when s is the bounce point x of a
// bidirectional camera path (mis.enabled), else ignored.
fn lights_radiance(s: Surface, v: vec3f, mis: CameraMis) -> vec3f {
    var radiance = vec3f(0.0);
    let origin = s.position + s.ng * ray_offset(s.position);
    var total_power = 0.0;
    if (mis.enabled) {
        total_power = photon_power_total();
    }
    for (var i = 0u; i < frame.light_count; i++) {
        let light = lights[i];
        let inc = light_incidence(light, s.position);
        if (all(inc.e <= vec3f(0.0))) {
            continue;
        }
        let l = inc.l;
        let n_dot_l = dot(s.ns, l);
        if (n_dot_l <= 0.0 || dot(s.ng, l) <= 0.0) {
            continue;
        }
        var shadow: Ray;
        if (light.kind == LIGHT_KIND_DIRECTIONAL) {
            // The light is at infinity: the ray runs until it has left the scene (every scene
            // point lies within one diagonal of every other).
            shadow = Ray(to_scene(origin), l, RAY_T_MAX_EXTENTS * frame.scene_extent, s.triangle);
        } else {
            // From the offset origin, stopping short of the light by its own offset.
            let seg = light.position - origin;
            let seg_len = length(seg);
            shadow = Ray(to_scene(origin), seg / max(seg_len, FLT_MIN), seg_len - ray_offset(light.position), s.triangle);
        }
        if (bvh_any_hit(shadow)) {
            continue;
        }
        let brdf = s.rd * lambert_brdf_over_rd(s.ns, l) + s.rs * ggx_brdf_over_rs(s.ns, l, v, s.alpha);
        var weight = 1.0;
        if (mis.enabled) {
            // The light strategy would have made this path by emitting towards x and sampling
            // x's BRDF towards y (v, from x to y) given the light's direction l.
            let q = select(0.0, light_power(light) / total_power, total_power > 0.0);
            let p_light = light_emission_density(light, q, s, l, inc.dist) * bsdf_pdf(s, v, l) * mis.cos_gy_x;
            weight = 1.0 - mis_light_weight(mis.p_cam, p_light);
        }
        radiance += brdf * inc.e * n_dot_l * weight;
    }
    return min(radiance, vec3f(FLT_MAX));
}

fn lerp_bary3(a: vec3f, b: vec3f, c: vec3f, w: vec2f) -> vec3f {
    return a + w.x * (b - a) + w.y * (c - a);
}

// Light reflected towards v at s from one emitter point drawn with u (next-event estimation,
// the header's formula), visible through a shadow ray. `mis` as in lights_radiance: the camera
// strategy drew z with density p_z, the light strategy with emitter_emission_density.
// Every shading point also counts the emitters its BSDF-sampled ray hits (emitter_bsdf_hit):
// the two share z's light by emitter_camera_weight.
fn emitters_radiance(s: Surface, v: vec3f, mis: CameraMis, u: vec3f) -> vec3f {
    let z = sample_emitter(u.x, u.y, u.z);
    let origin = s.position + s.ng * ray_offset(s.position);
    let seg = z.position - origin;
    let dist = length(seg);
    if (!(dist > 0.0) || !(z.pdf_area > 0.0)) {
        return vec3f(0.0);
    }
    let l = seg / dist;
    let cos_z = dot(z.normal, -l);
    let n_dot_l = dot(s.ns, l);
    if (cos_z <= 0.0 || n_dot_l <= 0.0 || dot(s.ng, l) <= 0.0 || all(z.radiance <= vec3f(0.0))) {
        return vec3f(0.0);
    }
    // Stops short of the emitter by its own offset (its triangle lies at the segment's end).
    if (bvh_any_hit(Ray(to_scene(origin), l, dist - ray_offset(z.position), s.triangle))) {
        return vec3f(0.0);
    }
    let brdf = s.rd * lambert_brdf_over_rd(s.ns, l) + s.rs * ggx_brdf_over_rs(s.ns, l, v, s.alpha);
    var p_light = 0.0;
    if (mis.enabled) {
        p_light = emitter_emission_density(z, cos_z, s, l, dist) * bsdf_pdf(s, v, l) * mis.cos_gy_x;
    }
    let p_bsdf = bsdf_pdf(s, l, v) * cos_z / (dist * dist);
    let weight = emitter_camera_weight(z.pdf_area, p_bsdf, mis, p_light);
    let geometry = n_dot_l * cos_z / (dist * dist * z.pdf_area);
    return min(brdf * z.radiance * (geometry * weight), vec3f(FLT_MAX));
}

// Light reflected towards v at s from the emitter, if any, that a ray drawn from s's BSDF with u
// hits (BSDF sampling: f ⟨n, l⟩ L_e / p_bsdf), weighted against next-event estimation and, in
// bidirectional mode, the light strategy. It finds light that next-event estimation draws
// rarely: the reflection of a small or distant emitter in a glossy lobe narrower than the
// emitter's solid angle, where a point drawn by area seldom lands in the lobe.
fn emitter_bsdf_hit(s: Surface, v: vec3f, mis: CameraMis, u: vec3f) -> vec3f {
    let l = sample_bsdf(s, v, u.x, u.y, u.z);
    let n_dot_l = dot(s.ns, l);
    if (n_dot_l <= 0.0 || dot(s.ng, l) <= 0.0) {
        return vec3f(0.0);
    }
    let p_bsdf = bsdf_pdf(s, l, v);
    if (!(p_bsdf > 0.0)) {
        return vec3f(0.0);
    }
    let origin = s.position + s.ng * ray_offset(s.position);
    let hit = bvh_closest_hit(Ray(to_scene(origin), l, RAY_T_MAX_EXTENTS * frame.scene_extent, s.triangle));
    if (hit.triangle == BVH_NO_TRIANGLE) {
        return vec3f(0.0);
    }
    let z = emitter_hit(l, hit);
    if (all(z.radiance <= vec3f(0.0))) {
        return vec3f(0.0);
    }
    let dist = distance(z.position, s.position);
    let cos_z = dot(z.normal, -l);
    var p_light = 0.0;
    if (mis.enabled) {
        p_light = emitter_emission_density(z, cos_z, s, l, dist) * bsdf_pdf(s, v, l) * mis.cos_gy_x;
    }
    let weight = emitter_camera_weight(p_bsdf * cos_z / max(dist * dist, FLT_MIN), z.pdf_area, mis, p_light);
    let brdf = s.rd * lambert_brdf_over_rd(s.ns, l) + s.rs * ggx_brdf_over_rs(s.ns, l, v, s.alpha);
    return min(brdf * z.radiance * (n_dot_l * weight / p_bsdf), vec3f(FLT_MAX));
}

// The surface a bounce ray hit: position from the barycentrics (not origin + t·dir, which
// carries the ray's rounding), normals facing the ray's origin, and the glTF material (with its
// textures at the finest level: a path tracer integrates texture detail itself).
fn hit_surface(dir: vec3f, hit: RayHit) -> Surface {
    let tri = hit.triangle;
    var a = scene_vertex(indices[3u * tri]);
    var b = scene_vertex(indices[3u * tri + 1u]);
    var c = scene_vertex(indices[3u * tri + 2u]);
    // Back to frame space.
    a.position -= frame.view_origin.xyz;
    b.position -= frame.view_origin.xyz;
    c.position -= frame.view_origin.xyz;
    let w = hit.bary;
    let position = lerp_bary3(a.position, b.position, c.position, w);
    var ng = safe_normalize(cross(b.position - a.position, c.position - a.position), -dir);
    if (dot(ng, dir) > 0.0) {
        ng = -ng;
    }
    var ns = safe_normalize(lerp_bary3(a.normal, b.normal, c.normal, w), ng);
    if (dot(ns, ng) < 0.0) {
        ns = -ns;
    }
    let material = materials[triangle_materials[tri]];
    // The finest mip: a bounce ray's footprint is not tracked.
    let uv = a.uv + w.x * (b.uv - a.uv) + w.y * (c.uv - a.uv);
    let sm = evaluate_material(material, uv, 0.0, ns, lerp_bary3(a.tangent.xyz, b.tangent.xyz, c.tangent.xyz, w), a.tangent.w);
    ns = sm.ns;
    // As in the material pass: a shading normal facing away from the viewer (here the bounce
    // ray's origin) falls back to the geometric normal.
    if (dot(ns, -dir) <= 0.0) {
        ns = ng;
    }
    return Surface(position, ng, ns, gbuffer_diffuse_reflectance(sm.base, sm.metallic),
                   gbuffer_specular_reflectance(sm.base, sm.metallic, material.specular_factor),
                   ggx_alpha_from_roughness(sm.roughness), tri);
}

// The G-buffer surface of a pixel (which must not be background).
fn pixel_surface(pixel: vec2u, index: u32) -> Surface {
    let pos = gbuf_position[index];
    let nr = gbuf_normal[index];
    let gm = gbuf_geo_normal[index];
    let base = gbuf_base_color[index].rgb;
    let tri = textureLoad(visibility, vec2i(pixel), 0).r - 1u;
    return Surface(pos.xyz, gm.xyz, nr.xyz, gbuffer_diffuse_reflectance(base, gm.w),
                   gbuffer_specular_reflectance(base, gm.w, gbuf_base_color[index].w), ggx_alpha_from_roughness(nr.w), tri);
}

// Radiance arriving at `s` from direction l: the direct light reflected by the first surface
// hit towards s (zero on a miss: there is no environment light).
// In bidirectional mode, `v` (the direction from s to the eye) and `p_y` (the image-plane
// density of s per unit area over the pixel's area, image_per_surface_area / A_pixel) weigh
// each light's path against the light strategy.
// `u_emit`: the random numbers of x's emitter sample (next-event estimation) and of x's
// BSDF-sampled ray towards the emitters (both unused without emitters).
fn incoming_radiance(s: Surface, l: vec3f, v: vec3f, p_y: f32, u_emit: array<vec3f, 2>) -> vec3f {
    let origin = s.position + s.ng * ray_offset(s.position);
    let hit = bvh_closest_hit(Ray(to_scene(origin), l, RAY_T_MAX_EXTENTS * frame.scene_extent, s.triangle));
    if (hit.triangle == BVH_NO_TRIANGLE) {
        return vec3f(0.0);
    }
    let x = hit_surface(l, hit);
    var mis = NO_MIS;
    if (params.strategy != STRATEGY_CAMERA) {
        mis = CameraMis(true, p_y * bsdf_pdf(s, l, v) * max(dot(x.ng, -l), 0.0), max(dot(s.ng, l), 0.0));
    }
    var radiance = lights_radiance(x, -l, mis);
    if (HAS_EMITTERS) {
        let nee = emitters_radiance(x, -l, mis, u_emit[0]);
        let bsdf = emitter_bsdf_hit(x, -l, mis, u_emit[1]);
        radiance = min(radiance + nee + bsdf, vec3f(FLT_MAX));
    }
    return radiance;
}

@compute @workgroup_size(WORKGROUP, WORKGROUP, 1)
fn indirect(@builtin(global_invocation_id) gid: vec3u) {
    if (gid.x >= frame.size.x || gid.y >= frame.size.y) {
        return;
    }
    let index = gid.y * frame.size.x + gid.x;
    // Camera paths start at the pixel centre's surface: a centre that sees the background has
    // none. The other strategies estimate the pixel's area average, of which a silhouette
    // pixel whose centre misses still covers a part (checked against Mitsuba 3: leaving those
    // pixels out lost 0.34–0.42% of the Cornell boxes' indirect light at 48²).
    let centre_missed = gbuf_position[index].w == GBUFFER_BACKGROUND;
    if (centre_missed && params.strategy == STRATEGY_CAMERA) {
        indirect_diffuse[index] = vec4f(0.0);
        indirect_specular[index] = vec4f(0.0);
        indirect_m2[index] = vec4f(0.0);
        if (HAS_EMITTERS) {
            emitted_direct[index] = vec4f(0.0);
        }
        return;
    }
    // Read only where the centre hit (the jittered rays below replace it otherwise).
    var centre = Surface(vec3f(0.0), vec3f(0.0, 1.0, 0.0), vec3f(0.0, 1.0, 0.0), vec3f(0.0), vec3f(0.0), 1.0, BVH_NO_TRIANGLE);
    if (!centre_missed) {
        centre = pixel_surface(gid.xy, index);
    }
    let v_centre = -centre.position / max(length(centre.position), FLT_MIN);
    // Primary rays of bidirectional mode start at the eye and run past the far side of the scene.
    let primary_t_max = length(frame.view_origin.xyz) + RAY_T_MAX_EXTENTS * frame.scene_extent;

    var mean = vec3f(0.0);
    var m2 = vec3f(0.0);
    var sum_d = vec3f(0.0);
    var sum_s = vec3f(0.0);
    var sum_emitted = vec3f(0.0);
    for (var k = 0u; k < params.batch_samples; k++) {
        var rng = rng_init(index, params.sample_offset + k, params.seed);
        // The emitters' direct light at the pixel centre, one next-event sample and one
        // BSDF-sampled ray per path sample (drawn first, so the path's own numbers are those of
        // a scene without emitters, shifted).
        var u_emit = array<vec3f, 2>(vec3f(0.0), vec3f(0.0));
        if (HAS_EMITTERS) {
            let u_nee = vec3f(rng_uniform(&rng), rng_uniform(&rng), rng_uniform(&rng));
            let u_bsdf = vec3f(rng_uniform(&rng), rng_uniform(&rng), rng_uniform(&rng));
            if (!centre_missed) {
                let nee = emitters_radiance(centre, v_centre, NO_MIS, u_nee);
                sum_emitted = min(sum_emitted + nee + emitter_bsdf_hit(centre, v_centre, NO_MIS, u_bsdf), vec3f(FLT_MAX));
            }
            u_emit[0] = vec3f(rng_uniform(&rng), rng_uniform(&rng), rng_uniform(&rng));
            u_emit[1] = vec3f(rng_uniform(&rng), rng_uniform(&rng), rng_uniform(&rng));
        }
        // The receiver: the pixel centre's G-buffer point, or in bidirectional mode the point a
        // ray through a uniformly jittered position in the pixel hits (p_y: its density per unit
        // area, for the MIS weights; a miss is a zero sample of the pixel's average).
        var s = centre;
        var v = v_centre;
        var p_y = 0.0;
        var hit_receiver = true;
        if (params.strategy == STRATEGY_LIGHT) {
            // Light tracing alone: the camera part is zero (no samples, no variance).
            hit_receiver = false;
        } else if (params.strategy != STRATEGY_CAMERA) {
            let jitter = vec2f(rng_uniform(&rng), rng_uniform(&rng));
            let dir = camera_ray(frame, vec2f(gid.xy) + jitter);
            let hit = bvh_closest_hit(Ray(to_scene(vec3f(0.0)), dir, primary_t_max, BVH_NO_TRIANGLE));
            hit_receiver = hit.triangle != BVH_NO_TRIANGLE;
            if (hit_receiver) {
                s = hit_surface(dir, hit);
                v = -dir;
                p_y = image_per_surface_area(s.position, s.ng) / pixel_area();
            }
        }
        let u_lobe = rng_uniform(&rng);
        let u1 = rng_uniform(&rng);
        let u2 = rng_uniform(&rng);
        var x_d = vec3f(0.0);
        var x_s = vec3f(0.0);
        let l = sample_bsdf(s, v, u_lobe, u1, u2);
        let n = s.ns;
        let cos_l = dot(n, l);
        if (hit_receiver && cos_l > 0.0 && dot(s.ng, l) > 0.0) {
            let pdf = bsdf_pdf(s, l, v);
            if (pdf > 0.0) {
                let li = incoming_radiance(s, l, v, p_y, u_emit);
                if (any(li > vec3f(0.0))) {
                    let w = li * (cos_l / pdf);
                    x_d = min(s.rd * INV_PI * w, vec3f(FLT_MAX));
                    x_s = min(s.rs * ggx_brdf_over_rs(n, l, v, s.alpha) * w, vec3f(FLT_MAX));
                }
            }
        }
        // Welford's running mean and sum of squared deviations of the sample total.
        let x = x_d + x_s;
        let delta = x - mean;
        mean += delta / f32(k + 1u);
        m2 += delta * (x - mean);
        sum_d += x_d;
        sum_s += x_s;
    }
    let n_b = f32(params.batch_samples);
    let mean_d = sum_d / n_b;
    let mean_s = sum_s / n_b;
    if (HAS_EMITTERS) {
        // Running mean over batches (the weights of Chan's merge below, without the variance).
        let batch = min(sum_emitted / n_b, vec3f(FLT_MAX));
        var merged = batch;
        if (params.sample_offset > 0u) {
            let old = emitted_direct[index].rgb;
            merged = old + (batch - old) * (n_b / (f32(params.sample_offset) + n_b));
        }
        emitted_direct[index] = vec4f(merged, 0.0);
    }
    if (params.sample_offset == 0u) {
        indirect_diffuse[index] = vec4f(mean_d, 0.0);
        indirect_specular[index] = vec4f(mean_s, 0.0);
        indirect_m2[index] = vec4f(min(m2, vec3f(FLT_MAX)), 0.0);
        return;
    }
    // Chan et al. 1979: merge (n_a, mean_a, M2_a) with (n_b, mean_b, M2_b).
    let n_a = f32(params.sample_offset);
    let f = n_b / (n_a + n_b);
    let old_d = indirect_diffuse[index].rgb;
    let old_s = indirect_specular[index].rgb;
    let delta = mean - (old_d + old_s);
    indirect_diffuse[index] = vec4f(old_d + (mean_d - old_d) * f, 0.0);
    indirect_specular[index] = vec4f(old_s + (mean_s - old_s) * f, 0.0);
    let m2_new = indirect_m2[index].rgb + m2 + delta * delta * (n_a * f);
    indirect_m2[index] = vec4f(min(m2_new, vec3f(FLT_MAX)), 0.0);
}

@compute @workgroup_size(WORKGROUP, WORKGROUP, 1)
fn direct(@builtin(global_invocation_id) gid: vec3u) {
    if (gid.x >= frame.size.x || gid.y >= frame.size.y) {
        return;
    }
    let index = gid.y * frame.size.x + gid.x;
    if (gbuf_position[index].w == GBUFFER_BACKGROUND) {
        direct_out[index] = vec4f(0.0, 0.0, 0.0, 1.0);
        return;
    }
    let s = pixel_surface(gid.xy, index);
    let v = -s.position / max(length(s.position), FLT_MIN);
    direct_out[index] = vec4f(lights_radiance(s, v, NO_MIS), 1.0);
}

#include "common/atomic_float.wgsl"

const LIGHT_WORKGROUP: u32 = 64u;

// One photon per thread (batch_samples · W · H of them): light → x → y → eye, splatted into y's
// pixel with its MIS weight, divided by the batch's photon count (so a batch's splats are its
// estimate of the light part). The path throughput follows the measurement with shading normals
// [Veach 1997, ch. 5: with shading normals the adjoint BRDF gains cos_s/cos_g where light arrives]:
//   C = I(ω)/(q p_dir) · cos_s(x,l)/cos_g(x,l) · f_x · cos_g(x,y)/p_x(y) · f_y · cos_s(y,x)/cos_g(y,x)
//       · image_per_surface_area(y) / A_pixel
// (for a directional light I/p_dir is E · π R², the disk's flux).
@compute @workgroup_size(LIGHT_WORKGROUP, 1, 1)
fn light_paths(@builtin(global_invocation_id) gid: vec3u, @builtin(num_workgroups) groups: vec3u) {
    let photon = gid.x + gid.y * groups.x * LIGHT_WORKGROUP;
    let photons = params.batch_samples * frame.size.x * frame.size.y;
    let emitting = HAS_EMITTERS && params.emitter_count > 0u;
    if (photon >= photons || (frame.light_count == 0u && !emitting)) {
        return;
    }
    // A stream apart from the camera paths' (those hash (pixel, sample, seed)).
    var rng = rng_init(photon, params.sample_offset, params.seed ^ 0x5bd1e995u);
    let total = photon_power_total();
    if (!(total > 0.0)) {
        return;
    }
    let u_pick = rng_uniform(&rng) * total;
    let lights_total = total_light_power();
    // Past the lights' power the photon leaves an emitter (HAS_EMITTERS).
    let from_emitter = emitting && u_pick >= lights_total;
    var pick = max(frame.light_count, 1u) - 1u;
    var acc = 0.0;
    for (var k = 0u; k < frame.light_count; k++) {
        acc += light_power(lights[k]);
        if (u_pick < acc) {
            pick = k;
            break;
        }
    }
    let light = lights[pick];
    let q = light_power(light) / total;
    let u1 = rng_uniform(&rng);
    let u2 = rng_uniform(&rng);
    var origin: vec3f;
    var dir: vec3f;
    var flux: vec3f;
    // The emitter point a photon from an emitter left, and the cosine at it.
    var z: EmitterPoint;
    var cos_z = 0.0;
    var skip = BVH_NO_TRIANGLE;
    if (from_emitter) {
        // The rest of u_pick picks the triangle; a point uniformly on it; a cosine-distributed
        // direction about its emitting side. Flux L_e cos_z / (share · p_z · cos_z/π).
        let u_e = min((u_pick - lights_total) / max(params.emitter_power, FLT_MIN), 0.99999994);
        z = sample_emitter(u_e, u1, u2);
        let local = sample_cosine_hemisphere(rng_uniform(&rng), rng_uniform(&rng));
        cos_z = local.z;
        dir = safe_normalize(orthonormal_basis(z.normal) * local, z.normal);
        origin = z.position + z.normal * ray_offset(z.position);
        skip = z.triangle;
        let share = params.emitter_power / total;
        flux = select(vec3f(0.0), z.radiance * (PI / (share * z.pdf_area)), cos_z > 0.0 && z.pdf_area > 0.0);
    } else if (light.kind == LIGHT_KIND_DIRECTIONAL) {
        dir = normalize(light.direction);
        let r = directional_disk_radius();
        // The scene's centre (the upload anchor) is at −view_origin in frame space.
        let centre = -frame.view_origin.xyz - dir * r;
        let radius = r * sqrt(u1);
        let phi = TWO_PI * u2;
        origin = centre + orthonormal_basis(dir) * vec3f(radius * cos(phi), radius * sin(phi), 0.0);
        flux = light.intensity * light.color * (PI * r * r) / q;
    } else {
        origin = light.position;
        var cos_t: f32;
        if (light.kind == LIGHT_KIND_SPOT) {
            cos_t = 1.0 - u1 * (1.0 - light.cos_outer);
        } else {
            cos_t = 1.0 - 2.0 * u1;
        }
        let sin_t = sqrt(max(1.0 - cos_t * cos_t, 0.0));
        let phi = TWO_PI * u2;
        let axis = select(vec3f(0.0, 0.0, 1.0), normalize(light.direction), light.kind == LIGHT_KIND_SPOT);
        dir = safe_normalize(orthonormal_basis(axis) * vec3f(sin_t * cos(phi), sin_t * sin(phi), cos_t), axis);
        var cone = 1.0;
        if (light.kind == LIGHT_KIND_SPOT) {
            cone = spot_cone_attenuation(light, -dir);
        }
        flux = light.intensity * light.color * cone / (light_direction_pdf(light) * q);
    }
    if (all(flux <= vec3f(0.0))) {
        return;
    }
    let t_max = length(to_scene(origin)) + RAY_T_MAX_EXTENTS * frame.scene_extent;
    let hit_x = bvh_closest_hit(Ray(to_scene(origin), dir, t_max, skip));
    if (hit_x.triangle == BVH_NO_TRIANGLE) {
        return;
    }
    let x = hit_surface(dir, hit_x);
    let to_light = -dir;
    let cos_gx_l = dot(x.ng, to_light);
    let cos_sx_l = dot(x.ns, to_light);
    if (cos_gx_l <= 0.0 || cos_sx_l <= 0.0) {
        return;
    }
    let to_y = sample_bsdf(x, to_light, rng_uniform(&rng), rng_uniform(&rng), rng_uniform(&rng));
    let cos_gx_y = dot(x.ng, to_y);
    if (dot(x.ns, to_y) <= 0.0 || cos_gx_y <= 0.0) {
        return;
    }
    let p_x = bsdf_pdf(x, to_y, to_light);
    if (!(p_x > 0.0)) {
        return;
    }
    let f_x = x.rd * INV_PI + x.rs * ggx_brdf_over_rs(x.ns, to_y, to_light, x.alpha);
    let throughput = flux * (cos_sx_l / cos_gx_l) * f_x * (cos_gx_y / p_x);
    let origin_x = x.position + x.ng * ray_offset(x.position);
    let hit_y = bvh_closest_hit(Ray(to_scene(origin_x), to_y, RAY_T_MAX_EXTENTS * frame.scene_extent, x.triangle));
    if (hit_y.triangle == BVH_NO_TRIANGLE) {
        return;
    }
    let y = hit_surface(to_y, hit_y);
    // Connect y to the eye (the frame origin): in front of the camera, inside the image, facing
    // the eye on the side x lit, and unoccluded.
    let d2 = dot(y.position, y.position);
    let d = sqrt(d2);
    let to_eye = -y.position / max(d, FLT_MIN);
    let to_x = -to_y;
    let cos_gy_x = dot(y.ng, to_x);
    let cos_sy_x = dot(y.ns, to_x);
    if (dot(y.ng, to_eye) <= 0.0 || dot(y.ns, to_eye) <= 0.0 || cos_sy_x <= 0.0 || cos_gy_x <= 0.0) {
        return;
    }
    let depth = dot(y.position, normalize(frame.cam_forward.xyz));
    if (depth <= 0.0) {
        return;
    }
    let right = frame.cam_right.xyz;
    let up = frame.cam_up.xyz;
    let ndc = vec2f(dot(y.position, right) / (dot(right, right) * depth), dot(y.position, up) / (dot(up, up) * depth));
    if (any(abs(ndc) >= vec2f(1.0))) {
        return;
    }
    let pixel = min(vec2u(vec2f((ndc.x + 1.0) * 0.5 * f32(frame.size.x), (1.0 - ndc.y) * 0.5 * f32(frame.size.y))), frame.size - vec2u(1u));
    let index = pixel.y * frame.size.x + pixel.x;
    // A splat lands anywhere in its pixel, whose area average it estimates, including pixels
    // whose centre sees the background (as `indirect` does in this mode).
    let origin_y = y.position + y.ng * ray_offset(y.position);
    let eye_len = length(origin_y);
    if (bvh_any_hit(Ray(to_scene(origin_y), -origin_y / max(eye_len, FLT_MIN), eye_len - ray_offset(vec3f(0.0)), y.triangle))) {
        return;
    }
    let p_y = image_per_surface_area(y.position, y.ng) / pixel_area();
    var p_cam = p_y * bsdf_pdf(y, to_x, to_eye) * cos_gx_y;
    var density_x: f32;
    if (from_emitter) {
        // The camera strategy reaches z by next-event estimation or by x's BSDF-sampled ray
        // (emitter_bsdf_hit): their densities of z join p_cam.
        let dist_xz = distance(x.position, z.position);
        p_cam *= z.pdf_area + bsdf_pdf(x, to_light, to_y) * cos_z / max(dist_xz * dist_xz, FLT_MIN);
        density_x = emitter_emission_density(z, cos_z, x, to_light, distance(x.position, z.position));
    } else {
        density_x = light_emission_density(light, q, x, to_light, distance(x.position, light.position));
    }
    let p_light = density_x * p_x * cos_gy_x;
    let weight = mis_light_weight(p_cam, p_light);
    if (!(weight > 0.0)) {
        return;
    }
    let arriving = throughput * (cos_sy_x / cos_gy_x) * p_y * (weight / f32(photons));
    let c_d = min(y.rd * INV_PI * arriving, vec3f(FLT_MAX));
    let c_s = min(y.rs * ggx_brdf_over_rs(y.ns, to_x, to_eye, y.alpha) * arriving, vec3f(FLT_MAX));
    let base = 8u * index;
    for (var c = 0u; c < 3u; c++) {
        if (c_d[c] > 0.0) {
            atomic_add_float(base + c, c_d[c]);
        }
        if (c_s[c] > 0.0) {
            atomic_add_float(base + 3u + c, c_s[c]);
        }
    }
}

// Folds this batch's splats (its estimate Y of the light part, weight c = batch_samples) into
// the light part's weighted running mean and M2 [West 1979: M2 += c·δ·(Y − mean_new)], and
// clears them for the next batch.
@compute @workgroup_size(WORKGROUP, WORKGROUP, 1)
fn light_fold(@builtin(global_invocation_id) gid: vec3u) {
    if (gid.x >= frame.size.x || gid.y >= frame.size.y) {
        return;
    }
    let index = gid.y * frame.size.x + gid.x;
    let base = 8u * index;
    var y_d: vec3f;
    var y_s: vec3f;
    for (var c = 0u; c < 3u; c++) {
        y_d[c] = bitcast<f32>(atomicLoad(&float_sums[base + c]));
        y_s[c] = bitcast<f32>(atomicLoad(&float_sums[base + 3u + c]));
        atomicStore(&float_sums[base + c], 0u);
        atomicStore(&float_sums[base + 3u + c], 0u);
    }
    let c = f32(params.batch_samples);
    let old_d = light_mean[2u * index];
    let old_s = light_mean[2u * index + 1u].rgb;
    let old_m2 = light_m2[index];
    let total = old_m2.w + c;
    let f = c / total;
    let y = y_d + y_s;
    let delta = y - (old_d.rgb + old_s);
    let new_d = old_d.rgb + (y_d - old_d.rgb) * f;
    let new_s = old_s + (y_s - old_s) * f;
    light_mean[2u * index] = vec4f(new_d, old_d.w + 1.0);
    light_mean[2u * index + 1u] = vec4f(new_s, 0.0);
    light_m2[index] = vec4f(min(old_m2.rgb + c * delta * (y - (new_d + new_s)), vec3f(FLT_MAX)), total);
}

// Standard error of the mean per channel: √(M2 / ((N − 1) N)). One sample carries no variance
// estimate; with N = 1 the AOV holds |x|, the one-sample estimate of √E[x²] ≥ σ.
@compute @workgroup_size(WORKGROUP, WORKGROUP, 1)
fn resolve(@builtin(global_invocation_id) gid: vec3u) {
    if (gid.x >= frame.size.x || gid.y >= frame.size.y) {
        return;
    }
    let index = gid.y * frame.size.x + gid.x;
    let n = f32(params.sample_offset);
    var err: vec3f;
    if (params.sample_offset < 2u) {
        err = abs(indirect_diffuse[index].rgb + indirect_specular[index].rgb);
    } else {
        err = sqrt(max(indirect_m2[index].rgb, vec3f(0.0)) / ((n - 1.0) * n));
    }
    if (params.strategy != STRATEGY_CAMERA) {
        // The light part: its mean joins the camera part's (the two MIS-weighted strategies add
        // up to the estimate) and its variance, over batches, joins the camera part's. Batch b's
        // estimate Y_b has variance σ²/c_b: σ² ≈ M2/(B − 1), the mean's variance σ²/Σc_b. One
        // batch carries no variance estimate: |Y| stands in, as |x| does above.
        let d = light_mean[2u * index];
        let sp = light_mean[2u * index + 1u].rgb;
        let m2 = light_m2[index];
        indirect_diffuse[index] = vec4f(indirect_diffuse[index].rgb + d.rgb, 0.0);
        indirect_specular[index] = vec4f(indirect_specular[index].rgb + sp, 0.0);
        var light_var: vec3f;
        if (d.w < 2.0) {
            light_var = (d.rgb + sp) * (d.rgb + sp);
        } else {
            light_var = max(m2.rgb, vec3f(0.0)) / ((d.w - 1.0) * max(m2.w, 1.0));
        }
        err = sqrt(err * err + light_var);
    }
    stderr_out[index] = vec4f(min(err, vec3f(FLT_MAX)), 0.0);
    if (HAS_EMITTERS) {
        let d = direct_out[index];
        direct_out[index] = vec4f(min(d.rgb + emitted_direct[index].rgb, vec3f(FLT_MAX)), d.w);
    }
}
