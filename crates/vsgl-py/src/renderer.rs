//! `vsgl.Renderer`, the stop check that lets Ctrl-C end a long render, and `vsgl.adapters()`.

use crate::args::IntArg;
use crate::camera::PyCamera;
use crate::errors::{argument_error, to_py};
use crate::frame::PyFrame;
use crate::options::render_options;
use crate::scene::PyScene;
use crate::sequence::PyFrameSequence;
use crate::sequence::SequenceState;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::sync::Arc;
use vsgl_core::scene::Scene;
use vsgl_core::{RenderOptions, Renderer};

/// The renderer: a headless GPU device and the compiled passes for one output size.
#[pyclass(name = "Renderer", module = "vsgl", frozen)]
pub(crate) struct PyRenderer {
    pub(crate) inner: Arc<Renderer>,
}

#[pymethods]
impl PyRenderer {
    /// `adapter=None` picks the best adapter (or the `VSGL_ADAPTER` substring); a string picks
    /// the first adapter whose name contains it, or, written `"pci:0000:17:00.0"`, the adapter
    /// at that PCI bus id (`vsgl.adapters()` lists each one's `pci_bus_id` and limits).
    #[new]
    // The sizes are `IntArg`s (any Python int, range-checked here by name); the text signature
    // shows their defaults, which PyO3 cannot print for a non-literal default.
    #[pyo3(signature = (width=IntArg::new(640), height=IntArg::new(360), adapter=None), text_signature = "(width=640, height=360, adapter=None)")]
    fn new(py: Python<'_>, width: IntArg, height: IntArg, adapter: Option<String>) -> PyResult<Self> {
        let width = width.in_range("width", 1, 16384)?;
        let height = height.in_range("height", 1, 16384)?;
        prepare_device_environment(py)?;
        let r = py
            .detach(|| {
                let gpu = vsgl_core::gpu::Gpu::new(adapter.as_deref())?;
                Renderer::new(gpu, width, height)
            })
            .map_err(to_py)?;
        Ok(Self { inner: Arc::new(r) })
    }
    #[getter]
    fn width(&self) -> u32 {
        self.inner.width()
    }
    #[getter]
    fn height(&self) -> u32 {
        self.inner.height()
    }
    /// Renders the next frames at `width` × `height` (each 1 to the adapter's largest 2D
    /// texture), keeping the device, the compiled passes and the scene upload: a live view
    /// resizes its renderer instead of opening a new one, which would compile every pass
    /// again. Frames already submitted keep their size.
    fn resize(&self, width: IntArg, height: IntArg) -> PyResult<()> {
        let width = width.in_range("width", 1, 16384)?;
        let height = height.in_range("height", 1, 16384)?;
        self.inner.resize(width, height).map_err(to_py)
    }
    /// Frees the GPU copy of the last scene rendered. The renderer keeps it while the scene's
    /// geometry and the camera position are unchanged, so repeated frames skip the upload
    /// (`frame.settings["scene_upload"]` says "reused" or "uploaded").
    fn clear_scene_cache(&self) {
        self.inner.clear_scene_cache();
    }
    /// Forgets the Markov chains of sampling="metropolis" (kept from render to render, one per
    /// virtual light per RSM view): the next such frame starts them afresh, as a new Renderer
    /// would, so a replayed seed sequence gives the same frames.
    fn reset_chains(&self) {
        self.inner.reset_chains();
    }
    /// The adapter in use: name, backend, device type, driver, timestamp support.
    #[getter]
    fn adapter<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = adapter_dict(py, &self.inner.gpu.adapter)?;
        // The device limits a scene's lights are checked against (ResourceLimitError).
        let limits = &self.inner.gpu.limits;
        d.set_item("max_texture_array_layers", limits.max_texture_array_layers)?;
        d.set_item("max_buffer_size", limits.max_buffer_size)?;
        d.set_item("max_storage_buffer_binding_size", limits.max_storage_buffer_binding_size)?;
        Ok(d)
    }
    /// Renders `scene` seen by `camera` (default: the scene's first camera, else one framing
    /// the scene) with `method`, and returns a `Frame`. Releases the GIL while the GPU works.
    ///
    /// `plan="auto"` leaves out what the scene does not need (`"full"` runs every variant);
    /// `aovs=["image"]` reads back only those AOVs (default: every float AOV the method makes;
    /// `"ldr"`, the (H, W, 4) uint8 display image tone-mapped on the GPU, only when named).
    /// Every other keyword is an option of the method; an option the method does not take
    /// raises `vsgl.ArgumentError` naming it. The methods are `vsgl.METHODS`; each one's options,
    /// with their types, ranges, choices, defaults and what each does, come from the method
    /// registry: `vsgl.describe_method(name)` prints them, `vsgl.method_info(name)["options"]`
    /// returns them, and the stubs type them per method (so an editor completes the options of
    /// the method named). docs/methods/ says when to use which.
    ///
    /// `capture_rsm=True` keeps the first light's RSM for `Frame.rsm(name)`.
    ///
    /// `progress`: called between the GPU batches of long renders (`pathtrace`, `reference`)
    /// as `progress(done, total, unit)`, e.g. `(1024, 4096, "spp")`; an exception it raises
    /// stops the render. Ctrl-C stops a long render there too (`KeyboardInterrupt`).
    #[pyo3(signature = (scene, camera=None, method="direct", *, plan="auto", aovs=None, progress=None, **options))]
    #[allow(clippy::too_many_arguments)]
    fn render(
        &self,
        py: Python<'_>,
        scene: PyRef<'_, PyScene>,
        camera: Option<PyCamera>,
        method: &str,
        plan: &str,
        aovs: Option<Vec<String>>,
        progress: Option<Py<PyAny>>,
        options: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<PyFrame> {
        if let Some(f) = &progress {
            if !f.bind(py).is_callable() {
                return Err(argument_error("progress: expected a callable (done, total, unit) or None"));
            }
        }
        let opts = render_options(method, plan, aovs, options)?;
        // A snapshot: the Python object is released before the GPU work, so other threads may
        // edit the scene while this frame renders the state it started with.
        let snapshot: Arc<Scene> = scene.inner.clone();
        drop(scene);
        let s: &Scene = &snapshot;
        let cam = camera.map(|c| c.inner);
        let r = &self.inner;
        let (opts, interrupt) = interruptible(opts, progress);
        let frame = py.detach(|| r.render(s, cam.as_ref(), &opts)).map_err(|e| interrupt.raise(e))?;
        PyFrame::new(py, frame)
    }
    /// Renders a sequence: `frames` is an iterable of dicts, each of which may set `"camera"`
    /// (a Camera, kept for later frames), `"lights"` (a list that replaces the lights) and
    /// `"transforms"` ({node name: 4×4 matrix}) and `"time"` (seconds: `Scene.set_time`, which
    /// poses the animated nodes and the lights on them) and `"seed"` (the method's seed from
    /// this frame on, e.g. the frame index for fresh random numbers each frame); `camera=` is
    /// the first frame's camera. Returns
    /// an iterator of Frames with the settings of `render` (validated once, here); frame k+1 is
    /// recorded and submitted before frame k is read back, so the GPU never waits for the copy.
    /// The sequence edits its own copy of `scene`, never `scene` itself. Each frame equals a
    /// `render` call of the same scene state, bit for bit.
    #[pyo3(signature = (scene, frames, camera=None, method="direct", *, plan="auto", aovs=None, **options))]
    #[allow(clippy::too_many_arguments)]
    fn render_sequence(
        &self,
        scene: PyRef<'_, PyScene>,
        frames: &Bound<'_, PyAny>,
        camera: Option<PyCamera>,
        method: &str,
        plan: &str,
        aovs: Option<Vec<String>>,
        options: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<PyFrameSequence> {
        let opts = render_options(method, plan, aovs, options)?;
        opts.resolve().map_err(to_py)?;
        let frames = frames.try_iter().map_err(|_| argument_error("frames: expected an iterable of dicts"))?;
        let state = SequenceState { scene: (*scene.inner).clone(), camera: camera.map(|c| c.inner), seed: None, index: 0, in_flight: None, deferred: None };
        Ok(PyFrameSequence { renderer: self.inner.clone(), frames: frames.unbind(), opts, state: std::sync::Mutex::new(state) })
    }
    /// Opens a desktop window on `scene` drawn by this renderer (resized to the window) and
    /// runs it until it is closed: `vsgl.window_view.view`, which documents the arguments
    /// (`compare=`, `size=`, `frames=`, `screenshot=`, `ui=`, the method's options).
    #[pyo3(signature = (scene, method="vsgl", **kwargs))]
    fn view<'py>(slf: &Bound<'py, Self>, scene: &Bound<'py, PyAny>, method: &str, kwargs: Option<&Bound<'py, PyDict>>) -> PyResult<Bound<'py, PyAny>> {
        let py = slf.py();
        let kwargs = match kwargs {
            Some(k) => k.copy()?,
            None => PyDict::new(py),
        };
        kwargs.set_item("renderer", slf)?;
        py.import("vsgl.window_view")?.getattr("view")?.call((scene, method), Some(&kwargs))
    }
    fn __repr__(&self) -> String {
        format!("Renderer(width={}, height={}, adapter={:?})", self.inner.width(), self.inner.height(), self.inner.gpu.adapter.name)
    }
}

/// The Python exception a render's stop check caught (KeyboardInterrupt for Ctrl-C, or what a
/// signal handler raised), to raise in place of the core's `Interrupted`.
#[derive(Clone, Default)]
pub(crate) struct Interrupt(Arc<std::sync::Mutex<Option<PyErr>>>);

impl Interrupt {
    pub(crate) fn raise(&self, e: vsgl_core::Error) -> PyErr {
        match e {
            vsgl_core::Error::Interrupted(_) => self.0.lock().unwrap_or_else(|p| p.into_inner()).take().unwrap_or_else(|| to_py(e)),
            e => to_py(e),
        }
    }
}

/// `opts` with a stop check that runs Python's signal handlers between the GPU batches of a
/// long render (the GIL is taken only for that), so Ctrl-C stops a `pathtrace` or `reference`
/// render within a batch and the renderer stays usable; `progress`, if given, is called there
/// with (done, total, unit), and an exception it raises stops the render too.
pub(crate) fn interruptible(mut opts: RenderOptions, progress: Option<Py<PyAny>>) -> (RenderOptions, Interrupt) {
    let interrupt = Interrupt::default();
    let slot = interrupt.clone();
    opts.stop = Some(vsgl_core::renderer::StopCheck(Arc::new(move |p: vsgl_core::renderer::Progress| {
        Python::attach(|py| {
            py.check_signals()?;
            if let Some(f) = &progress {
                f.call1(py, (p.done, p.total, p.unit))?;
            }
            Ok::<(), PyErr>(())
        })
        .map_err(|e| {
            let message = e.to_string();
            *slot.0.lock().unwrap_or_else(|p| p.into_inner()) = Some(e);
            vsgl_core::Error::Interrupted(message)
        })
    })));
    (opts, interrupt)
}

pub(crate) fn adapter_dict<'py>(py: Python<'py>, a: &vsgl_core::gpu::AdapterSummary) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("name", &a.name)?;
    d.set_item("backend", &a.backend)?;
    d.set_item("device_type", &a.device_type)?;
    d.set_item("driver", &a.driver)?;
    d.set_item("timestamps", a.timestamps)?;
    d.set_item("subgroups", a.subgroups)?;
    d.set_item("pci_bus_id", &a.pci_bus_id)?;
    let limits = PyDict::new(py);
    limits.set_item("max_storage_binding_bytes", a.max_storage_binding_bytes)?;
    limits.set_item("max_buffer_bytes", a.max_buffer_bytes)?;
    limits.set_item("max_texture_side", a.max_texture_side)?;
    d.set_item("limits", limits)?;
    Ok(d)
}

/// Every adapter wgpu sees, best first.
#[pyfunction]
pub(crate) fn adapters(py: Python<'_>) -> PyResult<Vec<Bound<'_, PyDict>>> {
    prepare_device_environment(py)?;
    let list = py.detach(vsgl_core::gpu::adapters);
    list.iter().map(|a| adapter_dict(py, a)).collect()
}

/// Runs `vsgl._prepare_device_environment()` (the process environment a GPU instance needs,
/// set where one is opened rather than at import); a no-op where the package does not define
/// it (the extension imported on its own).
pub(crate) fn prepare_device_environment(py: Python<'_>) -> PyResult<()> {
    let package = py.import("vsgl")?;
    if let Ok(prepare) = package.getattr("_prepare_device_environment") {
        prepare.call0()?;
    }
    Ok(())
}
