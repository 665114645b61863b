//! LPV geometry volume (compute, `method="lpv"` with `lpv_occlusion`): each RSM texel's
//! blocking potential as a clamped-cosine SH lobe scaled by its area over the cell's, added to
//! the nearest light-volume corner in every cascade (`wgsl/passes/lpv_geometry.wgsl`).

use crate::error::Result;
use crate::frame::Rsm;
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

/// The light whose RSM surfels are injected, as the pass needs it.
#[derive(Clone, Copy)]
pub struct SurfelSource {
    /// The light's position relative to the eye.
    pub light_offset: [f32; 3],
    /// [`LightRaw::rsm_light_dir`](crate::frame::uniforms::LightRaw::rsm_light_dir).
    pub light_dir: [f32; 4],
    /// `LightRsm::texel_footprint` of the RSM.
    pub texel_footprint: [f32; 4],
}

pub struct LpvGeometryPass {
    pipelines: PipelineVariants,
}

impl LpvGeometryPass {
    pub fn new(gpu: &Gpu) -> Result<Self> {
        Ok(Self { pipelines: PipelineVariants::new(gpu, "passes/lpv_geometry.wgsl", "main")? })
    }

    pub fn record(&self, rec: &mut Recorder<'_>, grid: &wgpu::Buffer, rsm: &Rsm, source: &SurfelSource, geometry_volume: &wgpu::Buffer) {
        let pipeline = self.pipelines.get(rec.gpu, &[]);
        let SurfelSource { light_offset, light_dir, texel_footprint } = *source;
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
