//! Reflective shadow map flux (compute): Φ·R_d, Φ·R_s and the sampling weight per RSM texel.
//! The RSM's geometry comes from the visibility and material passes run with the light's view.

use crate::frame::Rsm;
use crate::error::Result;
use crate::gpu::{groups, Gpu, PipelineVariants, Recorder};
use crate::plan::ShaderFeatures;

use crate::shader_lib::constants::rsm_flux::WORKGROUP;


pub struct RsmFluxPass {
    pipelines: PipelineVariants,
}

impl RsmFluxPass {
    pub fn new(gpu: &Gpu) -> Result<Self> {
        Ok(Self { pipelines: PipelineVariants::new(gpu, "passes/rsm_flux.wgsl", "main")? })
    }

    pub fn record(&self, rec: &mut Recorder<'_>, view: &wgpu::Buffer, light: wgpu::BindingResource<'_>, rsm: &Rsm, features: ShaderFeatures) {
        let gpu = rec.gpu;
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
        rec.compute(
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
