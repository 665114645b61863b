//! `method="reference"`: every texel of a high-resolution RSM as a VPL, no visibility (the
//! papers' own reference), in batches so no submission runs long enough to trip a watchdog.

use super::rsm_lights::{check_rsm_size, for_each_light, RsmSettings};
use super::{options::common, DirectLight, FrameContext, Method, MethodInfo, OptionSpec, OptionValue, Options};
use super::visibility::{VirtualLightVisibility, VisibilityMode, VPL_RECORD_WORDS};
use crate::error::Result;
use crate::gpu::Gpu;
use crate::passes::vpl_sample::{VplSamplePass, VplSource, VPL_BYTES};
use crate::frame::{ShadingInputs, VirtualLightList};
use crate::passes::vpl_shading::VplShadingPass;

pub const INFO: MethodInfo = MethodInfo {
    name: "reference",
    summary: "every texel of a high-resolution reflective shadow map as a VPL, unshadowed (the papers' reference)",
    option_groups: &[OPTIONS, common::VISIBILITY_OPTIONS, common::RSM_OPTIONS],
    direct_light: DirectLight::ShadowMapped,
    indirect: true,
    extra_aovs: &[],
    ground_truth: true,
    area_emitters: false,
    configure: |o| Ok(Box::new(Reference::new(o)?)),
};

const OPTIONS: &[OptionSpec] = &[
    common::SHADOW_SIZE,
    common::EMITTER_LIGHTS,
    // A larger default than the sampling methods: the reference must resolve what they miss.
    OptionSpec { default: OptionValue::Int(1024), ..common::RSM_SIZE },
    common::VPL_CLAMP,
];

/// Most VPL batches the reference splits its work into (each is one timed pass).
const MAX_BATCHES: u64 = 1024;
/// Pixel·VPL evaluations per submission: small enough that no batch runs long enough to trip
/// a GPU watchdog (~10 ms on an H100), unless that would exceed the batch cap.
const BATCH_EVALUATIONS: u64 = 1 << 31;
/// The same on a CPU adapter (lavapipe evaluates ~10⁷–10⁸ per second, so 2³¹ would be one
/// silent submission of minutes): ~0.2–2 s per batch, so progress and Ctrl-C come that often.
const BATCH_EVALUATIONS_CPU: u64 = 1 << 24;
/// Bytes of imperfect shadow maps one batch may hold (`visibility="ism"`): 4096 maps of 64²
/// with their pull-push levels are ~85 MiB, under the 128 MiB storage binding most adapters have.
const REFERENCE_ISM_BYTES: u64 = 96 << 20;

struct Reference {
    visibility: VisibilityMode,
    rsm: RsmSettings,
    vpl_clamp: f32,
}

impl Reference {
    fn new(o: &Options) -> Result<Self> {
        // Every texel a VPL: no sampling, no budget.
        Ok(Self { visibility: VisibilityMode::from_options(o)?, rsm: RsmSettings::from_options(o, false, 0)?, vpl_clamp: o.f32("vpl_clamp")? })
    }
}

impl Method for Reference {
    fn check(&self, gpu: &Gpu) -> Result<()> {
        check_rsm_size(gpu, self.rsm.size)
    }

    fn record(&self, ctx: &mut FrameContext<'_>) -> Result<()> {
        let (sample, shading) = (ctx.passes.get::<VplSamplePass>()?, ctx.passes.get::<VplShadingPass>()?);
        let n = self.rsm.size;
        let texels = n as u64 * n as u64;
        let capacity = texels.min(1 << 20);
        let vpls = ctx.rec.storage("vpl_buffer", capacity * VPL_BYTES);
        let min_distance2 = (self.vpl_clamp as f64 * ctx.extent).powi(2) as f32;
        // With imperfect shadow maps a batch's maps are held at once: batches of at most
        // REFERENCE_ISM_BYTES of maps.
        let max_batch = self.visibility.lights_within(REFERENCE_ISM_BYTES).map_or(capacity, |n| (n as u64).clamp(64, capacity));
        let vis = VirtualLightVisibility::new(ctx, self.visibility, max_batch as u32)?;
        let lit = for_each_light(ctx, &self.rsm, |ctx, light| {
            let (gpu, feat) = (ctx.gpu, ctx.features);
            let pixels = ctx.size.0 as u64 * ctx.size.1 as u64;
            let batch_evaluations = if gpu.adapter.device_type == "Cpu" { BATCH_EVALUATIONS_CPU } else { BATCH_EVALUATIONS };
            let per_batch = (batch_evaluations / pixels.max(1)).max(texels.div_ceil(MAX_BATCHES)).clamp(64, capacity).min(max_batch);
            let mut first = 0u64;
            while first < texels {
                let count = per_batch.min(texels - first);
                sample.record_every_texel(&mut ctx.rec, &VplSource { light: light.light, rsm: light.rsm, out: &vpls, features: feat }, first as u32, count as u32);
                vis.build_maps(ctx, &vpls, count as u32, VPL_RECORD_WORDS)?;
                let io = ShadingInputs { frame_uniforms: ctx.frame_uniforms, gbuffer: ctx.gbuffer, out: ctx.indirect, features: feat, size: ctx.size, visibility: &vis };
                shading.record(&mut ctx.rec, &io, VirtualLightList { records: &vpls, count: count as u32, interleave: 1 }, min_distance2);
                first += count;
                if first < texels && count * pixels >= batch_evaluations / 2 {
                    // Submit this batch on its own so no submission runs for long.
                    ctx.submit_so_far();
                    gpu.wait("reference batch")?;
                    if let Some(stop) = ctx.stop {
                        stop.check(crate::progress::Progress { done: first, total: texels, unit: "texels" })?;
                    }
                }
            }
            Ok(())
        })?;
        if lit {
            ctx.skip("pdf_mips", "the reference uses every RSM texel, no importance sampling");
        }
        Ok(())
    }
}
