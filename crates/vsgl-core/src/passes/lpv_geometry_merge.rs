//! LPV geometry-volume merge (compute, `method="lpv"` with `lpv_occlusion` and several lights):
//! one light's geometry volume folded into the frame's, keeping per cell the lobe with the
//! larger DC term, so an occluder that several lights see blocks once
//! (`wgsl/passes/lpv_geometry_merge.wgsl`).

use crate::error::Result;
use crate::gpu::{groups, Gpu, PipelineVariants, Recorder};
use crate::shader_lib::constants::lpv_geometry_merge::WORKGROUP;

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct MergeParamsRaw {
    cells: u32,
    _pad: [u32; 3],
}

pub struct LpvGeometryMergePass {
    pipelines: PipelineVariants,
}

impl LpvGeometryMergePass {
    pub fn new(gpu: &Gpu) -> Result<Self> {
        Ok(Self { pipelines: PipelineVariants::new(gpu, "passes/lpv_geometry_merge.wgsl", "main")? })
    }

    /// Folds `light_geometry` (`cells` two-band SH cells) into `geometry`.
    pub fn record(&self, rec: &mut Recorder<'_>, cells: u32, light_geometry: &wgpu::Buffer, geometry: &wgpu::Buffer) {
        let pipeline = self.pipelines.get(rec.gpu, &[]);
        let params = rec.uniform("lpv_geometry_merge_params_uniform_buffer", &MergeParamsRaw { cells, _pad: [0; 3] });
        rec.compute(
            "lpv_geometry_merge",
            &pipeline,
            &[&[params.as_entire_binding(), light_geometry.as_entire_binding(), geometry.as_entire_binding()]],
            (groups(cells, WORKGROUP), 1, 1),
        );
    }
}
