//! The interleaved importance map of bidirectional RSM importance recombined (compute,
//! `wgsl/passes/brsm_importance_filter.wgsl`, where the reason is given): with
//! `importance_interleave` = k > 1, each lit RSM texel gets the mean of the interleaved
//! estimates over the k×k window around it, which holds one texel of every interleave class.

use crate::error::Result;
use crate::frame::Rsm;
use crate::gpu::{groups, Gpu, Recorder};

use crate::shader_lib::constants::brsm_importance_filter::WORKGROUP;

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct FilterParamsRaw {
    rsm_size: u32,
    interleave: u32,
    _pad: [u32; 2],
}

pub struct BrsmImportanceFilterPass {
    pipeline: wgpu::ComputePipeline,
}

impl BrsmImportanceFilterPass {
    pub fn new(gpu: &Gpu) -> Result<Self> {
        let module = gpu.shader("passes/brsm_importance_filter.wgsl")?;
        Ok(Self { pipeline: gpu.compute_pipeline("brsm_importance_filter_pipeline", &module, "main") })
    }

    /// Writes level 0 of `importance` (a pyramid in the layout of `rsm.pyramid`) from the
    /// `interleaved` estimates (one per texel, `brsm_importance` with tile side `interleave`).
    pub fn record(&self, rec: &mut Recorder<'_>, rsm: &Rsm, interleave: u32, interleaved: &wgpu::Buffer, importance: &wgpu::Buffer) {
        let uniform = rec.uniform("brsm_importance_filter_params_uniform_buffer", &FilterParamsRaw { rsm_size: rsm.size, interleave, _pad: [0; 2] });
        rec.compute(
            "brsm_importance_filter",
            &self.pipeline,
            &[&[uniform.as_entire_binding(), rsm.pyramid.as_entire_binding(), interleaved.as_entire_binding(), importance.as_entire_binding()]],
            (groups(rsm.size, WORKGROUP), groups(rsm.size, WORKGROUP), 1),
        );
    }
}
