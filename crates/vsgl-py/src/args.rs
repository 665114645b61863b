//! Python ints as arguments. PyO3's typed extraction (`i64`, `u32`, …) raises a bare
//! `OverflowError` ("Python int too large to convert to C long") for an int beyond the Rust
//! type, before the function can say which argument it was or what it allows. Every int
//! argument goes through [`py_int`] instead, which keeps any Python int, and is then checked
//! against its range, so `Renderer(width=2**64)` is an `ArgumentError` naming `width` and
//! `1..=16384`.

use crate::errors::argument_error;
use pyo3::exceptions::PyTypeError;
use glam::DVec3;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyInt};

/// A Python int as given: its value when it fits an i128, else how large it is in words
/// (a value past i128 may have more digits than Python will print: `str(10**5000)` raises).
pub type PyIntValue = Result<i128, String>;

/// The value of a Python int (not a bool), or its size when it does not fit an i128; `None`
/// when `value` is not an int.
pub fn py_int(value: &Bound<'_, PyAny>) -> Option<PyIntValue> {
    if value.is_instance_of::<PyBool>() || !value.is_instance_of::<PyInt>() {
        return None;
    }
    Some(value.extract::<i128>().map_err(|_| {
        let bits: u64 = value.call_method0("bit_length").and_then(|b| b.extract()).unwrap_or(0);
        let sign = if value.lt(0).unwrap_or(false) { "-" } else { "" };
        format!("{sign}2**{} or beyond ({bits} bits)", bits.saturating_sub(1))
    }))
}

/// `value` as an int in `min..=max`, else an `ArgumentError` naming `name`, the range and the
/// value given (a `TypeError` for a value that is not an int).
pub fn int_in_range(name: &str, value: &Bound<'_, PyAny>, min: i128, max: i128) -> PyResult<i128> {
    let Some(v) = py_int(value) else {
        let ty = value.get_type().name().map(|n| n.to_string()).unwrap_or_default();
        return Err(PyTypeError::new_err(format!("{name}: expected an int in {min}..={max}, got {ty}")));
    };
    check_range(name, v, min, max)
}

fn check_range(name: &str, v: PyIntValue, min: i128, max: i128) -> PyResult<i128> {
    match v {
        Ok(v) if (min..=max).contains(&v) => Ok(v),
        Ok(v) => Err(argument_error(format!("{name}: must be in {min}..={max}, got {v}"))),
        Err(size) => Err(argument_error(format!("{name}: must be in {min}..={max}, got {size}"))),
    }
}

/// A typed int parameter that never fails extraction on size (only on type); the function
/// checks it with [`IntArg::in_range`], which names the parameter.
pub struct IntArg(PyIntValue);

impl IntArg {
    pub const fn new(v: i64) -> Self {
        Self(Ok(v as i128))
    }

    /// The value if in `min..=max` (both within u32 here: the sizes PyO3 hands to the core).
    pub fn in_range(&self, name: &str, min: u32, max: u32) -> PyResult<u32> {
        // The range is within u32, so the conversion cannot fail once it holds.
        check_range(name, self.0.clone(), min as i128, max as i128).map(|v| v as u32)
    }
}

impl<'a, 'py> FromPyObject<'a, 'py> for IntArg {
    type Error = PyErr;

    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        match py_int(&obj) {
            Some(v) => Ok(Self(v)),
            None => {
                let ty = obj.get_type().name().map(|n| n.to_string()).unwrap_or_default();
                Err(PyTypeError::new_err(format!("expected an int, got {ty}")))
            }
        }
    }
}

/// A float parameter (`#[pyo3(from_py_with = args::float)]`): an int too large for a float is
/// ±inf, the float it rounds to, rather than an `OverflowError`, so the function's own
/// finiteness and range checks name the parameter.
pub fn float(value: &Bound<'_, PyAny>) -> PyResult<f64> {
    match value.extract::<f64>() {
        Ok(v) => Ok(v),
        // Only an int past f64's range (about 1.8e308) fails to convert.
        Err(_) if py_int(value).is_some() => Ok(if value.lt(0)? { f64::NEG_INFINITY } else { f64::INFINITY }),
        Err(e) => Err(e),
    }
}

/// A list of floats (`#[pyo3(from_py_with = args::floats)]`), each as [`float`] takes it.
pub fn floats(value: &Bound<'_, PyAny>) -> PyResult<Vec<f64>> {
    if value.is_instance_of::<pyo3::types::PyString>() {
        return Err(PyTypeError::new_err("expected a sequence of numbers, got str"));
    }
    value.try_iter()?.map(|item| float(&item?)).collect()
}

pub fn vec3(name: &str, v: Vec<f64>) -> PyResult<DVec3> {
    if v.len() != 3 {
        return Err(argument_error(format!("{name}: expected 3 numbers, got {}", v.len())));
    }
    let d = DVec3::new(v[0], v[1], v[2]);
    if !d.is_finite() {
        return Err(argument_error(format!("{name}: every component must be finite, got {v:?}")));
    }
    Ok(d)
}

pub fn finite(name: &str, x: f64) -> PyResult<f64> {
    if x.is_finite() { Ok(x) } else { Err(argument_error(format!("{name}: must be finite, got {x}"))) }
}

