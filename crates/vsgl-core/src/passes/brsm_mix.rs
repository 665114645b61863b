//! Level 0 of the re-weighted sampling pyramid of bidirectional RSM importance (compute,
//! `wgsl/passes/brsm_mix.wgsl`): the importance map and the RSM's own weights mixed as
//! densities, so no texel that reflects light loses all its probability.

use crate::error::Result;
use crate::frame::Rsm;
use crate::gpu::{groups, Gpu, Recorder};

use crate::shader_lib::constants::brsm_mix::WORKGROUP;

/// ε of the shader: the RSM density's share in the mixture `(q/Q + ε w/W)/(1 + ε)`.
pub const RSM_SHARE: f64 = 0.1;

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct MixParamsRaw {
    rsm_size: u32,
    top: u32,
    _pad: [u32; 2],
}

pub struct BrsmMixPass {
    pipeline: wgpu::ComputePipeline,
}

impl BrsmMixPass {
    pub fn new(gpu: &Gpu) -> Result<Self> {
        let module = gpu.shader("passes/brsm_mix.wgsl")?;
        Ok(Self { pipeline: gpu.compute_pipeline("brsm_mix_pipeline", &module, "main") })
    }

    /// `importance`: a pyramid in the layout of `rsm.pyramid` whose level 0 holds the
    /// importance map and whose levels above are already summed (pdf_mips); its level 0 is
    /// replaced by the mixture (sum its levels again afterwards).
    pub fn record(&self, rec: &mut Recorder<'_>, rsm: &Rsm, importance: &wgpu::Buffer) {
        let (_, total) = crate::frame::pyramid_layout(rsm.size);
        let uniform = rec.uniform("brsm_mix_params_uniform_buffer", &MixParamsRaw { rsm_size: rsm.size, top: total - 1, _pad: [0; 2] });
        rec.compute(
            "brsm_mix",
            &self.pipeline,
            &[&[uniform.as_entire_binding(), rsm.pyramid.as_entire_binding(), importance.as_entire_binding()]],
            (groups(rsm.size, WORKGROUP), groups(rsm.size, WORKGROUP), 1),
        );
    }
}
