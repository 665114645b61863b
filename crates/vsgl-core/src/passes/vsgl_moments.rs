//! The papers' additional RSM buffers (compute): per-texel VSGL moments, level 0 of five mip
//! chains (layout in `wgsl/passes/vsgl_moments.wgsl`).

use crate::frame::MomentChains;
use crate::error::Result;
use crate::frame::{Rsm, RsmLight};
use crate::gpu::{groups, Gpu, PipelineVariants, Recorder};
use crate::plan::ShaderFeatures;

use crate::shader_lib::constants::vsgl_moments::WORKGROUP;

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct MomentParamsRaw {
    rsm_size: u32,
    chain_len: u32,
    // 1: also write chain F (tangent planes).
    planes: u32,
    _pad: u32,
    /// [`LightRaw::rsm_light_dir`](crate::frame::uniforms::LightRaw::rsm_light_dir).
    light_dir: [f32; 4],
    texel_footprint: [f32; 4],
}

pub struct VsglMomentsPass {
    pipelines: PipelineVariants,
}

impl VsglMomentsPass {
    pub fn new(gpu: &Gpu) -> Result<Self> {
        Ok(Self { pipelines: PipelineVariants::new(gpu, "passes/vsgl_moments.wgsl", "main")? })
    }

    /// The moments of `rsm`, rendered from `light`.
    pub fn record(&self, rec: &mut Recorder<'_>, rsm: &Rsm, light: &RsmLight, chains: &MomentChains, features: ShaderFeatures) {
        self.record_as(rec, "vsgl_moments", rsm, light, chains, features);
    }

    /// As [`Self::record`], timed as `label` (`RsmLight::default()`: texels taken as points, no
    /// light direction).
    pub fn record_as(&self, rec: &mut Recorder<'_>, label: &str, rsm: &Rsm, light: &RsmLight, chains: &MomentChains, features: ShaderFeatures) {
        let RsmLight { dir: light_dir, texel_footprint, .. } = *light;
        let gpu = rec.gpu;
        let pipeline = self.pipelines.get(gpu, &features.specular_flags());
        let uniform = rec.uniform("vsgl_moments_params_uniform_buffer", &MomentParamsRaw { rsm_size: rsm.size, chain_len: chains.chain_len, planes: u32::from(chains.has_planes()), _pad: 0, light_dir, texel_footprint });
        rec.compute(
            label,
            &pipeline,
            &[&[
                uniform.as_entire_binding(),
                rsm.gbuffer.position.as_entire_binding(),
                rsm.gbuffer.normal.as_entire_binding(),
                rsm.flux_diffuse.as_entire_binding(),
                rsm.flux_specular.as_entire_binding(),
                chains.buffer.as_entire_binding(),
            ]],
            (groups(rsm.size, WORKGROUP), groups(rsm.size, WORKGROUP), 1),
        );
    }
}
