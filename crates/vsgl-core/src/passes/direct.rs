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
    /// The points the emitter lights' direct light is summed over (`EmitterQuadrature` in
    /// direct.wgsl, [`emitter_quadrature_bytes`]), and whether the frame has emitter lights (else
    /// the sum is compiled out and the buffer a placeholder).
    pub emitter_points: &'a wgpu::Buffer,
    pub has_emitter_lights: bool,
    /// Whether this pass sums the emitter lights' points (`emitter_direct="points"`); else
    /// the emitter VSGLs light them (`methods/emitter_direct.rs`) and this pass leaves them out.
    pub emitter_point_sum: bool,
}

/// The bytes of direct.wgsl's `EmitterQuadrature`: the index of the frame's first emitter
/// light and the points per light, then each point relative to the frame origin with its share
/// of its light's intensity (`upload::emitters::EmitterClusters::points`).
pub fn emitter_quadrature_bytes(first_light: u32, points: &[(glam::DVec3, f32)], origin: glam::DVec3) -> Vec<u8> {
    let per_light = crate::upload::emitters::POINTS_PER_LIGHT as u32;
    let mut bytes: Vec<u8> = bytemuck::cast_slice(&[first_light, per_light, 0, 0]).to_vec();
    for &(p, w) in points {
        let r = (p - origin).as_vec3();
        bytes.extend_from_slice(bytemuck::cast_slice(&[r.x, r.y, r.z, w]));
    }
    if points.is_empty() {
        bytes.extend_from_slice(&[0u8; 16]);
    }
    bytes
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
        let ShadowMappedLights { lights, shadow_maps, emitter_points, has_emitter_lights, emitter_point_sum } = *lit;
        let size = gbuffer.size;
        let gpu = rec.gpu;
        let mut flags = features.specular_flags().to_vec();
        flags.push(("HAS_EMITTER_LIGHTS", has_emitter_lights));
        flags.push(("EMITTER_POINT_SUM", emitter_point_sum));
        let pipeline = &self.pipelines.get(gpu, &flags);
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
            emitter_points.as_entire_binding(),
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
