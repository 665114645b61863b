//! Reflective shadow map flux (compute): Φ·R_d, Φ·R_s and the sampling weight per RSM texel.
//! The RSM's geometry comes from the visibility and material passes run with the light's view.

use super::{run_compute, storage_buffer};
use crate::error::Result;
use crate::gpu::{groups, Gpu, PassTimer, PipelineVariants};
use crate::plan::ShaderFeatures;
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
    /// Whether the weight pyramid exists (the method samples texels by weight).
    pub sampling: bool,
}

impl Rsm {
    /// `specular = false` (no specular material): the specular flux is never written or read,
    /// so it gets a 16-byte placeholder; `sampling = false` (nothing is sampled from the RSM):
    /// neither is the weight pyramid.
    pub fn new(gpu: &Gpu, size: u32, specular: bool, sampling: bool) -> Self {
        let texels = size as u64 * size as u64;
        let (offsets, total) = super::pdf_mips::pyramid_layout(size);
        Self {
            size,
            gbuffer: GBuffer::new(gpu, size, size),
            flux_diffuse: storage_buffer(gpu, "rsm_flux_diffuse_buffer", texels * 16),
            flux_specular: storage_buffer(gpu, "rsm_flux_specular_buffer", if specular { texels * 16 } else { 16 }),
            pyramid: storage_buffer(gpu, "rsm_weight_pyramid_buffer", if sampling { total as u64 * 4 } else { 16 }),
            level_offsets: wgpu::util::DeviceExt::create_buffer_init(&gpu.device, &wgpu::util::BufferInitDescriptor {
                label: Some("rsm_level_offset_buffer"),
                contents: bytemuck::cast_slice(&offsets),
                usage: wgpu::BufferUsages::STORAGE,
            }),
            levels: offsets.len() as u32,
            sampling,
        }
    }
}

pub struct RsmFluxPass {
    pipelines: PipelineVariants,
}

impl RsmFluxPass {
    pub fn new(gpu: &Gpu) -> Result<Self> {
        Ok(Self { pipelines: PipelineVariants::new(gpu, "passes/rsm_flux.wgsl", "main")? })
    }

    pub fn record(&self, gpu: &Gpu, enc: &mut wgpu::CommandEncoder, timer: &mut PassTimer, view: &wgpu::Buffer, light: wgpu::BindingResource<'_>, rsm: &Rsm, features: ShaderFeatures) {
        let pipeline = self.pipelines.get(gpu, &[("HAS_SPECULAR", features.specular), ("SAMPLING_WEIGHTS", rsm.sampling)]);
        // The pyramid's level 0 is its first `size²` floats (the whole placeholder without one).
        let level0 = match rsm.sampling {
            true => wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                buffer: &rsm.pyramid,
                offset: 0,
                size: std::num::NonZeroU64::new(rsm.size as u64 * rsm.size as u64 * 4),
            }),
            false => rsm.pyramid.as_entire_binding(),
        };
        run_compute(
            gpu,
            enc,
            timer,
            "rsm_flux",
            &pipeline,
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
