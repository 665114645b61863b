//! Mip levels of the VSGL moment chains (compute): 2×2 averages, level by level.

use crate::error::Result;
use crate::frame::MomentChains;
use crate::gpu::{groups, Gpu, Recorder};

use crate::shader_lib::constants::moment_mips::WORKGROUP;

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct LevelRaw {
    src_offset: u32,
    dst_offset: u32,
    dst_size: u32,
    chain_len: u32,
    chains: u32,
    _pad: [u32; 3],
}

pub struct MomentMipsPass {
    pipeline: wgpu::ComputePipeline,
}

impl MomentMipsPass {
    pub fn new(gpu: &Gpu) -> Result<Self> {
        let module = gpu.shader("passes/moment_mips.wgsl")?;
        Ok(Self { pipeline: gpu.compute_pipeline("moment_mips_pipeline", &module, "main") })
    }

    pub fn record(&self, rec: &mut Recorder<'_>, rsm_size: u32, chains: &MomentChains) {
        self.record_as(rec, "moment_mips", rsm_size, chains);
    }

    /// As [`Self::record`], timed as `label`.
    pub fn record_as(&self, rec: &mut Recorder<'_>, label: &str, rsm_size: u32, chains: &MomentChains) {
        let (offsets, _) = crate::frame::pyramid_layout(rsm_size);
        for level in 1..offsets.len() {
            let dst_size = rsm_size >> level;
            let uniform = rec.uniform("moment_mips_level_uniform_buffer", &LevelRaw { src_offset: offsets[level - 1], dst_offset: offsets[level], dst_size, chain_len: chains.chain_len, chains: chains.count, _pad: [0; 3] });
            rec.compute(
                label,
                &self.pipeline,
                &[&[uniform.as_entire_binding(), chains.buffer.as_entire_binding()]],
                (groups(dst_size, WORKGROUP), groups(dst_size, WORKGROUP), 1),
            );
        }
    }
}
