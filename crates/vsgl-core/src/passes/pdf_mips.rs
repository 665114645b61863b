//! The sampling-weight pyramid (compute): 2×2 sums level by level, so the top holds the total
//! and hierarchical sample warping can descend it. wgpu has no GenerateMips, and sums (not
//! averages) keep the probabilities exact.

use crate::error::Result;
use crate::frame::Rsm;
use crate::gpu::{groups, Gpu, Recorder};

use crate::shader_lib::constants::pdf_mips::WORKGROUP;


#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct LevelRaw {
    src_offset: u32,
    dst_offset: u32,
    dst_size: u32,
    _pad: u32,
}

pub struct PdfMipsPass {
    pipeline: wgpu::ComputePipeline,
}

impl PdfMipsPass {
    pub fn new(gpu: &Gpu) -> Result<Self> {
        let module = gpu.shader("passes/pdf_mips.wgsl")?;
        Ok(Self { pipeline: gpu.compute_pipeline("pdf_mips_pipeline", &module, "main") })
    }

    pub fn record(&self, rec: &mut Recorder<'_>, rsm: &Rsm) {
        self.record_pyramid(rec, "pdf_mips", rsm.size, &rsm.pyramid);
    }

    /// Sums the levels above 0 of any pyramid of side `size` in the RSM layout, timed as
    /// `label` (bidirectional importance sums its view grid and its re-weighted pyramid too).
    pub fn record_pyramid(&self, rec: &mut Recorder<'_>, label: &str, size: u32, pyramid: &wgpu::Buffer) {
        let (offsets, _) = crate::frame::pyramid_layout(size);
        for level in 1..offsets.len() {
            let dst_size = size >> level;
            let uniform = rec.uniform("pdf_mips_level_uniform_buffer", &LevelRaw { src_offset: offsets[level - 1], dst_offset: offsets[level], dst_size, _pad: 0 });
            rec.compute(
                label,
                &self.pipeline,
                &[&[uniform.as_entire_binding(), pyramid.as_entire_binding()]],
                (groups(dst_size, WORKGROUP), groups(dst_size, WORKGROUP), 1),
            );
        }
    }
}

