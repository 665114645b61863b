//! `vsgl.Frame`: a rendered frame's AOVs as NumPy arrays, its timings, settings and records.

use crate::errors::{argument_error, os_error, to_py};
use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyBytes, PyDict, PyList, PyString};
use vsgl_core::methods::{self};
use vsgl_core::passes::vsgl_gen::{VSGL_FIELDS, VSGL_FLOATS};
use vsgl_core::{image_io, Frame, Setting};

/// A rendered frame: linear float32 AOVs of shape (H, W, C), row 0 at the top.
#[pyclass(name = "Frame", module = "vsgl", frozen)]
pub(crate) struct PyFrame {
    /// The frame without its AOV data, which lives in `arrays`.
    pub(crate) inner: Frame,
    /// Each AOV as the NumPy array `frame.aov(name)` returns: made once, from the readback's
    /// own allocation (no copy), and the same object on every access.
    pub(crate) arrays: Vec<(String, Py<PyAny>)>,
}

impl PyFrame {
    /// Moves the frame's AOV data into NumPy arrays without copying it.
    pub(crate) fn new(py: Python<'_>, mut frame: Frame) -> PyResult<Self> {
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
        let method = self.inner.settings.iter().find(|(k, _)| k == "method").and_then(|(_, v)| v.as_text());
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
    /// One of the light propagation volumes of a `method="lpv"` frame rendered with
    /// `capture_lpv=True`, float32: "injected" (the light injected from the RSMs) and "total"
    /// (injected plus every propagation iteration, what the lookup reads), each of shape
    /// (cascades, side, side, side, 3, 4) — cells z, y, x, then colour r, g, b, then the SH
    /// coefficients (c₀, c_x, c_y, c_z) of the radiant intensity in W/sr —, and with
    /// occlusion "geometry", (cascades, side+1, side+1, side+1, 4), the blocking potential
    /// on the cell corners. `frame.settings["lpv_cascade_grids"]` gives each cascade's world
    /// min corner and cell side.
    fn lpv<'py>(&self, py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyAny>> {
        let Some(volumes) = &self.inner.lpv else {
            return Err(argument_error("name: this frame kept no light propagation volume; render with method=\"lpv\" and capture_lpv=True"));
        };
        let (shape, data) = volumes.iter().find(|(k, _, _)| k == name).map(|(_, s, d)| (s.clone(), d)).ok_or_else(|| {
            let names: Vec<&str> = volumes.iter().map(|(k, _, _)| k.as_str()).collect();
            argument_error(format!("name: unknown volume {name:?}; available: {}", names.join(", ")))
        })?;
        Ok(PyArray1::from_slice(py, data).reshape(shape)?.into_any())
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
            d.set_item(k, setting_object(py, v)?)?;
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

/// A `frame.settings` value as the Python object of its type: int, float, bool, str, list, dict
/// or None.
fn setting_object<'py>(py: Python<'py>, value: &Setting) -> PyResult<Bound<'py, PyAny>> {
    Ok(match value {
        Setting::Int(v) => v.into_pyobject(py)?.into_any(),
        Setting::Float(v) => v.into_pyobject(py)?.into_any(),
        Setting::Bool(v) => PyBool::new(py, *v).to_owned().into_any(),
        Setting::Text(t) => PyString::new(py, t).into_any(),
        Setting::List(items) => PyList::new(py, items.iter().map(|item| setting_object(py, item)).collect::<PyResult<Vec<_>>>()?)?.into_any(),
        Setting::Record(fields) => {
            let d = PyDict::new(py);
            for (name, field) in fields {
                d.set_item(name, setting_object(py, field)?)?;
            }
            d.into_any()
        }
        Setting::Absent => py.None().into_bound(py),
    })
}
