//! `vsgl.Camera`: a perspective pinhole camera.

use crate::args::{vec3, finite};
use crate::errors::argument_error;
use pyo3::prelude::*;
use vsgl_core::scene::Camera;

/// A perspective pinhole camera.
#[pyclass(name = "Camera", module = "vsgl", from_py_object)]
#[derive(Clone)]
pub(crate) struct PyCamera {
    pub(crate) inner: Camera,
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
