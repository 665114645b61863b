//! Material pass (compute): visibility buffer → G-buffer. Two variants: textured, and
//! untextured with every texture fetch compiled out (`HAS_TEXTURES = false`).

use super::entries;
use crate::error::Result;
use crate::gpu::{groups, Gpu, PassTimer};
use crate::upload::GpuScene;

const WORKGROUP: u32 = 8;

/// The G-buffer: four vec4f storage buffers (layout in `wgsl/common/gbuffer.wgsl`).
pub struct GBuffer {
    pub position: wgpu::Buffer,
    pub normal: wgpu::Buffer,
    pub geo_normal: wgpu::Buffer,
    pub base_color: wgpu::Buffer,
}

impl GBuffer {
    pub fn new(gpu: &Gpu, width: u32, height: u32) -> Self {
        let make = |label| {
            gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: width as u64 * height as u64 * 16,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            })
        };
        Self {
            position: make("gbuffer_position_buffer"),
            normal: make("gbuffer_normal_buffer"),
            geo_normal: make("gbuffer_geo_normal_buffer"),
            base_color: make("gbuffer_base_color_buffer"),
        }
    }
}

pub struct MaterialPass {
    textured: wgpu::ComputePipeline,
    untextured: wgpu::ComputePipeline,
    sampler: wgpu::Sampler,
}

impl MaterialPass {
    pub fn new(gpu: &Gpu) -> Result<Self> {
        let module = gpu.shader("passes/material.wgsl")?;
        let variant = |label, has_textures: bool| {
            gpu.device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(label),
                layout: None,
                module: &module,
                entry_point: Some("main"),
                compilation_options: wgpu::PipelineCompilationOptions {
                    constants: &[("HAS_TEXTURES", if has_textures { 1.0 } else { 0.0 })],
                    ..Default::default()
                },
                cache: None,
            })
        };
        let sampler = gpu.device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("material_texture_sampler"),
            address_mode_u: wgpu::AddressMode::Repeat,
            address_mode_v: wgpu::AddressMode::Repeat,
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            mipmap_filter: wgpu::MipmapFilterMode::Linear,
            ..Default::default()
        });
        Ok(Self {
            textured: variant("material_textured_pipeline", true),
            untextured: variant("material_untextured_pipeline", false),
            sampler,
        })
    }

    #[allow(clippy::too_many_arguments)]
    pub fn record(
        &self,
        gpu: &Gpu,
        enc: &mut wgpu::CommandEncoder,
        timer: &mut PassTimer,
        label: &str,
        frame_uniforms: &wgpu::Buffer,
        ids: &wgpu::TextureView,
        scene: &GpuScene,
        textured: bool,
        gbuffer: &GBuffer,
        size: (u32, u32),
    ) {
        let pipeline = if textured { &self.textured } else { &self.untextured };
        let frame_bind = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("material_frame_bind_group"),
            layout: &pipeline.get_bind_group_layout(0),
            entries: &[wgpu::BindGroupEntry { binding: 0, resource: frame_uniforms.as_entire_binding() }],
        });
        // Both variants bind the same resources: the auto layout is derived before override
        // constants are applied, so the untextured one still declares bindings 5–7.
        let resources = vec![
            wgpu::BindingResource::TextureView(ids),
            scene.vertices.as_entire_binding(),
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
        ];
        let e = entries(&resources);
        let pass_bind = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("material_pass_bind_group"),
            layout: &pipeline.get_bind_group_layout(1),
            entries: &e,
        });
        let q = timer.begin(label);
        let mut pass = enc.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some(label),
            timestamp_writes: timer.compute_writes(q),
        });
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, &frame_bind, &[]);
        pass.set_bind_group(1, &pass_bind, &[]);
        pass.dispatch_workgroups(groups(size.0, WORKGROUP), groups(size.1, WORKGROUP), 1);
    }
}
