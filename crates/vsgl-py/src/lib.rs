//! PyO3 bindings of vsgl-core: argument checking, error mapping and NumPy conversion only.
//! The Python package `vsgl` (python/vsgl) re-exports these as its public API.

mod args;
mod camera;
mod errors;
mod frame;
mod lights;
mod options;
mod renderer;
mod scene;
mod sequence;
mod stability;
mod window;

use camera::PyCamera;
use frame::PyFrame;
use lights::{PyDirectionalLight, PyPointLight, PySpotLight};
use options::{check_method_options, describe_method, method_info, method_names, method_options};
use pyo3::prelude::*;
use renderer::{adapters, PyRenderer};
use scene::{builtin_scene, builtin_scene_names, PyScene};
use sequence::PyFrameSequence;
use numpy::PyArray1;

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
    m.add_class::<window::PyViewWindow>()?;
    m.add("WindowUnavailableError", py.get_type::<window::WindowUnavailableError>())?;
    m.add_function(wrap_pyfunction!(adapters, m)?)?;
    m.add_function(wrap_pyfunction!(describe_method, m)?)?;
    m.add_function(wrap_pyfunction!(method_options, m)?)?;
    m.add_function(wrap_pyfunction!(method_info, m)?)?;
    m.add_function(wrap_pyfunction!(check_method_options, m)?)?;
    m.add_function(wrap_pyfunction!(builtin_scene_names, m)?)?;
    m.add_function(wrap_pyfunction!(builtin_scene, m)?)?;
    m.add_function(wrap_pyfunction!(stability::stability_suite, m)?)?;
    Ok(())
}
