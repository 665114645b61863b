// vsgl:include-only (the includer declares `color_textures`, `data_textures` and `texture_sampler`)
// The glTF metallic-roughness material at a surface point, shared by the material pass (camera
// and RSM G-buffers) and the path tracer's bounce hits, so both see the same surface:
// base colour × the base colour texture (sRGB layer array), roughness × G and metallic × B of
// the metallic-roughness texture, and the tangent-space normal map (glTF 2.0 §3.9: +x along the
// tangent, +y along cross(n, t) × tangent.w, xy scaled by normalTexture.scale).
#include "common/frame.wgsl"

// Leave-outs (the pass plan): the untextured variant compiles every texture fetch out, the
// variant without normal maps the tangent frame.
override HAS_TEXTURES: bool = true;
override HAS_NORMAL_MAPS: bool = true;

struct SurfaceMaterial {
    // Base colour, >= 0.
    base: vec3f,
    // Both clamped to [0, 1].
    metallic: f32,
    roughness: f32,
    // Shading normal after the normal map (unit).
    ns: vec3f,
}

// A texture reference's coordinates under its KHR_texture_transform rows (see MaterialRaw).
fn transformed_uv(rows: array<vec4f, 2>, uv: vec2f) -> vec2f {
    let h = vec3f(uv, 1.0);
    return vec2f(dot(rows[0].xyz, h), dot(rows[1].xyz, h));
}

// `ns`: the interpolated unit shading normal; `tangent`: the interpolated tangent and
// `handedness` the sign of the first vertex's tangent.w; `uv` and `lod` (mip level) address
// the textures, and are not read by the untextured variant.
fn evaluate_material(material: MaterialRaw, uv: vec2f, lod: f32, ns: vec3f, tangent: vec3f, handedness: f32) -> SurfaceMaterial {
    var out = SurfaceMaterial(material.base_color.rgb, material.metallic, material.roughness, ns);
    if (HAS_TEXTURES) {
        if (material.base_color_layer >= 0) {
            out.base *= textureSampleLevel(color_textures, texture_sampler, transformed_uv(material.base_color_uv, uv), material.base_color_layer, lod + material.base_color_uv[0].w).rgb;
        }
        if (material.metallic_roughness_layer >= 0) {
            let mr = textureSampleLevel(data_textures, texture_sampler, transformed_uv(material.metallic_roughness_uv, uv), material.metallic_roughness_layer, lod + material.metallic_roughness_uv[0].w);
            out.roughness *= mr.g;
            out.metallic *= mr.b;
        }
        if (HAS_NORMAL_MAPS && material.normal_layer >= 0) {
            let tn = textureSampleLevel(data_textures, texture_sampler, transformed_uv(material.normal_uv, uv), material.normal_layer, lod + material.normal_uv[0].w).xyz * 2.0 - 1.0;
            // Gram-Schmidt: the tangent made orthogonal to the interpolated normal.
            let t_orth = tangent - ns * dot(ns, tangent);
            let t_len = length(t_orth);
            if (t_len > 1.0e-6) {
                let t = t_orth / t_len;
                let bt = cross(ns, t) * select(-1.0, 1.0, handedness >= 0.0);
                let scaled = vec3f(tn.xy * material.normal_scale, tn.z);
                let mapped = t * scaled.x + bt * scaled.y + ns * scaled.z;
                let m_len = length(mapped);
                if (m_len > 1.0e-6) {
                    out.ns = mapped / m_len;
                }
            }
        }
    }
    out.base = max(out.base, vec3f(0.0));
    out.metallic = clamp(out.metallic, 0.0, 1.0);
    out.roughness = clamp(out.roughness, 0.0, 1.0);
    return out;
}

// Emitted radiance L_e at a surface point (linear RGB): the material's emissiveFactor ×
// emissiveStrength times the emissive texture (sRGB colour layer, decoded by the sampler).
// Only what the camera sees reads it (the material pass's emission channel): emissive surfaces
// light no other surface (docs/scenes.md, "Emission").
fn material_emission(material: MaterialRaw, uv: vec2f, lod: f32) -> vec3f {
    var emitted = material.emissive;
    if (HAS_TEXTURES && material.emissive_layer >= 0) {
        emitted *= textureSampleLevel(color_textures, texture_sampler, transformed_uv(material.emissive_uv, uv), material.emissive_layer, lod + material.emissive_uv[0].w).rgb;
    }
    return max(emitted, vec3f(0.0));
}
