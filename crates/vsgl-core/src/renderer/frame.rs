//! One rendered frame as the renderer hands it out: AOVs, timings and what ran.

/// One rendered frame: linear float AOVs, row 0 at the top.
#[derive(Clone, Debug)]
pub struct Frame {
    pub width: u32,
    pub height: u32,
    /// (name, channels, data of width·height·channels floats).
    pub aovs: Vec<(String, usize, Vec<f32>)>,
    /// The `ldr` AOV when asked for: width·height RGBA bytes (sRGB, tone-mapped on the GPU).
    pub ldr: Option<Vec<u8>>,
    /// Milliseconds per pass and "total".
    pub timings_ms: Vec<(String, f64)>,
    /// "gpu-timestamp" or "cpu-wall" (adapters without timestamp queries).
    pub timings_clock: String,
    /// The passes that ran, in order, as the passes logged themselves (variants in brackets).
    pub passes: Vec<String>,
    pub skipped: Vec<(String, String)>,
    pub settings: Vec<(String, crate::setting::Setting)>,
    /// Why the image may not be what the caller expects (a black image and its cause), in words.
    pub warnings: Vec<String>,
    /// The first light's RSM when `capture_rsm` was set: side and (name, channels, data).
    pub rsm: Option<(u32, Vec<(String, usize, Vec<f32>)>)>,
    /// `method="lpv"` with `capture_lpv`: its volumes, (name, shape, data).
    pub lpv: Option<crate::methods::CapturedLpv>,
    /// The first light's VSGLs (`vsgl`): VSGL_FLOATS floats each, fields in VSGL_FIELDS order.
    pub vsgls: Option<Vec<f32>>,
    /// GPU buffers and render targets the frame used, created now or kept from an earlier
    /// frame: (label, bytes), summed per label. The scene's own upload (geometry, textures) is
    /// not included; `settings["allocated_bytes"]` is what the frame created.
    pub memory_bytes: Vec<(String, u64)>,
    /// The pipeline variants the frame bound: (shader path, entry point, override flags), so
    /// tests can check that each pass ran the variant its plan asked for.
    pub variants: Vec<(String, String, Vec<(&'static str, bool)>)>,
}

impl Frame {
    pub fn aov(&self, name: &str) -> Option<(usize, &[f32])> {
        self.aovs.iter().find(|(n, _, _)| n == name).map(|(_, c, d)| (*c, d.as_slice()))
    }
    pub fn aov_names(&self) -> Vec<String> {
        let mut names: Vec<String> = self.aovs.iter().map(|(n, _, _)| n.clone()).collect();
        if self.ldr.is_some() {
            names.push("ldr".into());
        }
        names
    }
}
