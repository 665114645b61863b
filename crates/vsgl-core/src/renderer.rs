//! The frame: validates settings, plans passes, records them top to bottom, reads back AOVs.

use crate::error::{Error, Result};
use crate::frame_data::{frame_uniforms, light_view_uniforms, spot_light_raw, SpotLightRaw};
use crate::gpu::{Gpu, PassTimer};
use crate::passes::vpl_sample::{Sampling, VplSamplePass, VPL_BYTES};
use crate::passes::vpl_shading::{IndirectTargets, VplShadingPass};
use crate::passes::vsgl_gen::{GenSettings, Kernel, VsglGenPass, VSGL_BYTES};
use crate::passes::vsgl_moments::{MomentChains, VsglMomentsPass};
use crate::passes::vsgl_shading::{DiffuseMode, VsglShadingPass};
use crate::passes::vsgl2_reduce::{Vsgl2Reduce, Vsgl2Reduction, VSGL2_COUNT};
use crate::passes::{denoise::DenoisePass, moment_mips::MomentMipsPass};
use crate::passes::pathtrace::{PathTraceInputs, PathTracePass};
use crate::passes::{
    direct::DirectPass, material::GBuffer, material::MaterialPass, pdf_mips::PdfMipsPass, rsm_flux::Rsm,
    rsm_flux::RsmFluxPass, shadow_map::ShadowMapPass, storage_buffer, uniform_buffer, visibility::VisibilityPass,
};
use crate::plan::Plan;
use crate::scene::{Camera, Scene};
use crate::upload::GpuScene;
use std::sync::{Arc, Mutex};
use std::time::Instant;
use wgpu::util::DeviceExt;

/// Methods that render in this build.
pub const METHODS: &[&str] = &["direct", "vpl", "vsgl", "vsgl2", "reference", "pathtrace"];
/// Methods of DESIGN.md that later work adds; asking for one says so.
pub const PLANNED_METHODS: &[&str] = &[];

/// Query pairs one frame may time: the reference's batches are the most numerous.
const TIMER_CAPACITY: u32 = 2048;
/// Most VPL batches the reference splits its work into (each is one timed pass).
const REFERENCE_MAX_BATCHES: u64 = 1024;
/// Pixel·VPL evaluations per reference submission: small enough that no batch runs long
/// enough to trip a GPU watchdog (~10 ms on an H100), unless that would exceed the batch cap.
const REFERENCE_BATCH_EVALUATIONS: u64 = 1 << 31;

/// Settings of one render (the keyword arguments of `Renderer.render`).
#[derive(Clone, Debug)]
pub struct RenderOptions {
    pub method: String,
    /// Side of each spot light's shadow map, 16…8192.
    pub shadow_size: u32,
    /// `"auto"` leaves out what the scene does not need; `"full"` runs every variant.
    pub plan: String,
    /// VPL count per spot light (`vpl`).
    pub num_lights: u32,
    /// RSM side (32…4096; a power of two except for `vsgl2`, which needs no pyramid);
    /// `None`: 1024 for `reference`, 256 otherwise.
    pub rsm_size: Option<u32>,
    pub sampling: Sampling,
    pub seed: u32,
    /// Lower bound of the VPL distance as a fraction of the scene's bounds diagonal
    /// (0 = no clamping, unbiased).
    pub vpl_clamp: f32,
    /// Visibility of virtual lights; only `"none"` so far (the papers' accuracy setting).
    pub visibility: String,
    /// Read back the first light's RSM into the frame (for tests and plots).
    pub capture_rsm: bool,
    /// Samples per pixel of `pathtrace` (1…65536).
    pub spp: u32,
    /// VSGL kernel size rule (`vsgl`).
    pub kernel: Kernel,
    /// K of the 2016 paper: kernel probability mass K/N (> 0).
    pub k: f32,
    /// Bisection iterations of the integral kernel (1…32).
    pub bisection_steps: u32,
    /// Interleaved sampling tile side (1…16): each pixel evaluates N/k² VSGLs.
    pub interleave: u32,
    /// Run the geometry-aware filter after interleaved shading.
    pub denoise: bool,
    pub diffuse: DiffuseMode,
    /// How `vsgl2`'s workgroups add (subgroups where available by default).
    pub vsgl2_reduction: Vsgl2Reduction,
    /// The AOVs to read back (names from [`AOV_NAMES`]); `None`: every AOV the method makes.
    /// Readback and the RGB conversion are most of a frame's wall time at high resolution, so
    /// a loop that only shows `image` should ask for it alone.
    pub aovs: Option<Vec<String>>,
}

/// Every AOV a frame can hold, in the order a frame lists them.
pub const AOV_NAMES: &[&str] = &["image", "indirect", "indirect_diffuse", "indirect_specular", "direct", "albedo", "normal", "depth", "stderr"];

/// Which methods make an AOV (`None`: every method).
fn aov_methods(name: &str) -> Option<&'static str> {
    match name {
        "indirect" | "indirect_diffuse" | "indirect_specular" => Some("every method but \"direct\""),
        "stderr" => Some("method=\"pathtrace\""),
        _ => None,
    }
}

fn method_makes_aov(method: &str, name: &str) -> bool {
    match name {
        "indirect" | "indirect_diffuse" | "indirect_specular" => method != "direct",
        "stderr" => method == "pathtrace",
        _ => true,
    }
}

impl Default for RenderOptions {
    fn default() -> Self {
        Self {
            method: "direct".into(),
            shadow_size: 1024,
            plan: "auto".into(),
            num_lights: 256,
            rsm_size: None,
            sampling: Sampling::Stratified,
            seed: 0,
            vpl_clamp: 0.0,
            visibility: "none".into(),
            capture_rsm: false,
            spp: 64,
            kernel: Kernel::Integral,
            k: 1.0,
            bisection_steps: 12,
            interleave: 8,
            denoise: true,
            diffuse: DiffuseMode::Papers,
            vsgl2_reduction: Vsgl2Reduction::Auto,
            aovs: None,
        }
    }
}

impl RenderOptions {
    pub fn validate(&self) -> Result<()> {
        if !METHODS.contains(&self.method.as_str()) {
            let planned = if PLANNED_METHODS.contains(&self.method.as_str()) {
                format!(" ({:?} is planned but not in this build yet)", self.method)
            } else {
                String::new()
            };
            return Err(Error::invalid("method", format!(
                "unknown method {:?}{planned}; valid methods: {}", self.method, METHODS.join(", ")
            )));
        }
        if !(16..=8192).contains(&self.shadow_size) {
            return Err(Error::invalid("shadow_size", format!("must be in 16..=8192, got {}", self.shadow_size)));
        }
        if self.plan != "auto" && self.plan != "full" {
            return Err(Error::invalid("plan", format!("must be \"auto\" or \"full\", got {:?}", self.plan)));
        }
        if !(1..=1 << 20).contains(&self.num_lights) {
            return Err(Error::invalid("num_lights", format!("must be in 1..=1048576, got {}", self.num_lights)));
        }
        if let Some(s) = self.rsm_size {
            if self.method == "vsgl2" {
                // The parallel sum tiles any side; only the mip-based methods need 2^k.
                if !(32..=4096).contains(&s) {
                    return Err(Error::invalid("rsm_size", format!("must be in 32..=4096 for method=\"vsgl2\", got {s}")));
                }
            } else if !(32..=4096).contains(&s) || !s.is_power_of_two() {
                return Err(Error::invalid("rsm_size", format!("must be a power of two in 32..=4096, got {s}")));
            }
        }
        if !(self.vpl_clamp.is_finite() && self.vpl_clamp >= 0.0) {
            return Err(Error::invalid("vpl_clamp", format!("must be finite and >= 0, got {}", self.vpl_clamp)));
        }
        if !(self.k.is_finite() && self.k > 0.0) {
            return Err(Error::invalid("K", format!("must be finite and > 0, got {}", self.k)));
        }
        if !(1..=32).contains(&self.bisection_steps) {
            return Err(Error::invalid("bisection_steps", format!("must be in 1..=32, got {}", self.bisection_steps)));
        }
        if !(1..=16).contains(&self.interleave) {
            return Err(Error::invalid("interleave", format!("must be in 1..=16, got {}", self.interleave)));
        }
        if !(1..=65536).contains(&self.spp) {
            return Err(Error::invalid("spp", format!("must be in 1..=65536, got {}", self.spp)));
        }
        for name in self.aovs.iter().flatten() {
            if !AOV_NAMES.contains(&name.as_str()) {
                return Err(Error::invalid("aovs", format!("unknown AOV {name:?}; valid: {}", AOV_NAMES.join(", "))));
            }
            if !method_makes_aov(&self.method, name) {
                let who = aov_methods(name).unwrap_or("every method");
                return Err(Error::invalid("aovs", format!("{name:?} is not made by method={:?}, only by {who}", self.method)));
            }
        }
        if self.visibility != "none" {
            return Err(Error::invalid("visibility", format!(
                "only \"none\" is available in this build (virtual lights are unshadowed), got {:?}", self.visibility
            )));
        }
        Ok(())
    }

    /// Whether the frame reads back AOV `name` (asked for, or all asked for and made).
    fn wants_aov(&self, name: &str) -> bool {
        method_makes_aov(&self.method, name) && self.aovs.as_ref().is_none_or(|a| a.iter().any(|n| n == name))
    }

    fn rsm_size(&self) -> u32 {
        self.rsm_size.unwrap_or(if self.method == "reference" { 1024 } else { 256 })
    }
}

/// One rendered frame: linear float AOVs, row 0 at the top.
#[derive(Clone, Debug)]
pub struct Frame {
    pub width: u32,
    pub height: u32,
    /// (name, channels, data of width·height·channels floats).
    pub aovs: Vec<(String, usize, Vec<f32>)>,
    /// Milliseconds per pass and "total".
    pub timings_ms: Vec<(String, f64)>,
    /// "gpu-timestamp" or "cpu-wall" (adapters without timestamp queries).
    pub timings_clock: String,
    pub passes: Vec<String>,
    pub skipped: Vec<(String, String)>,
    pub settings: Vec<(String, String)>,
    /// The first light's RSM when `capture_rsm` was set: side and (name, channels, data).
    pub rsm: Option<(u32, Vec<(String, usize, Vec<f32>)>)>,
    /// The first light's VSGLs (`vsgl`): VSGL_FLOATS floats each, fields in VSGL_FIELDS order.
    pub vsgls: Option<Vec<f32>>,
    /// GPU buffers and render targets the frame allocated: (label, bytes), summed per label.
    /// The scene's own upload (geometry, textures) is not included.
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
        self.aovs.iter().map(|(n, _, _)| n.clone()).collect()
    }
}

pub struct Renderer {
    pub gpu: Arc<Gpu>,
    pub width: u32,
    pub height: u32,
    visibility: VisibilityPass,
    shadow_map: ShadowMapPass,
    material: MaterialPass,
    direct: DirectPass,
    rsm_flux: RsmFluxPass,
    pdf_mips: PdfMipsPass,
    vpl_sample: VplSamplePass,
    vpl_shading: VplShadingPass,
    vsgl_moments: VsglMomentsPass,
    moment_mips: MomentMipsPass,
    vsgl_gen: VsglGenPass,
    vsgl_shading: VsglShadingPass,
    vsgl2_reduce: Vsgl2Reduce,
    denoise: DenoisePass,
    pathtrace: PathTracePass,
    /// The last scene uploaded and what it was uploaded from: reused while the key matches.
    scene_cache: Mutex<Option<(SceneUploadKey, Arc<GpuScene>)>>,
}

/// What [`GpuScene::upload`] reads: the scene instance, its geometry version, and the frame
/// origin (positions are uploaded relative to the camera, so a moved camera re-uploads).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct SceneUploadKey {
    scene: u64,
    geometry_version: u64,
    origin_bits: [u64; 3],
}

impl SceneUploadKey {
    fn new(scene: &Scene, origin: glam::DVec3) -> Self {
        Self { scene: scene.id.get(), geometry_version: scene.geometry_version, origin_bits: origin.to_array().map(f64::to_bits) }
    }
}

fn light_storage(gpu: &Gpu, light: &SpotLightRaw) -> wgpu::Buffer {
    gpu.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("spot_light_storage_buffer"),
        contents: bytemuck::bytes_of(light),
        usage: wgpu::BufferUsages::STORAGE,
    })
}

fn rgb(v: &[f32]) -> Vec<f32> {
    v.chunks_exact(4).flat_map(|p| [p[0], p[1], p[2]]).collect()
}

impl Renderer {
    pub fn new(gpu: Arc<Gpu>, width: u32, height: u32) -> Result<Self> {
        let max = gpu.limits.max_texture_dimension_2d;
        for (name, v) in [("width", width), ("height", height)] {
            if v == 0 || v > max {
                return Err(Error::invalid(name, format!("must be in 1..={max} on this adapter, got {v}")));
            }
        }
        let r = gpu.scoped("pipeline creation", || {
            Ok(Self {
                gpu: gpu.clone(),
                width,
                height,
                visibility: VisibilityPass::new(&gpu)?,
                shadow_map: ShadowMapPass::new(&gpu)?,
                material: MaterialPass::new(&gpu)?,
                direct: DirectPass::new(&gpu)?,
                rsm_flux: RsmFluxPass::new(&gpu)?,
                pdf_mips: PdfMipsPass::new(&gpu)?,
                vpl_sample: VplSamplePass::new(&gpu)?,
                vpl_shading: VplShadingPass::new(&gpu)?,
                vsgl_moments: VsglMomentsPass::new(&gpu)?,
                moment_mips: MomentMipsPass::new(&gpu)?,
                vsgl_gen: VsglGenPass::new(&gpu)?,
                vsgl_shading: VsglShadingPass::new(&gpu)?,
                vsgl2_reduce: Vsgl2Reduce::new(&gpu)?,
                denoise: DenoisePass::new(&gpu)?,
                pathtrace: PathTracePass::new(&gpu)?,
                scene_cache: Mutex::new(None),
            })
        })?;
        Ok(r)
    }

    pub fn render(&self, scene: &Scene, camera: Option<&Camera>, opts: &RenderOptions) -> Result<Frame> {
        opts.validate()?;
        if opts.method == "vsgl2" {
            Vsgl2Reduce::resolve(&self.gpu, opts.vsgl2_reduction)?;
        }
        if opts.method != "direct" {
            let n = opts.rsm_size() as u64;
            if n * n * 16 > self.gpu.limits.max_storage_buffer_binding_size as u64 {
                return Err(Error::invalid("rsm_size", format!(
                    "{n}² texels exceed this adapter's storage binding limit of {} bytes",
                    self.gpu.limits.max_storage_buffer_binding_size
                )));
            }
            if opts.method == "vsgl" && MomentChains::bytes(n as u32) > self.gpu.limits.max_storage_buffer_binding_size as u64 {
                return Err(Error::invalid("rsm_size", format!(
                    "the VSGL moment mips of a {n}² RSM ({} bytes) exceed this adapter's storage binding limit of {} bytes",
                    MomentChains::bytes(n as u32),
                    self.gpu.limits.max_storage_buffer_binding_size
                )));
            }
        }
        let camera = match camera.or(scene.cameras.first()) {
            Some(c) => *c,
            None => default_camera(scene)?,
        };
        let (frame, log) = crate::passes::log_frame(|| self.gpu.scoped("render", || self.render_inner(scene, &camera, opts)));
        frame.map(|f| Frame { memory_bytes: log.allocations, variants: log.variants, ..f })
    }

    /// The scene's GPU copy for a frame at `origin`: the cached one when nothing it was made
    /// from has changed (then `true`), else a fresh upload that replaces it. One scene is
    /// kept, so alternating between two scenes re-uploads each time.
    fn uploaded_scene(&self, scene: &Scene, origin: glam::DVec3) -> Result<(Arc<GpuScene>, bool)> {
        let key = SceneUploadKey::new(scene, origin);
        if let Some((cached_key, gscene)) = self.scene_cache.lock().unwrap_or_else(|e| e.into_inner()).as_ref() {
            if *cached_key == key {
                return Ok((gscene.clone(), true));
            }
        }
        let gscene = Arc::new(GpuScene::upload(&self.gpu, scene, origin)?);
        *self.scene_cache.lock().unwrap_or_else(|e| e.into_inner()) = Some((key, gscene.clone()));
        Ok((gscene, false))
    }

    /// Drops the cached scene upload (its GPU memory is freed once no frame uses it).
    pub fn clear_scene_cache(&self) {
        *self.scene_cache.lock().unwrap_or_else(|e| e.into_inner()) = None;
    }

    fn render_inner(&self, scene: &Scene, camera: &Camera, opts: &RenderOptions) -> Result<Frame> {
        let gpu = &*self.gpu;
        let (w, h) = (self.width, self.height);
        let wall = Instant::now();
        let plan = Plan::new(scene, opts.plan == "full");
        let feat = plan.features;
        let mut passes: Vec<String> = Vec::new();
        let mut skipped: Vec<(String, String)> = plan.skipped.clone();

        let origin = camera.eye;
        let (gscene, scene_reused) = self.uploaded_scene(scene, origin)?;
        let extent = gscene.extent;
        let lights: Vec<_> = scene
            .lights
            .iter()
            .enumerate()
            .map(|(i, l)| spot_light_raw(l, origin, extent, i as u32, opts.shadow_size))
            .collect();
        let uniforms = frame_uniforms(camera, w, h, lights.len() as u32, gscene.texture_layer_size, extent, opts.shadow_size);
        let frame_buf = uniform_buffer(gpu, "frame_uniform_buffer", &uniforms);
        let light_bytes: Vec<u8> = if lights.is_empty() { vec![0; 128] } else { bytemuck::cast_slice(&lights).to_vec() };
        let light_buf = gpu.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("spot_light_buffer"),
            contents: &light_bytes,
            usage: wgpu::BufferUsages::STORAGE,
        });

        let mut timer = PassTimer::new(gpu, TIMER_CAPACITY);
        let new_encoder = || gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("frame_encoder") });
        let mut enc = new_encoder();

        let vis = VisibilityPass::targets(gpu, w, h);
        self.visibility.record(gpu, &mut enc, &mut timer, "visibility", &frame_buf, &gscene.raster_vertices, gscene.raster_vertex_count, &vis);
        passes.push("visibility".into());

        let shadow_needed = !lights.is_empty() && opts.method != "pathtrace";
        // Unneeded: the smallest placeholder layer, so the binding exists.
        let shadow_tex = ShadowMapPass::target(gpu, if shadow_needed { opts.shadow_size } else { 16 }, lights.len() as u32);
        if shadow_needed {
            let vps: Vec<_> = lights.iter().map(|l| l.view_proj).collect();
            self.shadow_map.record(gpu, &mut enc, &mut timer, &shadow_tex, &vps, &gscene.raster_vertices, gscene.raster_vertex_count);
            passes.push("shadow_map".into());
        } else {
            // Clear the one placeholder layer so the binding is defined.
            self.shadow_map.record(gpu, &mut enc, &mut PassTimer::new_disabled(), &shadow_tex, &[], &gscene.raster_vertices, 0);
            let why = if lights.is_empty() { "the scene has no spot light" } else { "method=\"pathtrace\" traces shadow rays" };
            skipped.push(("shadow_map".into(), why.into()));
        }

        let gbuffer = GBuffer::new(gpu, w, h);
        self.material.record(gpu, &mut enc, &mut timer, "material", &frame_buf, &vis.ids, &gscene, feat, &gbuffer, (w, h));
        passes.push(feat.pass_name("material"));

        let direct_out = storage_buffer(gpu, "direct_radiance_buffer", w as u64 * h as u64 * 16);
        let shadow_view = shadow_tex.create_view(&wgpu::TextureViewDescriptor {
            label: Some("shadow_map_array_view"),
            dimension: Some(wgpu::TextureViewDimension::D2Array),
            ..Default::default()
        });
        if opts.method != "pathtrace" {
            self.direct.record(gpu, &mut enc, &mut timer, &frame_buf, &light_buf, &shadow_view, &gbuffer, &direct_out, feat, (w, h));
            passes.push(feat.pass_name("direct"));
        }

        // Indirect light: one RSM per spot light, then VPLs (sampled, or every texel).
        let pixel_bytes = w as u64 * h as u64 * 16;
        // Without specular materials the specular targets are never bound for writing: a
        // 16-byte placeholder keeps the bind group layouts of the full variants.
        let specular_bytes = if feat.specular { pixel_bytes } else { 16 };
        let indirect = IndirectTargets {
            diffuse: storage_buffer(gpu, "indirect_diffuse_buffer", pixel_bytes),
            specular: storage_buffer(gpu, "indirect_specular_buffer", specular_bytes),
        };
        let mut captured_rsm: Option<(u32, Vec<(String, usize, Vec<f32>)>)> = None;
        // VSGLs with interleaving are shaded into `noisy` and filtered into `indirect`.
        let filter = opts.method == "vsgl" && opts.interleave > 1 && opts.denoise;
        let noisy = IndirectTargets {
            diffuse: storage_buffer(gpu, "indirect_noisy_diffuse_buffer", if filter { pixel_bytes } else { 16 }),
            specular: storage_buffer(gpu, "indirect_noisy_specular_buffer", if filter { specular_bytes } else { 16 }),
        };
        let mut vsgl_chains: Option<MomentChains> = None;
        let mut first_vsgls: Option<wgpu::Buffer> = None;
        let mut pathtrace_stderr: Option<wgpu::Buffer> = None;
        if opts.method == "direct" {
            skipped.push(("indirect".into(), "method=\"direct\" computes direct light only".into()));
        } else if opts.method == "pathtrace" {
            // Direct light by shadow rays, then `spp` BRDF-sampled bounces per pixel in batches.
            let input = PathTraceInputs {
                scene, origin, frame: &frame_buf, lights: &light_buf, gscene: &gscene, gbuffer: &gbuffer, ids: &vis.ids, features: feat,
            };
            let out = self.pathtrace.record(gpu, &mut enc, &new_encoder, &mut timer, &input, &indirect, &direct_out, opts.spp, opts.seed, (w, h))?;
            passes.extend(out.passes);
            pathtrace_stderr = Some(out.stderr);
            skipped.push(("rsm".into(), "method=\"pathtrace\" traces rays instead of virtual lights".into()));
        } else if lights.is_empty() {
            skipped.push(("indirect".into(), "the scene has no spot light".into()));
        } else {
            let n = opts.rsm_size();
            let sampling = matches!(opts.method.as_str(), "vpl" | "vsgl");
            let rsm = Rsm::new(gpu, n, feat.specular, sampling);
            let rsm_vis = VisibilityPass::targets(gpu, n, n);
            let min_distance2 = (opts.vpl_clamp as f64 * extent).powi(2) as f32;
            let reference = opts.method == "reference";
            let vpl_capacity = match opts.method.as_str() {
                "reference" => (n as u64 * n as u64).min(1 << 20),
                "vpl" => opts.num_lights as u64,
                _ => 1,
            };
            let vpls = storage_buffer(gpu, "vpl_buffer", vpl_capacity * VPL_BYTES);
            for (i, light) in scene.lights.iter().enumerate() {
                let view = light_view_uniforms(light, origin, extent, n, gscene.texture_layer_size);
                let view_buf = uniform_buffer(gpu, "rsm_view_uniform_buffer", &view);
                let light_one = light_storage(gpu, &lights[i]);
                self.visibility.record(gpu, &mut enc, &mut timer, "rsm_visibility", &view_buf, &gscene.raster_vertices, gscene.raster_vertex_count, &rsm_vis);
                self.material.record(gpu, &mut enc, &mut timer, "rsm_material", &view_buf, &rsm_vis.ids, &gscene, feat, &rsm.gbuffer, (n, n));
                self.rsm_flux.record(gpu, &mut enc, &mut timer, &view_buf, light_one.as_entire_binding(), &rsm, feat);
                if reference {
                    // Every texel is a VPL, in batches bounded by the evaluation budget.
                    let texels = n as u64 * n as u64;
                    let pixels = w as u64 * h as u64;
                    let per_batch = (REFERENCE_BATCH_EVALUATIONS / pixels.max(1))
                        .max(texels.div_ceil(REFERENCE_MAX_BATCHES))
                        .clamp(64, vpl_capacity);
                    let mut first = 0u64;
                    while first < texels {
                        let count = per_batch.min(texels - first);
                        self.vpl_sample.record_every_texel(gpu, &mut enc, &mut timer, light_one.as_entire_binding(), &rsm, first as u32, count as u32, &vpls, feat);
                        self.vpl_shading.record(gpu, &mut enc, &mut timer, &frame_buf, &vpls, count as u32, min_distance2, &gbuffer, &indirect, feat, (w, h));
                        first += count;
                        if first < texels && count * pixels >= REFERENCE_BATCH_EVALUATIONS / 2 {
                            // Submit this batch on its own so no submission runs for long.
                            let done = std::mem::replace(&mut enc, new_encoder());
                            gpu.queue.submit([done.finish()]);
                            gpu.wait("reference batch")?;
                        }
                    }
                } else if opts.method == "vsgl" {
                    let chains = vsgl_chains.get_or_insert_with(|| MomentChains::new(gpu, n));
                    self.pdf_mips.record(gpu, &mut enc, &mut timer, &rsm);
                    self.vsgl_moments.record(gpu, &mut enc, &mut timer, &rsm, chains, feat);
                    self.moment_mips.record(gpu, &mut enc, &mut timer, n, chains);
                    let buf = storage_buffer(gpu, "vsgl_buffer", opts.num_lights as u64 * VSGL_BYTES);
                    let gen = GenSettings {
                        count: opts.num_lights,
                        stratified: opts.sampling == Sampling::Stratified,
                        seed: opts.seed,
                        kernel: opts.kernel,
                        k: opts.k,
                        bisection_steps: opts.bisection_steps,
                        light_offset: lights[i].position,
                    };
                    self.vsgl_gen.record(gpu, &mut enc, &mut timer, &rsm, chains, &gen, &buf);
                    let target = if filter { &noisy } else { &indirect };
                    self.vsgl_shading.record(gpu, &mut enc, &mut timer, &frame_buf, &buf, opts.num_lights, opts.interleave, opts.diffuse, &gbuffer, target, feat, (w, h));
                    if i == 0 {
                        first_vsgls = Some(buf);
                    }
                } else if opts.method == "vsgl2" {
                    // The poster: the whole RSM summed to one diffuse and one specular VSGL.
                    let buf = storage_buffer(gpu, "vsgl2_buffer", VSGL2_COUNT as u64 * VSGL_BYTES);
                    self.vsgl2_reduce.record(gpu, &mut enc, &mut timer, &rsm, lights[i].position, &buf, feat, opts.vsgl2_reduction)?;
                    self.vsgl_shading.record(gpu, &mut enc, &mut timer, &frame_buf, &buf, VSGL2_COUNT, 1, opts.diffuse, &gbuffer, &indirect, feat, (w, h));
                    if i == 0 {
                        first_vsgls = Some(buf);
                    }
                } else {
                    self.pdf_mips.record(gpu, &mut enc, &mut timer, &rsm);
                    self.vpl_sample.record_importance(gpu, &mut enc, &mut timer, light_one.as_entire_binding(), &rsm, opts.num_lights, opts.sampling, opts.seed, &vpls, feat);
                    self.vpl_shading.record(gpu, &mut enc, &mut timer, &frame_buf, &vpls, opts.num_lights, min_distance2, &gbuffer, &indirect, feat, (w, h));
                }
                if i == 0 && opts.capture_rsm {
                    // Read back before the next light overwrites the shared RSM buffers.
                    let done = std::mem::replace(&mut enc, new_encoder());
                    gpu.queue.submit([done.finish()]);
                    let b = gpu.read_buffers(&[&rsm.gbuffer.position, &rsm.gbuffer.normal, &rsm.flux_diffuse, &rsm.flux_specular])?;
                    let f = |x: &Vec<u8>| -> Vec<f32> { bytemuck::cast_slice::<u8, f32>(x).to_vec() };
                    let texels = n as usize * n as usize;
                    let fs = if feat.specular { f(&b[3]) } else { vec![0.0; texels * 4] };
                    let (pos, nrm, fd) = (f(&b[0]), f(&b[1]), f(&b[2]));
                    let roughness: Vec<f32> = nrm.chunks_exact(4).map(|p| p[3]).collect();
                    let weight: Vec<f32> = fd.chunks_exact(4).map(|p| p[3]).collect();
                    captured_rsm = Some((n, vec![
                        ("position".into(), 3, rgb(&pos)),
                        ("normal".into(), 3, rgb(&nrm)),
                        ("roughness".into(), 1, roughness),
                        ("flux_diffuse".into(), 3, rgb(&fd)),
                        ("flux_specular".into(), 3, rgb(&fs)),
                        ("weight".into(), 1, weight),
                    ]));
                }
            }
            let mut ran: Vec<&str> = vec!["rsm_visibility", "rsm_material", "rsm_flux"];
            if opts.method == "vsgl" {
                ran.extend(["pdf_mips", "vsgl_moments", "moment_mips", "vsgl_gen", "vsgl_shading"]);
                if filter {
                    self.denoise.record(gpu, &mut enc, &mut timer, &frame_buf, opts.interleave, &gbuffer, &noisy, &indirect, feat, (w, h));
                    ran.push("denoise");
                } else if opts.interleave == 1 {
                    skipped.push(("denoise".into(), "interleave=1: every pixel evaluates every VSGL".into()));
                } else {
                    skipped.push(("denoise".into(), "denoise=False".into()));
                }
            } else if opts.method == "vsgl2" {
                ran.extend(["vsgl2_reduce", "vsgl_shading"]);
                let why = "method=\"vsgl2\": two VSGLs from a parallel sum over the whole RSM";
                skipped.push(("pdf_mips".into(), format!("{why}, no importance sampling")));
                skipped.push(("moment_mips".into(), format!("{why}, no mipmapped moments")));
                skipped.push(("vsgl_sampling".into(), format!("{why}, no kernels to place")));
                skipped.push(("denoise".into(), format!("{why}: every pixel evaluates both VSGLs (no interleaving)")));
            } else if reference {
                ran.extend(["vpl_sample[every_texel]", "vpl_shading"]);
                skipped.push(("pdf_mips".into(), "the reference uses every RSM texel, no importance sampling".into()));
            } else {
                ran.extend(["pdf_mips", "vpl_sample", "vpl_shading"]);
            }
            passes.extend(ran.iter().map(|p| feat.pass_name(p)));
            skipped.push(("vpl_shadow_maps".into(), "visibility=\"none\": virtual lights are unshadowed".into()));
        }

        timer.resolve(&mut enc);
        gpu.queue.submit([enc.finish()]);
        // Read back only the buffers the asked-for AOVs are made from.
        let wants = |names: &[&str]| names.iter().any(|n| opts.wants_aov(n));
        let specular_wanted = wants(&["image", "indirect", "indirect_specular"]);
        let sources: Vec<(&str, &wgpu::Buffer)> = [
            ("direct", &direct_out, wants(&["image", "direct"])),
            ("indirect_diffuse", &indirect.diffuse, wants(&["image", "indirect", "indirect_diffuse"])),
            ("indirect_specular", &indirect.specular, feat.specular && specular_wanted),
            ("albedo", &gbuffer.base_color, wants(&["albedo"])),
            ("normal", &gbuffer.normal, wants(&["normal"])),
            ("depth", &gbuffer.position, wants(&["depth"])),
        ]
        .into_iter()
        .chain(pathtrace_stderr.as_ref().map(|b| ("stderr", b, wants(&["stderr"]))))
        .filter(|(_, _, wanted)| *wanted)
        .map(|(name, buffer, _)| (name, buffer))
        .collect();
        let buffers: Vec<&wgpu::Buffer> = sources.iter().map(|(_, b)| *b).collect();
        let read = if buffers.is_empty() { Vec::new() } else { gpu.read_buffers(&buffers)? };
        let mut raw: std::collections::HashMap<&str, Vec<f32>> =
            sources.iter().zip(read).map(|((name, _), bytes)| (*name, bytemuck::cast_slice::<u8, f32>(&bytes).to_vec())).collect();
        let vsgls = match &first_vsgls {
            Some(b) => Some(bytemuck::cast_slice::<u8, f32>(&gpu.read_buffers(&[b])?[0]).to_vec()),
            None => None,
        };
        let wall_ms = wall.elapsed().as_secs_f64() * 1e3;
        let mut timings = timer.read(gpu)?;
        let clock = if timings.is_empty() {
            timings.push(("total".into(), wall_ms));
            "cpu-wall"
        } else {
            let total: f64 = timings.iter().map(|(_, t)| t).sum();
            timings.push(("total".into(), total));
            "gpu-timestamp"
        };

        let pixels = w as usize * h as usize;
        let mut take_rgb = |name: &str| raw.remove(name).map(|v| rgb(&v));
        let direct = take_rgb("direct");
        let ind_d = take_rgb("indirect_diffuse");
        // Without specular materials the specular target is a placeholder: zero by definition
        // (made whenever the specular part is wanted, with or without the diffuse readback).
        let ind_s = take_rgb("indirect_specular").or_else(|| specular_wanted.then(|| vec![0.0; pixels * 3]));
        let albedo = take_rgb("albedo");
        let normal = take_rgb("normal");
        let stderr = take_rgb("stderr");
        // View depth; 0 where no surface was hit (never Inf, see docs/rendering.md).
        let depth = raw.remove("depth").map(|p| p.chunks_exact(4).map(|p| if p[3] > 0.0 { p[3] } else { 0.0 }).collect::<Vec<f32>>());
        let sum = |a: &[f32], b: &[f32]| -> Vec<f32> { a.iter().zip(b).map(|(x, y)| x + y).collect() };
        let indirect_sum = match (&ind_d, &ind_s) {
            (Some(d), Some(s)) => Some(sum(d, s)),
            _ => None,
        };
        // With method="direct" the image is the direct AOV: moved, not copied, unless both are
        // asked for.
        let (image, direct) = match (&direct, &indirect_sum) {
            _ if opts.method == "direct" && opts.wants_aov("direct") => (direct.clone(), direct),
            _ if opts.method == "direct" => (direct, None),
            (Some(d), Some(i)) => (Some(sum(d, i)), direct),
            _ => (None, direct),
        };
        let made: [(&str, usize, Option<Vec<f32>>); 9] = [
            ("image", 3, image),
            ("indirect", 3, indirect_sum),
            ("indirect_diffuse", 3, ind_d),
            ("indirect_specular", 3, ind_s),
            ("direct", 3, direct),
            ("albedo", 3, albedo),
            ("normal", 3, normal),
            ("depth", 1, depth),
            ("stderr", 3, stderr),
        ];
        let aovs: Vec<(String, usize, Vec<f32>)> = made
            .into_iter()
            .filter(|(name, _, _)| opts.wants_aov(name))
            .filter_map(|(name, c, data)| data.map(|d| (name.to_string(), c, d)))
            .collect();
        let mut settings = vec![
            ("method".into(), opts.method.clone()),
            ("width".into(), w.to_string()),
            ("height".into(), h.to_string()),
            ("shadow_size".into(), opts.shadow_size.to_string()),
            ("plan".into(), opts.plan.clone()),
            ("adapter".into(), gpu.adapter.name.clone()),
            ("scene_upload".into(), if scene_reused { "reused" } else { "uploaded" }.into()),
        ];
        if opts.method == "pathtrace" {
            settings.push(("spp".into(), opts.spp.to_string()));
            settings.push(("seed".into(), opts.seed.to_string()));
        } else if opts.method != "direct" {
            settings.push(("rsm_size".into(), opts.rsm_size().to_string()));
            settings.push(("visibility".into(), opts.visibility.clone()));
            settings.push(("vpl_clamp".into(), opts.vpl_clamp.to_string()));
        }
        if opts.method == "vsgl" {
            settings.push(("kernel".into(), match opts.kernel { Kernel::Density => "density", Kernel::Integral => "integral" }.into()));
            settings.push(("K".into(), opts.k.to_string()));
            settings.push(("bisection_steps".into(), opts.bisection_steps.to_string()));
            settings.push(("interleave".into(), opts.interleave.to_string()));
            settings.push(("denoise".into(), opts.denoise.to_string()));
            settings.push(("diffuse".into(), opts.diffuse.name().into()));
        }
        if opts.method == "vsgl2" {
            settings.push(("diffuse".into(), opts.diffuse.name().into()));
            settings.push(("vsgl2_temporary_bytes".into(), Vsgl2Reduce::temporary_bytes(opts.rsm_size()).to_string()));
            let reduction = Vsgl2Reduce::resolve(gpu, opts.vsgl2_reduction)?;
            settings.push(("vsgl2_reduction".into(), reduction.name().into()));
        }
        if opts.method == "vpl" || opts.method == "vsgl" {
            settings.push(("num_lights".into(), opts.num_lights.to_string()));
            settings.push(("sampling".into(), match opts.sampling { Sampling::Stratified => "stratified", Sampling::Random => "random" }.into()));
            settings.push(("seed".into(), opts.seed.to_string()));
        }
        Ok(Frame { width: w, height: h, aovs, timings_ms: timings, timings_clock: clock.into(), passes, skipped, settings, rsm: captured_rsm, vsgls, memory_bytes: Vec::new(), variants: Vec::new() })
    }
}

/// A camera that frames the scene bounds when the scene has none: from the front (+Z) and
/// above, so flat scenes such as a ground plane are not seen edge-on.
pub fn default_camera(scene: &Scene) -> Result<Camera> {
    let b = scene.bounds();
    if b.is_empty() {
        return Err(Error::invalid("camera", "the scene has no camera and no geometry to frame; pass camera="));
    }
    let c = b.center();
    let r = 0.5 * b.diagonal().max(1e-12);
    let fov = 45f32.to_radians();
    let dist = r / (fov as f64 * 0.5).sin();
    let from = glam::DVec3::new(0.0, 0.6, 1.0).normalize();
    Camera::look_at(c + from * dist, c, glam::DVec3::Y, fov).map_err(|e| Error::invalid("camera", e))
}
