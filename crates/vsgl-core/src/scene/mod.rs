//! CPU-side scene: meshes, materials, textures, node hierarchy, lights and cameras.
//!
//! The scene is plain data. Everything the GPU needs is derived from it per frame (see
//! `crate::upload`), so moving a node with [`Scene::set_transform`] invalidates nothing that
//! was precomputed: the papers' scenes are fully dynamic.

pub mod animation;
pub mod builtin;
pub mod gltf;
mod light;
pub mod limits;

pub use light::{DirectionalLight, EmitterLight, Light, PointLight, SpotLight};

use std::collections::BTreeMap;

use animation::{Animation, LightAttachment, Trs};
use glam::{DMat4, DVec3};

/// One triangle list with one material. Attributes are in the mesh's local space.
#[derive(Clone, Debug, Default)]
pub struct Primitive {
    pub positions: Vec<[f32; 3]>,
    /// Per-vertex normals; generated (area-weighted) when the file has none.
    pub normals: Vec<[f32; 3]>,
    /// UV0; empty when the primitive has no texture coordinates.
    pub uvs: Vec<[f32; 2]>,
    /// xyz tangent + w bitangent sign; empty unless a normal map needs them.
    pub tangents: Vec<[f32; 4]>,
    /// Triangle list indices (always present: non-indexed primitives get 0..n).
    pub indices: Vec<u32>,
    /// Index into [`Scene::materials`].
    pub material: usize,
}

#[derive(Clone, Debug, Default)]
pub struct Mesh {
    pub name: String,
    pub primitives: Vec<Primitive>,
}

/// Which data a texture holds decides its colour space on the GPU.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TextureUsage {
    /// sRGB-encoded colour (baseColor).
    Color,
    /// Linear data (metallicRoughness, normal maps).
    Data,
}

/// A decoded RGBA8 image.
#[derive(Clone, Debug)]
pub struct Texture {
    pub name: String,
    pub width: u32,
    pub height: u32,
    pub rgba8: Vec<u8>,
    pub usage: TextureUsage,
}

/// The texture-coordinate transform of one texture reference (`KHR_texture_transform`):
/// uv' = M·(u, v, 1) with M = T·R·S, the extension's translation, rotation and scale matrices
/// (offset o, rotation θ counter-clockwise in UV space, scale s):
/// M = [[s_u cos θ, s_v sin θ, o_u], [−s_u sin θ, s_v cos θ, o_v]].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UvTransform {
    /// The two rows of M.
    pub rows: [[f32; 3]; 2],
}

impl Default for UvTransform {
    fn default() -> Self {
        Self::IDENTITY
    }
}

impl UvTransform {
    pub const IDENTITY: Self = Self { rows: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]] };

    /// M = T·R·S of `KHR_texture_transform` (composed in f64, stored in f32).
    pub fn from_offset_rotation_scale(offset: [f64; 2], rotation: f64, scale: [f64; 2]) -> Self {
        let (sin, cos) = rotation.sin_cos();
        Self {
            rows: [
                [(scale[0] * cos) as f32, (scale[1] * sin) as f32, offset[0] as f32],
                [(-scale[0] * sin) as f32, (scale[1] * cos) as f32, offset[1] as f32],
            ],
        }
    }

    /// The transformed coordinates of `uv`.
    pub fn apply(&self, uv: [f32; 2]) -> [f32; 2] {
        let [a, b] = self.rows;
        [a[0] * uv[0] + a[1] * uv[1] + a[2], b[0] * uv[0] + b[1] * uv[1] + b[2]]
    }
}

/// glTF metallic-roughness material (docs/scenes.md, "Materials").
#[derive(Clone, Debug)]
pub struct Material {
    pub name: String,
    pub base_color_factor: [f32; 4],
    pub metallic_factor: f32,
    pub roughness_factor: f32,
    /// Indices into [`Scene::textures`].
    pub base_color_texture: Option<usize>,
    /// glTF packs roughness in G and metallic in B.
    pub metallic_roughness_texture: Option<usize>,
    pub normal_texture: Option<usize>,
    pub normal_scale: f32,
    /// Strength of the dielectric specular reflection (`KHR_materials_specular`
    /// `specularFactor`, 0…1): R_s = mix(0.04·specular_factor, base, metallic). 0 with
    /// metallic 0 is a purely Lambertian material.
    pub specular_factor: f32,
    /// Emitted radiance L_e (linear RGB, the image's radiance units): glTF `emissiveFactor`
    /// × `KHR_materials_emissive_strength`, times the emissive texture where there is one.
    /// Seen by the camera only: an emissive surface lights no other surface (docs/scenes.md,
    /// "Emission").
    pub emissive: [f32; 3],
    /// sRGB colour texture that multiplies `emissive` (index into [`Scene::textures`]).
    pub emissive_texture: Option<usize>,
    /// `KHR_texture_transform` of each texture reference (identity without one).
    pub base_color_uv: UvTransform,
    pub metallic_roughness_uv: UvTransform,
    pub normal_uv: UvTransform,
    pub emissive_uv: UvTransform,
}

impl Default for Material {
    fn default() -> Self {
        // glTF 2.0 default material (spec §3.9.2: base colour 1, metallic 1, roughness 1).
        Self {
            name: "default".into(),
            base_color_factor: [1.0; 4],
            metallic_factor: 1.0,
            roughness_factor: 1.0,
            base_color_texture: None,
            metallic_roughness_texture: None,
            normal_texture: None,
            normal_scale: 1.0,
            specular_factor: 1.0,
            emissive: [0.0; 3],
            emissive_texture: None,
            base_color_uv: UvTransform::IDENTITY,
            metallic_roughness_uv: UvTransform::IDENTITY,
            normal_uv: UvTransform::IDENTITY,
            emissive_uv: UvTransform::IDENTITY,
        }
    }
}

impl Material {
    /// A dielectric (metallic 0) material with the given diffuse colour and roughness.
    pub fn dielectric(name: &str, color: [f32; 3], roughness: f32) -> Self {
        Self {
            name: name.into(),
            base_color_factor: [color[0], color[1], color[2], 1.0],
            metallic_factor: 0.0,
            roughness_factor: roughness,
            ..Default::default()
        }
    }
    /// A purely Lambertian material (metallic 0, specular factor 0): R_s = 0.
    pub fn lambertian(name: &str, color: [f32; 3]) -> Self {
        Self { specular_factor: 0.0, ..Self::dielectric(name, color, 1.0) }
    }
    /// Whether this material reflects specularly anywhere (R_s > 0 for some texel).
    pub fn has_specular(&self) -> bool {
        self.metallic_factor > 0.0 || self.specular_factor > 0.0
    }
    /// A metal (metallic 1) material: Rs = base colour, Rd = 0.
    pub fn metal(name: &str, color: [f32; 3], roughness: f32) -> Self {
        Self {
            name: name.into(),
            base_color_factor: [color[0], color[1], color[2], 1.0],
            metallic_factor: 1.0,
            roughness_factor: roughness,
            ..Default::default()
        }
    }
    /// Whether any texture is bound to this material.
    pub fn has_texture(&self) -> bool {
        self.base_color_texture.is_some()
            || self.metallic_roughness_texture.is_some()
            || self.normal_texture.is_some()
            || self.emissive_texture.is_some()
    }
    /// Whether this material emits light anywhere (a texture cannot make a zero factor emit).
    pub fn has_emission(&self) -> bool {
        self.emissive.iter().any(|&e| e > 0.0)
    }
}

/// A node of the hierarchy. World transforms are composed on demand.
#[derive(Clone, Debug)]
pub struct Node {
    pub name: String,
    pub local: DMat4,
    pub parent: Option<usize>,
    pub mesh: Option<usize>,
}

/// A perspective pinhole camera.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    pub eye: DVec3,
    /// Unit viewing direction.
    pub forward: DVec3,
    /// Unit up vector, orthogonal to `forward`.
    pub up: DVec3,
    /// Vertical field of view in radians.
    pub fov_y: f32,
}

impl Camera {
    /// A camera at `eye` looking at `target`; `up` need not be orthogonal to the view.
    /// Positions beyond ±[`limits::MAX_COORDINATE`] are refused with that cause, and every
    /// vector is normalised without overflow.
    pub fn look_at(eye: DVec3, target: DVec3, up: DVec3, fov_y: f32) -> Result<Self, String> {
        let eye = limits::position("eye", eye).map_err(|e| e.to_string())?;
        let target = limits::position("target", target).map_err(|e| e.to_string())?;
        let forward = target - eye;
        if !(forward.length() > 0.0) {
            return Err("eye and target must differ".into());
        }
        let forward = forward.normalize();
        let up = limits::unit_direction("up", up).map_err(|e| e.to_string())?;
        let right = forward.cross(up);
        if !(right.length() > 1e-9) || !right.is_finite() {
            return Err("up must not be parallel to the viewing direction".into());
        }
        let up = right.normalize().cross(forward);
        Ok(Self { eye, forward, up, fov_y })
    }
}

/// Axis-aligned bounds in world space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bounds {
    pub min: DVec3,
    pub max: DVec3,
}

impl Bounds {
    pub fn empty() -> Self {
        Self { min: DVec3::splat(f64::INFINITY), max: DVec3::splat(f64::NEG_INFINITY) }
    }
    pub fn is_empty(&self) -> bool {
        !(self.min.x <= self.max.x)
    }
    pub fn grow(&mut self, p: DVec3) {
        self.min = self.min.min(p);
        self.max = self.max.max(p);
    }
    pub fn center(&self) -> DVec3 {
        0.5 * (self.min + self.max)
    }
    pub fn diagonal(&self) -> f64 {
        if self.is_empty() { 0.0 } else { (self.max - self.min).length() }
    }
}

/// A whole scene: what `vsgl.Scene` wraps.
#[derive(Clone, Debug, Default)]
pub struct Scene {
    /// Where the scene came from (file path or built-in name), for messages.
    pub source: String,
    pub meshes: Vec<Mesh>,
    pub materials: Vec<Material>,
    pub textures: Vec<Texture>,
    pub nodes: Vec<Node>,
    pub lights: Vec<Light>,
    pub cameras: Vec<Camera>,
    /// Human-readable notes from loading (skipped primitives, unsupported features).
    pub warnings: Vec<String>,
    /// Which scene instance this is, for the renderer's upload cache (a clone is another
    /// instance: it gets a new id, see [`SceneId`]).
    pub id: SceneId,
    /// Bumped by every change to what [`crate::upload::GpuScene`] reads (nodes, meshes,
    /// materials, textures), so the renderer knows when its uploaded copy is stale. Lights and
    /// cameras are read anew every frame and do not bump it. Code that edits those fields
    /// directly, not through the methods below, must bump it too.
    pub geometry_version: u64,
    /// Keyframed node animations (glTF `animations`, or a built-in's), played by
    /// [`Scene::set_time`].
    pub animations: Vec<Animation>,
    /// The rest pose of every node an animation targets: [`Scene::set_time`] starts each from
    /// here, so a channel that drives only the rotation keeps the file's translation and scale.
    pub rest_poses: BTreeMap<usize, Trs>,
    /// Lights that sit on nodes (KHR_lights_punctual): they follow their node when
    /// [`Scene::set_transform`] or [`Scene::set_time`] moves it, until the lights are replaced
    /// ([`Scene::set_lights`]).
    pub light_attachments: Vec<LightAttachment>,
}

/// Identity of one [`Scene`] value: unique in the process, and a clone gets a fresh one, so
/// two copies edited apart can never share an (id, geometry_version) key in the upload cache.
#[derive(Debug, PartialEq, Eq, Hash)]
pub struct SceneId(u64);

impl SceneId {
    fn fresh() -> Self {
        static NEXT: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(1);
        Self(NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed))
    }

    pub fn get(&self) -> u64 {
        self.0
    }
}

impl Default for SceneId {
    fn default() -> Self {
        Self::fresh()
    }
}

impl Clone for SceneId {
    fn clone(&self) -> Self {
        Self::fresh()
    }
}

impl Scene {
    /// World transform of node `i` (parents composed, root first).
    pub fn world_transform(&self, mut i: usize) -> DMat4 {
        let mut m = self.nodes[i].local;
        let mut guard = 0;
        while let Some(p) = self.nodes[i].parent {
            m = self.nodes[p].local * m;
            i = p;
            guard += 1;
            if guard > self.nodes.len() {
                break; // cycles are rejected by the loader; never loop forever anyway
            }
        }
        m
    }

    /// Replaces the local transform of every node called `name`; returns how many matched.
    pub fn set_transform(&mut self, name: &str, local: DMat4) -> usize {
        let mut n = 0;
        for node in self.nodes.iter_mut().filter(|n| n.name == name) {
            node.local = local;
            n += 1;
        }
        if n > 0 {
            self.geometry_version += 1;
            self.update_attached_lights();
        }
        n
    }

    /// Poses every animated node at time `t` seconds: each animation is sampled at `t`
    /// clamped to its own [0, duration], starting from the nodes' rest poses. Bumps the
    /// geometry version only when an animated node carries a mesh below it (a light-only
    /// animation keeps the uploaded scene, like a moved light), and moves the lights attached
    /// to nodes. A pose that would take geometry beyond ±[`limits::MAX_COORDINATE`] is
    /// refused and nothing changes.
    pub fn set_time(&mut self, t: f64) -> crate::error::Result<()> {
        if !t.is_finite() {
            return Err(crate::error::Error::invalid("t", format!("time must be a finite number of seconds, got {t}")));
        }
        if self.animations.is_empty() {
            return Ok(());
        }
        let mut pose = self.rest_poses.clone();
        for a in &self.animations {
            let ta = t.clamp(0.0, a.duration());
            for c in &a.channels {
                let trs = pose.entry(c.node).or_default();
                trs.set(c.property, c.sample(ta));
            }
        }
        let before: Vec<(usize, DMat4)> =
            pose.keys().filter_map(|&i| self.nodes.get(i).map(|n| (i, n.local))).collect();
        for (&i, trs) in &pose {
            if let Some(n) = self.nodes.get_mut(i) {
                n.local = trs.matrix();
            }
        }
        let moves_geometry = self.any_mesh_below(pose.keys().copied());
        if moves_geometry {
            let b = self.bounds();
            let max = limits::MAX_COORDINATE;
            if !b.is_empty() && (!b.min.is_finite() || !b.max.is_finite() || b.min.abs().max(b.max.abs()).max_element() > max) {
                for (i, local) in before {
                    self.nodes[i].local = local;
                }
                return Err(crate::error::Error::invalid("t", format!(
                    "at time {t} the animation moves the geometry to {:?} .. {:?}, beyond ±{max:e} m \
                     (squared distances are formed in f32); the pose was not applied",
                    b.min.to_array(), b.max.to_array()
                )));
            }
            self.geometry_version += 1;
        }
        self.update_attached_lights();
        Ok(())
    }

    /// Whether a node with a mesh has one of `moved` as itself or an ancestor.
    fn any_mesh_below(&self, moved: impl Iterator<Item = usize>) -> bool {
        let mut is_moved = vec![false; self.nodes.len()];
        for i in moved {
            if let Some(m) = is_moved.get_mut(i) {
                *m = true;
            }
        }
        self.nodes.iter().enumerate().any(|(i, node)| {
            if node.mesh.is_none() {
                return false;
            }
            let (mut cur, mut guard) = (Some(i), 0);
            while let Some(c) = cur {
                if is_moved[c] {
                    return true;
                }
                cur = self.nodes[c].parent;
                guard += 1;
                if guard > self.nodes.len() {
                    break; // cycles are rejected by the loader; never loop forever anyway
                }
            }
            false
        })
    }

    /// Puts light `light` on node `node`: from now on it sits at the node's world origin and
    /// points along its world −Z whenever the node moves.
    pub fn attach_light(&mut self, light: usize, node: usize) {
        self.light_attachments.push(LightAttachment { light, node });
    }

    /// Replaces every light; the new lights sit on no node.
    pub fn set_lights(&mut self, lights: Vec<Light>) {
        self.lights = lights;
        self.light_attachments.clear();
    }

    /// Moves every attached light to its node's world transform. A transform that has no
    /// direction (a zero scale) or lies beyond the coordinate bound leaves the light where it
    /// was: a light cannot be placed there, and hiding it would change the scene's light count.
    pub fn update_attached_lights(&mut self) {
        for k in 0..self.light_attachments.len() {
            let LightAttachment { light, node } = self.light_attachments[k];
            if node >= self.nodes.len() {
                continue;
            }
            let world = self.world_transform(node);
            let position = world.transform_point3(DVec3::ZERO);
            let direction = world.transform_vector3(DVec3::NEG_Z);
            let len = direction.length();
            let placeable = position.is_finite()
                && position.abs().max_element() <= limits::MAX_COORDINATE
                && len.is_finite()
                && len > 1e-12;
            if !placeable {
                continue;
            }
            let direction = direction / len;
            match self.lights.get_mut(light) {
                Some(Light::Spot(s)) => {
                    s.position = position;
                    s.direction = direction;
                }
                Some(Light::Point(p)) => p.position = position,
                Some(Light::Directional(d)) => d.direction = direction,
                // Emitter clusters are made per frame from the meshes, never attached.
                Some(Light::Emitter(_)) | None => {}
            }
        }
    }

    /// Applies `edit` to every material called `name`; returns how many matched. Materials
    /// are part of the upload, so an edit re-uploads the scene at the next frame.
    pub fn edit_materials(&mut self, name: &str, edit: impl Fn(&mut Material)) -> usize {
        let mut n = 0;
        for m in self.materials.iter_mut().filter(|m| m.name == name) {
            edit(m);
            n += 1;
        }
        if n > 0 {
            self.geometry_version += 1;
        }
        n
    }

    pub fn add_light(&mut self, light: impl Into<Light>) {
        self.lights.push(light.into());
    }

    /// Adds a mesh instanced by a new root node; returns the node index.
    pub fn add_mesh_node(&mut self, name: &str, mesh: Mesh, local: DMat4) -> usize {
        self.meshes.push(mesh);
        self.nodes.push(Node { name: name.into(), local, parent: None, mesh: Some(self.meshes.len() - 1) });
        self.geometry_version += 1;
        self.nodes.len() - 1
    }

    /// World-space bounds of every instanced triangle vertex.
    pub fn bounds(&self) -> Bounds {
        let mut b = Bounds::empty();
        for (i, node) in self.nodes.iter().enumerate() {
            let Some(m) = node.mesh else { continue };
            let w = self.world_transform(i);
            for p in &self.meshes[m].primitives {
                for v in &p.positions {
                    b.grow(w.transform_point3(DVec3::new(v[0] as f64, v[1] as f64, v[2] as f64)));
                }
            }
        }
        b
    }

    pub fn stats(&self) -> SceneStats {
        let mut triangles = 0usize;
        for node in &self.nodes {
            if let Some(m) = node.mesh {
                triangles += self.meshes[m].primitives.iter().map(|p| p.indices.len() / 3).sum::<usize>();
            }
        }
        let used: Vec<&Material> = self
            .nodes
            .iter()
            .filter_map(|n| n.mesh)
            .flat_map(|m| self.meshes[m].primitives.iter().map(|p| &self.materials[p.material]))
            .collect();
        SceneStats {
            triangles,
            meshes: self.meshes.len(),
            materials: self.materials.len(),
            textures: self.textures.len(),
            lights: self.lights.len(),
            has_textures: used.iter().any(|m| m.has_texture()),
            has_normal_maps: used.iter().any(|m| m.normal_texture.is_some()),
            has_metallic: used.iter().any(|m| m.metallic_factor > 0.0),
            has_specular: used.iter().any(|m| m.has_specular()),
            has_diffuse: used.iter().any(|m| m.metallic_factor < 1.0 || m.metallic_roughness_texture.is_some()),
            has_emission: used.iter().any(|m| m.has_emission()),
        }
    }
}

/// What `scene.stats` reports.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SceneStats {
    pub triangles: usize,
    pub meshes: usize,
    pub materials: usize,
    pub textures: usize,
    pub lights: usize,
    pub has_textures: bool,
    pub has_normal_maps: bool,
    pub has_metallic: bool,
    /// Some used material has R_s > 0 (metallic > 0 or a non-zero dielectric specular).
    pub has_specular: bool,
    pub has_diffuse: bool,
    /// Some used material emits light (L_e > 0): the camera's G-buffer gets an emission channel.
    pub has_emission: bool,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_scene_value_has_its_own_id_and_geometry_edits_bump_the_version() {
        let a = builtin::cornell_box();
        let b = builtin::cornell_box();
        assert_ne!(a.id, b.id, "two scenes built apart share an id");
        let mut c = a.clone();
        assert_ne!(a.id, c.id, "a clone shares its original's id: editing either would alias the upload cache");
        let v = c.geometry_version;
        c.add_light(a.lights[0]);
        assert_eq!(c.geometry_version, v, "lights are read every frame; they must not force a re-upload");
        assert_eq!(c.set_transform("short_block", DMat4::IDENTITY), 1);
        assert_eq!(c.geometry_version, v + 1);
        assert_eq!(c.set_transform("no such node", DMat4::IDENTITY), 0);
        assert_eq!(c.geometry_version, v + 1);
    }

    #[test]
    fn a_pose_beyond_the_coordinate_bound_is_refused_and_changes_nothing() {
        use animation::{AnimatedProperty, Channel, Interpolation, Keyframes};
        let mut s = builtin::cornell_box();
        let node = s.nodes.iter().position(|n| n.name == "short_block").unwrap();
        let keys = Keyframes::new(vec![0.0, 1.0], vec![0.0, 0.0, 0.0, 1e19, 0.0, 0.0], 3, Interpolation::Linear).unwrap();
        s.rest_poses.insert(node, Trs::default());
        s.animations.push(Animation { name: "away".into(), channels: vec![Channel { node, property: AnimatedProperty::Translation, keys }] });
        s.set_time(0.0).unwrap();
        let (local, version) = (s.nodes[node].local, s.geometry_version);
        let e = s.set_time(1.0).unwrap_err().to_string();
        assert!(e.contains("beyond ±1e18"), "{e}");
        assert_eq!((s.nodes[node].local, s.geometry_version), (local, version));
        s.set_time(1e-19).unwrap(); // 1 m: fine
        assert_eq!(s.geometry_version, version + 1, "a moved mesh must be uploaded again");
    }
}
