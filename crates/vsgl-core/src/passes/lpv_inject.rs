//! LPV light injection (compute, `method="lpv"`): each lit RSM texel's diffusely reflected flux
//! as a clamped-cosine SH lobe, added to its cell in every cascade (`wgsl/passes/lpv_inject.wgsl`).

use crate::error::Result;
use crate::frame::Rsm;
use crate::gpu::{groups, Gpu, PipelineVariants, Recorder};
use crate::shader_lib::constants::lpv_inject::WORKGROUP;

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct InjectParamsRaw {
    light_offset: [f32; 3],
    rsm_size: u32,
}

pub struct LpvInjectPass {
    pipelines: PipelineVariants,
}

impl LpvInjectPass {
    pub fn new(gpu: &Gpu) -> Result<Self> {
        Ok(Self { pipelines: PipelineVariants::new(gpu, "passes/lpv_inject.wgsl", "main")? })
    }

    /// Adds `rsm`'s texels (positions relative to the light at `light_offset` from the eye)
    /// into `light_volume`.
    pub fn record(&self, rec: &mut Recorder<'_>, grid: &wgpu::Buffer, rsm: &Rsm, light_offset: [f32; 3], light_volume: &wgpu::Buffer) {
        let pipeline = self.pipelines.get(rec.gpu, &[]);
        let params = rec.uniform("lpv_inject_params_uniform_buffer", &InjectParamsRaw { light_offset, rsm_size: rsm.size });
        let g = groups(rsm.size, WORKGROUP);
        rec.compute(
            "lpv_inject",
            &pipeline,
            &[&[
                grid.as_entire_binding(),
                params.as_entire_binding(),
                rsm.gbuffer.position.as_entire_binding(),
                rsm.gbuffer.normal.as_entire_binding(),
                rsm.flux_diffuse.as_entire_binding(),
                light_volume.as_entire_binding(),
            ]],
            (g, g, 1),
        );
    }
}
