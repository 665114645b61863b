//! Material pass (compute): visibility buffer → G-buffer. Variants by the frame's plan:
//! untextured with every texture fetch compiled out (`HAS_TEXTURES = false`), and without
//! normal maps with the tangent frame compiled out (`HAS_NORMAL_MAPS = false`); and by the
//! G-buffer: emitted radiance is written only into one that has an emission channel
//! (`HAS_EMISSION`).

use crate::frame::GBuffer;
use crate::error::Result;
use crate::gpu::buffers::{later_storage_pages, spans_pages, storage_pages};
use crate::gpu::{groups, Gpu, PipelineRef, PipelineVariants, Recorder};
use crate::plan::ShaderFeatures;
use crate::upload::GpuScene;

use crate::shader_lib::constants::material::WORKGROUP;


/// The view whose visibility buffer the material pass resolves.
#[derive(Clone, Copy)]
pub struct RasterView<'a> {
    /// The pass name in `frame.passes` (`material`, `rsm_material`, `rsm_power_material`).
    pub label: &'a str,
    pub frame_uniforms: &'a wgpu::Buffer,
    /// The triangle ids the visibility pass rasterized.
    pub ids: &'a wgpu::TextureView,
}

pub struct MaterialPass {
    pipelines: PipelineVariants,
    sampler: wgpu::Sampler,
}

impl MaterialPass {
    pub fn new(gpu: &Gpu) -> Result<Self> {
        let sampler = gpu.device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("material_texture_sampler"),
            address_mode_u: wgpu::AddressMode::Repeat,
            address_mode_v: wgpu::AddressMode::Repeat,
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            mipmap_filter: wgpu::MipmapFilterMode::Linear,
            ..Default::default()
        });
        Ok(Self { pipelines: PipelineVariants::new(gpu, "passes/material.wgsl", "main")?, sampler })
    }

    pub fn record(
        &self,
        rec: &mut Recorder<'_>,
        view: &RasterView<'_>,
        scene: &GpuScene,
        features: ShaderFeatures,
        gbuffer: &GBuffer,
    ) {
        let RasterView { label, frame_uniforms, ids } = *view;
        let size = gbuffer.size;
        let gpu = rec.gpu;
        // Emission follows the target, not the plan: only a G-buffer made with an emission
        // channel (the camera's, when some material emits) has one to write.
        let flags = [
            ("HAS_TEXTURES", features.textures),
            ("HAS_NORMAL_MAPS", features.normal_maps),
            ("HAS_EMISSION", gbuffer.has_emission),
            ("STORAGE_PAGED", spans_pages(&scene.vertices)),
        ];
        let pipeline = &self.pipelines.get(gpu, &flags);
        let frame_bind = rec.bind_group("material_frame_bind_group", PipelineRef::Compute(pipeline), 0, &[frame_uniforms.as_entire_binding()]);
        // Every variant binds the same resources: the auto layout is derived before override
        // constants are applied, so the untextured one still declares bindings 5–7.
        let [vertices, ..] = storage_pages(&scene.vertices);
        let resources = vec![
            wgpu::BindingResource::TextureView(ids),
            vertices,
            scene.indices.as_entire_binding(),
            scene.triangle_materials.as_entire_binding(),
            scene.materials.as_entire_binding(),
            wgpu::BindingResource::TextureView(&scene.color_textures),
            wgpu::BindingResource::TextureView(&scene.data_textures),
            wgpu::BindingResource::Sampler(&self.sampler),
            gbuffer.position.as_entire_binding(),
            gbuffer.normal.as_entire_binding(),
            gbuffer.geo_normal.as_entire_binding(),
            gbuffer.base_color.as_entire_binding(),
            gbuffer.emission.as_entire_binding(),
        ]
        .into_iter()
        .chain(later_storage_pages(&[&scene.vertices]))
        .collect::<Vec<_>>();
        let pass_bind = rec.bind_group("material_pass_bind_group", PipelineRef::Compute(pipeline), 1, &resources);
        rec.in_debug_group(label, |rec| {
            let q = rec.timer.begin(label);
            let mut pass = rec.enc.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some(label),
                timestamp_writes: rec.timer.compute_writes(q),
            });
            pass.set_pipeline(pipeline);
            pass.set_bind_group(0, &frame_bind, &[]);
            pass.set_bind_group(1, &pass_bind, &[]);
            pass.dispatch_workgroups(groups(size.0, WORKGROUP), groups(size.1, WORKGROUP), 1);
        });
    }
}
