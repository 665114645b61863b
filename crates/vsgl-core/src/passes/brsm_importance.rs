//! The importance map of bidirectional RSM importance (compute,
//! `wgsl/passes/brsm_importance.wgsl`): every RSM texel shaded by the view's VSGLs with its own
//! BRDF, an estimate of what it adds to the image.

use crate::error::Result;
use crate::frame::{Rsm, VirtualLightList};
use crate::gpu::{interleaved_groups, Gpu, PipelineVariants, Recorder};
use crate::plan::ShaderFeatures;

use crate::shader_lib::constants::brsm_importance::WORKGROUP;

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct ImportanceParamsRaw {
    rsm_size: u32,
    count: u32,
    interleave: u32,
    _pad: u32,
}

pub struct BrsmImportancePass {
    pipelines: PipelineVariants,
}

impl BrsmImportancePass {
    pub fn new(gpu: &Gpu) -> Result<Self> {
        Ok(Self { pipelines: PipelineVariants::new(gpu, "passes/brsm_importance.wgsl", "main")? })
    }

    /// Writes level 0 of `importance` (a pyramid in the layout of `rsm.pyramid`) from the
    /// `count` view VSGLs in `view_vsgls`, each texel evaluating those of its class of the
    /// `interleave`² classes (k = 1: all); `light`: the RSM's light as its passes bind it.
    pub fn record(&self, rec: &mut Recorder<'_>, light: wgpu::BindingResource<'_>, rsm: &Rsm, view: VirtualLightList<'_>, importance: &wgpu::Buffer, features: ShaderFeatures) {
        let VirtualLightList { records: view_vsgls, count, interleave } = view;
        let gpu = rec.gpu;
        let pipeline = self.pipelines.get(gpu, &features.specular_flags());
        let uniform = rec.uniform("brsm_importance_params_uniform_buffer", &ImportanceParamsRaw { rsm_size: rsm.size, count, interleave, _pad: 0 });
        rec.compute(
            "brsm_importance",
            &pipeline,
            &[&[
                uniform.as_entire_binding(),
                light,
                rsm.gbuffer.position.as_entire_binding(),
                rsm.gbuffer.normal.as_entire_binding(),
                rsm.flux_diffuse.as_entire_binding(),
                rsm.flux_specular.as_entire_binding(),
                view_vsgls.as_entire_binding(),
                importance.as_entire_binding(),
            ]],
            // Deinterleaved workgroups: each covers texels of one class (common/interleave.wgsl).
            interleaved_groups((rsm.size, rsm.size), interleave, WORKGROUP),
        );
    }
}
