//! Materials: glTF metallic-roughness materials (with the KHR_materials_specular factor and
//! emission: emissiveFactor, emissiveTexture, KHR_materials_emissive_strength) become scene
//! materials, one per (glTF material, normal map kept) pair; unsupported
//! features are skipped with a warning.

use gltf::json;
use json::validation::Checked;

use super::image::texture_index;
use super::{finite_all, Builder, Ctx};
use crate::error::Result;
use crate::scene::{limits, Material, TextureUsage};

fn unit_factor(ctx: &Ctx, v: f32, element: String) -> Result<f32> {
    if !v.is_finite() {
        return Err(ctx.err(element, "non-finite value"));
    }
    Ok(v.clamp(0.0, 1.0))
}

/// The material's emitted radiance L_e = emissiveFactor × emissiveStrength (linear RGB, the
/// image's radiance units; docs/rendering.md, "Emission"). The factor is clamped to 0…1 like
/// the other factors; the strength (KHR_materials_emissive_strength, default 1) must be finite
/// and >= 0, and the product at most `limits::MAX_EMITTED_RADIANCE`.
fn emitted_radiance(ctx: &Ctx, m: &json::Material, el: &str) -> Result<[f32; 3]> {
    let factor = m.emissive_factor.0;
    if !finite_all(&factor) {
        return Err(ctx.err(format!("{el}.emissiveFactor"), "non-finite value"));
    }
    let strength = m.extensions.as_ref().and_then(|e| e.emissive_strength.as_ref()).map_or(1.0, |s| s.emissive_strength.0);
    let strength_el = format!("{el}.extensions.KHR_materials_emissive_strength.emissiveStrength");
    if !(strength.is_finite() && strength >= 0.0) {
        return Err(ctx.err(strength_el, format!("must be finite and >= 0, got {strength}")));
    }
    let mut out = [0.0f32; 3];
    for (o, f) in out.iter_mut().zip(factor) {
        // In f64: the product of two f32 values in range cannot overflow before it is checked.
        let radiance = f.clamp(0.0, 1.0) as f64 * strength as f64;
        *o = limits::emitted_radiance("emissiveFactor × emissiveStrength", radiance)
            .map_err(|e| ctx.err(strength_el.clone(), e.to_string()))?;
    }
    Ok(out)
}

pub(super) fn material_index(
    ctx: &Ctx,
    b: &mut Builder,
    gm: Option<usize>,
    keep_normal_map: bool,
) -> Result<usize> {
    let key = (gm, keep_normal_map && gm.is_some());
    if let Some(&s) = b.material_map.get(&key) {
        return Ok(s);
    }
    let material = match gm {
        None => Material::default(),
        Some(g) => {
            let el = format!("materials[{g}]");
            let m = ctx
                .root
                .materials
                .get(g)
                .ok_or_else(|| ctx.err(el.clone(), "material does not exist"))?;
            let pbr = &m.pbr_metallic_roughness;
            let bcf = pbr.base_color_factor.0;
            if !finite_all(&bcf) {
                return Err(ctx.err(
                    format!("{el}.pbrMetallicRoughness.baseColorFactor"),
                    "non-finite value",
                ));
            }
            let metallic = unit_factor(
                ctx,
                pbr.metallic_factor.0,
                format!("{el}.pbrMetallicRoughness.metallicFactor"),
            )?;
            let roughness = unit_factor(
                ctx,
                pbr.roughness_factor.0,
                format!("{el}.pbrMetallicRoughness.roughnessFactor"),
            )?;
            let base_color_texture = match &pbr.base_color_texture {
                Some(info) => texture_index(
                    ctx,
                    b,
                    info.index.value(),
                    info.tex_coord,
                    TextureUsage::Color,
                    format!("{el}.pbrMetallicRoughness.baseColorTexture"),
                )?,
                None => None,
            };
            let metallic_roughness_texture = match &pbr.metallic_roughness_texture {
                Some(info) => texture_index(
                    ctx,
                    b,
                    info.index.value(),
                    info.tex_coord,
                    TextureUsage::Data,
                    format!("{el}.pbrMetallicRoughness.metallicRoughnessTexture"),
                )?,
                None => None,
            };
            let mut normal_scale = 1.0;
            let normal_texture = match (&m.normal_texture, keep_normal_map) {
                (Some(nt), true) => {
                    if !nt.scale.is_finite() {
                        return Err(
                            ctx.err(format!("{el}.normalTexture.scale"), "non-finite value")
                        );
                    }
                    normal_scale = nt.scale;
                    texture_index(
                        ctx,
                        b,
                        nt.index.value(),
                        nt.tex_coord,
                        TextureUsage::Data,
                        format!("{el}.normalTexture"),
                    )?
                }
                (Some(nt), false) if nt.tex_coord != 0 => {
                    b.warn(format!(
                        "{el}.normalTexture: texCoord {} is not supported (TEXCOORD_0 only); texture ignored",
                        nt.tex_coord
                    ));
                    None
                }
                _ => None,
            };
            // KHR_materials_specular: the scalar factor scales the dielectric F0 (0.04); the
            // coloured factor and the textures are not supported.
            let mut specular_factor = 1.0;
            if let Some(spec) = m.extensions.as_ref().and_then(|e| e.specular.as_ref()) {
                let sel = format!("{el}.extensions.KHR_materials_specular");
                specular_factor = unit_factor(ctx, spec.specular_factor.0, format!("{sel}.specularFactor"))?;
                if spec.specular_texture.is_some() || spec.specular_color_texture.is_some() {
                    b.warn(format!("{sel}: specular textures are not supported; the factor alone is used"));
                }
                if spec.specular_color_factor.0 != [1.0; 3] {
                    b.warn(format!("{sel}.specularColorFactor: coloured specular is not supported; treated as white"));
                }
            }
            let emissive = emitted_radiance(ctx, m, &el)?;
            // A texture cannot make a zero factor emit: decode it only when it can show.
            let emissive_texture = match &m.emissive_texture {
                Some(info) if emissive.iter().any(|&e| e > 0.0) => texture_index(
                    ctx,
                    b,
                    info.index.value(),
                    info.tex_coord,
                    TextureUsage::Color,
                    format!("{el}.emissiveTexture"),
                )?,
                _ => None,
            };
            if !matches!(
                m.alpha_mode,
                Checked::Valid(json::material::AlphaMode::Opaque)
            ) {
                b.warn(format!(
                    "{el}: alphaMode other than OPAQUE is not supported; rendered opaque"
                ));
            }
            Material {
                name: m.name.clone().unwrap_or_else(|| el.clone()),
                base_color_factor: bcf.map(|c| c.clamp(0.0, 1.0)),
                metallic_factor: metallic,
                roughness_factor: roughness,
                base_color_texture,
                metallic_roughness_texture,
                normal_texture,
                normal_scale,
                specular_factor,
                emissive,
                emissive_texture,
            }
        }
    };
    b.scene.materials.push(material);
    let s = b.scene.materials.len() - 1;
    b.material_map.insert(key, s);
    Ok(s)
}
