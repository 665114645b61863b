//! PyO3 bindings of vsgl-core: argument checking, error mapping and NumPy conversion only.
//! The Python package `vsgl` (python/vsgl) re-exports these as its public API.

mod args;
mod errors;
mod lights;
mod stability;

use args::{int_in_range, py_int, IntArg};
use errors::{argument_error, to_py};
use glam::{DMat4, DVec3};
use numpy::{PyArray1, PyArrayMethods};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyBytes, PyDict, PyFloat, PyIterator, PyString, PyTuple};
use std::sync::Arc;
use vsgl_core::methods::{self, OptionValue};
use vsgl_core::passes::vsgl_gen::{VSGL_FIELDS, VSGL_FLOATS};
use lights::{light_to_py, AnyLight, PyDirectionalLight, PyPointLight};
use vsgl_core::scene::{builtin, limits, Camera, Light, Scene, SpotLight};
use vsgl_core::{image_io, Frame, RenderOptions, Renderer};

fn vec3(name: &str, v: Vec<f64>) -> PyResult<DVec3> {
    if v.len() != 3 {
        return Err(argument_error(format!("{name}: expected 3 numbers, got {}", v.len())));
    }
    let d = DVec3::new(v[0], v[1], v[2]);
    if !d.is_finite() {
        return Err(argument_error(format!("{name}: every component must be finite, got {v:?}")));
    }
    Ok(d)
}

fn finite(name: &str, x: f64) -> PyResult<f64> {
    if x.is_finite() { Ok(x) } else { Err(argument_error(format!("{name}: must be finite, got {x}"))) }
}

/// A spot light (KHR_lights_punctual conventions): intensity in candela, smooth cone falloff
/// between `inner_cone_deg` and `outer_cone_deg` (half-angles).
#[pyclass(name = "SpotLight", module = "vsgl", from_py_object)]
#[derive(Clone)]
struct PySpotLight {
    inner: SpotLight,
}

#[pymethods]
impl PySpotLight {
    #[new]
    #[pyo3(signature = (position, direction, intensity, color=vec![1.0, 1.0, 1.0], inner_cone_deg=30.0, outer_cone_deg=40.0))]
    fn new(
        #[pyo3(from_py_with = crate::args::floats)] position: Vec<f64>,
        #[pyo3(from_py_with = crate::args::floats)] direction: Vec<f64>,
        #[pyo3(from_py_with = crate::args::float)] intensity: f64,
        #[pyo3(from_py_with = crate::args::floats)] color: Vec<f64>,
        #[pyo3(from_py_with = crate::args::float)] inner_cone_deg: f64,
        #[pyo3(from_py_with = crate::args::float)] outer_cone_deg: f64,
    ) -> PyResult<Self> {
        let position = limits::position("position", vec3("position", position)?).map_err(to_py)?;
        let direction = limits::unit_direction("direction", vec3("direction", direction)?).map_err(to_py)?;
        let intensity = limits::intensity("intensity", "candela", finite("intensity", intensity)?).map_err(to_py)?;
        let color = vec3("color", color)?;
        if color.min_element() < 0.0 {
            return Err(argument_error(format!("color: components must be >= 0, got {color:?}")));
        }
        let outer = finite("outer_cone_deg", outer_cone_deg)?;
        let inner = finite("inner_cone_deg", inner_cone_deg)?;
        if !(outer > 0.0 && outer <= 90.0) {
            return Err(argument_error(format!("outer_cone_deg: must be in (0, 90], got {outer}")));
        }
        if !(inner >= 0.0 && inner < outer) {
            return Err(argument_error(format!("inner_cone_deg: must be in [0, outer_cone_deg={outer}), got {inner}")));
        }
        Ok(Self {
            inner: SpotLight {
                position,
                direction,
                intensity,
                color: color.as_vec3(),
                inner_cone: (inner as f32).to_radians(),
                outer_cone: (outer as f32).to_radians(),
            },
        })
    }
    #[getter]
    fn position(&self) -> (f64, f64, f64) {
        self.inner.position.into()
    }
    #[getter]
    fn direction(&self) -> (f64, f64, f64) {
        self.inner.direction.into()
    }
    #[getter]
    fn intensity(&self) -> f32 {
        self.inner.intensity
    }
    #[getter]
    fn color(&self) -> (f32, f32, f32) {
        self.inner.color.into()
    }
    #[getter]
    fn inner_cone_deg(&self) -> f32 {
        self.inner.inner_cone.to_degrees()
    }
    #[getter]
    fn outer_cone_deg(&self) -> f32 {
        self.inner.outer_cone.to_degrees()
    }
    fn __repr__(&self) -> String {
        let l = &self.inner;
        format!(
            "SpotLight(position={:?}, direction={:?}, intensity={}, color={:?}, inner_cone_deg={:.3}, outer_cone_deg={:.3})",
            l.position.to_array(), l.direction.to_array(), l.intensity, l.color.to_array(),
            l.inner_cone.to_degrees(), l.outer_cone.to_degrees()
        )
    }
}

/// A perspective pinhole camera.
#[pyclass(name = "Camera", module = "vsgl", from_py_object)]
#[derive(Clone)]
struct PyCamera {
    inner: Camera,
}

#[pymethods]
impl PyCamera {
    /// A camera at `eye` looking at `target`, with vertical field of view `fov_y_deg`.
    #[staticmethod]
    #[pyo3(signature = (eye, target, up=vec![0.0, 1.0, 0.0], fov_y_deg=45.0))]
    fn look_at(
        #[pyo3(from_py_with = crate::args::floats)] eye: Vec<f64>,
        #[pyo3(from_py_with = crate::args::floats)] target: Vec<f64>,
        #[pyo3(from_py_with = crate::args::floats)] up: Vec<f64>,
        #[pyo3(from_py_with = crate::args::float)] fov_y_deg: f64,
    ) -> PyResult<Self> {
        let fov = finite("fov_y_deg", fov_y_deg)?;
        if !(fov > 0.0 && fov < 180.0) {
            return Err(argument_error(format!("fov_y_deg: must be in (0, 180), got {fov}")));
        }
        let cam = Camera::look_at(vec3("eye", eye)?, vec3("target", target)?, vec3("up", up)?, (fov as f32).to_radians())
            .map_err(|e| argument_error(format!("Camera.look_at: {e}")))?;
        Ok(Self { inner: cam })
    }
    #[getter]
    fn eye(&self) -> (f64, f64, f64) {
        self.inner.eye.into()
    }
    #[getter]
    fn forward(&self) -> (f64, f64, f64) {
        self.inner.forward.into()
    }
    #[getter]
    fn up(&self) -> (f64, f64, f64) {
        self.inner.up.into()
    }
    #[getter]
    fn fov_y_deg(&self) -> f32 {
        self.inner.fov_y.to_degrees()
    }
    fn __repr__(&self) -> String {
        let c = &self.inner;
        format!("Camera(eye={:?}, forward={:?}, up={:?}, fov_y_deg={:.3})", c.eye.to_array(), c.forward.to_array(), c.up.to_array(), c.fov_y.to_degrees())
    }
}

/// A scene: meshes, materials, textures, nodes, spot lights and cameras.
#[pyclass(name = "Scene", module = "vsgl")]
struct PyScene {
    /// Shared with the renders in flight: a render takes a snapshot (this Arc) and lets go of
    /// the Python object, so another thread may edit the scene meanwhile; an edit then copies
    /// the scene (`Arc::make_mut`) and the render finishes with the state it started from.
    inner: Arc<Scene>,
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
        for (kind, n) in lights::count_by_type(&self.inner.lights) {
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
            // The one place a user reads that emission is not a light (no warning per frame).
            d.set_item("emission", "emissive surfaces show in the image with their emitted radiance but light no other surface; add lights to light the scene")?;
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
fn optional_float(value: &Bound<'_, PyAny>) -> PyResult<Option<f64>> {
    if value.is_none() { Ok(None) } else { crate::args::float(value).map(Some) }
}

/// An optional list of floats (`None` allowed), as `args::floats` takes it.
fn optional_floats(value: &Bound<'_, PyAny>) -> PyResult<Option<Vec<f64>>> {
    if value.is_none() { Ok(None) } else { crate::args::floats(value).map(Some) }
}

/// The `OSError` that Python's own `open()` would raise for `e` on `path`: the subclass of its
/// kind (`PermissionError`, `FileNotFoundError`, `IsADirectoryError`, ...) with `errno`,
/// `strerror` and `filename` set, so the message names the path.
fn os_error(py: Python<'_>, path: &std::path::Path, e: std::io::Error) -> PyErr {
    let ty = PyErr::from(std::io::Error::from(e.kind())).get_type(py);
    let filename = path.display().to_string();
    match e.raw_os_error() {
        Some(code) => {
            let text = e.to_string();
            // Rust appends " (os error N)"; errno already says it.
            let strerror = text.split(" (os error").next().unwrap_or(&text).to_string();
            PyErr::from_type(ty, (code, strerror, filename))
        }
        None => PyErr::from_type(ty, format!("cannot write {filename}: {e}")),
    }
}

/// A byte count given as a positive Python int (not a bool, not a float), below 2**64.
fn positive_bytes(name: &str, value: &Bound<'_, PyAny>) -> PyResult<u64> {
    if py_int(value).is_none() {
        return Err(argument_error(format!("{name}: expected a positive int (bytes), got {}", value.get_type().name()?)));
    }
    // In range by the check, so the conversion cannot fail.
    Ok(int_in_range(name, value, 1, u64::MAX as i128)? as u64)
}

/// Sets the local transform of every node called `node_name` (the checks of
/// `Scene.set_transform`; `what` names the matrix and `node_arg` the node in errors).
fn set_node_transform(scene: &mut Scene, node_name: &str, matrix: Vec<Vec<f64>>, what: &str, node_arg: &str) -> PyResult<()> {
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

/// The frames of `Renderer.render_sequence`. Frame k+1 is recorded and submitted before frame
/// k is read back, so the GPU works on the next frame while this one is copied out.
#[pyclass(name = "FrameSequence", module = "vsgl", frozen)]
struct PyFrameSequence {
    renderer: Arc<Renderer>,
    frames: Py<PyIterator>,
    opts: RenderOptions,
    state: std::sync::Mutex<SequenceState>,
}

/// What a sequence carries from frame to frame.
struct SequenceState {
    /// The sequence's own copy of the scene, which the per-frame changes edit.
    scene: Scene,
    camera: Option<Camera>,
    /// The seed set by a frame's `"seed"` (kept for later frames), replacing the sequence's.
    seed: Option<OptionValue>,
    /// Index of the next item of `frames`.
    index: usize,
    /// The frame submitted ahead of the one being returned.
    in_flight: Option<vsgl_core::renderer::SubmittedFrame>,
    /// An error met while submitting ahead, raised when its frame is asked for.
    deferred: Option<PyErr>,
}

impl PyFrameSequence {
    /// Applies the next item of `frames` to the scene copy and submits its frame (`None` when
    /// `frames` is exhausted).
    fn submit_next(&self, py: Python<'_>, st: &mut SequenceState) -> PyResult<Option<vsgl_core::renderer::SubmittedFrame>> {
        let Some(item) = self.frames.bind(py).clone().next() else { return Ok(None) };
        let item = item?;
        let index = st.index;
        st.index += 1;
        let changes = item.cast::<PyDict>().map_err(|_| argument_error(format!("frames[{index}]: expected a dict of \"camera\", \"lights\", \"transforms\", \"time\", \"seed\", got {}", item.get_type().name().map(|n| n.to_string()).unwrap_or_default())))?;
        for (key, value) in changes.iter() {
            let key: String = key.extract()?;
            match key.as_str() {
                "camera" => st.camera = Some(value.extract::<PyCamera>().map_err(|_| argument_error(format!("frames[{index}][\"camera\"]: expected a vsgl.Camera")))?.inner),
                "lights" => {
                    let lights: Vec<AnyLight> = value.extract().map_err(|_| argument_error(format!("frames[{index}][\"lights\"]: expected a list of lights")))?;
                    st.scene.set_lights(lights.into_iter().map(Light::from).collect());
                }
                "seed" => {
                    // A new seed per frame, as a real-time renderer draws fresh random numbers;
                    // checked against the method's own range like the `seed=` of `render`.
                    let what = format!("frames[{index}][\"seed\"]");
                    let v = option_value(&self.opts.method, "seed", &value).map_err(|e| argument_error(format!("{what}: {e}")))?;
                    let mut trial = self.opts.clone();
                    trial.options.retain(|(n, _)| n != "seed");
                    trial.options.push(("seed".into(), v.clone()));
                    trial.resolve().map_err(|e| argument_error(format!("{what}: {e}")))?;
                    st.seed = Some(v);
                }
                "time" => {
                    let t = crate::args::float(&value).map_err(|_| argument_error(format!("frames[{index}][\"time\"]: expected a number of seconds")))?;
                    st.scene.set_time(t).map_err(|e| argument_error(format!("frames[{index}][\"time\"]: {e}")))?;
                }
                "transforms" => {
                    let d = value.cast::<PyDict>().map_err(|_| argument_error(format!("frames[{index}][\"transforms\"]: expected a dict of node name -> 4x4 matrix")))?;
                    for (node, matrix) in d.iter() {
                        let node: String = node.extract()?;
                        let matrix: Vec<Vec<f64>> = matrix.extract().map_err(|_| argument_error(format!("frames[{index}][\"transforms\"][{node:?}]: expected a 4x4 matrix")))?;
                        let what = format!("frames[{index}][\"transforms\"]");
                        set_node_transform(&mut st.scene, &node, matrix, &format!("{what}[{node:?}]"), &what)?;
                    }
                }
                other => return Err(argument_error(format!("frames[{index}]: unknown key {other:?}; a frame may set \"camera\", \"lights\", \"transforms\", \"time\", \"seed\""))),
            }
        }
        let mut opts = self.opts.clone();
        if let Some(seed) = &st.seed {
            opts.options.retain(|(n, _)| n != "seed");
            opts.options.push(("seed".into(), seed.clone()));
        }
        let (r, scene, cam, opts) = (&self.renderer, &st.scene, st.camera, &opts);
        // The submission reads nothing of the scene afterwards: the next item may edit it.
        let (opts, interrupt) = interruptible(opts.clone(), None);
        let submitted = py.detach(|| r.submit(scene, cam.as_ref(), &opts)).map_err(|e| interrupt.raise(e))?;
        Ok(Some(submitted))
    }
}

#[pymethods]
impl PyFrameSequence {
    fn __iter__(slf: PyRef<'_, Self>) -> PyRef<'_, Self> {
        slf
    }

    fn __next__(&self, py: Python<'_>) -> PyResult<Option<PyFrame>> {
        // Never block on the lock while holding the GIL: a thread that holds it may be waiting
        // for the GIL to come back from the GPU.
        let mut st = self.state.try_lock().map_err(|_| pyo3::exceptions::PyRuntimeError::new_err("FrameSequence: another thread is advancing this sequence"))?;
        let current = match st.in_flight.take() {
            Some(f) => f,
            None => {
                if let Some(e) = st.deferred.take() {
                    return Err(e);
                }
                match self.submit_next(py, &mut st)? {
                    Some(f) => f,
                    None => return Ok(None),
                }
            }
        };
        // Submit frame k+1 before reading frame k back; its errors wait for its turn.
        match self.submit_next(py, &mut st) {
            Ok(next) => st.in_flight = next,
            Err(e) => st.deferred = Some(e),
        }
        let r = &self.renderer;
        let frame = py.detach(|| r.finish(current)).map_err(to_py)?;
        Ok(Some(PyFrame::new(py, frame)?))
    }
}

/// A rendered frame: linear float32 AOVs of shape (H, W, C), row 0 at the top.
#[pyclass(name = "Frame", module = "vsgl", frozen)]
struct PyFrame {
    /// The frame without its AOV data, which lives in `arrays`.
    inner: Frame,
    /// Each AOV as the NumPy array `frame.aov(name)` returns: made once, from the readback's
    /// own allocation (no copy), and the same object on every access.
    arrays: Vec<(String, Py<PyAny>)>,
}

impl PyFrame {
    /// Moves the frame's AOV data into NumPy arrays without copying it.
    fn new(py: Python<'_>, mut frame: Frame) -> PyResult<Self> {
        let (h, w) = (frame.height as usize, frame.width as usize);
        let mut arrays = Vec::new();
        for (name, c, data) in std::mem::take(&mut frame.aovs) {
            arrays.push((name, PyArray1::from_vec(py, data).reshape([h, w, c])?.into_any().unbind()));
        }
        if let Some(ldr) = frame.ldr.take() {
            arrays.push(("ldr".to_string(), PyArray1::from_vec(py, ldr).reshape([h, w, 4])?.into_any().unbind()));
        }
        Ok(Self { inner: frame, arrays })
    }

    fn names(&self) -> Vec<String> {
        self.arrays.iter().map(|(n, _)| n.clone()).collect()
    }

    /// The image as floats (for encoding), as it is now (edits through `frame.image` included).
    fn image_floats(&self, py: Python<'_>) -> PyResult<Vec<f32>> {
        let image = self.array(py, "image")?;
        let image = image.cast::<numpy::PyArray3<f32>>().map_err(|_| argument_error("frame.image is not a float32 (H, W, 3) array"))?;
        Ok(image.to_vec()?)
    }

    fn array<'py>(&self, py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyAny>> {
        if let Some((_, a)) = self.arrays.iter().find(|(n, _)| n == name) {
            return Ok(a.bind(py).clone());
        }
        // `self.names()`, not `inner.aov_names()`: the AOV data moved into `arrays`.
        let read = self.names();
        let available = if read.is_empty() { "none (rendered with aovs=[])".to_string() } else { read.join(", ") };
        if !vsgl_core::renderer::AOV_NAMES.contains(&name) {
            return Err(argument_error(format!("name: unknown AOV {name:?}; read back: {available}")));
        }
        let method = self.inner.settings.iter().find(|(k, _)| k == "method").map(|(_, v)| v.as_str());
        let made = method.and_then(|m| methods::info(m).ok()).map(|info| info.makes_aov(name));
        Err(match (method, made) {
            (Some(method), Some(false)) => argument_error(format!(
                "name: method={method:?} does not make AOV {name:?} ({} does); read back: {available}",
                methods::aov_makers(name)
            )),
            // The method makes it: the render's `aovs=` did not ask for it, so it never left
            // the GPU. Say how to get it rather than only that it is missing.
            _ => {
                let mut ask: Vec<&str> = read.iter().map(String::as_str).collect();
                ask.push(name);
                // AOVs made only on request (such as "ldr") are not in the default set.
                let default_too = if vsgl_core::renderer::ON_REQUEST_AOVS.contains(&name) {
                    format!("({name:?} is read back only when named)")
                } else {
                    "or leave aovs out to read back every AOV the method makes".to_string()
                };
                argument_error(format!(
                    "name: AOV {name:?} was not read back (the render's aovs= did not name it); ask for it \
                     with render(..., aovs={ask:?}), {default_too}; read back: {available}"
                ))
            }
        })
    }
}

#[pymethods]
impl PyFrame {
    /// Direct + indirect radiance, (H, W, 3) float32. Like every AOV, the same array on every
    /// access (the readback's own memory, never copied): edit a `.copy()` to keep the frame as
    /// rendered; `save()` writes the array as it is.
    #[getter]
    fn image<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.array(py, "image")
    }
    /// One AOV by name (see `aovs`), (H, W, C) float32; `"ldr"` (asked for with
    /// `render(..., aovs=["ldr"])`) is (H, W, 4) uint8 sRGB, tone-mapped on the GPU.
    fn aov<'py>(&self, py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyAny>> {
        self.array(py, name)
    }
    #[getter]
    fn aovs(&self) -> Vec<String> {
        self.names()
    }
    /// The first light's VSGLs (`method="vsgl"`; `"vsgl2"`: record 0 diffuse, 1 specular) as a
    /// NumPy structured array with fields
    /// mean (relative to the camera), variance, diffuse_axis, diffuse_sharpness, diffuse_power
    /// (rgb, W), level, specular_axis, specular_sharpness, specular_power, pdf, center (kernel
    /// centre in RSM texels), mass (the kernel's probability mass (4^l/M)·p̄), _pad,
    /// plane_normal and plane_offset (the cluster's mean tangent plane Σw·n/Σw and
    /// E_w[(μ − y)·n]; zero unless `diffuse` is "accurate" or "sg_product", or for vsgl2),
    /// shadow_target (relative to the camera: where `visibility="raytrace"` aims the VSGL's
    /// shadow ray, its sampled centre texel's surface point; μ for vsgl2) and _pad2.
    fn vsgls<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let Some(data) = &self.inner.vsgls else {
            return Err(argument_error("this frame has no VSGLs; render with method=\"vsgl\" or \"vsgl2\" and a spot light"));
        };
        let np = py.import("numpy")?;
        let fields = pyo3::types::PyList::empty(py);
        for (name, n) in VSGL_FIELDS {
            if *n == 1 {
                fields.append((*name, "<f4"))?;
            } else {
                fields.append((*name, "<f4", (*n,)))?;
            }
        }
        let dtype = np.call_method1("dtype", (fields,))?;
        let flat = PyArray1::from_slice(py, data).reshape([data.len() / VSGL_FLOATS, VSGL_FLOATS])?;
        let structured = flat.call_method1("view", (dtype,))?;
        structured.call_method1("reshape", (data.len() / VSGL_FLOATS,))
    }
    /// One buffer of the first light's reflective shadow map, (N, N, C) float32 ((6N, N, C)
    /// for a point light: its six cube faces +X, −X, +Y, −Y, +Z, −Z stacked), when the
    /// frame was rendered with `capture_rsm=True`: position (relative to the light), normal,
    /// roughness, flux_diffuse (Φ·R_d), flux_specular (Φ·R_s), weight (Φ·(R_d+R_s) summed),
    /// sampling_weight (each texel's unnormalised probability in the pyramid the virtual lights
    /// were drawn from: weight, or with importance="brsm" the re-weighted q/Q + 0.1·w/W).
    fn rsm<'py>(&self, py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyAny>> {
        let Some((n, buffers)) = &self.inner.rsm else {
            return Err(argument_error("name: this frame kept no RSM; render with capture_rsm=True and a method that uses one"));
        };
        let (c, data) = buffers.iter().find(|(k, _, _)| k == name).map(|(_, c, d)| (*c, d)).ok_or_else(|| {
            let names: Vec<&str> = buffers.iter().map(|(k, _, _)| k.as_str()).collect();
            argument_error(format!("name: unknown RSM buffer {name:?}; available: {}", names.join(", ")))
        })?;
        // n rows per RSM: a point light's six cube faces are stacked along the first axis.
        let rows = data.len() / (*n as usize * c).max(1);
        Ok(PyArray1::from_slice(py, data).reshape([rows, *n as usize, c])?.into_any())
    }
    #[getter]
    fn width(&self) -> u32 {
        self.inner.width
    }
    #[getter]
    fn height(&self) -> u32 {
        self.inner.height
    }
    /// Milliseconds per pass and "total"; `timings_clock` says which clock measured them.
    #[getter]
    fn timings_ms<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        for (k, v) in &self.inner.timings_ms {
            d.set_item(k, v)?;
        }
        Ok(d)
    }
    /// "gpu-timestamp" (per-pass GPU timestamp queries) or "cpu-wall" (whole frame, CPU clock).
    #[getter]
    fn timings_clock(&self) -> String {
        self.inner.timings_clock.clone()
    }
    #[getter]
    fn passes(&self) -> Vec<String> {
        self.inner.passes.clone()
    }
    /// GPU buffers and render targets this frame allocated, label → bytes (the scene upload
    /// excluded): what a pruned plan does not allocate is absent or a 16-byte placeholder.
    #[getter]
    fn memory_bytes<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        for (k, v) in &self.inner.memory_bytes {
            d.set_item(k, v)?;
        }
        Ok(d)
    }
    /// Why the image may not be what was expected, in words: a black image and its cause (no
    /// light in the scene, no geometry in view, no light reaching anything visible). Empty for
    /// an ordinary frame. The black-image checks need an AOV read back (not with `aovs=[]`).
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.inner.warnings.clone()
    }
    /// Left-out passes or variants mapped to the reason, in words.
    #[getter]
    fn skipped<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        for (k, v) in &self.inner.skipped {
            d.set_item(k, v)?;
        }
        Ok(d)
    }
    #[getter]
    fn settings<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        for (k, v) in &self.inner.settings {
            d.set_item(k, v)?;
        }
        Ok(d)
    }
    /// Writes the image: `.png` (tone-mapped sRGB, `exposure` multiplies first), `.exr` or
    /// `.npy` (both linear float32, the latter of shape (H, W, 3)).
    #[pyo3(signature = (path, exposure=1.0))]
    fn save(&self, py: Python<'_>, path: std::path::PathBuf, #[pyo3(from_py_with = crate::args::float)] exposure: f64) -> PyResult<()> {
        // Checked in f64: a value past f32's range would be Inf once converted.
        if !(exposure.is_finite() && exposure > 0.0 && exposure <= f32::MAX as f64) {
            return Err(argument_error(format!("exposure: must be positive and finite in f32, got {exposure}")));
        }
        let exposure = exposure as f32;
        let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase();
        let rgb = self.image_floats(py)?;
        let (w, h) = (self.inner.width, self.inner.height);
        let bytes = py.detach(|| match ext.as_str() {
            "png" => image_io::encode_png(&rgb, w, h, exposure),
            "npy" => Ok(image_io::encode_npy(&rgb, &[h as usize, w as usize, 3])),
            "exr" => image_io::encode_exr(&rgb, w, h),
            _ => Err(vsgl_core::Error::invalid("path", format!("unsupported extension {ext:?}; use .png, .exr or .npy"))),
        });
        let bytes = bytes.map_err(to_py)?;
        image_io::write_file(&path, &bytes).map_err(|e| os_error(py, &path, e))
    }
    /// PNG bytes for Jupyter.
    fn _repr_png_<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyBytes>> {
        let rgb = self.image_floats(py)?;
        let png = image_io::encode_png(&rgb, self.inner.width, self.inner.height, 1.0).map_err(to_py)?;
        Ok(PyBytes::new(py, &png))
    }
    fn __repr__(&self) -> String {
        let total = self.inner.timings_ms.iter().find(|(k, _)| k == "total").map(|(_, v)| *v).unwrap_or(0.0);
        format!("Frame({}x{}, passes={:?}, total_ms={total:.3})", self.inner.width, self.inner.height, self.inner.passes)
    }
}

/// The renderer: a headless GPU device and the compiled passes for one output size.
#[pyclass(name = "Renderer", module = "vsgl", frozen)]
struct PyRenderer {
    inner: Arc<Renderer>,
}

#[pymethods]
impl PyRenderer {
    /// `adapter=None` picks the best adapter (or the `VSGL_ADAPTER` substring); a string picks
    /// the first adapter whose name contains it.
    #[new]
    // The sizes are `IntArg`s (any Python int, range-checked here by name); the text signature
    // shows their defaults, which PyO3 cannot print for a non-literal default.
    #[pyo3(signature = (width=IntArg::new(640), height=IntArg::new(360), adapter=None), text_signature = "(width=640, height=360, adapter=None)")]
    fn new(py: Python<'_>, width: IntArg, height: IntArg, adapter: Option<String>) -> PyResult<Self> {
        let width = width.in_range("width", 1, 16384)?;
        let height = height.in_range("height", 1, 16384)?;
        prepare_device_environment(py)?;
        let r = py
            .detach(|| {
                let gpu = vsgl_core::gpu::Gpu::new(adapter.as_deref())?;
                Renderer::new(gpu, width, height)
            })
            .map_err(to_py)?;
        Ok(Self { inner: Arc::new(r) })
    }
    #[getter]
    fn width(&self) -> u32 {
        self.inner.width
    }
    #[getter]
    fn height(&self) -> u32 {
        self.inner.height
    }
    /// Frees the GPU copy of the last scene rendered. The renderer keeps it while the scene's
    /// geometry and the camera position are unchanged, so repeated frames skip the upload
    /// (`frame.settings["scene_upload"]` says "reused" or "uploaded").
    fn clear_scene_cache(&self) {
        self.inner.clear_scene_cache();
    }
    /// Forgets the Markov chains of sampling="metropolis" (kept from render to render, one per
    /// virtual light per RSM view): the next such frame starts them afresh, as a new Renderer
    /// would, so a replayed seed sequence gives the same frames.
    fn reset_chains(&self) {
        self.inner.reset_chains();
    }
    /// The adapter in use: name, backend, device type, driver, timestamp support.
    #[getter]
    fn adapter<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = adapter_dict(py, &self.inner.gpu.adapter)?;
        // The device limits a scene's lights are checked against (ResourceLimitError).
        let limits = &self.inner.gpu.limits;
        d.set_item("max_texture_array_layers", limits.max_texture_array_layers)?;
        d.set_item("max_buffer_size", limits.max_buffer_size)?;
        d.set_item("max_storage_buffer_binding_size", limits.max_storage_buffer_binding_size)?;
        Ok(d)
    }
    /// Renders `scene` seen by `camera` (default: the scene's first camera, else one framing
    /// the scene) with `method`, and returns a `Frame`. Releases the GIL while the GPU works.
    ///
    /// `plan="auto"` leaves out what the scene does not need (`"full"` runs every variant);
    /// `aovs=["image"]` reads back only those AOVs (default: every float AOV the method makes;
    /// `"ldr"`, the (H, W, 4) uint8 display image tone-mapped on the GPU, only when named).
    /// Every other keyword is an option of the method; an option the method does not take
    /// raises `vsgl.ArgumentError` naming it. `vsgl.describe_method(name)` lists each
    /// method's options with their ranges and defaults:
    ///
    /// - "direct": direct light only. shadow_size.
    /// - "vpl": num_lights VPLs (in all, split over lights by reflected power)
    ///   importance-sampled from rsm_size² reflective shadow maps. shadow_size, num_lights,
    ///   rsm_size, sampling ("stratified" | "random" | "metropolis": Markov chains kept across
    ///   frames, one step per frame, see reset_chains), chain_space ("world" | "rsm": where a
    ///   metropolis chain's state lives between frames), seed, vpl_clamp (minimum VPL distance as a fraction of the scene size; 0 = unbiased),
    ///   interleave (default 1), denoise, denoise_form ("gather", the default: each pixel the
    ///   normalised average of its taps | "exchange": pixels trade light, so the image keeps
    ///   its total light exactly), visibility ("none" | "ism" | "raytrace"), ism_size,
    ///   ism_points, ism_points_per_map, ism_bias, ism_pcf (imperfect shadow maps, with
    ///   visibility="ism"), importance ("rsm" | "brsm": bidirectional RSM importance from
    ///   importance_lights VSGLs of the camera's view; combines with every sampling),
    ///   importance_lights, importance_interleave (1..16: with "brsm", RSM texel (x, y)
    ///   evaluates only the view VSGLs of its interleave class, k² times cheaper), rsm_fit
    ///   ("scene", the default: a spot light's RSM covers only the part of its cone the
    ///   scene's bounds can fill | "cone": the whole cone, before 2026-12-02), capture_rsm.
    /// - "vsgl": num_lights VSGLs (in all) by filtered importance sampling. shadow_size,
    ///   num_lights, rsm_size, sampling, seed, kernel ("integral" | "density" | "node"),
    ///   kernel_filter (how "integral" and "density" read the mips: "nodes", the default: the
    ///   quadtree node holding the kernel's centre at each level, so a texel-sized kernel is
    ///   that texel | "trilinear": the papers' read, bilinear within a level), K,
    ///   coherence (0..1, default 0.9: each kernel shrinks until its texels' mean normal is at
    ///   least this long, so clusters do not straddle creases; 0: the papers' kernels),
    ///   bisection_steps, interleave, denoise, denoise_form (as for "vpl"), diffuse ("papers" | "accurate" | "sg_product",
    ///   with lighting="asg"), lighting ("blend", the default: the two specular forms weighted
    ///   by the receiver's share of the widened lobe, and the clamped-cosine diffuse | "asg":
    ///   the papers' SG–ASG specular and diffuse= | "accurate": GGX with its NDF widened by the
    ///   light's spread, after Tokuyoshi et al. 2024, and the clamped-cosine diffuse;
    ///   docs/rendering.md "SG lighting" and "The real-scene corpus"),
    ///   lambert_lobe ("exact_compact", the default: the hemisphere-normalized Lambert SG
    ///   blended with an exact Lambertian point emitter where a cluster is compact as seen
    ///   from the receiver | "hemisphere": each texel's Lambert SG normalized over its
    ///   hemisphere, the default until 2026-12-01 | "papers": over the sphere, 9.2% of the
    ///   diffuse power lost), plane_fade (with lighting="asg" and diffuse="papers", True fades
    ///   each VSGL's light below its cluster's mean tangent plane, as the other forms always
    ///   do; False: the papers' formula, which lights the back of a lit surface), visibility,
    ///   shadow_target (with visibility="raytrace": "resampled", the default: each VSGL's ray
    ///   aims at one of 8 texels of its cluster kept per receiver by its geometric term |
    ///   "centre": at the sampled centre texel), near_field ("texels", the default: inside a
    ///   VSGL's Gaussian or behind its tangent plane the diffuse light is also taken from 8 of
    ///   its texels one by one | "sg": the Gaussian's SG alone), ism_size, ism_points, ism_points_per_map, ism_bias, ism_pcf, importance,
    ///   importance_lights, importance_interleave, rsm_fit, capture_rsm.
    /// - "vsgl2": two VSGLs per light by a parallel sum. shadow_size, rsm_size (any side
    ///   32..4096), diffuse, lighting, lambert_lobe, plane_fade (default False: one plane
    ///   spans the whole RSM), vsgl2_reduction ("auto" | "subgroup" | "shared_memory"),
    ///   visibility, ism_size, ism_points, ism_points_per_map, ism_bias, ism_pcf, rsm_fit,
    ///   capture_rsm.
    /// - "reference": every texel of an rsm_size² RSM (default 1024²) as a VPL. shadow_size,
    ///   rsm_size, vpl_clamp, visibility, ism_size, ism_points, ism_points_per_map, ism_bias,
    ///   ism_pcf, rsm_fit, capture_rsm.
    /// - "pathtrace": path-traced one-bounce ground truth with a stderr AOV. spp, seed,
    ///   time_budget_s (stop sampling after this many seconds; Ctrl-C stops any long render),
    ///   strategy ("bidirectional", the default: light tracing + camera paths by MIS over pixel
    ///   areas, which converges on caustics, repeatable within float rounding | "camera": pixel
    ///   centres, bit-deterministic | "light": light tracing alone).
    ///
    /// `capture_rsm=True` keeps the first light's RSM for `Frame.rsm(name)`.
    ///
    /// `progress`: called between the GPU batches of long renders (`pathtrace`, `reference`)
    /// as `progress(done, total, unit)`, e.g. `(1024, 4096, "spp")`; an exception it raises
    /// stops the render. Ctrl-C stops a long render there too (`KeyboardInterrupt`).
    #[pyo3(signature = (scene, camera=None, method="direct", *, plan="auto", aovs=None, progress=None, **options))]
    #[allow(clippy::too_many_arguments)]
    fn render(
        &self,
        py: Python<'_>,
        scene: PyRef<'_, PyScene>,
        camera: Option<PyCamera>,
        method: &str,
        plan: &str,
        aovs: Option<Vec<String>>,
        progress: Option<Py<PyAny>>,
        options: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<PyFrame> {
        if let Some(f) = &progress {
            if !f.bind(py).is_callable() {
                return Err(argument_error("progress: expected a callable (done, total, unit) or None"));
            }
        }
        let opts = render_options(method, plan, aovs, options)?;
        // A snapshot: the Python object is released before the GPU work, so other threads may
        // edit the scene while this frame renders the state it started with.
        let snapshot: Arc<Scene> = scene.inner.clone();
        drop(scene);
        let s: &Scene = &snapshot;
        let cam = camera.map(|c| c.inner);
        let r = &self.inner;
        let (opts, interrupt) = interruptible(opts, progress);
        let frame = py.detach(|| r.render(s, cam.as_ref(), &opts)).map_err(|e| interrupt.raise(e))?;
        PyFrame::new(py, frame)
    }
    /// Renders a sequence: `frames` is an iterable of dicts, each of which may set `"camera"`
    /// (a Camera, kept for later frames), `"lights"` (a list that replaces the lights) and
    /// `"transforms"` ({node name: 4×4 matrix}) and `"time"` (seconds: `Scene.set_time`, which
    /// poses the animated nodes and the lights on them) and `"seed"` (the method's seed from
    /// this frame on, e.g. the frame index for fresh random numbers each frame); `camera=` is
    /// the first frame's camera. Returns
    /// an iterator of Frames with the settings of `render` (validated once, here); frame k+1 is
    /// recorded and submitted before frame k is read back, so the GPU never waits for the copy.
    /// The sequence edits its own copy of `scene`, never `scene` itself. Each frame equals a
    /// `render` call of the same scene state, bit for bit.
    #[pyo3(signature = (scene, frames, camera=None, method="direct", *, plan="auto", aovs=None, **options))]
    #[allow(clippy::too_many_arguments)]
    fn render_sequence(
        &self,
        scene: PyRef<'_, PyScene>,
        frames: &Bound<'_, PyAny>,
        camera: Option<PyCamera>,
        method: &str,
        plan: &str,
        aovs: Option<Vec<String>>,
        options: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<PyFrameSequence> {
        let opts = render_options(method, plan, aovs, options)?;
        opts.resolve().map_err(to_py)?;
        let frames = frames.try_iter().map_err(|_| argument_error("frames: expected an iterable of dicts"))?;
        let state = SequenceState { scene: (*scene.inner).clone(), camera: camera.map(|c| c.inner), seed: None, index: 0, in_flight: None, deferred: None };
        Ok(PyFrameSequence { renderer: self.inner.clone(), frames: frames.unbind(), opts, state: std::sync::Mutex::new(state) })
    }
    fn __repr__(&self) -> String {
        format!("Renderer(width={}, height={}, adapter={:?})", self.inner.width, self.inner.height, self.inner.gpu.adapter.name)
    }
}

/// The Python exception a render's stop check caught (KeyboardInterrupt for Ctrl-C, or what a
/// signal handler raised), to raise in place of the core's `Interrupted`.
#[derive(Clone, Default)]
struct Interrupt(Arc<std::sync::Mutex<Option<PyErr>>>);

impl Interrupt {
    fn raise(&self, e: vsgl_core::Error) -> PyErr {
        match e {
            vsgl_core::Error::Interrupted(_) => self.0.lock().unwrap_or_else(|p| p.into_inner()).take().unwrap_or_else(|| to_py(e)),
            e => to_py(e),
        }
    }
}

/// `opts` with a stop check that runs Python's signal handlers between the GPU batches of a
/// long render (the GIL is taken only for that), so Ctrl-C stops a `pathtrace` or `reference`
/// render within a batch and the renderer stays usable; `progress`, if given, is called there
/// with (done, total, unit), and an exception it raises stops the render too.
fn interruptible(mut opts: RenderOptions, progress: Option<Py<PyAny>>) -> (RenderOptions, Interrupt) {
    let interrupt = Interrupt::default();
    let slot = interrupt.clone();
    opts.stop = Some(vsgl_core::renderer::StopCheck(Arc::new(move |p: vsgl_core::renderer::Progress| {
        Python::attach(|py| {
            py.check_signals()?;
            if let Some(f) = &progress {
                f.call1(py, (p.done, p.total, p.unit))?;
            }
            Ok::<(), PyErr>(())
        })
        .map_err(|e| {
            let message = e.to_string();
            *slot.0.lock().unwrap_or_else(|p| p.into_inner()) = Some(e);
            vsgl_core::Error::Interrupted(message)
        })
    })));
    (opts, interrupt)
}

/// The settings of `render` and `render_sequence` as the core takes them.
fn render_options(method: &str, plan: &str, aovs: Option<Vec<String>>, options: Option<&Bound<'_, PyDict>>) -> PyResult<RenderOptions> {
    let mut opts = RenderOptions::new(method);
    opts.plan = plan.into();
    opts.aovs = aovs;
    for (key, value) in options.into_iter().flat_map(|d| d.iter()) {
        let name: String = key.extract()?;
        if value.is_none() {
            continue; // None: the method's default
        }
        opts.options.push((name.clone(), option_value(method, &name, &value)?));
    }
    Ok(opts)
}

/// A keyword option as the core takes it. Names that no method takes are a `TypeError`, as
/// for any unexpected keyword; values are checked by the method's option specs.
fn option_value(method: &str, name: &str, value: &Bound<'_, PyAny>) -> PyResult<OptionValue> {
    if !methods::every_option_name().contains(&name) {
        return Err(PyTypeError::new_err(format!(
            "render() got an unexpected keyword argument {name:?}; options of the methods: {}",
            methods::every_option_name().join(", ")
        )));
    }
    if value.is_instance_of::<PyBool>() {
        Ok(OptionValue::Bool(value.extract()?))
    } else if let Some(v) = py_int(value) {
        match v.as_ref().map(|v| i64::try_from(*v)) {
            Ok(Ok(v)) => Ok(OptionValue::Int(v)),
            // Beyond i64: no option allows it; say what the method's option does allow.
            _ => {
                let size = match v { Ok(v) => v.to_string(), Err(size) => size };
                let spec = methods::info(method).ok().and_then(|info| info.options.iter().find(|o| o.name == name));
                let allowed = spec.map(|s| s.allowed()).unwrap_or_else(|| format!("an option of method={method:?}"));
                Err(argument_error(format!("{name}: must be {allowed}, got {size}")))
            }
        }
    } else if value.is_instance_of::<PyFloat>() {
        Ok(OptionValue::Float(value.extract()?))
    } else if value.is_instance_of::<PyString>() {
        Ok(OptionValue::from(value.extract::<String>()?))
    } else {
        Err(argument_error(format!("{name}: expected an int, float, bool or str, got {}", value.get_type().name()?)))
    }
}

/// The method names, in registry order (`vsgl.METHODS`).
fn method_names<'py>(py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
    PyTuple::new(py, methods::names())
}

/// What method `name` does and the options it takes, with their allowed values and defaults.
#[pyfunction]
fn describe_method(name: &str) -> PyResult<String> {
    Ok(methods::info(name).map_err(to_py)?.describe())
}

/// The keyword options of method `name` mapped to their defaults.
#[pyfunction]
fn method_options<'py>(py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyDict>> {
    let info = methods::info(name).map_err(to_py)?;
    let d = PyDict::new(py);
    for o in info.options {
        match &o.default {
            OptionValue::Int(v) => d.set_item(o.name, v)?,
            OptionValue::Float(v) => d.set_item(o.name, v)?,
            OptionValue::Bool(v) => d.set_item(o.name, v)?,
            OptionValue::Str(v) => d.set_item(o.name, v.as_ref())?,
        }
    }
    Ok(d)
}

/// Checks keyword options for method `name` as `render` would, without rendering: raises the
/// same `ArgumentError` (or `TypeError` for a name no method takes) naming the option. The
/// benchmark calls it for every configuration of a sweep before the first (possibly long)
/// reference render.
#[pyfunction]
#[pyo3(signature = (name, **options))]
fn check_method_options(name: &str, options: Option<&Bound<'_, PyDict>>) -> PyResult<()> {
    let info = methods::info(name).map_err(to_py)?;
    let given = render_options(name, "auto", None, options)?.options;
    info.parse_options(&given).map_err(to_py)?;
    Ok(())
}

fn adapter_dict<'py>(py: Python<'py>, a: &vsgl_core::gpu::AdapterSummary) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("name", &a.name)?;
    d.set_item("backend", &a.backend)?;
    d.set_item("device_type", &a.device_type)?;
    d.set_item("driver", &a.driver)?;
    d.set_item("timestamps", a.timestamps)?;
    d.set_item("subgroups", a.subgroups)?;
    Ok(d)
}

/// Every adapter wgpu sees, best first.
#[pyfunction]
fn adapters(py: Python<'_>) -> PyResult<Vec<Bound<'_, PyDict>>> {
    prepare_device_environment(py)?;
    let list = py.detach(vsgl_core::gpu::adapters);
    list.iter().map(|a| adapter_dict(py, a)).collect()
}

/// Runs `vsgl._prepare_device_environment()` (the process environment a GPU instance needs,
/// set where one is opened rather than at import); a no-op where the package does not define
/// it (the extension imported on its own).
pub(crate) fn prepare_device_environment(py: Python<'_>) -> PyResult<()> {
    let package = py.import("vsgl")?;
    if let Ok(prepare) = package.getattr("_prepare_device_environment") {
        prepare.call0()?;
    }
    Ok(())
}

/// Names of the built-in procedural scenes.
#[pyfunction]
fn builtin_scene_names() -> Vec<&'static str> {
    builtin::NAMES.to_vec()
}

/// A built-in procedural scene by name.
#[pyfunction]
fn builtin_scene(name: &str) -> PyResult<PyScene> {
    builtin::by_name(name)
        .map(|s| PyScene { inner: Arc::new(s) })
        .ok_or_else(|| argument_error(format!("name: unknown built-in scene {name:?}; valid: {}", builtin::NAMES.join(", "))))
}

#[pymodule(gil_used = false)]
fn _vsgl(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    // Load NumPy's C API now, at import: loading it lazily with the first frame runs Python
    // code (numpy's version check) that a pending KeyboardInterrupt can fail, which the numpy
    // crate turns into a panic.
    PyArray1::<f32>::zeros(py, [0], false);
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("VsglError", py.get_type::<errors::VsglError>())?;
    m.add("SceneError", py.get_type::<errors::SceneError>())?;
    m.add("NoAdapterError", py.get_type::<errors::NoAdapterError>())?;
    m.add("ShaderError", py.get_type::<errors::ShaderError>())?;
    m.add("GpuError", py.get_type::<errors::GpuError>())?;
    m.add("NumericsError", py.get_type::<errors::NumericsError>())?;
    m.add("ArgumentError", errors::argument_error_type(py)?)?;
    m.add("ResourceLimitError", errors::resource_limit_error_type(py)?)?;
    m.add("METHODS", method_names(py)?)?;
    m.add_class::<PyRenderer>()?;
    m.add_class::<PyScene>()?;
    m.add_class::<PyCamera>()?;
    m.add_class::<PySpotLight>()?;
    m.add_class::<PyPointLight>()?;
    m.add_class::<PyDirectionalLight>()?;
    m.add_class::<PyFrame>()?;
    m.add_class::<PyFrameSequence>()?;
    m.add_function(wrap_pyfunction!(adapters, m)?)?;
    m.add_function(wrap_pyfunction!(describe_method, m)?)?;
    m.add_function(wrap_pyfunction!(method_options, m)?)?;
    m.add_function(wrap_pyfunction!(check_method_options, m)?)?;
    m.add_function(wrap_pyfunction!(builtin_scene_names, m)?)?;
    m.add_function(wrap_pyfunction!(builtin_scene, m)?)?;
    m.add_function(wrap_pyfunction!(stability::stability_suite, m)?)?;
    Ok(())
}
