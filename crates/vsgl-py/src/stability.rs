//! `vsgl._vsgl.stability_suite`: the numerical stability suite of vsgl-core (every WGSL math
//! function in f32 on the GPU against its f64 oracle), as a list of dicts for `vsgl.stability`.

use crate::errors::to_py;
use crate::errors::argument_error;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// Runs the stability suite on `adapter` (None: the best adapter, or `VSGL_ADAPTER`) and returns
/// one dict per (function output, case family) row: function, family, cases, max_rel_error,
/// bound, worst_ratio, nonfinite, passed, worst_case. `bound_scale` multiplies every bound (1 for
/// the real suite; a small value shows that the suite can fail). Releases the GIL while it runs.
#[pyfunction]
#[pyo3(signature = (adapter=None, bound_scale=1.0))]
pub fn stability_suite(
    py: Python<'_>,
    adapter: Option<String>,
    #[pyo3(from_py_with = crate::args::float)] bound_scale: f64,
) -> PyResult<Vec<Bound<'_, PyDict>>> {
    if !(bound_scale.is_finite() && bound_scale > 0.0) {
        return Err(argument_error(format!("bound_scale: must be positive and finite, got {bound_scale}")));
    }
    crate::renderer::prepare_device_environment(py)?;
    let rows = py
        .detach(|| vsgl_core::verify::stability::run_on_adapter(adapter.as_deref(), bound_scale))
        .map_err(to_py)?;
    rows.iter()
        .map(|r| {
            let d = PyDict::new(py);
            d.set_item("function", &r.function)?;
            d.set_item("family", &r.family)?;
            d.set_item("cases", r.cases)?;
            d.set_item("max_rel_error", r.max_rel_error)?;
            d.set_item("bound", r.bound)?;
            d.set_item("worst_ratio", r.worst_ratio)?;
            d.set_item("nonfinite", r.nonfinite)?;
            d.set_item("passed", r.pass)?;
            d.set_item("worst_case", &r.worst_case)?;
            Ok(d)
        })
        .collect()
}
