//! LPV propagation (compute, `method="lpv"`): `iterations` gathers from the six face
//! neighbours through five faces each, ping-ponging between two volumes and adding every
//! iteration into the total the lookup reads (`wgsl/passes/lpv_propagate.wgsl`).

use crate::error::Result;
use crate::frame::lpv::LpvVolumes;
use crate::gpu::{groups, Gpu, PipelineVariants, Recorder};
use crate::shader_lib::constants::lpv_propagate::WORKGROUP;

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct PropagateParamsRaw {
    occlude: u32,
    _pad: [u32; 3],
}

pub struct LpvPropagatePass {
    pipelines: PipelineVariants,
}

impl LpvPropagatePass {
    pub fn new(gpu: &Gpu) -> Result<Self> {
        Ok(Self { pipelines: PipelineVariants::new(gpu, "passes/lpv_propagate.wgsl", "main")? })
    }

    /// `volumes.current` holds the injected light; afterwards `volumes.total` holds it plus
    /// every iteration's. `occlusion`: attenuate by `volumes.geometry` from the second
    /// iteration on.
    pub fn record(&self, rec: &mut Recorder<'_>, grid: &wgpu::Buffer, volumes: &LpvVolumes, iterations: u32, occlusion: bool) {
        let pipeline = self.pipelines.get(rec.gpu, &[]);
        rec.enc.copy_buffer_to_buffer(&volumes.current, 0, &volumes.total, 0, volumes.total.size());
        let uniform = |rec: &mut Recorder<'_>, occlude: bool| rec.uniform(if occlude { "lpv_propagate_occluded_params_uniform_buffer" } else { "lpv_propagate_params_uniform_buffer" }, &PropagateParamsRaw { occlude: occlude as u32, _pad: [0; 3] });
        let first = uniform(rec, false);
        let later = uniform(rec, occlusion);
        let (side, cascades) = (volumes.side, volumes.cascades);
        let g = groups(side, WORKGROUP);
        let (mut from, mut to) = (&volumes.current, &volumes.next);
        for i in 0..iterations {
            let params = if i == 0 { &first } else { &later };
            rec.compute(
                "lpv_propagate",
                &pipeline,
                &[&[grid.as_entire_binding(), params.as_entire_binding(), from.as_entire_binding(), volumes.geometry.as_entire_binding(), to.as_entire_binding(), volumes.total.as_entire_binding()]],
                (g, g, groups(side * cascades, WORKGROUP)),
            );
            std::mem::swap(&mut from, &mut to);
        }
    }
}
