//! The papers' additional RSM buffers (compute): per-texel VSGL moments, level 0 of five mip
//! chains (layout in `wgsl/passes/vsgl_moments.wgsl`).

use super::{run_compute, storage_buffer, uniform_buffer};
use crate::error::Result;
use crate::gpu::{groups, Gpu, PassTimer, PipelineVariants};
use crate::plan::ShaderFeatures;
use crate::passes::rsm_flux::Rsm;

const WORKGROUP: u32 = 8;
/// A, B, C, D, E of the shader.
pub const CHAINS: u64 = 5;

/// The five moment mip chains in one buffer (chain c at c·chain_len vec4s).
pub struct MomentChains {
    pub buffer: wgpu::Buffer,
    pub chain_len: u32,
}

impl MomentChains {
    pub fn new(gpu: &Gpu, rsm_size: u32) -> Self {
        let (_, chain_len) = super::pdf_mips::pyramid_layout(rsm_size);
        Self { buffer: storage_buffer(gpu, "vsgl_moment_chain_buffer", CHAINS * chain_len as u64 * 16), chain_len }
    }

    /// Bytes needed for an RSM of side `rsm_size`.
    pub fn bytes(rsm_size: u32) -> u64 {
        CHAINS * super::pdf_mips::pyramid_layout(rsm_size).1 as u64 * 16
    }
}

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct MomentParamsRaw {
    rsm_size: u32,
    chain_len: u32,
    _pad: [u32; 2],
}

pub struct VsglMomentsPass {
    pipelines: PipelineVariants,
}

impl VsglMomentsPass {
    pub fn new(gpu: &Gpu) -> Result<Self> {
        Ok(Self { pipelines: PipelineVariants::new(gpu, "passes/vsgl_moments.wgsl", "main")? })
    }

    pub fn record(&self, gpu: &Gpu, enc: &mut wgpu::CommandEncoder, timer: &mut PassTimer, rsm: &Rsm, chains: &MomentChains, features: ShaderFeatures) {
        let pipeline = self.pipelines.get(gpu, &features.specular_flags());
        let uniform = uniform_buffer(gpu, "vsgl_moments_params_uniform_buffer", &MomentParamsRaw { rsm_size: rsm.size, chain_len: chains.chain_len, _pad: [0; 2] });
        run_compute(
            gpu,
            enc,
            timer,
            "vsgl_moments",
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
