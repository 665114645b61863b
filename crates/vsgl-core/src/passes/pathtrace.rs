//! Path-traced one-bounce ground truth (compute, `method="pathtrace"`): a BVH built on the CPU
//! ([`crate::upload::bvh`], built once per scene upload), then progressive batches of BRDF-sampled bounce rays with shadow rays at the
//! bounce point, a ray-traced direct pass, and the per-pixel standard error. The estimator is
//! documented in `wgsl/passes/pathtrace.wgsl`.

use crate::error::Result;
use crate::frame::{GBuffer, IndirectTargets};
use crate::gpu::buffers::{later_storage_pages, spans_pages, storage_pages};
use crate::gpu::frame_log::note_pass;
use crate::gpu::{groups, storage_binding, PipelineRef, uniform_binding, Gpu, PipelineVariants, Recorder};
use crate::plan::ShaderFeatures;
use crate::scene::Scene;
use crate::upload::GpuScene;

use crate::shader_lib::constants::pathtrace::WORKGROUP;
/// Bounce paths (pixel samples) per dispatch and submission. Each path is one closest-hit ray
/// and one shadow ray per light. Measured on an H100 at 1920×1088 (2^21 pixels): 2^22 paths
/// took 0.9 ms (built-in Cornell box, 36 triangles) to 1.8 ms (FlightHelmet, 95k triangles), so
/// 2^24 keeps a submission near 4–7 ms, well inside a ~10 ms watchdog budget even for larger
/// scenes, while the per-submission overhead (~2 ms of CPU work and round trip) stays small.
const PATHS_PER_BATCH: u64 = 1 << 24;
/// Submissions queued before the CPU waits for the GPU (bounds queued work and memory).
const SUBMISSIONS_IN_FLIGHT: u32 = 4;
/// A wait for the queued batches longer than this makes the path tracer queue one at a time.
const SLOW_WAIT: std::time::Duration = std::time::Duration::from_millis(250);
/// Most samples one thread takes in one dispatch (bounds a dispatch on tiny images too).
const MAX_SAMPLES_PER_DISPATCH: u32 = 1024;
/// The same where the adapter caps an invocation's loop iterations (`Gpu::caps_loop_iterations`,
/// lavapipe): each sample loops over BVH nodes for its rays (~50–300 iterations per ray in the
/// built-ins), so 1024 samples ran past the cap. Measured on glossy_cornell at 64², camera paths:
/// 1024 spp in one dispatch gave an image mean 0.73× that of 64 spp, blocks down to 0.27×.
const CPU_MAX_SAMPLES_PER_DISPATCH: u32 = 16;
// Threads of a `light_paths` workgroup (pathtrace.wgsl LIGHT_WORKGROUP).
use crate::shader_lib::constants::pathtrace::LIGHT_WORKGROUP;
/// WebGPU's guaranteed limit on workgroups per dispatch dimension.
const MAX_WORKGROUPS_PER_DIMENSION: u32 = 65535;
/// Fewest batches in bidirectional mode, whose light part's variance is taken over batches.
const MIN_LIGHT_BATCHES: u32 = 8;

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct PathParamsRaw {
    seed: u32,
    sample_offset: u32,
    batch_samples: u32,
    strategy: u32,
    /// Emissive triangles in the upload's emitter table, and their total power.
    emitter_count: u32,
    emitter_power: f32,
    _pad: [u32; 2],
}

/// `strategy=` of `pathtrace` (the shader's STRATEGY_* values).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Strategy {
    /// BRDF-sampled bounces from each pixel centre's G-buffer point.
    Camera = 0,
    /// Camera paths jittered over each pixel's area and light tracing, combined by MIS.
    Bidirectional = 1,
    /// Light tracing alone (over each pixel's area).
    Light = 2,
}

/// What the path tracer reads: the frame, its lights, the uploaded scene, the camera G-buffer
/// and the visibility ids (for the pixel's own triangle).
pub struct PathTraceInputs<'a> {
    pub scene: &'a Scene,
    pub frame: &'a wgpu::Buffer,
    pub lights: &'a wgpu::Buffer,
    pub gscene: &'a GpuScene,
    pub gbuffer: &'a GBuffer,
    pub ids: &'a wgpu::TextureView,
    /// Asked between batches; an error stops the render.
    pub stop: Option<&'a crate::progress::StopCheck>,
    /// Stop adding samples once this many seconds have passed (the mean so far is the image).
    pub time_budget_s: Option<f64>,
    /// The plan's features: no texture fetches at bounce points without textured materials,
    /// no tangent frames without normal maps.
    pub features: ShaderFeatures,
    /// Which paths estimate the indirect light.
    pub strategy: Strategy,
    /// Samples per pixel, and the seed of their random numbers.
    pub spp: u32,
    pub seed: u32,
}

/// What one path-traced frame produced besides the indirect buffers and the direct buffer.
pub struct PathTraceOutput {
    /// Standard error of the mean indirect radiance, vec4f per pixel (rgb).
    pub stderr: wgpu::Buffer,
    /// Whether this frame built the BVH (else the scene upload's was reused).
    pub bvh_built: bool,
    pub bvh_nodes: usize,
    pub bvh_depth: usize,
    /// Samples per dispatch (the last may have fewer).
    pub samples_per_batch: u32,
    /// Samples per pixel taken (fewer than asked when a time budget ended the sampling).
    pub spp_done: u32,
}

pub struct PathTracePass {
    indirect: PipelineVariants,
    direct: PipelineVariants,
    resolve: PipelineVariants,
    light_paths: PipelineVariants,
    light_fold: PipelineVariants,
    sampler: wgpu::Sampler,
}

/// The one bind group layout every entry point shares (binding order of pathtrace.wgsl).
fn binding_types() -> Vec<wgpu::BindingType> {
    let ro = storage_binding(true);
    let rw = storage_binding(false);
    let tex = |sample_type, view_dimension| wgpu::BindingType::Texture { sample_type, view_dimension, multisampled: false };
    vec![
        uniform_binding(),                                                            // 0 frame
        uniform_binding(),                                                            // 1 params
        ro,                                                                           // 2 bvh_nodes
        ro,                                                                           // 3 bvh_triangle_ids
        ro,                                                                           // 4 vertices
        ro,                                                                           // 5 indices
        ro,                                                                           // 6 triangle_materials
        ro,                                                                           // 7 materials
        ro,                                                                           // 8 lights
        ro,                                                                           // 9 gbuf_position
        ro,                                                                           // 10 gbuf_normal
        ro,                                                                           // 11 gbuf_geo_normal
        ro,                                                                           // 12 gbuf_base_color
        tex(wgpu::TextureSampleType::Uint, wgpu::TextureViewDimension::D2),           // 13 visibility
        tex(wgpu::TextureSampleType::Float { filterable: true }, wgpu::TextureViewDimension::D2Array), // 14
        tex(wgpu::TextureSampleType::Float { filterable: true }, wgpu::TextureViewDimension::D2Array), // 15
        wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),              // 16 sampler
        rw,                                                                           // 17 indirect_diffuse
        rw,                                                                           // 18 indirect_specular
        rw,                                                                           // 19 indirect_m2
        rw,                                                                           // 20 direct_out
        rw,                                                                           // 21 stderr_out
        rw,                                                                           // 22 light_splat
        rw,                                                                           // 23 light_mean
        rw,                                                                           // 24 light_m2
        ro,                                                                           // 25 emitters
        rw,                                                                           // 26 emitted_direct
        ro,                                                                           // 27 triangle_corners
        // The other pages of nodes, corners and vertices (gpu::buffers::storage_pages).
        ro,                                                                           // 28 bvh_nodes_1
        ro,                                                                           // 29 bvh_nodes_2
        ro,                                                                           // 30 bvh_nodes_3
        ro,                                                                           // 31 triangle_corners_1
        ro,                                                                           // 32 triangle_corners_2
        ro,                                                                           // 33 triangle_corners_3
        ro,                                                                           // 34 vertices_1
        ro,                                                                           // 35 vertices_2
        ro,                                                                           // 36 vertices_3
    ]
}

impl PathTracePass {
    pub fn new(gpu: &Gpu) -> Result<Self> {
        let module = gpu.shader("passes/pathtrace.wgsl")?;
        // One explicit layout (the entry points bind different subsets of it).
        let variants = |entry: &str| PipelineVariants::from_module(module.clone(), "passes/pathtrace.wgsl", entry, Some(binding_types()));
        let sampler = gpu.device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("pathtrace_texture_sampler"),
            address_mode_u: wgpu::AddressMode::Repeat,
            address_mode_v: wgpu::AddressMode::Repeat,
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            mipmap_filter: wgpu::MipmapFilterMode::Linear,
            ..Default::default()
        });
        Ok(Self {
            indirect: variants("indirect"),
            direct: variants("direct"),
            resolve: variants("resolve"),
            light_paths: variants("light_paths"),
            light_fold: variants("light_fold"),
            sampler,
        })
    }

    /// Builds the BVH, traces the direct light into `direct_out`, accumulates `spp` samples per
    /// pixel into `indirect` (means of the diffuse and specular parts) in batches, and resolves
    /// the standard error. Each batch after the first goes in its own submission, so no
    /// submission runs long (the recorder continues in a fresh encoder).
    pub fn record(
        &self,
        rec: &mut Recorder<'_>,
        input: &PathTraceInputs,
        indirect: &IndirectTargets,
        direct_out: &wgpu::Buffer,
        size: (u32, u32),
    ) -> Result<PathTraceOutput> {
        let (spp, seed) = (input.spp, input.seed);
        let gpu = rec.gpu;
        let (w, h) = size;
        let (bvh, bvh_built) = input.gscene.bvh(gpu, input.scene)?;
        if bvh_built {
            note_pass("bvh_build");
        }
        let (nodes, triangle_ids) = (&bvh.nodes, &bvh.triangle_ids);
        let pixels = w as u64 * h as u64;
        let m2 = rec.storage("pathtrace_m2_buffer", pixels * 16);
        let stderr = rec.storage("pathtrace_stderr_buffer", pixels * 16);
        let workgroups = (groups(w, WORKGROUP), groups(h, WORKGROUP), 1);
        // Light tracing's buffers (16-byte placeholders in camera-only mode): this batch's
        // splats (8 words a pixel), the light part's means (2 vec4 a pixel) and M2 (1 vec4).
        let bidirectional = input.strategy != Strategy::Camera;
        let light_bytes = |per_pixel: u64| if bidirectional { pixels * per_pixel } else { 16 };
        let light_splat = rec.storage("pathtrace_light_splat_buffer", light_bytes(32));
        let light_mean = rec.storage("pathtrace_light_mean_buffer", light_bytes(32));
        let light_m2 = rec.storage("pathtrace_light_m2_buffer", light_bytes(16));
        // Emissive triangles light the scene: their direct light at each pixel centre is
        // sampled alongside the bounces, its running mean kept here (a placeholder without).
        let has_emitters = input.gscene.emitter_count > 0;
        let emitted_direct = rec.storage("pathtrace_emitted_direct_buffer", if has_emitters { pixels * 16 } else { 16 });

        let dispatch = |rec: &mut Recorder<'_>, label: &str, pipeline: &wgpu::ComputePipeline, params: PathParamsRaw, workgroups: (u32, u32, u32)| {
            let uniform = rec.uniform("pathtrace_params_uniform_buffer", &params);
            let [nodes_0, ..] = storage_pages(nodes);
            let [corners_0, ..] = storage_pages(&input.gscene.raster_vertices);
            let [vertices_0, ..] = storage_pages(&input.gscene.vertices);
            let mut resources = vec![
                input.frame.as_entire_binding(),
                uniform.as_entire_binding(),
                nodes_0,
                triangle_ids.as_entire_binding(),
                vertices_0,
                input.gscene.indices.as_entire_binding(),
                input.gscene.triangle_materials.as_entire_binding(),
                input.gscene.materials.as_entire_binding(),
                input.lights.as_entire_binding(),
                input.gbuffer.position.as_entire_binding(),
                input.gbuffer.normal.as_entire_binding(),
                input.gbuffer.geo_normal.as_entire_binding(),
                input.gbuffer.base_color.as_entire_binding(),
                wgpu::BindingResource::TextureView(input.ids),
                wgpu::BindingResource::TextureView(&input.gscene.color_textures),
                wgpu::BindingResource::TextureView(&input.gscene.data_textures),
                wgpu::BindingResource::Sampler(&self.sampler),
                indirect.diffuse.as_entire_binding(),
                indirect.specular.as_entire_binding(),
                m2.as_entire_binding(),
                direct_out.as_entire_binding(),
                stderr.as_entire_binding(),
                light_splat.as_entire_binding(),
                light_mean.as_entire_binding(),
                light_m2.as_entire_binding(),
                input.gscene.emitters.as_entire_binding(),
                emitted_direct.as_entire_binding(),
                corners_0,
            ];
            resources.extend(later_storage_pages(&[nodes, &input.gscene.raster_vertices, &input.gscene.vertices]));
            let bind = rec.bind_group("pathtrace_bind_group", PipelineRef::Compute(pipeline), 0, &resources);
            rec.in_debug_group(label, |rec| {
                let q = rec.timer.begin(label);
                let mut pass = rec.enc.begin_compute_pass(&wgpu::ComputePassDescriptor { label: Some(label), timestamp_writes: rec.timer.compute_writes(q) });
                pass.set_pipeline(pipeline);
                pass.set_bind_group(0, &bind, &[]);
                pass.dispatch_workgroups(workgroups.0, workgroups.1, workgroups.2);
            });
        };

        // Power in f32 as the shader sums it (capped: a sum of radiances each at most 1e32
        // times areas may pass f32's range).
        let emitter_power = input.gscene.emitter_power.min(f32::MAX as f64) as f32;
        let params = |sample_offset, batch_samples| PathParamsRaw {
            seed,
            sample_offset,
            batch_samples,
            strategy: input.strategy as u32,
            emitter_count: input.gscene.emitter_count,
            emitter_power,
            _pad: [0; 2],
        };
        // The entry points share one shader, so they take the same leave-out flags. Without
        // emitters no emitter code runs and no random number is drawn for them: the images of
        // scenes without emission are the ones the path tracer made before emitters.
        let flags = [
            ("HAS_TEXTURES", input.features.textures),
            ("HAS_NORMAL_MAPS", input.features.normal_maps),
            ("HAS_EMITTERS", has_emitters),
            ("STORAGE_PAGED", [&bvh.nodes, &input.gscene.raster_vertices, &input.gscene.vertices].into_iter().any(spans_pages)),
        ];
        dispatch(rec, "pathtrace_direct", &self.direct.get(gpu, &flags), params(0, 0), workgroups);
        let indirect_pipeline = &self.indirect.get(gpu, &flags);
        // `frame.passes` names the untextured variant of the bounce pass (timed as `pathtrace`).
        let indirect_label = if input.features.textures { "pathtrace" } else { "pathtrace[untextured]" };
        let max_per_dispatch = if gpu.caps_loop_iterations() { CPU_MAX_SAMPLES_PER_DISPATCH } else { MAX_SAMPLES_PER_DISPATCH };
        let mut per_batch = (PATHS_PER_BATCH / pixels.max(1)).clamp(1, max_per_dispatch as u64) as u32;
        if bidirectional {
            // The light part's variance is taken over batches: at least MIN_LIGHT_BATCHES of them.
            per_batch = per_batch.min(spp.div_ceil(MIN_LIGHT_BATCHES)).max(1);
        }
        let (light_paths, light_fold) = (self.light_paths.get(gpu, &flags), self.light_fold.get(gpu, &flags));
        let started = std::time::Instant::now();
        let mut done = 0u32;
        let mut batch = 0u32;
        // Batches queued before waiting: a few keep a fast GPU busy; on a device where one wait
        // takes long (lavapipe), one at a time, so a stop or the time budget is seen within
        // about one batch. Only the waiting adapts: batch sizes, and so the image, do not.
        let mut in_flight = SUBMISSIONS_IN_FLIGHT;
        while done < spp {
            let count = per_batch.min(spp - done);
            if done > 0 {
                // Submit what is recorded so far on its own, so no submission runs for long.
                rec.submit_so_far();
                batch += 1;
                if batch % in_flight == 0 {
                    let waited = std::time::Instant::now();
                    gpu.wait("pathtrace batch")?;
                    if waited.elapsed() > SLOW_WAIT {
                        in_flight = 1;
                    }
                }
                // Between batches: the caller may stop the render (Ctrl-C), and a time budget
                // ends the sampling with the samples taken so far (a valid, noisier estimate).
                if let Some(stop) = input.stop {
                    stop.check(crate::progress::Progress { done: done as u64, total: spp as u64, unit: "spp" })?;
                }
                if input.time_budget_s.is_some_and(|b| started.elapsed().as_secs_f64() >= b) {
                    break;
                }
            }
            dispatch(rec, indirect_label, indirect_pipeline, params(done, count), workgroups);
            if bidirectional {
                // count · W · H photons: the same number of light paths as camera paths.
                let photon_groups = (count as u64 * pixels).div_ceil(LIGHT_WORKGROUP as u64);
                let x = photon_groups.min(MAX_WORKGROUPS_PER_DIMENSION as u64) as u32;
                let y = photon_groups.div_ceil(x.max(1) as u64) as u32;
                dispatch(rec, "pathtrace_light_paths", &light_paths, params(done, count), (x.max(1), y.max(1), 1));
                dispatch(rec, "pathtrace_light_fold", &light_fold, params(done, count), workgroups);
            }
            done += count;
        }
        dispatch(rec, "pathtrace_resolve", &self.resolve.get(gpu, &flags), params(done, 0), workgroups);
        Ok(PathTraceOutput {
            stderr,
            bvh_built,
            bvh_nodes: bvh.node_count,
            bvh_depth: bvh.depth,
            samples_per_batch: per_batch,
            spp_done: done,
        })
    }
}
