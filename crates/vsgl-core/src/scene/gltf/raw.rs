//! The few glTF values the `gltf` crate's data model reads too coarsely or not at all, read
//! from the same JSON a second time:
//!
//! - node transforms (`matrix`, `translation`, `rotation`, `scale`) in f64. The crate stores
//!   them as f32, which rounds a node 1e5 m from the origin to 8 mm: a camera or light node
//!   there moves, and a file renders differently from the same file at the origin, where
//!   the same move through the API (f64 throughout) does not.
//! - `KHR_texture_transform` on every texture reference of a material. The crate has it on
//!   `textureInfo` only behind a feature, and not on `normalTexture` at all.
//!
//! Everything else in the document is skipped by serde without being stored, so this pass
//! costs no memory beyond the values it keeps.

use serde::Deserialize;

/// A node's transform as written in the file, f64.
#[derive(Debug, Default, Deserialize)]
#[serde(default)]
pub(super) struct RawNode {
    pub matrix: Option<[f64; 16]>,
    pub translation: Option<[f64; 3]>,
    pub rotation: Option<[f64; 4]>,
    pub scale: Option<[f64; 3]>,
}

/// `KHR_texture_transform` (glTF extension registry): offset, rotation (radians,
/// counter-clockwise in UV space) and scale of one texture reference, and the optional
/// `texCoord` override.
#[derive(Clone, Debug, Default, Deserialize, PartialEq)]
#[serde(default, rename_all = "camelCase")]
pub(super) struct RawTextureTransform {
    pub offset: Option<[f64; 2]>,
    pub rotation: Option<f64>,
    pub scale: Option<[f64; 2]>,
    pub tex_coord: Option<u32>,
}

#[derive(Debug, Default, Deserialize)]
#[serde(default)]
struct RawTextureExtensions {
    #[serde(rename = "KHR_texture_transform")]
    texture_transform: Option<RawTextureTransform>,
}

#[derive(Debug, Default, Deserialize)]
#[serde(default)]
struct RawTextureInfo {
    extensions: Option<RawTextureExtensions>,
}

impl RawTextureInfo {
    fn transform(info: &Option<Self>) -> Option<&RawTextureTransform> {
        info.as_ref()?.extensions.as_ref()?.texture_transform.as_ref()
    }
}

#[derive(Debug, Default, Deserialize)]
#[serde(default, rename_all = "camelCase")]
struct RawPbr {
    base_color_texture: Option<RawTextureInfo>,
    metallic_roughness_texture: Option<RawTextureInfo>,
}

/// The texture references of one material, for their `KHR_texture_transform`s.
#[derive(Debug, Default, Deserialize)]
#[serde(default, rename_all = "camelCase")]
pub(super) struct RawMaterial {
    pbr_metallic_roughness: Option<RawPbr>,
    normal_texture: Option<RawTextureInfo>,
    emissive_texture: Option<RawTextureInfo>,
}

impl RawMaterial {
    pub fn base_color_transform(&self) -> Option<&RawTextureTransform> {
        RawTextureInfo::transform(&self.pbr_metallic_roughness.as_ref()?.base_color_texture)
    }
    pub fn metallic_roughness_transform(&self) -> Option<&RawTextureTransform> {
        RawTextureInfo::transform(&self.pbr_metallic_roughness.as_ref()?.metallic_roughness_texture)
    }
    pub fn normal_transform(&self) -> Option<&RawTextureTransform> {
        RawTextureInfo::transform(&self.normal_texture)
    }
    pub fn emissive_transform(&self) -> Option<&RawTextureTransform> {
        RawTextureInfo::transform(&self.emissive_texture)
    }
}

/// The part of the document this module reads.
#[derive(Debug, Default, Deserialize)]
#[serde(default)]
pub(super) struct RawRoot {
    pub nodes: Vec<RawNode>,
    pub materials: Vec<RawMaterial>,
}

/// Reads the f64 node transforms and the texture transforms from the glTF JSON.
pub(super) fn parse(json: &[u8]) -> Result<RawRoot, serde_json::Error> {
    serde_json::from_slice(json)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_translation_keeps_the_digits_f32_loses() {
        let root = parse(br#"{"asset": {"version": "2.0"}, "nodes": [{"translation": [100000.3, 0, -99999.7]}, {}]}"#).unwrap();
        assert_eq!(root.nodes[0].translation, Some([100000.3, 0.0, -99999.7]));
        assert_ne!(f64::from(100000.3f32), 100000.3);
        assert!(root.nodes[1].translation.is_none());
    }

    #[test]
    fn texture_transforms_are_read_from_every_slot() {
        let t = r#"{"extensions": {"KHR_texture_transform": {"offset": [0.5, 0], "rotation": 1.5, "scale": [2, 3], "texCoord": 0}}}"#;
        let doc = format!(
            r#"{{"materials": [{{"pbrMetallicRoughness": {{"baseColorTexture": {t}, "metallicRoughnessTexture": {{"index": 0}}}},
                "normalTexture": {t}, "emissiveTexture": {t}}}, {{}}]}}"#
        );
        let root = parse(doc.as_bytes()).unwrap();
        let want = RawTextureTransform { offset: Some([0.5, 0.0]), rotation: Some(1.5), scale: Some([2.0, 3.0]), tex_coord: Some(0) };
        let m = &root.materials[0];
        assert_eq!(m.base_color_transform(), Some(&want));
        assert_eq!(m.normal_transform(), Some(&want));
        assert_eq!(m.emissive_transform(), Some(&want));
        assert_eq!(m.metallic_roughness_transform(), None);
        assert_eq!(root.materials[1].base_color_transform(), None);
    }
}
