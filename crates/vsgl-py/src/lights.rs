//! Point and directional lights as Python classes, and the conversions between Python light
//! objects (any of the three classes) and the core `Light` enum.

use crate::errors::{argument_error, to_py};
use crate::args::{finite, vec3};
use vsgl_core::scene::SpotLight;
use pyo3::prelude::*;
use vsgl_core::scene::{limits, DirectionalLight, Light, PointLight};

/// A positive, finite f32 `intensity` in `unit`, at most `limits::MAX_INTENSITY`.
fn intensity(x: f64, unit: &str) -> PyResult<f32> {
    limits::intensity("intensity", unit, finite("intensity", x)?).map_err(to_py)
}

fn color(c: Vec<f64>) -> PyResult<glam::Vec3> {
    let c = vec3("color", c)?;
    if c.min_element() < 0.0 {
        return Err(argument_error(format!("color: components must be >= 0, got {c:?}")));
    }
    Ok(c.as_vec3())
}

/// A point light (KHR_lights_punctual conventions): intensity in candela, equal in every
/// direction, inverse-square falloff.
#[pyclass(name = "PointLight", module = "vsgl", from_py_object)]
#[derive(Clone)]
pub struct PyPointLight {
    pub inner: PointLight,
}

#[pymethods]
impl PyPointLight {
    #[new]
    #[pyo3(signature = (position, intensity, color=vec![1.0, 1.0, 1.0]))]
    fn new(
        #[pyo3(from_py_with = crate::args::floats)] position: Vec<f64>,
        #[pyo3(from_py_with = crate::args::float)] intensity: f64,
        #[pyo3(from_py_with = crate::args::floats)] color: Vec<f64>,
    ) -> PyResult<Self> {
        let position = limits::position("position", vec3("position", position)?).map_err(to_py)?;
        let intensity = self::intensity(intensity, "candela")?;
        let color = self::color(color)?;
        Ok(Self { inner: PointLight { position, intensity, color } })
    }
    #[getter]
    fn position(&self) -> (f64, f64, f64) {
        self.inner.position.into()
    }
    #[getter]
    fn intensity(&self) -> f32 {
        self.inner.intensity
    }
    #[getter]
    fn color(&self) -> (f32, f32, f32) {
        self.inner.color.into()
    }
    fn __repr__(&self) -> String {
        let l = &self.inner;
        format!("PointLight(position={:?}, intensity={}, color={:?})", l.position.to_array(), l.intensity, l.color.to_array())
    }
}

/// A directional light (KHR_lights_punctual conventions): illuminance in lux on a surface
/// facing it, light travelling along `direction`, no falloff.
#[pyclass(name = "DirectionalLight", module = "vsgl", from_py_object)]
#[derive(Clone)]
pub struct PyDirectionalLight {
    pub inner: DirectionalLight,
}

#[pymethods]
impl PyDirectionalLight {
    #[new]
    #[pyo3(signature = (direction, intensity, color=vec![1.0, 1.0, 1.0]))]
    fn new(
        #[pyo3(from_py_with = crate::args::floats)] direction: Vec<f64>,
        #[pyo3(from_py_with = crate::args::float)] intensity: f64,
        #[pyo3(from_py_with = crate::args::floats)] color: Vec<f64>,
    ) -> PyResult<Self> {
        let direction = limits::unit_direction("direction", vec3("direction", direction)?).map_err(to_py)?;
        let intensity = self::intensity(intensity, "lux")?;
        let color = self::color(color)?;
        Ok(Self { inner: DirectionalLight { direction, intensity, color } })
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
    fn __repr__(&self) -> String {
        let l = &self.inner;
        format!("DirectionalLight(direction={:?}, intensity={}, color={:?})", l.direction.to_array(), l.intensity, l.color.to_array())
    }
}

/// Any Python light object.
#[derive(FromPyObject)]
pub(crate) enum AnyLight {
    Spot(PySpotLight),
    Point(PyPointLight),
    Directional(PyDirectionalLight),
}

impl From<AnyLight> for Light {
    fn from(l: AnyLight) -> Self {
        match l {
            AnyLight::Spot(s) => Light::Spot(s.inner),
            AnyLight::Point(p) => Light::Point(p.inner),
            AnyLight::Directional(d) => Light::Directional(d.inner),
        }
    }
}

/// A scene light as its Python class.
pub(crate) fn light_to_py(py: Python<'_>, light: &Light) -> PyResult<Py<PyAny>> {
    Ok(match light {
        Light::Spot(s) => Py::new(py, PySpotLight { inner: *s })?.into_any(),
        Light::Point(p) => Py::new(py, PyPointLight { inner: *p })?.into_any(),
        Light::Directional(d) => Py::new(py, PyDirectionalLight { inner: *d })?.into_any(),
        // Made per frame from the emissive triangles, never stored in a scene.
        Light::Emitter(_) => return Err(pyo3::exceptions::PyTypeError::new_err("an emitter cluster is not a scene light")),
    })
}

/// Counts of the scene's lights by glTF type name (`scene.stats["lights_by_type"]`).
pub fn count_by_type(lights: &[Light]) -> Vec<(&'static str, usize)> {
    ["spot", "point", "directional"].iter().map(|&k| (k, lights.iter().filter(|l| l.kind() == k).count())).collect()
}

/// A spot light (KHR_lights_punctual conventions): intensity in candela, smooth cone falloff
/// between `inner_cone_deg` and `outer_cone_deg` (half-angles).
#[pyclass(name = "SpotLight", module = "vsgl", from_py_object)]
#[derive(Clone)]
pub(crate) struct PySpotLight {
    pub(crate) inner: SpotLight,
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
