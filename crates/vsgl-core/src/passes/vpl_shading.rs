//! VPL shading (compute): adds the radiance of a batch of VPLs to the indirect buffers.

use crate::error::Result;
use crate::frame::{ShadingInputs, VirtualLightList};
use crate::gpu::{for_each_chunk, interleaved_groups, traced_lights_per_dispatch, Gpu, PipelineVariants, Recorder};

use crate::shader_lib::constants::vpl_shading::WORKGROUP;

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct ShadeParamsRaw {
    vpl_count: u32,
    min_distance2: f32,
    first: u32,
    interleave: u32,
}

/// Most VPLs one dispatch loops over. lavapipe (Mesa 22.3) silently ends shader loops after
/// 65536 iterations in all (seen: 131072 VPLs shaded as 65536), so long VPL lists are split
/// over several dispatches that add into the same targets. With shadow rays:
/// `traced_lights_per_dispatch`.
const VPLS_PER_DISPATCH: u32 = 16384;


pub struct VplShadingPass {
    pipelines: PipelineVariants,
}

impl VplShadingPass {
    pub fn new(gpu: &Gpu) -> Result<Self> {
        Ok(Self { pipelines: PipelineVariants::new(gpu, "passes/vpl_shading.wgsl", "main")? })
    }

    pub fn record(&self, rec: &mut Recorder<'_>, io: &ShadingInputs<'_>, lights: VirtualLightList<'_>, min_distance2: f32) {
        let ShadingInputs { frame_uniforms: frame, gbuffer, out, features, size, visibility } = *io;
        let VirtualLightList { records: vpls, count: vpl_count, interleave } = lights;
        let gpu = rec.gpu;
        let [specular] = features.specular_flags();
        let [traced, ism, paged] = visibility.flags();
        let pipeline = self.pipelines.get(gpu, &[specular, traced, ism, paged]);
        // `frame.passes` names the visibility variant.
        let label = format!("vpl_shading{}", visibility.label_suffix());
        // Chunks are multiples of k² so the interleaved classes stay j ≡ c (mod k²).
        // With shadow rays each VPL also loops over BVH nodes: fewer VPLs per dispatch keep
        // lavapipe under its loop-iteration cap (and a GPU dispatch short).
        let per_dispatch = if visibility.traced { traced_lights_per_dispatch(gpu) } else { VPLS_PER_DISPATCH };
        for_each_chunk(vpl_count, per_dispatch * interleave * interleave, |first, count| {
            let uniform = rec.uniform("vpl_shading_params_uniform_buffer", &ShadeParamsRaw { vpl_count: count, min_distance2, first, interleave });
            rec.compute(
                &label,
                &pipeline,
                &[&[frame.as_entire_binding()], &out.shading_bindings(&uniform, vpls, gbuffer), &visibility.bindings()],
                interleaved_groups(size, interleave, WORKGROUP),
            );
        });
    }
}
