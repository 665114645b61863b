// Per-frame data shared by every pass (GPU twins of the structs in crates/vsgl-core/src/frame/uniforms.rs;
// a test checks that their sizes agree with naga's layout). Positions are relative to the frame
// origin (the camera position), computed in f64 on the CPU; only the uploaded scene (vertex
// buffers, BVH) is relative to the upload's anchor (the centre of the scene bounds), and
// view_proj / view_origin take it from there.

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
    // never a fixed length in world units (DESIGN.md, Numerics).
    scene_extent: f32,
    shadow_size: f32,
    _pad0: f32,
    _pad1: f32,
}

struct LightRaw {
    position: vec3f,
    intensity: f32,
    direction: vec3f,
    cos_outer: f32,
    color: vec3f,
    cos_inner: f32,
    view_proj: mat4x4f,
    // 2·tan(shadow half-angle)/shadow map size: the world size of a shadow texel is this times
    // the distance to the light.
    texel_tan: f32,
    shadow_layer: u32,
    // LIGHT_KIND_SPOT, …: the light's type (only spot lights are rendered so far).
    kind: u32,
    _pad: f32,
}

const LIGHT_KIND_SPOT: u32 = 0u;

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
    _pad1: i32,
}

// The unit camera ray through pixel centre `pixel` (+0.5 offsets included by the caller).
fn camera_ray(frame: FrameUniforms, pixel: vec2f) -> vec3f {
    let ndc = vec2f(2.0 * pixel.x / f32(frame.size.x) - 1.0, 1.0 - 2.0 * pixel.y / f32(frame.size.y));
    return normalize(frame.cam_forward.xyz + ndc.x * frame.cam_right.xyz + ndc.y * frame.cam_up.xyz);
}

// glTF KHR_lights_punctual smooth cone attenuation: a quadratic ramp in cos θ between the
// outer and the inner cone (the extension's recommended implementation).
fn spot_cone_attenuation(light: LightRaw, to_light: vec3f) -> f32 {
    let cd = dot(light.direction, -to_light);
    let t = clamp((cd - light.cos_outer) / max(light.cos_inner - light.cos_outer, 1.0e-4), 0.0, 1.0);
    return t * t;
}
