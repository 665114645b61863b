//! Direct lighting (compute): spot lights, Lambert + GGX/Smith, shadow-mapped.

use crate::error::Result;
use crate::frame::GBuffer;
use crate::gpu::{groups, Gpu, PipelineRef, PipelineVariants, Recorder};
use crate::plan::ShaderFeatures;

use crate::shader_lib::constants::direct::WORKGROUP;

/// The lights and the shadow maps the direct pass reads.
#[derive(Clone, Copy)]
pub struct ShadowMappedLights<'a> {
    /// Every light of the frame (`LightRaw` records).
    pub lights: &'a wgpu::Buffer,
    /// Their shadow maps (one layer per spot or directional light, six per point light).
    pub shadow_maps: &'a wgpu::TextureView,
}

pub struct DirectPass {
    pipelines: PipelineVariants,
    sampler: wgpu::Sampler,
}

impl DirectPass {
    pub fn new(gpu: &Gpu) -> Result<Self> {
        let pipelines = PipelineVariants::new(gpu, "passes/direct.wgsl", "main")?;
        let sampler = gpu.device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("direct_shadow_sampler"),
            address_mode_u: wgpu::AddressMode::ClampToEdge,
            address_mode_v: wgpu::AddressMode::ClampToEdge,
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            // Reverse-Z: the receiver is lit when it is at least as near as the occluder.
            compare: Some(wgpu::CompareFunction::GreaterEqual),
            ..Default::default()
        });
        Ok(Self { pipelines, sampler })
    }

    /// Direct light of `lit` at every pixel of `gbuffer`, into `out`.
    pub fn record(
        &self,
        rec: &mut Recorder<'_>,
        frame_uniforms: &wgpu::Buffer,
        lit: &ShadowMappedLights<'_>,
        gbuffer: &GBuffer,
        out: &wgpu::Buffer,
        features: ShaderFeatures,
    ) {
        let ShadowMappedLights { lights, shadow_maps } = *lit;
        let size = gbuffer.size;
        let gpu = rec.gpu;
        let pipeline = &self.pipelines.get(gpu, &features.specular_flags());
        let frame_bind = rec.bind_group("direct_frame_bind_group", PipelineRef::Compute(pipeline), 0, &[frame_uniforms.as_entire_binding()]);
        let pass_resources = [
            lights.as_entire_binding(),
            wgpu::BindingResource::TextureView(shadow_maps),
            wgpu::BindingResource::Sampler(&self.sampler),
            gbuffer.position.as_entire_binding(),
            gbuffer.normal.as_entire_binding(),
            gbuffer.geo_normal.as_entire_binding(),
            gbuffer.base_color.as_entire_binding(),
            out.as_entire_binding(),
        ];
        let pass_bind = rec.bind_group("direct_pass_bind_group", PipelineRef::Compute(pipeline), 1, &pass_resources);
        rec.in_debug_group("direct", |rec| {
            let q = rec.timer.begin("direct");
            let mut pass = rec.enc.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("direct_pass"),
                timestamp_writes: rec.timer.compute_writes(q),
            });
            pass.set_pipeline(pipeline);
            pass.set_bind_group(0, &frame_bind, &[]);
            pass.set_bind_group(1, &pass_bind, &[]);
            pass.dispatch_workgroups(groups(size.0, WORKGROUP), groups(size.1, WORKGROUP), 1);
        });
    }
}
