//! The only place that defines Python exceptions, and the one conversion from core errors.

use pyo3::create_exception;
use pyo3::exceptions::{PyException, PyValueError};
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyDict, PyTuple, PyType};
use pyo3::PyErr;
use vsgl_core::Error;

create_exception!(vsgl, VsglError, PyException, "Base class of every vsgl error.");
create_exception!(vsgl, SceneError, VsglError, "A malformed or hostile scene file; the message names the file and element.");
create_exception!(vsgl, NoAdapterError, VsglError, "No usable GPU or CPU adapter; the message says how to install one.");
create_exception!(vsgl, ShaderError, VsglError, "A shader failed to compose or compile (a bug in vsgl).");
create_exception!(vsgl, GpuError, VsglError, "The GPU reported a validation error or ran out of memory.");
create_exception!(vsgl, NumericsError, VsglError, "A frame computed NaN or Inf values; the message names the AOVs and counts.");

/// `vsgl.ArgumentError(VsglError, ValueError)`: both `except vsgl.VsglError` and
/// `except ValueError` catch a bad argument. `create_exception!` takes one base, so the class is
/// made by calling `type` once.
static ARGUMENT_ERROR: PyOnceLock<Py<PyType>> = PyOnceLock::new();

pub fn argument_error_type(py: Python<'_>) -> PyResult<Bound<'_, PyType>> {
    let ty = ARGUMENT_ERROR.get_or_try_init(py, || -> PyResult<Py<PyType>> {
        let bases = PyTuple::new(py, [py.get_type::<VsglError>(), py.get_type::<PyValueError>()])?;
        let namespace = PyDict::new(py);
        namespace.set_item("__doc__", "A bad argument value; the message names the argument and what was expected.")?;
        namespace.set_item("__module__", "vsgl")?;
        let made = py.import("builtins")?.getattr("type")?.call1(("ArgumentError", bases, namespace))?;
        Ok(made.cast_into::<PyType>()?.unbind())
    })?;
    Ok(ty.bind(py).clone())
}

/// `vsgl.ResourceLimitError(ArgumentError)`: the scene and settings need more of a device
/// resource than the adapter has (shadow-map layers or memory, the light list); the message
/// names the limit, the numbers and how to stay within it. An `ArgumentError` (so also a
/// `ValueError`): fewer lights or a smaller `shadow_size` fix it.
static RESOURCE_LIMIT_ERROR: PyOnceLock<Py<PyType>> = PyOnceLock::new();

pub fn resource_limit_error_type(py: Python<'_>) -> PyResult<Bound<'_, PyType>> {
    let ty = RESOURCE_LIMIT_ERROR.get_or_try_init(py, || -> PyResult<Py<PyType>> {
        let bases = PyTuple::new(py, [argument_error_type(py)?])?;
        let namespace = PyDict::new(py);
        namespace.set_item("__doc__", "The scene needs more of a device resource than the adapter has; the message names the limit and how to stay within it.")?;
        namespace.set_item("__module__", "vsgl")?;
        let made = py.import("builtins")?.getattr("type")?.call1(("ResourceLimitError", bases, namespace))?;
        Ok(made.cast_into::<PyType>()?.unbind())
    })?;
    Ok(ty.bind(py).clone())
}

fn resource_limit_error(message: String) -> PyErr {
    Python::attach(|py| match resource_limit_error_type(py) {
        Ok(ty) => PyErr::from_type(ty, message),
        Err(_) => argument_error(message),
    })
}

/// A `vsgl.ArgumentError` with `message` (which names the argument).
pub fn argument_error(message: impl Into<String>) -> PyErr {
    let message = message.into();
    Python::attach(|py| match argument_error_type(py) {
        Ok(ty) => PyErr::from_type(ty, message),
        // Only if `type(...)` itself failed: still a ValueError with the message.
        Err(_) => PyValueError::new_err(message),
    })
}

pub fn to_py(e: Error) -> PyErr {
    let msg = e.to_string();
    match e {
        Error::NoAdapter(_) => NoAdapterError::new_err(msg),
        Error::Scene { .. } => SceneError::new_err(msg),
        Error::ShaderCompile { .. } => ShaderError::new_err(msg),
        Error::Validation { .. } | Error::OutOfMemory { .. } => GpuError::new_err(msg),
        Error::NonFinite { .. } => NumericsError::new_err(msg),
        Error::Interrupted(_) => pyo3::exceptions::PyKeyboardInterrupt::new_err(msg),
        Error::InvalidArgument { .. } => argument_error(msg),
        Error::ResourceLimit(_) => resource_limit_error(msg),
    }
}

/// The `OSError` that Python's own `open()` would raise for `e` on `path`: the subclass of its
/// kind (`PermissionError`, `FileNotFoundError`, `IsADirectoryError`, ...) with `errno`,
/// `strerror` and `filename` set, so the message names the path.
pub(crate) fn os_error(py: Python<'_>, path: &std::path::Path, e: std::io::Error) -> PyErr {
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
