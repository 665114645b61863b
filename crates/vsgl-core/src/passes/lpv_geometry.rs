//! LPV geometry volume (compute, `method="lpv"` with `lpv_occlusion`): each RSM texel's
//! blocking potential as a clamped-cosine SH lobe scaled by its area over the cell's, added to
//! the nearest light-volume corner in every cascade (`wgsl/passes/lpv_geometry.wgsl`).

use crate::error::Result;
use crate::frame::{Rsm, RsmLight};
use crate::gpu::{groups, Gpu, PipelineVariants, Recorder};
use crate::shader_lib::constants::lpv_geometry::WORKGROUP;

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct GeometryParamsRaw {
    light_offset: [f32; 3],
    rsm_size: u32,
    light_dir: [f32; 4],
    texel_footprint: [f32; 4],
}

pub struct LpvGeometryPass {
    pipelines: PipelineVariants,
}

impl LpvGeometryPass {
    pub fn new(gpu: &Gpu) -> Result<Self> {
        Ok(Self { pipelines: PipelineVariants::new(gpu, "passes/lpv_geometry.wgsl", "main")? })
    }

    pub fn record(&self, rec: &mut Recorder<'_>, grid: &wgpu::Buffer, rsm: &Rsm, light: &RsmLight, geometry_volume: &wgpu::Buffer) {
        let pipeline = self.pipelines.get(rec.gpu, &[]);
        let RsmLight { offset: light_offset, dir: light_dir, texel_footprint } = *light;
        let params = rec.uniform("lpv_geometry_params_uniform_buffer", &GeometryParamsRaw { light_offset, rsm_size: rsm.size, light_dir, texel_footprint });
        let g = groups(rsm.size, WORKGROUP);
        rec.compute(
            "lpv_geometry",
            &pipeline,
            &[&[
                grid.as_entire_binding(),
                params.as_entire_binding(),
                rsm.gbuffer.position.as_entire_binding(),
                rsm.gbuffer.normal.as_entire_binding(),
                geometry_volume.as_entire_binding(),
            ]],
            (g, g, 1),
        );
    }
}
