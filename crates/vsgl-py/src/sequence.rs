//! `vsgl.FrameSequence`: the frames of `Renderer.render_sequence`, one submitted ahead.

use crate::camera::PyCamera;
use crate::errors::{argument_error, to_py};
use crate::frame::PyFrame;
use crate::lights::AnyLight;
use crate::options::option_value;
use crate::renderer::interruptible;
use crate::scene::set_node_transform;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyIterator};
use std::sync::Arc;
use vsgl_core::methods::OptionValue;
use vsgl_core::scene::{Camera, Light, Scene};
use vsgl_core::{RenderOptions, Renderer};

/// The frames of `Renderer.render_sequence`. Frame k+1 is recorded and submitted before frame
/// k is read back, so the GPU works on the next frame while this one is copied out.
#[pyclass(name = "FrameSequence", module = "vsgl", frozen)]
pub(crate) struct PyFrameSequence {
    pub(crate) renderer: Arc<Renderer>,
    pub(crate) frames: Py<PyIterator>,
    pub(crate) opts: RenderOptions,
    pub(crate) state: std::sync::Mutex<SequenceState>,
}

/// What a sequence carries from frame to frame.
pub(crate) struct SequenceState {
    /// The sequence's own copy of the scene, which the per-frame changes edit.
    pub(crate) scene: Scene,
    pub(crate) camera: Option<Camera>,
    /// The seed set by a frame's `"seed"` (kept for later frames), replacing the sequence's.
    pub(crate) seed: Option<OptionValue>,
    /// Index of the next item of `frames`.
    pub(crate) index: usize,
    /// The frame submitted ahead of the one being returned.
    pub(crate) in_flight: Option<vsgl_core::renderer::SubmittedFrame>,
    /// An error met while submitting ahead, raised when its frame is asked for.
    pub(crate) deferred: Option<PyErr>,
}

impl PyFrameSequence {
    /// Applies the next item of `frames` to the scene copy and submits its frame (`None` when
    /// `frames` is exhausted).
    fn submit_next(&self, py: Python<'_>, st: &mut SequenceState) -> PyResult<Option<vsgl_core::renderer::SubmittedFrame>> {
        let Some(item) = self.frames.bind(py).clone().next() else { return Ok(None) };
        let item = item?;
        let index = st.index;
        st.index += 1;
        let changes = item.cast::<PyDict>().map_err(|_| argument_error(format!("frames[{index}]: expected a dict of \"camera\", \"lights\", \"transforms\", \"time\", \"seed\", got {}", item.get_type().name().map(|n| n.to_string()).unwrap_or_default())))?;
        for (key, value) in changes.iter() {
            let key: String = key.extract()?;
            match key.as_str() {
                "camera" => st.camera = Some(value.extract::<PyCamera>().map_err(|_| argument_error(format!("frames[{index}][\"camera\"]: expected a vsgl.Camera")))?.inner),
                "lights" => {
                    let lights: Vec<AnyLight> = value.extract().map_err(|_| argument_error(format!("frames[{index}][\"lights\"]: expected a list of lights")))?;
                    st.scene.set_lights(lights.into_iter().map(Light::from).collect());
                }
                "seed" => {
                    // A new seed per frame, as a real-time renderer draws fresh random numbers;
                    // checked against the method's own range like the `seed=` of `render`.
                    let what = format!("frames[{index}][\"seed\"]");
                    let v = option_value(&self.opts.method, "seed", &value).map_err(|e| argument_error(format!("{what}: {e}")))?;
                    let mut trial = self.opts.clone();
                    trial.options.retain(|(n, _)| n != "seed");
                    trial.options.push(("seed".into(), v.clone()));
                    trial.resolve().map_err(|e| argument_error(format!("{what}: {e}")))?;
                    st.seed = Some(v);
                }
                "time" => {
                    let t = crate::args::float(&value).map_err(|_| argument_error(format!("frames[{index}][\"time\"]: expected a number of seconds")))?;
                    st.scene.set_time(t).map_err(|e| argument_error(format!("frames[{index}][\"time\"]: {e}")))?;
                }
                "transforms" => {
                    let d = value.cast::<PyDict>().map_err(|_| argument_error(format!("frames[{index}][\"transforms\"]: expected a dict of node name -> 4x4 matrix")))?;
                    for (node, matrix) in d.iter() {
                        let node: String = node.extract()?;
                        let matrix: Vec<Vec<f64>> = matrix.extract().map_err(|_| argument_error(format!("frames[{index}][\"transforms\"][{node:?}]: expected a 4x4 matrix")))?;
                        let what = format!("frames[{index}][\"transforms\"]");
                        set_node_transform(&mut st.scene, &node, matrix, &format!("{what}[{node:?}]"), &what)?;
                    }
                }
                other => return Err(argument_error(format!("frames[{index}]: unknown key {other:?}; a frame may set \"camera\", \"lights\", \"transforms\", \"time\", \"seed\""))),
            }
        }
        let mut opts = self.opts.clone();
        if let Some(seed) = &st.seed {
            opts.options.retain(|(n, _)| n != "seed");
            opts.options.push(("seed".into(), seed.clone()));
        }
        let (r, scene, cam, opts) = (&self.renderer, &st.scene, st.camera, &opts);
        // The submission reads nothing of the scene afterwards: the next item may edit it.
        let (opts, interrupt) = interruptible(opts.clone(), None);
        let submitted = py.detach(|| r.submit(scene, cam.as_ref(), &opts)).map_err(|e| interrupt.raise(e))?;
        Ok(Some(submitted))
    }
}

#[pymethods]
impl PyFrameSequence {
    fn __iter__(slf: PyRef<'_, Self>) -> PyRef<'_, Self> {
        slf
    }

    fn __next__(&self, py: Python<'_>) -> PyResult<Option<PyFrame>> {
        // Never block on the lock while holding the GIL: a thread that holds it may be waiting
        // for the GIL to come back from the GPU.
        let mut st = self.state.try_lock().map_err(|_| pyo3::exceptions::PyRuntimeError::new_err("FrameSequence: another thread is advancing this sequence"))?;
        let current = match st.in_flight.take() {
            Some(f) => f,
            None => {
                if let Some(e) = st.deferred.take() {
                    return Err(e);
                }
                match self.submit_next(py, &mut st)? {
                    Some(f) => f,
                    None => return Ok(None),
                }
            }
        };
        // Submit frame k+1 before reading frame k back; its errors wait for its turn.
        match self.submit_next(py, &mut st) {
            Ok(next) => st.in_flight = next,
            Err(e) => st.deferred = Some(e),
        }
        let r = &self.renderer;
        let frame = py.detach(|| r.finish(current)).map_err(to_py)?;
        Ok(Some(PyFrame::new(py, frame)?))
    }
}
