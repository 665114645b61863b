//! The frame: validates settings, plans passes, records them top to bottom, reads back AOVs.

use crate::error::{Error, Result};
use crate::frame_data::{frame_uniforms, spot_light_raw};
use crate::gpu::{Gpu, PassTimer};
use crate::passes::{direct::DirectPass, material::GBuffer, material::MaterialPass, shadow_map::ShadowMapPass, visibility::VisibilityPass};
use crate::scene::{Camera, Scene};
use crate::upload::GpuScene;
use std::sync::Arc;
use std::time::Instant;
use wgpu::util::DeviceExt;

/// Methods that render in this build.
pub const METHODS: &[&str] = &["direct"];
/// Methods of DESIGN.md that later work adds; asking for one says so.
pub const PLANNED_METHODS: &[&str] = &["vpl", "vsgl", "vsgl2", "reference", "pathtrace"];

/// Settings of one render (the keyword arguments of `Renderer.render`).
#[derive(Clone, Debug)]
pub struct RenderOptions {
    pub method: String,
    /// Side of each spot light's shadow map, 16…8192.
    pub shadow_size: u32,
    /// `"auto"` leaves out what the scene does not need; `"full"` runs every variant.
    pub plan: String,
}

impl Default for RenderOptions {
    fn default() -> Self {
        Self { method: "direct".into(), shadow_size: 1024, plan: "auto".into() }
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
        Ok(())
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
}

/// Whether a vector of f64 is finite, for argument checks.
pub fn finite3(v: glam::DVec3) -> bool {
    v.is_finite()
}

impl Renderer {
    pub fn new(gpu: Arc<Gpu>, width: u32, height: u32) -> Result<Self> {
        let max = gpu.limits.max_texture_dimension_2d;
        for (name, v) in [("width", width), ("height", height)] {
            if v == 0 || v > max {
                return Err(Error::invalid(name, format!("must be in 1..={max} on this adapter, got {v}")));
            }
        }
        let (visibility, shadow_map, material, direct) = gpu.scoped("pipeline creation", || {
            Ok((VisibilityPass::new(&gpu)?, ShadowMapPass::new(&gpu)?, MaterialPass::new(&gpu)?, DirectPass::new(&gpu)?))
        })?;
        Ok(Self { gpu, width, height, visibility, shadow_map, material, direct })
    }

    pub fn render(&self, scene: &Scene, camera: Option<&Camera>, opts: &RenderOptions) -> Result<Frame> {
        opts.validate()?;
        let camera = match camera.or(scene.cameras.first()) {
            Some(c) => *c,
            None => default_camera(scene)?,
        };
        self.gpu.scoped("render", || self.render_inner(scene, &camera, opts))
    }

    fn render_inner(&self, scene: &Scene, camera: &Camera, opts: &RenderOptions) -> Result<Frame> {
        let gpu = &*self.gpu;
        let (w, h) = (self.width, self.height);
        let wall = Instant::now();
        let stats = scene.stats();
        let full = opts.plan == "full";
        let mut passes = Vec::new();
        let mut skipped = Vec::new();

        let origin = camera.eye;
        let gscene = GpuScene::upload(gpu, scene, origin)?;
        let extent = gscene.extent;
        let lights: Vec<_> = scene
            .lights
            .iter()
            .enumerate()
            .map(|(i, l)| spot_light_raw(l, origin, extent, i as u32, opts.shadow_size))
            .collect();
        let uniforms = frame_uniforms(camera, w, h, lights.len() as u32, gscene.texture_layer_size, extent, opts.shadow_size);
        let frame_buf = gpu.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("frame_uniform_buffer"),
            contents: bytemuck::bytes_of(&uniforms),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let light_bytes: Vec<u8> = if lights.is_empty() { vec![0; 128] } else { bytemuck::cast_slice(&lights).to_vec() };
        let light_buf = gpu.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("spot_light_buffer"),
            contents: &light_bytes,
            usage: wgpu::BufferUsages::STORAGE,
        });

        let mut timer = PassTimer::new(gpu, 64);
        let mut enc = gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("frame_encoder") });

        let vis = VisibilityPass::targets(gpu, w, h);
        self.visibility.record(gpu, &mut enc, &mut timer, &frame_buf, &gscene.raster_vertices, gscene.raster_vertex_count, &vis);
        passes.push("visibility".to_string());

        let shadow_tex = ShadowMapPass::target(gpu, opts.shadow_size, lights.len() as u32);
        if !lights.is_empty() {
            let vps: Vec<_> = lights.iter().map(|l| l.view_proj).collect();
            self.shadow_map.record(gpu, &mut enc, &mut timer, &shadow_tex, &vps, &gscene.raster_vertices, gscene.raster_vertex_count);
            passes.push("shadow_map".to_string());
        } else {
            // Clear the one placeholder layer so the binding is defined.
            self.shadow_map.record(gpu, &mut enc, &mut PassTimer::new_disabled(), &shadow_tex, &[], &gscene.raster_vertices, 0);
            skipped.push(("shadow_map".to_string(), "the scene has no spot light".to_string()));
        }

        let gbuffer = GBuffer::new(gpu, w, h);
        let textured = full || stats.has_textures;
        self.material.record(gpu, &mut enc, &mut timer, &frame_buf, &vis.ids, &gscene, textured, &gbuffer, (w, h));
        if textured {
            passes.push("material".to_string());
        } else {
            passes.push("material[untextured]".to_string());
            skipped.push(("material_texture_fetch".to_string(), "no material in the scene uses a texture".to_string()));
        }

        let direct_out = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("direct_radiance_buffer"),
            size: w as u64 * h as u64 * 16,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let shadow_view = shadow_tex.create_view(&wgpu::TextureViewDescriptor {
            label: Some("shadow_map_array_view"),
            dimension: Some(wgpu::TextureViewDimension::D2Array),
            ..Default::default()
        });
        self.direct.record(gpu, &mut enc, &mut timer, &frame_buf, &light_buf, &shadow_view, &gbuffer, &direct_out, (w, h));
        passes.push("direct".to_string());

        timer.resolve(&mut enc);
        gpu.queue.submit([enc.finish()]);
        let read = gpu.read_buffers(&[&direct_out, &gbuffer.base_color, &gbuffer.normal, &gbuffer.position])?;
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

        let n = (w * h) as usize;
        let f = |b: &Vec<u8>| -> Vec<f32> { bytemuck::cast_slice::<u8, f32>(b).to_vec() };
        let rgb = |v: &[f32]| -> Vec<f32> { v.chunks_exact(4).flat_map(|p| [p[0], p[1], p[2]]).collect() };
        let direct = rgb(&f(&read[0]));
        let albedo = rgb(&f(&read[1]));
        let normal_cam = f(&read[2]);
        let normal: Vec<f32> = normal_cam.chunks_exact(4).flat_map(|p| [p[0], p[1], p[2]]).collect();
        let pos = f(&read[3]);
        // View depth; 0 where no surface was hit (never Inf, see docs).
        let depth: Vec<f32> = pos.chunks_exact(4).map(|p| if p[3] > 0.0 { p[3] } else { 0.0 }).collect();
        debug_assert_eq!(depth.len(), n);
        let aovs = vec![
            ("image".to_string(), 3, direct.clone()),
            ("direct".to_string(), 3, direct),
            ("albedo".to_string(), 3, albedo),
            ("normal".to_string(), 3, normal),
            ("depth".to_string(), 1, depth),
        ];
        let settings = vec![
            ("method".into(), opts.method.clone()),
            ("width".into(), w.to_string()),
            ("height".into(), h.to_string()),
            ("shadow_size".into(), opts.shadow_size.to_string()),
            ("plan".into(), opts.plan.clone()),
            ("adapter".into(), gpu.adapter.name.clone()),
        ];
        Ok(Frame { width: w, height: h, aovs, timings_ms: timings, timings_clock: clock.into(), passes, skipped, settings })
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
