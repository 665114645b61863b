// G-buffer layout (storage buffers, one vec4f per pixel each; row-major, row 0 at the top):
//   position:   xyz relative to the frame origin, w = view depth (> 0), or w = −1 for background
//   normal:     xyz unit shading normal facing the camera, w = perceptual roughness
//   geo_normal: xyz unit geometric normal facing the camera, w = metallic
//   base_color: rgb base colour (linear), w = specular factor (KHR_materials_specular, 0…1)
// Rd = base·(1 − metallic), Rs = mix(0.04·specular, base, metallic) (docs/scenes.md, "Materials";
// glTF KHR_materials_specular scales the dielectric F0 by its factor).

const GBUFFER_BACKGROUND: f32 = -1.0;

fn gbuffer_diffuse_reflectance(base: vec3f, metallic: f32) -> vec3f {
    return base * (1.0 - metallic);
}

fn gbuffer_specular_reflectance(base: vec3f, metallic: f32, specular: f32) -> vec3f {
    return mix(vec3f(0.04 * specular), base, metallic);
}
