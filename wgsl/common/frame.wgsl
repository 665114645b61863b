// Per-frame data shared by every pass (GPU twins of the structs in crates/vsgl-core/src/frame/uniforms.rs;
// a test checks that their sizes agree with naga's layout). Positions are relative to the frame
// origin (the camera position), computed in f64 on the CPU; only the uploaded scene (vertex
// buffers, BVH) is relative to the upload's anchor (the centre of the scene bounds), and
// view_proj / view_origin take it from there.
#include "common/constants.wgsl"

struct FrameUniforms {
    view_proj: mat4x4f,
    // Camera basis scaled for ray generation: right·tan(fov/2)·aspect, up·tan(fov/2), forward.
    cam_right: vec4f,
    cam_up: vec4f,
    cam_forward: vec4f,
    // Where the view's rays start, relative to the upload anchor: the eye for the camera, the
    // light position for a reflective shadow map. Positions a view writes are relative to it.
    view_origin: vec4f,
    size: vec2u,
    light_count: u32,
    texture_layer_size: u32,
    // Diagonal of the scene bounds: every epsilon is a fraction of it or of a local distance,
    // never a fixed length in world units (docs/frames.md, "Precision far from the origin").
    scene_extent: f32,
    shadow_size: f32,
    // 1: orthographic view (a directional light's RSM): rays start on the image plane at
    // view_origin + view_ray_origin(…) and all run along cam_forward; cam_right and cam_up are
    // the plane's half-widths. 0: perspective, every ray starts at view_origin.
    orthographic: u32,
    _pad1: f32,
}

struct LightRaw {
    position: vec3f,
    intensity: f32,
    direction: vec3f,
    cos_outer: f32,
    color: vec3f,
    cos_inner: f32,
    // Frame-relative shadow view-projection (spot, directional; a point light's cube faces are
    // projected by point_shadow_projection).
    view_proj: mat4x4f,
    // Perspective maps (spot, point): 2·tan(shadow half-angle)/shadow map size, so the world
    // size of a shadow texel is this times the distance to the light. Directional
    // (orthographic) map: the world size of a texel itself.
    texel_tan: f32,
    // First shadow array layer of the light (a point light has six: CUBE_FACE_* order).
    shadow_layer: u32,
    // LIGHT_KIND_SPOT, LIGHT_KIND_POINT, LIGHT_KIND_DIRECTIONAL or LIGHT_KIND_EMITTER (a
    // cluster of emissive triangles: a point light whose intensity follows a cosine lobe about
    // `direction`, the emitting side's normal).
    kind: u32,
    // Near plane of a point light's cube faces (0 for the other kinds).
    shadow_near: f32,
}

const LIGHT_KIND_SPOT: u32 = 0u;
const LIGHT_KIND_POINT: u32 = 1u;
const LIGHT_KIND_DIRECTIONAL: u32 = 2u;
const LIGHT_KIND_EMITTER: u32 = 3u;

// Whether the light's shadow and reflective shadow maps are six cube faces (point, emitter).
fn light_has_cube_faces(light: LightRaw) -> bool {
    return light.kind == LIGHT_KIND_POINT || light.kind == LIGHT_KIND_EMITTER;
}

// A point light's shadow cube faces, in layer order (+X, −X, +Y, −Y, +Z, −Z): the view's
// forward axis and up vector, as frame/uniforms.rs::CUBE_FACES rasterises them.
const CUBE_FACE_FORWARD = array<vec3f, 6>(vec3f(1.0, 0.0, 0.0), vec3f(-1.0, 0.0, 0.0), vec3f(0.0, 1.0, 0.0),
                                          vec3f(0.0, -1.0, 0.0), vec3f(0.0, 0.0, 1.0), vec3f(0.0, 0.0, -1.0));
const CUBE_FACE_UP = array<vec3f, 6>(vec3f(0.0, 1.0, 0.0), vec3f(0.0, 1.0, 0.0), vec3f(0.0, 0.0, 1.0),
                                     vec3f(0.0, 0.0, 1.0), vec3f(0.0, 1.0, 0.0), vec3f(0.0, 1.0, 0.0));

// The cube face that sees direction d from the light: the axis of d's largest component,
// face 2k for +axis k, 2k + 1 for −axis k.
fn cube_face(d: vec3f) -> u32 {
    let a = abs(d);
    if (a.x >= a.y && a.x >= a.z) {
        return select(1u, 0u, d.x >= 0.0);
    }
    if (a.y >= a.z) {
        return select(3u, 2u, d.y >= 0.0);
    }
    return select(5u, 4u, d.z >= 0.0);
}

// Normalised device coordinates of offset d from a point light on cube face `face`: what
// DMat4::perspective_infinite_reverse_rh(90°, 1, near) · look_to_rh(light, forward, up) gives,
// written out: x = s·d / w, y = u·d / w, z = near / w with w = forward·d (the depth along the
// face axis), s = normalize(forward × up), u = s × forward.
fn point_shadow_ndc(light: LightRaw, d: vec3f, face: u32) -> vec3f {
    let f = CUBE_FACE_FORWARD[face];
    let s = normalize(cross(f, CUBE_FACE_UP[face]));
    let u = cross(s, f);
    let w = max(dot(f, d), FLT_MIN);
    return vec3f(dot(s, d), dot(u, d), light.shadow_near) / w;
}

// The light arriving at a point: the unit direction l towards the light, the irradiance e on
// a surface facing it, and the distance to the light (0 for a directional light, which is at
// infinity). e = 0 where the light does not reach (outside a spot cone, at the light itself).
struct LightIncidence {
    l: vec3f,
    dist: f32,
    e: vec3f,
}

// KHR_lights_punctual: spot and point intensities are in candela (W/sr per unit colour here),
// so the irradiance facing the light is I·color·cone/d² (inverse-square law); a directional
// light's intensity is an illuminance in lux: E·color, with no falloff, from −direction.
fn light_incidence(light: LightRaw, p: vec3f) -> LightIncidence {
    var out: LightIncidence;
    if (light.kind == LIGHT_KIND_DIRECTIONAL) {
        out.l = -light.direction;
        out.dist = 0.0;
        out.e = light.intensity * light.color;
        return out;
    }
    let to_light = light.position - p;
    let dist2 = dot(to_light, to_light);
    if (dist2 <= FLT_MIN) {
        // At the light itself: no direction, no light (not an infinite one).
        out.l = vec3f(0.0, 0.0, 1.0);
        out.dist = 0.0;
        out.e = vec3f(0.0);
        return out;
    }
    out.dist = sqrt(dist2);
    out.l = to_light / out.dist;
    out.e = light.intensity * light.color * (light_lobe(light, out.l) / dist2);
    return out;
}

// The fraction of a spot, point or emitter light's peak intensity sent towards a point that
// sees it in direction l (from the point to the light): the glTF smooth cone of a spot light,
// 1 for a point light, and for an emitter cluster the Lambertian cosine max(n · (−l), 0) of a
// flat emitter seen from afar (I(ω) = L_e·A·cosθ; upload/emitters.rs).
fn light_lobe(light: LightRaw, l: vec3f) -> f32 {
    if (light.kind == LIGHT_KIND_SPOT) {
        return spot_cone_attenuation(light, l);
    }
    if (light.kind == LIGHT_KIND_EMITTER) {
        return max(dot(light.direction, -l), 0.0);
    }
    return 1.0;
}

struct VertexRaw {
    position: vec3f,
    _pad0: f32,
    normal: vec3f,
    _pad1: f32,
    tangent: vec4f,
    uv: vec2f,
    _pad2: vec2f,
}

struct MaterialRaw {
    base_color: vec4f,
    metallic: f32,
    roughness: f32,
    normal_scale: f32,
    // KHR_materials_specular factor: dielectric R_s = 0.04·specular_factor.
    specular_factor: f32,
    base_color_layer: i32,
    metallic_roughness_layer: i32,
    normal_layer: i32,
    // Layer of the emissive texture in the colour (sRGB) array, −1 when absent.
    emissive_layer: i32,
    // Emitted radiance L_e (linear RGB): emissiveFactor × KHR_materials_emissive_strength.
    emissive: vec3f,
    _pad1: f32,
    // KHR_texture_transform of the base colour, metallic-roughness, normal and emissive
    // references: uv' = (u_row.xyz · (u, v, 1), v_row.xyz · (u, v, 1)); u_row.w is the mip-level
    // shift ½·log2|det M|, v_row.w unused (identity rows without the extension).
    base_color_uv: array<vec4f, 2>,
    metallic_roughness_uv: array<vec4f, 2>,
    normal_uv: array<vec4f, 2>,
    emissive_uv: array<vec4f, 2>,
}

fn view_ndc(frame: FrameUniforms, pixel: vec2f) -> vec2f {
    return vec2f(2.0 * pixel.x / f32(frame.size.x) - 1.0, 1.0 - 2.0 * pixel.y / f32(frame.size.y));
}

// The unit camera ray through pixel centre `pixel` (+0.5 offsets included by the caller):
// through the image plane for a perspective view, cam_forward for an orthographic one.
fn camera_ray(frame: FrameUniforms, pixel: vec2f) -> vec3f {
    if (frame.orthographic != 0u) {
        return frame.cam_forward.xyz;
    }
    let ndc = view_ndc(frame, pixel);
    return normalize(frame.cam_forward.xyz + ndc.x * frame.cam_right.xyz + ndc.y * frame.cam_up.xyz);
}

// Where the ray through `pixel` starts, relative to view_origin: 0 for a perspective view (the
// eye, the light), the point of the image plane for an orthographic one.
fn view_ray_origin(frame: FrameUniforms, pixel: vec2f) -> vec3f {
    if (frame.orthographic == 0u) {
        return vec3f(0.0);
    }
    let ndc = view_ndc(frame, pixel);
    return ndc.x * frame.cam_right.xyz + ndc.y * frame.cam_up.xyz;
}

// glTF KHR_lights_punctual smooth cone attenuation: a quadratic ramp in cos θ between the
// outer and the inner cone (the extension's recommended implementation).
fn spot_cone_attenuation(light: LightRaw, to_light: vec3f) -> f32 {
    let cd = dot(light.direction, -to_light);
    let t = clamp((cd - light.cos_outer) / max(light.cos_inner - light.cos_outer, 1.0e-4), 0.0, 1.0);
    return t * t;
}
