//! LPV lookup (compute, `method="lpv"`): each pixel's diffuse indirect light from the summed
//! light volume, added to the indirect diffuse target (`wgsl/passes/lpv_lookup.wgsl`).

use crate::error::Result;
use crate::frame::{GBuffer, IndirectTargets};
use crate::gpu::{groups, Gpu, PipelineVariants, Recorder};
use crate::shader_lib::constants::lpv_lookup::WORKGROUP;

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct LookupParamsRaw {
    size: [u32; 2],
    _pad: [u32; 2],
}

pub struct LpvLookupPass {
    pipelines: PipelineVariants,
}

impl LpvLookupPass {
    pub fn new(gpu: &Gpu) -> Result<Self> {
        Ok(Self { pipelines: PipelineVariants::new(gpu, "passes/lpv_lookup.wgsl", "main")? })
    }

    pub fn record(&self, rec: &mut Recorder<'_>, grid: &wgpu::Buffer, total: &wgpu::Buffer, gbuffer: &GBuffer, out: &IndirectTargets, size: (u32, u32)) {
        let pipeline = self.pipelines.get(rec.gpu, &[]);
        let params = rec.uniform("lpv_lookup_params_uniform_buffer", &LookupParamsRaw { size: [size.0, size.1], _pad: [0; 2] });
        let mut bindings = vec![grid.as_entire_binding(), params.as_entire_binding(), total.as_entire_binding()];
        bindings.extend(gbuffer.bindings());
        bindings.push(out.diffuse.as_entire_binding());
        rec.compute("lpv_lookup", &pipeline, &[&bindings], (groups(size.0, WORKGROUP), groups(size.1, WORKGROUP), 1));
    }
}
