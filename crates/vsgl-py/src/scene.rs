//! `vsgl.Scene` (glTF loading, edits, animation, the built-in scenes) and the argument
//! helpers only its methods use.

use crate::args::vec3;
use crate::args::{int_in_range, py_int};
use crate::camera::PyCamera;
use crate::errors::{argument_error, to_py};
use crate::lights::{light_to_py, AnyLight};
use glam::DMat4;
use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::sync::Arc;
use vsgl_core::scene::{builtin, limits, Light, Scene};

/// A scene: meshes, materials, textures, nodes, spot lights and cameras.
#[pyclass(name = "Scene", module = "vsgl")]
pub(crate) struct PyScene {
    /// Shared with the renders in flight: a render takes a snapshot (this Arc) and lets go of
    /// the Python object, so another thread may edit the scene meanwhile; an edit then copies
    /// the scene (`Arc::make_mut`) and the render finishes with the state it started from.
    pub(crate) inner: Arc<Scene>,
}

#[pymethods]
impl PyScene {
    /// Loads a glTF 2.0 file (`.gltf` or `.glb`). Raises `SceneError` naming the file and element.
    /// `max_texture_bytes` (default 512 MiB) bounds the decoded texture memory: an image that
    /// would take the scene's textures past it is refused (from its header, before decoding)
    /// with a `SceneError` naming it; raise the budget for trusted files with large textures.
    #[staticmethod]
    #[pyo3(signature = (path, *, max_texture_bytes=None))]
    fn load(py: Python<'_>, path: std::path::PathBuf, max_texture_bytes: Option<&Bound<'_, PyAny>>) -> PyResult<Self> {
        let mut options = vsgl_core::scene::gltf::LoadOptions::default();
        if let Some(v) = max_texture_bytes {
            options.max_texture_bytes = positive_bytes("max_texture_bytes", v)?;
        }
        let scene = py.detach(|| vsgl_core::scene::gltf::load_with(&path, &options)).map_err(to_py)?;
        Ok(Self { inner: Arc::new(scene) })
    }
    /// Triangle, mesh, material, texture and light counts and the features the scene uses;
    /// `emission`, when a material emits, says what emission does (shown, lights nothing).
    #[getter]
    fn stats<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let s = self.inner.stats();
        let d = PyDict::new(py);
        d.set_item("triangles", s.triangles)?;
        d.set_item("meshes", s.meshes)?;
        d.set_item("materials", s.materials)?;
        d.set_item("textures", s.textures)?;
        d.set_item("lights", s.lights)?;
        let by_type = PyDict::new(py);
        for (kind, n) in crate::lights::count_by_type(&self.inner.lights) {
            by_type.set_item(kind, n)?;
        }
        d.set_item("lights_by_type", by_type)?;
        d.set_item("cameras", self.inner.cameras.len())?;
        let mut features = Vec::new();
        if s.has_textures { features.push("textures"); }
        if s.has_normal_maps { features.push("normal_maps"); }
        if s.has_metallic { features.push("metallic"); }
        if s.has_specular { features.push("specular"); }
        if s.has_diffuse { features.push("diffuse"); }
        if s.has_emission { features.push("emissive"); }
        d.set_item("features", features)?;
        if s.has_emission {
            // How emission lights the scene, said once per scene.
            d.set_item(
                "emission",
                "emissive surfaces show with their emitted radiance and light the scene: as area lights in method=\"pathtrace\", as clusters of lights (option emitter_lights) in the other methods",
            )?;
        }
        Ok(d)
    }
    /// The materials as dicts: name, base_color (RGBA, linear), metallic, roughness, specular
    /// (the KHR_materials_specular factor), emissive (the emitted radiance L_e, linear RGB; 0 for
    /// a material that does not emit), which textures it has and, as uv_transforms, the
    /// KHR_texture_transform of each texture reference that has one (slot -> the two rows of
    /// the 2×3 matrix M, uv' = M·(u, v, 1)).
    #[getter]
    fn materials<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyDict>>> {
        self.inner.materials.iter().map(|m| {
            let d = PyDict::new(py);
            d.set_item("name", &m.name)?;
            d.set_item("base_color", m.base_color_factor.to_vec())?;
            d.set_item("metallic", m.metallic_factor)?;
            d.set_item("roughness", m.roughness_factor)?;
            d.set_item("specular", m.specular_factor)?;
            d.set_item("emissive", m.emissive.to_vec())?;
            let textures: Vec<&str> = [
                ("base_color", m.base_color_texture),
                ("metallic_roughness", m.metallic_roughness_texture),
                ("normal", m.normal_texture),
                ("emissive", m.emissive_texture),
            ].into_iter().filter(|(_, t)| t.is_some()).map(|(n, _)| n).collect();
            d.set_item("textures", textures)?;
            // KHR_texture_transform per texture reference, as the two rows of uv' = M·(u, v, 1);
            // only the references that have one.
            let uv = PyDict::new(py);
            for (slot, t) in [
                ("base_color", &m.base_color_uv),
                ("metallic_roughness", &m.metallic_roughness_uv),
                ("normal", &m.normal_uv),
                ("emissive", &m.emissive_uv),
            ] {
                if *t != vsgl_core::scene::UvTransform::IDENTITY {
                    uv.set_item(slot, t.rows.iter().map(|r| r.to_vec()).collect::<Vec<_>>())?;
                }
            }
            d.set_item("uv_transforms", uv)?;
            Ok(d)
        }).collect()
    }
    /// Edits every material called `name`: the factors given replace the material's own
    /// (`base_color`: 3 or 4 numbers in [0, 1]; `metallic`, `roughness` in [0, 1]; `emissive`:
    /// the emitted radiance L_e, 3 numbers >= 0, shown where the camera sees the surface but
    /// lighting nothing). Raises ArgumentError naming a bad value, or `name` when no material
    /// has it; nothing is changed then.
    #[pyo3(signature = (name, *, base_color=None, metallic=None, roughness=None, emissive=None))]
    fn set_material(
        &mut self,
        name: &str,
        #[pyo3(from_py_with = optional_floats)] base_color: Option<Vec<f64>>,
        #[pyo3(from_py_with = optional_float)] metallic: Option<f64>,
        #[pyo3(from_py_with = optional_float)] roughness: Option<f64>,
        #[pyo3(from_py_with = optional_floats)] emissive: Option<Vec<f64>>,
    ) -> PyResult<()> {
        let unit = |arg: &str, v: f64| -> PyResult<f32> {
            if (0.0..=1.0).contains(&v) { Ok(v as f32) } else { Err(argument_error(format!("{arg}: must be in [0, 1], got {v}"))) }
        };
        let base_color = match base_color {
            Some(c) if c.len() == 3 || c.len() == 4 => {
                let mut rgba = [1.0f32; 4];
                for (i, v) in c.iter().enumerate() {
                    rgba[i] = unit("base_color", *v)?;
                }
                Some(rgba)
            }
            Some(c) => return Err(argument_error(format!("base_color: expected 3 or 4 numbers, got {}", c.len()))),
            None => None,
        };
        let metallic = metallic.map(|v| unit("metallic", v)).transpose()?;
        let roughness = roughness.map(|v| unit("roughness", v)).transpose()?;
        let emissive = match emissive {
            Some(e) => {
                let e = vec3("emissive", e)?;
                let mut out = [0.0f32; 3];
                for (o, v) in out.iter_mut().zip(e.to_array()) {
                    *o = limits::emitted_radiance("emissive", v).map_err(to_py)?;
                }
                Some(out)
            }
            None => None,
        };
        if !self.inner.materials.iter().any(|m| m.name == name) {
            let names: Vec<&str> = self.inner.materials.iter().map(|m| m.name.as_str()).collect();
            return Err(argument_error(format!("name: no material named {name:?}; materials: {names:?}")));
        }
        Arc::make_mut(&mut self.inner).edit_materials(name, |m| {
            if let Some(c) = base_color { m.base_color_factor = c; }
            if let Some(v) = metallic { m.metallic_factor = v; }
            if let Some(v) = roughness { m.roughness_factor = v; }
            if let Some(e) = emissive { m.emissive = e; }
        });
        Ok(())
    }
    /// Adds a light: a SpotLight, PointLight or DirectionalLight.
    fn add_light(&mut self, light: AnyLight) {
        Arc::make_mut(&mut self.inner).add_light(Light::from(light));
    }
    /// Sets the local transform of every node called `node_name` to `matrix` (4×4, row-major as
    /// NumPy prints it: p' = M @ p). Raises ValueError when no node has that name.
    fn set_transform(&mut self, node_name: &str, matrix: Vec<Vec<f64>>) -> PyResult<()> {
        set_node_transform(Arc::make_mut(&mut self.inner), node_name, matrix, "matrix", "node_name")
    }
    /// The transform of the first node called `node_name` as a 4×4 row-major list (as
    /// `set_transform` takes it): its local transform, or with `world=True` its parents'
    /// composed with it. Raises ArgumentError when no node has that name.
    #[pyo3(signature = (node_name, *, world=false))]
    fn transform(&self, node_name: &str, world: bool) -> PyResult<Vec<Vec<f64>>> {
        let Some(i) = self.inner.nodes.iter().position(|n| n.name == node_name) else {
            let names: Vec<&str> = self.inner.nodes.iter().map(|n| n.name.as_str()).collect();
            return Err(argument_error(format!("node_name: no node named {node_name:?}; nodes: {names:?}")));
        };
        let m = if world { self.inner.world_transform(i) } else { self.inner.nodes[i].local };
        Ok((0..4).map(|r| m.row(r).to_array().to_vec()).collect())
    }
    #[getter]
    fn node_names(&self) -> Vec<String> {
        self.inner.nodes.iter().map(|n| n.name.clone()).collect()
    }
    /// The lights; assign a list to replace them all.
    #[getter]
    fn lights(&self, py: Python<'_>) -> PyResult<Vec<Py<PyAny>>> {
        self.inner.lights.iter().map(|l| light_to_py(py, l)).collect()
    }
    #[setter]
    fn set_lights(&mut self, lights: Vec<AnyLight>) {
        Arc::make_mut(&mut self.inner).set_lights(lights.into_iter().map(Light::from).collect());
    }
    /// The node animations (glTF `animations`, or a built-in's) as dicts: name, duration (the
    /// last keyframe time, seconds), channels (how many properties it drives), nodes (the names
    /// of the nodes it moves) and interpolations (the samplers' modes).
    #[getter]
    fn animations<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyDict>>> {
        self.inner.animations.iter().map(|a| {
            let d = PyDict::new(py);
            d.set_item("name", &a.name)?;
            d.set_item("duration", a.duration())?;
            d.set_item("channels", a.channels.len())?;
            let mut nodes: Vec<&str> = Vec::new();
            let mut modes: Vec<&str> = Vec::new();
            for c in &a.channels {
                let name = self.inner.nodes.get(c.node).map_or("", |n| n.name.as_str());
                if !nodes.contains(&name) { nodes.push(name); }
                let mode = c.keys.interpolation().name();
                if !modes.contains(&mode) { modes.push(mode); }
            }
            d.set_item("nodes", nodes)?;
            d.set_item("interpolations", modes)?;
            Ok(d)
        }).collect()
    }
    /// Poses every animated node at time `t` (seconds): each animation is sampled at `t`
    /// clamped to its own [0, duration] (rotations by shortest-arc slerp), lights on animated
    /// nodes follow, and moved geometry is uploaded again at the next render (as after
    /// `set_transform`). Without animations nothing changes. Raises ArgumentError for a time
    /// that is not finite, or a pose that moves geometry beyond ±1e18 m (nothing changes then).
    fn set_time(&mut self, #[pyo3(from_py_with = crate::args::float)] t: f64) -> PyResult<()> {
        Arc::make_mut(&mut self.inner).set_time(t).map_err(to_py)
    }
    /// The camera `render` uses when given `camera=None`: the file's first camera, else one
    /// that frames the scene's bounds from the front (+Z) and above. ArgumentError for a scene
    /// with neither cameras nor geometry.
    fn default_camera(&self) -> PyResult<PyCamera> {
        Ok(PyCamera { inner: vsgl_core::renderer::default_camera(&self.inner).map_err(to_py)? })
    }
    #[getter]
    fn cameras(&self) -> Vec<PyCamera> {
        self.inner.cameras.iter().map(|c| PyCamera { inner: *c }).collect()
    }
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.inner.warnings.clone()
    }
    #[getter]
    fn source(&self) -> String {
        self.inner.source.clone()
    }
    /// World-space bounds as ((min x, y, z), (max x, y, z)).
    #[getter]
    fn bounds(&self) -> ((f64, f64, f64), (f64, f64, f64)) {
        let b = self.inner.bounds();
        (b.min.into(), b.max.into())
    }
    /// Every triangle of the scene in world space at its current pose, for other renderers and
    /// checks: a dict of NumPy arrays, ``positions`` (T, 3, 3) float64, ``normals`` (T, 3, 3)
    /// float32 (the vertices' shading normals, by the inverse transpose, unit length),
    /// ``uvs`` (T, 3, 2) float32 (zeros where a primitive has none) and ``material`` (T,) int64,
    /// the index into ``materials``. Node order, then primitive, then index order.
    fn triangles<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let scene = &*self.inner;
        let (mut pos, mut nrm, mut uvs, mut mat) = (Vec::<f64>::new(), Vec::<f32>::new(), Vec::<f32>::new(), Vec::<i64>::new());
        for (i, node) in scene.nodes.iter().enumerate() {
            let Some(mesh) = node.mesh.and_then(|m| scene.meshes.get(m)) else { continue };
            let world = scene.world_transform(i);
            let normal_matrix = glam::DMat3::from_mat4(world).inverse().transpose();
            for prim in &mesh.primitives {
                for &k in &prim.indices {
                    let k = k as usize;
                    let p = prim.positions.get(k).copied().unwrap_or_default();
                    pos.extend(world.transform_point3(glam::DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64)).to_array());
                    let n = prim.normals.get(k).copied().unwrap_or_default();
                    let n = (normal_matrix * glam::DVec3::new(n[0] as f64, n[1] as f64, n[2] as f64)).normalize_or_zero();
                    nrm.extend(n.as_vec3().to_array());
                    uvs.extend(prim.uvs.get(k).copied().unwrap_or_default());
                }
                mat.extend(std::iter::repeat_n(prim.material as i64, prim.indices.len() / 3));
            }
        }
        let t = mat.len();
        let d = PyDict::new(py);
        d.set_item("positions", PyArray1::from_vec(py, pos).reshape([t, 3, 3])?)?;
        d.set_item("normals", PyArray1::from_vec(py, nrm).reshape([t, 3, 3])?)?;
        d.set_item("uvs", PyArray1::from_vec(py, uvs).reshape([t, 3, 2])?)?;
        d.set_item("material", PyArray1::from_vec(py, mat))?;
        Ok(d)
    }
    fn __repr__(&self) -> String {
        let s = self.inner.stats();
        format!("Scene({:?}, triangles={}, materials={}, lights={})", self.inner.source, s.triangles, s.materials, s.lights)
    }
}

/// An optional float keyword (`None` allowed), as `args::float` takes it.
pub(crate) fn optional_float(value: &Bound<'_, PyAny>) -> PyResult<Option<f64>> {
    if value.is_none() { Ok(None) } else { crate::args::float(value).map(Some) }
}

/// An optional list of floats (`None` allowed), as `args::floats` takes it.
pub(crate) fn optional_floats(value: &Bound<'_, PyAny>) -> PyResult<Option<Vec<f64>>> {
    if value.is_none() { Ok(None) } else { crate::args::floats(value).map(Some) }
}

/// A byte count given as a positive Python int (not a bool, not a float), below 2**64.
pub(crate) fn positive_bytes(name: &str, value: &Bound<'_, PyAny>) -> PyResult<u64> {
    if py_int(value).is_none() {
        return Err(argument_error(format!("{name}: expected a positive int (bytes), got {}", value.get_type().name()?)));
    }
    // In range by the check, so the conversion cannot fail.
    Ok(int_in_range(name, value, 1, u64::MAX as i128)? as u64)
}

/// Sets the local transform of every node called `node_name` (the checks of
/// `Scene.set_transform`; `what` names the matrix and `node_arg` the node in errors).
pub(crate) fn set_node_transform(scene: &mut Scene, node_name: &str, matrix: Vec<Vec<f64>>, what: &str, node_arg: &str) -> PyResult<()> {
    if matrix.len() != 4 || matrix.iter().any(|r| r.len() != 4) {
        return Err(argument_error(format!("{what}: expected a 4x4 matrix")));
    }
    if matrix.iter().flatten().any(|x| !x.is_finite()) {
        return Err(argument_error(format!("{what}: every entry must be finite")));
    }
    let rows: Vec<f64> = matrix.into_iter().flatten().collect();
    let m = DMat4::from_cols_slice(&rows).transpose();
    if m.determinant() == 0.0 {
        return Err(argument_error(format!("{what}: must be invertible")));
    }
    let before: Vec<(usize, DMat4)> = scene.nodes.iter().enumerate().filter(|(_, n)| n.name == node_name).map(|(i, n)| (i, n.local)).collect();
    if scene.set_transform(node_name, m) == 0 {
        let names: Vec<&str> = scene.nodes.iter().map(|n| n.name.as_str()).collect();
        return Err(argument_error(format!("{node_arg}: no node named {node_name:?}; nodes: {names:?}")));
    }
    // The geometry must stay where f32 distances are finite (scene::limits); else undo.
    let b = scene.bounds();
    if !b.is_empty() && (!b.min.is_finite() || !b.max.is_finite() || b.min.abs().max(b.max.abs()).max_element() > limits::MAX_COORDINATE) {
        for (i, local) in before {
            scene.nodes[i].local = local;
        }
        return Err(argument_error(format!(
            "{what}: moves the geometry to {:?} .. {:?}, beyond ±{:e} m (squared distances are formed in f32); the transform was not applied",
            b.min.to_array(), b.max.to_array(), limits::MAX_COORDINATE
        )));
    }
    Ok(())
}

/// Names of the built-in procedural scenes.
#[pyfunction]
pub(crate) fn builtin_scene_names() -> Vec<&'static str> {
    builtin::NAMES.to_vec()
}

/// A built-in procedural scene by name.
#[pyfunction]
pub(crate) fn builtin_scene(name: &str) -> PyResult<PyScene> {
    builtin::by_name(name)
        .map(|s| PyScene { inner: Arc::new(s) })
        .ok_or_else(|| argument_error(format!("name: unknown built-in scene {name:?}; valid: {}", builtin::NAMES.join(", "))))
}
