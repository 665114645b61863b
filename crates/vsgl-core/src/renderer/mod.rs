//! The renderer and the frame script: upload the scene, then visibility → shadow maps →
//! material → direct light → the method's own passes → readback. The script names no method:
//! what differs between methods is in `crate::methods`, what a frame reads back in
//! [`readback`], its settings in [`options`]. Layers and data flow: docs/architecture.md.

pub mod device_limits;
mod frame;
mod options;
mod readback;

pub use frame::Frame;
pub use options::{PlanMode, Progress, RenderOptions, StopCheck, AOV_NAMES, ON_REQUEST_AOVS};

use crate::error::{Error, Result};
use crate::frame::uniforms::{frame_uniforms, light_raws, shadow_layer_count, shadow_view_projs, views_seeing_scene};
use crate::frame::{GBuffer, IndirectTargets, VisibilityTargets};
use crate::gpu::frame_log::{log_frame, FrameLog};
use crate::gpu::{kept_staging_buffer, read_staging, FrameResources, Gpu, PassCache, PassTimer, Recorder};
use crate::methods::options::ChoiceEnum;
use crate::methods::emitter_direct::EmitterDirect;
use crate::methods::{options::common, DirectLight, FrameContext, Method, MethodInfo, OptionValue, Options};
use crate::passes::{direct::{emitter_quadrature_bytes, DirectPass, ShadowMappedLights}, material::{MaterialPass, RasterView}, shadow_map::ShadowMapPass, visibility::VisibilityPass};
use crate::plan::{Plan, ShaderFeatures};
use crate::scene::{Camera, Light, Scene};
use crate::setting::Setting;
use crate::upload::GpuScene;
use crate::passes::aov_pack::{AovPackPass, PackSources};
use readback::{record_aovs, PendingAovs};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Instant;

/// Query pairs one frame may time: the reference's batches are the most numerous.
const TIMER_CAPACITY: u32 = 2048;

pub struct Renderer {
    pub gpu: Arc<Gpu>,
    /// Width and height of the frames rendered from now on ([`Self::resize`] changes them;
    /// a frame reads them once, when it is recorded).
    size: Mutex<(u32, u32)>,
    /// Every pass a frame has needed so far, created on first use.
    passes: PassCache,
    /// The last scene uploaded and what it was uploaded from: reused while the key matches.
    scene_cache: Mutex<Option<(SceneUploadKey, Arc<GpuScene>)>>,
    /// Kept from frame to frame; held while a frame is recorded (frames of one renderer are
    /// recorded one at a time).
    frame_state: Mutex<FrameState>,
    /// Idle readback slots: a frame takes one when it is recorded and gives it back when it
    /// has been read, so a frame in flight never shares its staging buffers or queries with
    /// the next one (a ring of two in `render_sequence`).
    readback_slots: Mutex<Vec<ReadbackSlot>>,
    /// Frames submitted and neither finished nor dropped (`frame.settings["frames_in_flight"]`).
    in_flight: Arc<AtomicUsize>,
}

/// What a renderer keeps between frames besides passes, readback slots and the scene upload.
#[derive(Default)]
struct FrameState {
    resources: FrameResources,
    /// `sampling="metropolis"`: the Markov chains, one per virtual light per RSM view.
    chains: Option<crate::methods::metropolis::MetropolisChains>,
}

/// Idle readback slots kept beyond this many are dropped (more exist only while several
/// threads render with one renderer).
const READBACK_SLOTS_KEPT: usize = 4;

/// What one frame in flight reads back through: its timestamp queries and staging buffers,
/// kept from frame to frame.
struct ReadbackSlot {
    timer: PassTimer,
    aov_staging: Option<wgpu::Buffer>,
    vsgl_staging: Option<wgpu::Buffer>,
    /// The RSM powers of a frame with several lights or cube faces (read in mid-frame).
    power_staging: Option<wgpu::Buffer>,
}

/// What the frame script hands [`Renderer::submit`]: see [`SubmittedFrame`].
struct Recorded {
    frame: Frame,
    features: ShaderFeatures,
    submission: wgpu::SubmissionIndex,
    aovs: PendingAovs,
    vsgl_bytes: Option<u64>,
}

/// A frame recorded and submitted, not yet read back: [`Renderer::finish`] waits for its
/// submission only, so the next frame can be recorded and submitted meanwhile.
pub struct SubmittedFrame {
    /// The frame without its AOVs, timings and log-derived fields.
    frame: Frame,
    features: ShaderFeatures,
    log: FrameLog,
    slot: ReadbackSlot,
    submission: wgpu::SubmissionIndex,
    aovs: PendingAovs,
    /// Bytes of the first light's VSGLs in the slot's VSGL staging buffer.
    vsgl_bytes: Option<u64>,
    started: Instant,
    in_flight: InFlight,
}

/// Counts a frame as in flight from its submission until it is read back or dropped unread (a
/// sequence abandoned with a frame submitted ahead must not leave the count raised).
struct InFlight(Arc<AtomicUsize>);

impl InFlight {
    fn new(count: &Arc<AtomicUsize>) -> Self {
        count.fetch_add(1, Ordering::SeqCst);
        Self(count.clone())
    }
}

impl SubmittedFrame {
    /// Where AOV `name` lies on the GPU, packed (buffer, byte offset), for a frame rendered with
    /// [`RenderOptions::keep_on_gpu`]; None otherwise or when the frame did not make it. The
    /// buffer is the renderer's and the next frame packs into it: copy out what must outlive
    /// that before submitting it (the queue runs submissions in order).
    pub fn packed_aov(&self, name: &str) -> Option<(&wgpu::Buffer, u64)> {
        self.aovs.kept(name)
    }

    /// (width, height) of the frame.
    pub fn size(&self) -> (u32, u32) {
        (self.frame.width, self.frame.height)
    }
}

impl Drop for InFlight {
    fn drop(&mut self) {
        self.0.fetch_sub(1, Ordering::SeqCst);
    }
}

/// What [`GpuScene::upload`] reads: the scene instance and its geometry version (positions
/// are uploaded relative to the scene's own anchor, so a moved camera reuses the upload).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct SceneUploadKey {
    scene: u64,
    geometry_version: u64,
}

impl SceneUploadKey {
    fn new(scene: &Scene) -> Self {
        Self { scene: scene.id.get(), geometry_version: scene.geometry_version }
    }
}

impl Renderer {
    pub fn new(gpu: Arc<Gpu>, width: u32, height: u32) -> Result<Self> {
        check_size(&gpu, width, height)?;
        let passes = PassCache::new(gpu.clone());
        // The passes of every frame, so a broken install fails here rather than at the first
        // render; the methods' passes are created when a frame first needs them.
        gpu.scoped("pipeline creation", || {
            passes.get::<VisibilityPass>()?;
            passes.get::<ShadowMapPass>()?;
            passes.get::<MaterialPass>()?;
            passes.get::<DirectPass>()?;
            Ok(())
        })?;
        Ok(Self { gpu, size: Mutex::new((width, height)), passes, scene_cache: Mutex::new(None), frame_state: Mutex::default(), readback_slots: Mutex::default(), in_flight: Default::default() })
    }

    /// Width of the frames rendered from now on.
    pub fn width(&self) -> u32 {
        self.size().0
    }

    /// Height of the frames rendered from now on.
    pub fn height(&self) -> u32 {
        self.size().1
    }

    /// (width, height) of the frames rendered from now on.
    pub fn size(&self) -> (u32, u32) {
        *self.size.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Renders the next frames at `width` × `height`, keeping the device, the compiled passes
    /// and the scene upload (a live view's window is resized many times; a new renderer would
    /// compile every pass again). Frames already submitted keep their own size; the frame
    /// targets of the old size are dropped as any target no frame asks for.
    pub fn resize(&self, width: u32, height: u32) -> Result<()> {
        check_size(&self.gpu, width, height)?;
        *self.size.lock().unwrap_or_else(|e| e.into_inner()) = (width, height);
        Ok(())
    }

    /// Renders one frame: [`Self::submit`] then [`Self::finish`].
    pub fn render(&self, scene: &Scene, camera: Option<&Camera>, opts: &RenderOptions) -> Result<Frame> {
        self.finish(self.submit(scene, camera, opts)?)
    }

    /// Records and submits a frame without waiting for it. Nothing of `scene` is read after
    /// this returns, so the caller may edit it for the next frame.
    pub fn submit(&self, scene: &Scene, camera: Option<&Camera>, opts: &RenderOptions) -> Result<SubmittedFrame> {
        let (info, mut options) = opts.resolve()?;
        // The method parses its options and resolves the defaults that depend on others.
        let method = (info.configure)(&mut options)?;
        method.check(&self.gpu)?;
        let camera = match camera {
            Some(c) => *c,
            None => default_camera(scene)?,
        };
        let job = FrameJob { scene, camera: &camera, opts, info, options: &options, method: &*method };
        let started = Instant::now();
        let slot = self.readback_slots.lock().unwrap_or_else(|e| e.into_inner()).pop();
        let mut slot = slot.unwrap_or_else(|| ReadbackSlot { timer: PassTimer::new(&self.gpu, TIMER_CAPACITY), aov_staging: None, vsgl_staging: None, power_staging: None });
        let (recorded, log) = log_frame(|| self.gpu.scoped("render", || self.render_inner(&job, &mut slot)));
        match recorded {
            Ok(Recorded { frame, features, submission, aovs, vsgl_bytes }) => {
                let in_flight = InFlight::new(&self.in_flight);
                Ok(SubmittedFrame { frame, features, log, slot, submission, aovs, vsgl_bytes, started, in_flight })
            }
            Err(e) => {
                self.give_back(slot);
                Err(e)
            }
        }
    }

    /// Waits for a submitted frame (and for nothing submitted after it) and reads it back.
    pub fn finish(&self, submitted: SubmittedFrame) -> Result<Frame> {
        let SubmittedFrame { frame, features, log, slot, submission, aovs, vsgl_bytes, started, in_flight } = submitted;
        // This frame and those submitted after it that are still unread: 2 when the next frame
        // of a sequence was already on the GPU while this one was read back.
        let frames_in_flight = in_flight.0.load(Ordering::SeqCst);
        drop(in_flight);
        let gpu = &*self.gpu;
        let read_start = Instant::now();
        let read = gpu.scoped("readback", || {
            let aovs = aovs.read(gpu, &submission)?;
            let vsgls = match (&slot.vsgl_staging, vsgl_bytes) {
                (Some(st), Some(bytes)) => Some(read_staging::<f32>(gpu, st, bytes, Some(&submission), "VSGL readback")?),
                _ => None,
            };
            Ok((aovs, vsgls, slot.timer.read(gpu, &submission)?))
        });
        self.give_back(slot);
        let (aovs, vsgls, mut timings) = read?;
        let mut warnings = frame.warnings;
        if let Some((covered, lit)) = aovs.coverage {
            let pixels = frame.width as u64 * frame.height as u64;
            if covered == 0 {
                warnings.push(format!("the camera sees no geometry: all {pixels} pixels are background (is the scene behind the camera, or the camera inside an object facing away?)"));
            } else if lit == 0 && !warnings.iter().any(|w| w.starts_with("the scene has no light")) {
                warnings.push(format!(
                    "the image is black: no light reaches any of the {covered} visible surface pixels (lights outside the view, pointing away, occluded, or with cones too narrow to hit anything)"
                ));
            }
        }
        // Waiting for the GPU, mapping and copying out: the wall cost of the readback on top of
        // the GPU frame (the GPU's own packing and copy are the `aov_pack` timing).
        let readback_ms = read_start.elapsed().as_secs_f64() * 1e3;
        let wall_ms = started.elapsed().as_secs_f64() * 1e3;
        let clock = if timings.is_empty() {
            timings.push(("total".into(), wall_ms));
            "cpu-wall"
        } else {
            let total: f64 = timings.iter().map(|(_, t)| t).sum();
            timings.push(("total".into(), total));
            "gpu-timestamp"
        };
        // What ran is what the passes logged as they began, with their plan variants named.
        let passes = log.passes.iter().map(|p| features.pass_name(p)).collect();
        let mut settings = frame.settings;
        // What this frame created; 0 when it reused every target of an earlier frame.
        settings.push(("allocated_bytes".into(), log.allocations.iter().map(|(_, b)| b).sum::<u64>().into()));
        // Bind groups made now (0 when every pass bound what an earlier frame bound).
        settings.push(("bind_groups_created".into(), log.bind_groups_created.into()));
        settings.push(("frames_in_flight".into(), frames_in_flight.into()));
        settings.push(("readback_ms".into(), readback_ms.into()));
        settings.extend(log.settings.iter().cloned());
        Ok(Frame {
            aovs: aovs.float,
            ldr: aovs.ldr,
            vsgls,
            timings_ms: timings,
            timings_clock: clock.into(),
            memory_bytes: log.uses,
            variants: log.variants,
            passes,
            settings,
            warnings,
            ..frame
        })
    }

    fn give_back(&self, slot: ReadbackSlot) {
        let mut slots = self.readback_slots.lock().unwrap_or_else(|e| e.into_inner());
        if slots.len() < READBACK_SLOTS_KEPT {
            slots.push(slot);
        }
    }

    /// The scene's GPU copy: the cached one when nothing it was made from has changed (then
    /// `true`), else a fresh upload that replaces it. One scene is kept, so alternating
    /// between two scenes re-uploads each time.
    fn uploaded_scene(&self, scene: &Scene) -> Result<(Arc<GpuScene>, bool)> {
        let key = SceneUploadKey::new(scene);
        if let Some((cached_key, gscene)) = self.scene_cache.lock().unwrap_or_else(|e| e.into_inner()).as_ref() {
            if *cached_key == key {
                return Ok((gscene.clone(), true));
            }
        }
        let started = Instant::now();
        let gscene = Arc::new(GpuScene::upload(&self.gpu, scene)?);
        crate::gpu::frame_log::note_setting("scene_upload_ms", (started.elapsed().as_secs_f64() * 1e3).into());
        *self.scene_cache.lock().unwrap_or_else(|e| e.into_inner()) = Some((key, gscene.clone()));
        Ok((gscene, false))
    }

    /// Forgets the Metropolis–Hastings chains of `sampling="metropolis"`: the next such frame
    /// starts them afresh from the warp, as a new renderer would.
    pub fn reset_chains(&self) {
        crate::methods::metropolis::reset(&mut self.frame_state.lock().unwrap_or_else(|e| e.into_inner()).chains);
    }

    /// Drops the cached scene upload (its GPU memory is freed once no frame uses it).
    pub fn clear_scene_cache(&self) {
        *self.scene_cache.lock().unwrap_or_else(|e| e.into_inner()) = None;
    }

    /// The frame script: records the frame, with `slot`'s timer and staging buffers, and
    /// submits it.
    fn render_inner(&self, job: &FrameJob<'_>, slot: &mut ReadbackSlot) -> Result<Recorded> {
        let (gpu, scene, camera, info) = (&*self.gpu, job.scene, job.camera, job.info);
        let (w, h) = self.size();
        let plan = Plan::new(scene, job.opts.plan == PlanMode::Full);
        let feat = plan.features;
        let mut skipped: Vec<(String, String)> = plan.skipped.clone();

        // What the lights need from the device, before any GPU work (the upload included): a
        // scene too large for the adapter is refused with the limit and how to stay within it.
        let shadow_size = if info.takes("shadow_size") { job.options.u32("shadow_size")? } else { default_shadow_size() };
        let shadow_mapped = info.direct_light == DirectLight::ShadowMapped;
        device_limits::check_lights(&scene.lights, shadow_mapped.then_some(shadow_size), &gpu.limits)?;

        // Frame space: positions relative to the eye (rays start at 0). Uploaded vertices are
        // relative to the scene's anchor; the passes that read them shift them to the eye.
        let origin = camera.eye;
        let (gscene, scene_reused) = self.uploaded_scene(scene)?;
        let (extent, anchor) = (gscene.extent, gscene.anchor);
        // The frame's lights: the scene's, then its emissive surfaces as clusters of lights in
        // the methods that light with shadow and reflective shadow maps (`emitter_lights`;
        // `pathtrace` samples the emissive triangles themselves). Their device needs are
        // checked again now that the upload has counted the emitters.
        let mut light_sources = scene.lights.clone();
        // How the emitter lights' direct light is shaded (`emitter_direct`), with the visibility
        // that shadows their VSGLs; checked whether or not the scene emits.
        let (emitter_direct, emitter_visibility) = EmitterDirect::from_options(job.options, info.takes("emitter_direct"))?;
        let emitter_clusters = if info.takes("emitter_lights") && gscene.emitter_count > 0 {
            gscene.emitter_lights(scene, job.options.u32("emitter_lights")? as usize)
        } else {
            std::sync::Arc::new(crate::upload::emitters::EmitterClusters::default())
        };
        if !emitter_clusters.lights.is_empty() {
            let emitter_lights = &emitter_clusters.lights;
            // A cluster's intensity Σ L_e·A is bounded like a light's (the same check): radiance
            // (≤ 1e32) times a large enough area passes f32's range, and the frame would
            // saturate, not fail.
            for light in emitter_lights.iter() {
                crate::scene::limits::intensity("emissive surfaces", "candela: a cluster's radiance × area; lower the emission or the scene's length unit", light.intensity as f64)?;
            }
            light_sources.extend(emitter_lights.iter().copied().map(Light::Emitter));
            device_limits::check_lights(&light_sources, shadow_mapped.then_some(shadow_size), &gpu.limits)?;
        }
        // Methods without shadow maps still fill the lights' shadow fields (with the default).
        let lights = light_raws(&light_sources, origin, anchor, extent, shadow_size);
        // Shadow layers: one per spot or directional light, a cube of six per point or
        // emitter light.
        let shadow_layers: u32 = light_sources.iter().map(shadow_layer_count).sum();
        let uniforms = frame_uniforms(camera, anchor, (w, h), lights.len() as u32, gscene.texture_layer_size, extent, shadow_size);

        // What the renderer keeps from frame to frame: targets, buffers, the timer's queries.
        let mut state = self.frame_state.lock().unwrap_or_else(|e| e.into_inner());
        let FrameState { resources, chains } = &mut *state;
        let timer = &mut slot.timer;
        timer.reset();
        resources.begin_frame();
        let mut rec = Recorder::new(gpu, timer, resources);
        let frame_buf = rec.uniform("frame_uniform_buffer", &uniforms);
        let light_bytes: Vec<u8> = if lights.is_empty() { vec![0; 128] } else { bytemuck::cast_slice(&lights).to_vec() };
        let light_buf = rec.storage_init("spot_light_buffer", &light_bytes);
        let vis = VisibilityTargets::new(&mut rec, w, h);
        self.passes.get::<VisibilityPass>()?.record(&mut rec, "visibility", &frame_buf, &gscene.raster_vertices, gscene.raster_vertex_count, &vis);

        let shadow_needed = !lights.is_empty() && shadow_mapped;
        // Unneeded: one placeholder layer of the smallest size, so the binding exists (and a
        // method without shadow maps is not bound by the layer limit).
        let shadow_tex = if shadow_needed { ShadowMapPass::target(&mut rec, shadow_size, shadow_layers) } else { ShadowMapPass::target(&mut rec, 16, 1) };
        let shadow_map = self.passes.get::<ShadowMapPass>()?;
        if shadow_needed {
            // The shadow maps rasterise anchor-relative vertices; the direct pass looks them
            // up with eye-relative positions through `LightRaw::view_proj`.
            // Layers whose view misses the scene's bounding sphere are left out (a cube face
            // looking away from the scene, a spot light pointing away: nothing looks them up).
            let mut vps = Vec::new();
            for (index, light) in light_sources.iter().enumerate() {
                let seeing = views_seeing_scene(light, anchor, extent);
                let faces = seeing.len();
                for (face, (m, sees)) in shadow_view_projs(light, anchor, extent).into_iter().zip(seeing).enumerate() {
                    if !sees {
                        let what = if faces > 1 { format!("shadow_map of light {index} face {face}") } else { format!("shadow_map of light {index}") };
                        skipped.push((what, "its view misses the scene's bounds: no shaded point looks it up".into()));
                    }
                    vps.push(sees.then(|| m.to_cols_array_2d()));
                }
            }
            shadow_map.record(&mut rec, &shadow_tex, &vps, &gscene.raster_vertices, gscene.raster_vertex_count);
        } else {
            // Clear the one placeholder layer so the binding is defined.
            rec.untimed(|rec| shadow_map.record(rec, &shadow_tex, &[], &gscene.raster_vertices, 0));
            let why = if lights.is_empty() { "the scene has no light".to_string() } else { format!("method={:?} traces shadow rays", info.name) };
            skipped.push(("shadow_map".into(), why));
        }

        // Emission is seen by the camera only, so only the camera's G-buffer gets the channel,
        // and only when some material emits (`plan="full"`: always). The rule lives here
        // rather than in the plan's shader features because no pass but the camera's material
        // pass and the compositing (aov_pack) reads it.
        let scene_emits = scene.stats().has_emission;
        let emission = scene_emits || job.opts.plan == PlanMode::Full;
        if !emission {
            skipped.push(("emission".into(), "no material in the scene is emissive: no emission channel, nothing added to the image".into()));
        }
        let gbuffer = GBuffer::with_emission(&mut rec, w, h, emission);
        self.passes.get::<MaterialPass>()?.record(&mut rec, &RasterView { label: "material", frame_uniforms: &frame_buf, ids: &vis.ids }, &gscene, feat, &gbuffer);

        // Written for every pixel by the direct pass (or the path tracer's direct entry point).
        let direct_out = rec.storage_written("direct_radiance_buffer", w as u64 * h as u64 * 16);
        if shadow_mapped {
            let shadow_view = rec.texture_view(&shadow_tex, &wgpu::TextureViewDescriptor {
                label: Some("shadow_map_array_view"),
                dimension: Some(wgpu::TextureViewDimension::D2Array),
                ..Default::default()
            });
            let first_emitter_light = scene.lights.len() as u32;
            let emitter_points = rec.storage_init("emitter_point_buffer", &emitter_quadrature_bytes(first_emitter_light, &emitter_clusters.points, origin));
            let lit = ShadowMappedLights {
                lights: &light_buf,
                shadow_maps: &shadow_view,
                emitter_points: &emitter_points,
                has_emitter_lights: !emitter_clusters.lights.is_empty(),
                emitter_point_sum: emitter_direct == EmitterDirect::Points,
            };
            self.passes.get::<DirectPass>()?.record(&mut rec, &frame_buf, &lit, &gbuffer, &direct_out, feat);
        }

        // Indirect targets; without specular materials the specular one is never bound for
        // writing: a 16-byte placeholder keeps the bind group layouts of the full variants.
        let pixel_bytes = if info.indirect { w as u64 * h as u64 * 16 } else { 16 };
        let indirect = IndirectTargets {
            diffuse: rec.storage("indirect_diffuse_buffer", pixel_bytes),
            specular: rec.storage("indirect_specular_buffer", if feat.specular { pixel_bytes } else { 16 }),
        };
        // The emitter VSGLs' direct light, added to the direct light by aov_pack.
        let emitter_targets = (emitter_direct == EmitterDirect::Sg && !emitter_clusters.lights.is_empty()).then(|| {
            let pixels = w as u64 * h as u64 * 16;
            IndirectTargets {
                diffuse: rec.storage("emitter_direct_diffuse_buffer", pixels),
                specular: rec.storage("emitter_direct_specular_buffer", if feat.specular { pixels } else { 16 }),
            }
        });
        let mut ctx = FrameContext {
            gpu,
            passes: &self.passes,
            rec,
            scene,
            gpu_scene: &gscene,
            origin,
            extent,
            features: feat,
            size: (w, h),
            frame_uniforms: &frame_buf,
            light_sources: &light_sources,
            lights: &lights,
            light_buffer: &light_buf,
            visibility: &vis,
            gbuffer: &gbuffer,
            direct: &direct_out,
            indirect: &indirect,
            skipped: Vec::new(),
            vsgls: None,
            captured_rsm: None,
            captured_lpv: None,
            sampling_pyramid: None,
            stderr: None,
            settings: Vec::new(),
            stop: job.opts.stop.as_ref(),
            power_staging: &mut slot.power_staging,
            plan_full: job.opts.plan == PlanMode::Full,
            chains,
        };
        job.method.record(&mut ctx)?;
        if let Some(targets) = &emitter_targets {
            crate::methods::emitter_direct::record(&mut ctx, &emitter_clusters, emitter_visibility, targets)?;
        }
        let FrameContext { mut rec, skipped: method_skipped, vsgls, captured_rsm, captured_lpv, stderr, settings: method_settings, .. } = ctx;
        skipped.extend(method_skipped);

        let sources = PackSources {
            direct: &direct_out,
            indirect: &indirect,
            gbuffer: &gbuffer,
            stderr: stderr.as_ref(),
            indirect_light: info.indirect,
            specular: feat.specular,
            emitter_direct: emitter_targets.as_ref(),
        };
        let pack = self.passes.get::<AovPackPass>()?;
        // Timed like any pass (`aov_pack`): readback work is part of the frame's GPU time.
        let pending = record_aovs(&mut rec, &pack, job.opts, info, &sources, (w, h), &mut slot.aov_staging);
        // The first light's VSGLs, copied in the same submission into the slot's staging buffer.
        let vsgl_bytes = vsgls.as_ref().map(|b| {
            let staging = kept_staging_buffer(gpu, &mut slot.vsgl_staging, "vsgl_readback_staging_buffer", b.size());
            rec.enc.copy_buffer_to_buffer(b, 0, &staging, 0, b.size());
            b.size()
        });
        let mut enc = rec.finish();
        timer.resolve(&mut enc);
        let submission = gpu.queue.submit([enc.finish()]);
        resources.end_frame();
        let mut settings: Vec<(String, Setting)> = vec![
            ("method".into(), info.name.into()),
            ("width".into(), w.into()),
            ("height".into(), h.into()),
            ("plan".into(), job.opts.plan.name().into()),
            ("adapter".into(), gpu.adapter.name.clone().into()),
            ("scene_upload".into(), if scene_reused { "reused" } else { "uploaded" }.into()),
        ];
        // Every option as the method resolved it, then what it adds or what ran instead.
        settings.extend(job.options.rows());
        for (name, value) in job.method.settings(gpu)? {
            match settings.iter_mut().find(|(n, _)| *n == name) {
                Some(row) => row.1 = value,
                None => settings.push((name, value)),
            }
        }
        settings.extend(method_settings);
        let frame = Frame {
            width: w,
            height: h,
            aovs: Vec::new(),
            ldr: None,
            timings_ms: Vec::new(),
            timings_clock: String::new(),
            passes: Vec::new(),
            skipped,
            settings,
            warnings: if scene.lights.is_empty() && scene_emits && gscene.emitters_face_nothing {
                vec!["the scene has no light, and nothing lies in front of its emissive surfaces (each emits on the side its vertex normals point to): they show but light nothing (flip their normals, or add a light with scene.add_light)".to_string()]
            } else if scene.lights.is_empty() && scene_emits && info.emitter_lighting() == "none" {
                // Not black: emissive surfaces show, but in this method they light nothing else.
                let lit_by: Vec<String> = crate::methods::REGISTRY.iter().filter(|m| m.emitter_lighting() != "none").map(|m| format!("method=\"{}\"", m.name)).collect();
                vec![format!(
                    "the scene has no light: only its emissive surfaces show, and method=\"{}\" lights no other surface with them ({} do; or add a light with scene.add_light, or load a file with KHR_lights_punctual lights)",
                    info.name,
                    lit_by.join(", ")
                )]
            } else if scene.lights.is_empty() && !scene_emits {
                vec!["the scene has no light: the image is black (add one with scene.add_light, or load a file with KHR_lights_punctual lights)".to_string()]
            } else {
                Vec::new()
            },
            rsm: captured_rsm,
            lpv: captured_lpv,
            vsgls: None,
            memory_bytes: Vec::new(),
            variants: Vec::new(),
        };
        Ok(Recorded { frame, features: feat, submission, aovs: pending, vsgl_bytes })
    }
}

/// One render's inputs, resolved.
struct FrameJob<'a> {
    scene: &'a Scene,
    camera: &'a Camera,
    opts: &'a RenderOptions,
    info: &'static MethodInfo,
    options: &'a Options,
    method: &'a dyn Method,
}

/// The shadow map side of methods that take no `shadow_size`.
fn default_shadow_size() -> u32 {
    match common::SHADOW_SIZE.default {
        OptionValue::Int(v) => v as u32,
        _ => 1024,
    }
}

/// Frame sizes from 1 to the adapter's largest 2D texture, by name.
fn check_size(gpu: &Gpu, width: u32, height: u32) -> Result<()> {
    let max = gpu.limits.max_texture_dimension_2d;
    for (name, v) in [("width", width), ("height", height)] {
        if v == 0 || v > max {
            return Err(Error::invalid(name, format!("must be in 1..={max} on this adapter, got {v}")));
        }
    }
    Ok(())
}

/// The camera a frame without one uses: the scene's first camera, else one that frames the
/// scene bounds from the front (+Z) and above, so flat scenes such as a ground plane are not
/// seen edge-on.
pub fn default_camera(scene: &Scene) -> Result<Camera> {
    if let Some(c) = scene.cameras.first() {
        return Ok(*c);
    }
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
