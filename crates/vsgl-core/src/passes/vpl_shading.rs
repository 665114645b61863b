//! VPL shading (compute): adds the radiance of a batch of VPLs to the indirect buffers.

use super::{for_each_chunk, run_compute, uniform_buffer};
use crate::error::Result;
use crate::gpu::{groups, Gpu, PassTimer, PipelineVariants};
use crate::plan::ShaderFeatures;
use crate::passes::material::GBuffer;

const WORKGROUP: u32 = 8;

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct ShadeParamsRaw {
    vpl_count: u32,
    min_distance2: f32,
    first: u32,
    _pad: u32,
}

/// Most VPLs one dispatch loops over. lavapipe (Mesa 22.3) silently ends shader loops after
/// 65536 iterations in all (seen: 131072 VPLs shaded as 65536), so long VPL lists are split
/// over several dispatches that add into the same targets.
const VPLS_PER_DISPATCH: u32 = 16384;

/// Diffuse and specular indirect radiance (vec4f per pixel each).
pub struct IndirectTargets {
    pub diffuse: wgpu::Buffer,
    pub specular: wgpu::Buffer,
}

impl IndirectTargets {
    /// What a shading pass binds (group 1): its parameters, its light list, the G-buffer and
    /// both targets, in the order of vpl_shading.wgsl and vsgl_shading.wgsl.
    pub fn shading_bindings<'a>(&'a self, params: &'a wgpu::Buffer, lights: &'a wgpu::Buffer, gbuffer: &'a GBuffer) -> Vec<wgpu::BindingResource<'a>> {
        let mut b = vec![params.as_entire_binding(), lights.as_entire_binding()];
        b.extend(gbuffer.bindings());
        b.extend([self.diffuse.as_entire_binding(), self.specular.as_entire_binding()]);
        b
    }
}

pub struct VplShadingPass {
    pipelines: PipelineVariants,
}

impl VplShadingPass {
    pub fn new(gpu: &Gpu) -> Result<Self> {
        Ok(Self { pipelines: PipelineVariants::new(gpu, "passes/vpl_shading.wgsl", "main")? })
    }

    #[allow(clippy::too_many_arguments)]
    pub fn record(
        &self,
        gpu: &Gpu,
        enc: &mut wgpu::CommandEncoder,
        timer: &mut PassTimer,
        frame: &wgpu::Buffer,
        vpls: &wgpu::Buffer,
        vpl_count: u32,
        min_distance2: f32,
        gbuffer: &GBuffer,
        out: &IndirectTargets,
        features: ShaderFeatures,
        size: (u32, u32),
    ) {
        let pipeline = self.pipelines.get(gpu, &features.specular_flags());
        for_each_chunk(vpl_count, VPLS_PER_DISPATCH, |first, count| {
            let uniform = uniform_buffer(gpu, "vpl_shading_params_uniform_buffer", &ShadeParamsRaw { vpl_count: count, min_distance2, first, _pad: 0 });
            run_compute(
                gpu,
                enc,
                timer,
                "vpl_shading",
                &pipeline,
                &[&[frame.as_entire_binding()], &out.shading_bindings(&uniform, vpls, gbuffer)],
                (groups(size.0, WORKGROUP), groups(size.1, WORKGROUP), 1),
            );
        });
    }
}
