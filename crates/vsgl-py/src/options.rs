//! Keyword options: their conversion to the core's values, and the registry's description of
//! each method (`describe_method`, `method_options`, `check_method_options`).

use crate::args::py_int;
use crate::errors::{argument_error, to_py};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyString, PyTuple};
use vsgl_core::RenderOptions;
use vsgl_core::methods::{self, OptionValue};

/// The settings of `render` and `render_sequence` as the core takes them.
pub(crate) fn render_options(method: &str, plan: &str, aovs: Option<Vec<String>>, options: Option<&Bound<'_, PyDict>>) -> PyResult<RenderOptions> {
    let mut opts = RenderOptions::new(method);
    opts.plan = vsgl_core::renderer::PlanMode::parse(plan).map_err(to_py)?;
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
pub(crate) fn option_value(method: &str, name: &str, value: &Bound<'_, PyAny>) -> PyResult<OptionValue> {
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
                let spec = methods::info(method).ok().and_then(|info| info.options().find(|o| o.name == name));
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
pub(crate) fn method_names<'py>(py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
    PyTuple::new(py, methods::names())
}

/// What method `name` does and the options it takes, with their allowed values and defaults.
#[pyfunction]
pub(crate) fn describe_method(name: &str) -> PyResult<String> {
    Ok(methods::info(name).map_err(to_py)?.describe())
}

/// What the registry says of method `name`, so callers need not list methods by hand: its
/// summary, the AOVs its frames make, how it gets direct light, whether it is a ground truth
/// that other methods are measured against, and whether its frames depend on `seed`.
#[pyfunction]
pub(crate) fn method_info<'py>(py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyDict>> {
    let info = methods::info(name).map_err(to_py)?;
    let d = PyDict::new(py);
    d.set_item("name", info.name)?;
    d.set_item("summary", info.summary)?;
    let aovs: Vec<&str> = vsgl_core::renderer::AOV_NAMES.iter().copied().filter(|a| info.makes_aov(a)).collect();
    d.set_item("aovs", aovs)?;
    d.set_item("direct_light", match info.direct_light {
        methods::DirectLight::ShadowMapped => "shadow_mapped",
        methods::DirectLight::ByMethod => "by_method",
    })?;
    d.set_item("ground_truth", info.ground_truth)?;
    d.set_item("emitters", info.emitter_lighting())?;
    d.set_item("stochastic", info.takes("seed"))?;
    let options = PyDict::new(py);
    for o in info.options() {
        options.set_item(o.name, option_spec(py, o)?)?;
    }
    d.set_item("options", options)?;
    Ok(d)
}

/// One option as `method_info(name)["options"][option]`: its type ("int", "float", "bool" or
/// "choice"), what it allows (min/max/power_of_two, min/min_exclusive, choices), its default and
/// its help line, so a notebook can build a control for it and the stubs' TypedDicts are checked.
fn option_spec<'py>(py: Python<'py>, o: &methods::OptionSpec) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    match o.kind {
        methods::OptionKind::Int { min, max, power_of_two } => {
            d.set_item("type", "int")?;
            d.set_item("min", min)?;
            d.set_item("max", max)?;
            d.set_item("power_of_two", power_of_two)?;
        }
        methods::OptionKind::Float { min, min_exclusive } => {
            d.set_item("type", "float")?;
            d.set_item("min", min)?;
            d.set_item("min_exclusive", min_exclusive)?;
        }
        methods::OptionKind::Bool => d.set_item("type", "bool")?,
        methods::OptionKind::Choice(choices) => {
            d.set_item("type", "choice")?;
            d.set_item("choices", choices.to_vec())?;
        }
    }
    set_default(&d, "default", &o.default)?;
    d.set_item("help", o.help)?;
    Ok(d)
}

fn set_default(d: &Bound<'_, PyDict>, key: &str, value: &OptionValue) -> PyResult<()> {
    match value {
        OptionValue::Int(v) => d.set_item(key, v),
        OptionValue::Float(v) => d.set_item(key, v),
        OptionValue::Bool(v) => d.set_item(key, v),
        OptionValue::Str(v) => d.set_item(key, v.as_ref()),
    }
}

/// The keyword options of method `name` mapped to their defaults.
#[pyfunction]
pub(crate) fn method_options<'py>(py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyDict>> {
    let info = methods::info(name).map_err(to_py)?;
    let d = PyDict::new(py);
    for o in info.options() {
        set_default(&d, o.name, &o.default)?;
    }
    Ok(d)
}

/// Checks keyword options for method `name` as `render` would, without rendering: raises the
/// same `ArgumentError` (or `TypeError` for a name no method takes) naming the option, for
/// each option alone and for options that contradict each other (the method's own parse runs;
/// what depends on the adapter is checked at render). The benchmark calls it for every
/// configuration of a sweep before the first (possibly long) reference render.
#[pyfunction]
#[pyo3(signature = (name, **options))]
pub(crate) fn check_method_options(name: &str, options: Option<&Bound<'_, PyDict>>) -> PyResult<()> {
    let info = methods::info(name).map_err(to_py)?;
    let given = render_options(name, "auto", None, options)?.options;
    let mut options = info.parse_options(&given).map_err(to_py)?;
    (info.configure)(&mut options).map_err(to_py)?;
    Ok(())
}
