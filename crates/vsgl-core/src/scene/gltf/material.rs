//! Materials: glTF metallic-roughness materials (with the KHR_materials_specular factor and
//! emission: emissiveFactor, emissiveTexture, KHR_materials_emissive_strength) become scene
//! materials, one per (glTF material, normal map kept) pair; unsupported
//! features are skipped with a warning.

use gltf::json;
use json::validation::Checked;

use super::image::texture_index;
use super::raw::RawTextureTransform;
use super::{finite_all, Builder, Ctx};
use crate::error::Result;
use crate::scene::{limits, Material, TextureUsage, UvTransform};

/// The `KHR_texture_transform` of the texture reference `el` (identity without one) and the
/// texture coordinate set it reads: the extension's `texCoord` overrides the reference's.
fn uv_transform(ctx: &Ctx, transform: Option<&RawTextureTransform>, tex_coord: u32, el: &str) -> Result<(UvTransform, u32)> {
    let Some(t) = transform else { return Ok((UvTransform::IDENTITY, tex_coord)) };
    let tel = format!("{el}.extensions.KHR_texture_transform");
    let offset = t.offset.unwrap_or([0.0, 0.0]);
    let rotation = t.rotation.unwrap_or(0.0);
    let scale = t.scale.unwrap_or([1.0, 1.0]);
    for (name, values) in [("offset", &offset[..]), ("rotation", &[rotation][..]), ("scale", &scale[..])] {
        if !values.iter().all(|v| v.is_finite() && v.abs() <= f64::from(f32::MAX)) {
            return Err(ctx.err(format!("{tel}.{name}"), format!("must be finite (f32 range), got {values:?}")));
        }
    }
    let m = UvTransform::from_offset_rotation_scale(offset, rotation, scale);
    if !m.rows.iter().flatten().all(|v| v.is_finite()) {
        return Err(ctx.err(tel, "the transform overflows f32"));
    }
    Ok((m, t.tex_coord.unwrap_or(tex_coord)))
}

fn unit_factor(ctx: &Ctx, v: f32, element: String) -> Result<f32> {
    if !v.is_finite() {
        return Err(ctx.err(element, "non-finite value"));
    }
    Ok(v.clamp(0.0, 1.0))
}

/// The material's emitted radiance L_e = emissiveFactor × emissiveStrength (linear RGB, the
/// image's radiance units; docs/scenes.md, "Emission"). The factor is clamped to 0…1 like
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
            let raw = ctx.raw.materials.get(g);
            let bel = format!("{el}.pbrMetallicRoughness.baseColorTexture");
            let (base_color_uv, base_color_set) =
                uv_transform(ctx, raw.and_then(|r| r.base_color_transform()), pbr.base_color_texture.as_ref().map_or(0, |i| i.tex_coord), &bel)?;
            let base_color_texture = match &pbr.base_color_texture {
                Some(info) => texture_index(ctx, b, info.index.value(), base_color_set, TextureUsage::Color, bel)?,
                None => None,
            };
            let mel = format!("{el}.pbrMetallicRoughness.metallicRoughnessTexture");
            let (metallic_roughness_uv, metallic_roughness_set) = uv_transform(
                ctx,
                raw.and_then(|r| r.metallic_roughness_transform()),
                pbr.metallic_roughness_texture.as_ref().map_or(0, |i| i.tex_coord),
                &mel,
            )?;
            let metallic_roughness_texture = match &pbr.metallic_roughness_texture {
                Some(info) => texture_index(ctx, b, info.index.value(), metallic_roughness_set, TextureUsage::Data, mel)?,
                None => None,
            };
            let mut normal_scale = 1.0;
            let nel = format!("{el}.normalTexture");
            let (normal_uv, normal_set) =
                uv_transform(ctx, raw.and_then(|r| r.normal_transform()), m.normal_texture.as_ref().map_or(0, |n| n.tex_coord), &nel)?;
            let normal_texture = match (&m.normal_texture, keep_normal_map) {
                (Some(nt), true) => {
                    if !nt.scale.is_finite() {
                        return Err(
                            ctx.err(format!("{el}.normalTexture.scale"), "non-finite value")
                        );
                    }
                    normal_scale = nt.scale;
                    texture_index(ctx, b, nt.index.value(), normal_set, TextureUsage::Data, nel)?
                }
                (Some(_), false) if normal_set != 0 => {
                    b.warn(format!(
                        "{nel}: texCoord {normal_set} is not supported (TEXCOORD_0 only); texture ignored"
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
            let eel = format!("{el}.emissiveTexture");
            let (emissive_uv, emissive_set) =
                uv_transform(ctx, raw.and_then(|r| r.emissive_transform()), m.emissive_texture.as_ref().map_or(0, |i| i.tex_coord), &eel)?;
            let emissive_texture = match &m.emissive_texture {
                Some(info) if emissive.iter().any(|&e| e > 0.0) => {
                    texture_index(ctx, b, info.index.value(), emissive_set, TextureUsage::Color, eel)?
                }
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
                base_color_uv,
                metallic_roughness_uv,
                normal_uv,
                emissive_uv,
            }
        }
    };
    b.scene.materials.push(material);
    let s = b.scene.materials.len() - 1;
    b.material_map.insert(key, s);
    Ok(s)
}
