//! `vsgl._vsgl.ViewWindow`: the desktop window of the live view (crate `vsgl-window`), driven
//! from Python (`vsgl.window_view`), which owns the loop so the camera and light controls are
//! the notebook view's own modules.

use crate::camera::PyCamera;
use crate::errors::{argument_error, to_py};
use crate::frame::PyFrame;
use crate::options::render_options;
use crate::renderer::PyRenderer;
use crate::scene::PyScene;
use numpy::{PyArray1, PyArrayMethods, PyReadonlyArray3, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyTuple};
use std::sync::Arc;
use std::time::Duration;
use vsgl_core::Renderer;
use vsgl_window::{Control, InputEvent, PanelSpec, PanelValue, ViewWindow, WindowError};

pyo3::create_exception!(vsgl, WindowUnavailableError, crate::errors::VsglError, "No window can be opened here: no display, or an adapter that cannot present to it (the message names the cause and what to use instead).");

fn window_error(e: WindowError) -> PyErr {
    match e {
        WindowError::Render(e) => to_py(e),
        other => WindowUnavailableError::new_err(other.to_string()),
    }
}

/// A window (or its offscreen stand-in) presenting one renderer's frames. Made and used on
/// one thread (winit's event loop is the thread's).
#[pyclass(name = "ViewWindow", module = "vsgl", unsendable)]
pub(crate) struct PyViewWindow {
    window: ViewWindow,
    renderer: Arc<Renderer>,
}

fn event_dict<'py>(py: Python<'py>, e: &InputEvent) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("event_type", e.kind)?;
    d.set_item("type", e.kind)?;
    match e.kind {
        "pointer_down" | "pointer_move" | "pointer_up" | "wheel" => {
            d.set_item("x", e.x)?;
            d.set_item("y", e.y)?;
            d.set_item("button", e.button)?;
            d.set_item("buttons", PyTuple::new(py, &e.buttons)?)?;
            d.set_item("modifiers", PyTuple::new(py, &e.modifiers)?)?;
            if e.kind == "wheel" {
                d.set_item("dx", e.dx)?;
                d.set_item("dy", e.dy)?;
            }
        }
        "key_down" | "key_up" => {
            d.set_item("key", &e.key)?;
            d.set_item("modifiers", PyTuple::new(py, &e.modifiers)?)?;
        }
        "resize" => {
            d.set_item("width", e.width)?;
            d.set_item("height", e.height)?;
            d.set_item("pixel_ratio", e.pixel_ratio)?;
        }
        _ => {}
    }
    Ok(d)
}

/// A panel control from its Python tuple: ("choice", name, [choices], current),
/// ("int" | "float", name, min, max, current, logarithmic), ("toggle", name, current).
fn control(item: &Bound<'_, PyAny>) -> PyResult<Control> {
    let kind: String = item.get_item(0)?.extract()?;
    let name: String = item.get_item(1)?.extract()?;
    Ok(match kind.as_str() {
        "choice" => Control::Choice { name, choices: item.get_item(2)?.extract()?, current: item.get_item(3)?.extract()? },
        "int" => Control::Int { name, min: item.get_item(2)?.extract()?, max: item.get_item(3)?.extract()?, current: item.get_item(4)?.extract()?, logarithmic: item.get_item(5)?.extract()? },
        "float" => Control::Float { name, min: item.get_item(2)?.extract()?, max: item.get_item(3)?.extract()?, current: item.get_item(4)?.extract()?, logarithmic: item.get_item(5)?.extract()? },
        "toggle" => Control::Toggle { name, current: item.get_item(2)?.extract()? },
        other => return Err(argument_error(format!("controls: unknown control kind {other:?} (choice, int, float, toggle)"))),
    })
}

#[pymethods]
impl PyViewWindow {
    /// Opens a window of `width` × `height` logical pixels presenting from `renderer`'s device.
    #[staticmethod]
    #[pyo3(signature = (renderer, title="vsgl", width=960, height=540, ui=true, vsync=true))]
    fn open(renderer: PyRef<'_, PyRenderer>, title: &str, width: u32, height: u32, ui: bool, vsync: bool) -> PyResult<Self> {
        if width == 0 || height == 0 {
            return Err(argument_error(format!("size: width and height must be positive, got {width} × {height}")));
        }
        let r = renderer.inner.clone();
        let window = ViewWindow::open(r.gpu.clone(), title, (width, height), ui, vsync).map_err(window_error)?;
        Ok(Self { window, renderer: r })
    }

    /// The same frame path without a window: frames are composed (and the panel drawn) into a
    /// target of `width` × `height` pixels, nothing is presented.
    #[staticmethod]
    #[pyo3(signature = (renderer, width, height, ui=false))]
    fn offscreen(renderer: PyRef<'_, PyRenderer>, width: u32, height: u32, ui: bool) -> PyResult<Self> {
        if width == 0 || height == 0 {
            return Err(argument_error(format!("size: width and height must be positive, got {width} × {height}")));
        }
        let r = renderer.inner.clone();
        Ok(Self { window: ViewWindow::offscreen(r.gpu.clone(), (width, height), ui), renderer: r })
    }

    /// Events since the last call as remote-frame-buffer dicts, waiting up to `wait` seconds
    /// for the first.
    #[pyo3(signature = (wait=0.0))]
    fn poll_events<'py>(&mut self, py: Python<'py>, wait: f64) -> PyResult<Bound<'py, PyList>> {
        let wait = Duration::from_secs_f64(if wait.is_finite() { wait.clamp(0.0, 10.0) } else { 0.0 });
        let events = self.window.poll_events(wait).map_err(window_error)?;
        let dicts = events.iter().map(|e| event_dict(py, e)).collect::<PyResult<Vec<_>>>()?;
        PyList::new(py, dicts)
    }

    /// Renders a frame of `method` with its `ldr` image kept on the GPU and shows it as image
    /// `slot` (0: left or alone, 1: right). Returns the frame (timings and settings, no AOV).
    #[pyo3(signature = (slot, scene, camera=None, method="vsgl", **options))]
    fn render_into(&mut self, py: Python<'_>, slot: usize, scene: PyRef<'_, PyScene>, camera: Option<PyCamera>, method: &str, options: Option<&Bound<'_, PyDict>>) -> PyResult<PyFrame> {
        if slot > 1 {
            return Err(argument_error(format!("slot: 0 or 1, got {slot}")));
        }
        let mut opts = render_options(method, "auto", Some(vec!["ldr".into()]), options)?;
        opts.keep_on_gpu = true;
        let snapshot = scene.inner.clone();
        drop(scene);
        let cam = camera.map(|c| c.inner);
        let (r, window) = (&self.renderer, &mut self.window);
        let submitted = py.detach(|| r.submit(&snapshot, cam.as_ref(), &opts)).map_err(to_py)?;
        if submitted.size() != window.size() {
            return Err(argument_error(format!("renderer: its size {:?} is not the window's {:?} (resize the renderer to window.size)", submitted.size(), window.size())));
        }
        window.take_frame(slot, &submitted).map_err(window_error)?;
        let frame = py.detach(|| r.finish(submitted)).map_err(to_py)?;
        PyFrame::new(py, frame)
    }

    /// Shows an (H, W, 3) or (H, W, 4) uint8 sRGB image as image `slot`.
    fn upload_image(&mut self, slot: usize, image: PyReadonlyArray3<'_, u8>) -> PyResult<()> {
        let shape = image.shape().to_vec();
        let (h, w, c) = (shape[0], shape[1], shape[2]);
        if (w as u32, h as u32) != self.window.size() || !(c == 3 || c == 4) {
            return Err(argument_error(format!("image: expected shape ({}, {}, 3 or 4), got {shape:?}", self.window.size().1, self.window.size().0)));
        }
        // Row-major (H, W, C) bytes (a copy only for a non-contiguous view), then RGBA.
        let bytes: Vec<u8> = match image.as_slice() {
            Ok(s) => s.to_vec(),
            Err(_) => image.as_array().iter().copied().collect(),
        };
        let rgba: Vec<u8> = if c == 4 {
            bytes.chunks_exact(4).flat_map(|p| [p[0], p[1], p[2], 255]).collect()
        } else {
            bytes.chunks_exact(3).flat_map(|p| [p[0], p[1], p[2], 255]).collect()
        };
        self.window.upload_image(slot.min(1), (w as u32, h as u32), &rgba).map_err(window_error)
    }

    /// Draws the images (`split`: the right image's first column when two are shown), the
    /// panel's `controls` with the `status` line and `labels` ([(text, x)]), and presents.
    /// Returns the panel's changes as [(name, value)].
    #[pyo3(signature = (split=None, controls=None, status="", labels=None))]
    fn present<'py>(&mut self, py: Python<'py>, split: Option<u32>, controls: Option<&Bound<'py, PyList>>, status: &str, labels: Option<Vec<(String, f32)>>) -> PyResult<Bound<'py, PyList>> {
        let controls = match controls {
            Some(list) => list.iter().map(|c| control(&c)).collect::<PyResult<Vec<_>>>()?,
            None => Vec::new(),
        };
        let spec = PanelSpec { controls, status: status.to_string(), labels: labels.unwrap_or_default() };
        let changes = self.window.present(split, &spec).map_err(window_error)?;
        let items = changes
            .into_iter()
            .map(|c| {
                let value = match c.value {
                    PanelValue::Text(s) => s.into_pyobject(py)?.into_any(),
                    PanelValue::Int(i) => i.into_pyobject(py)?.into_any(),
                    PanelValue::Float(f) => f.into_pyobject(py)?.into_any(),
                    PanelValue::Bool(b) => pyo3::types::PyBool::new(py, b).to_owned().into_any(),
                };
                PyTuple::new(py, [c.name.into_pyobject(py)?.into_any(), value])
            })
            .collect::<PyResult<Vec<_>>>()?;
        PyList::new(py, items)
    }

    /// The last frame presented as (H, W, 4) uint8 (the target blitted to the surface).
    fn screenshot<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let ((w, h), bytes) = py.detach(|| self.window.screenshot()).map_err(window_error)?;
        Ok(PyArray1::from_vec(py, bytes).reshape([h as usize, w as usize, 4])?.into_any())
    }

    /// (width, height) in pixels of the frames the window shows.
    #[getter]
    fn size(&self) -> (u32, u32) {
        self.window.size()
    }

    /// Physical pixels per logical pixel.
    #[getter]
    fn pixel_ratio(&self) -> f64 {
        self.window.pixel_ratio()
    }

    #[getter]
    fn closed(&self) -> bool {
        self.window.is_closed()
    }

    /// Whether a real window presents (False: offscreen).
    #[getter]
    fn has_window(&self) -> bool {
        self.window.has_window()
    }

    /// Milliseconds the last `present` took on the CPU (recording, submitting, presenting).
    #[getter]
    fn last_present_ms(&self) -> f64 {
        self.window.last_present.as_secs_f64() * 1e3
    }

    fn close(&mut self) {
        self.window.close();
    }

    fn __repr__(&self) -> String {
        let (w, h) = self.window.size();
        format!("ViewWindow({w}×{h}, {})", if self.window.has_window() { if self.window.is_closed() { "closed" } else { "open" } } else { "offscreen" })
    }
}
