//! Reflective shadow map flux (compute): Φ·R_d, Φ·R_s and the sampling weight per RSM texel.
//! The RSM's geometry comes from the visibility and material passes run with the light's view.

use super::{run_compute, storage_buffer};
use crate::error::Result;
use crate::gpu::{groups, Gpu, PassTimer};
use crate::passes::material::GBuffer;

const WORKGROUP: u32 = 8;

/// The per-texel RSM data: the light-view G-buffer plus flux and the weight pyramid.
pub struct Rsm {
    pub size: u32,
    pub gbuffer: GBuffer,
    pub flux_diffuse: wgpu::Buffer,
    pub flux_specular: wgpu::Buffer,
    /// Sampling-weight pyramid, all levels (see `pdf_mips`).
    pub pyramid: wgpu::Buffer,
    pub level_offsets: wgpu::Buffer,
    pub levels: u32,
}

impl Rsm {
    pub fn new(gpu: &Gpu, size: u32) -> Self {
        let texels = size as u64 * size as u64;
        let (offsets, total) = super::pdf_mips::pyramid_layout(size);
        Self {
            size,
            gbuffer: GBuffer::new(gpu, size, size),
            flux_diffuse: storage_buffer(gpu, "rsm_flux_diffuse_buffer", texels * 16),
            flux_specular: storage_buffer(gpu, "rsm_flux_specular_buffer", texels * 16),
            pyramid: storage_buffer(gpu, "rsm_weight_pyramid_buffer", total as u64 * 4),
            level_offsets: wgpu::util::DeviceExt::create_buffer_init(&gpu.device, &wgpu::util::BufferInitDescriptor {
                label: Some("rsm_level_offset_buffer"),
                contents: bytemuck::cast_slice(&offsets),
                usage: wgpu::BufferUsages::STORAGE,
            }),
            levels: offsets.len() as u32,
        }
    }
}

pub struct RsmFluxPass {
    pipeline: wgpu::ComputePipeline,
}

impl RsmFluxPass {
    pub fn new(gpu: &Gpu) -> Result<Self> {
        let module = gpu.shader("passes/rsm_flux.wgsl")?;
        Ok(Self { pipeline: gpu.compute_pipeline("rsm_flux_pipeline", &module, "main") })
    }

    pub fn record(&self, gpu: &Gpu, enc: &mut wgpu::CommandEncoder, timer: &mut PassTimer, view: &wgpu::Buffer, light: wgpu::BindingResource<'_>, rsm: &Rsm) {
        // The pyramid's level 0 is its first `size²` floats.
        let level0 = wgpu::BindingResource::Buffer(wgpu::BufferBinding {
            buffer: &rsm.pyramid,
            offset: 0,
            size: std::num::NonZeroU64::new(rsm.size as u64 * rsm.size as u64 * 4),
        });
        run_compute(
            gpu,
            enc,
            timer,
            "rsm_flux",
            &self.pipeline,
            &[
                &[view.as_entire_binding()],
                &[
                    light,
                    rsm.gbuffer.position.as_entire_binding(),
                    rsm.gbuffer.geo_normal.as_entire_binding(),
                    rsm.gbuffer.base_color.as_entire_binding(),
                    rsm.flux_diffuse.as_entire_binding(),
                    rsm.flux_specular.as_entire_binding(),
                    level0,
                ],
            ],
            (groups(rsm.size, WORKGROUP), groups(rsm.size, WORKGROUP), 1),
        );
    }
}
