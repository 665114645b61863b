//! The only place that defines Python exceptions, and the one conversion from core errors.

use pyo3::create_exception;
use pyo3::exceptions::{PyException, PyValueError};
use pyo3::PyErr;
use vsgl_core::Error;

create_exception!(vsgl, VsglError, PyException, "Base class of every vsgl error.");
create_exception!(vsgl, SceneError, VsglError, "A malformed or hostile scene file; the message names the file and element.");
create_exception!(vsgl, NoAdapterError, VsglError, "No usable GPU or CPU adapter; the message says how to install one.");
create_exception!(vsgl, ShaderError, VsglError, "A shader failed to compose or compile (a bug in vsgl).");
create_exception!(vsgl, GpuError, VsglError, "The GPU reported a validation error or ran out of memory.");

pub fn to_py(e: Error) -> PyErr {
    let msg = e.to_string();
    match e {
        Error::NoAdapter(_) => NoAdapterError::new_err(msg),
        Error::Scene { .. } => SceneError::new_err(msg),
        Error::ShaderCompile { .. } => ShaderError::new_err(msg),
        Error::Validation { .. } | Error::OutOfMemory { .. } => GpuError::new_err(msg),
        Error::InvalidArgument { .. } => PyValueError::new_err(msg),
    }
}
