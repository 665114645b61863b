//! `method="vpl"`: N virtual point lights, importance-sampled from the lights' RSMs by
//! hierarchical sample warping over the weight pyramid (the papers' baseline; Dachsbacher and
//! Stamminger 2005 for the RSM), optionally interleaved and denoised like `vsgl`.

use super::brsm::{Importance, ViewImportance};
use super::interleaved::{InterleaveSettings, InterleavedShading};
use super::metropolis::{MetropolisSampling, TexelSampling};
use super::rsm_lights::{check_rsm_size, for_each_light, resolve_rsm_size_for_num_lights, RsmSettings};
use super::{options::common, DirectLight, FrameContext, Method, MethodInfo, Options};
use super::visibility::{VirtualLightVisibility, VisibilityMode, VPL_RECORD_WORDS};
use crate::error::Result;
use crate::gpu::Gpu;
use crate::passes::pdf_mips::PdfMipsPass;
use crate::passes::vpl_sample::{ImportanceDraw, Sampling, VplSamplePass, VplSource, VPL_BYTES};
use crate::frame::{ShadingInputs, VirtualLightList};
use crate::passes::vpl_shading::VplShadingPass;

pub const INFO: MethodInfo = MethodInfo {
    name: "vpl",
    summary: "num_lights virtual point lights importance-sampled from the lights' reflective shadow maps (the papers' baseline)",
    option_groups: &[
        &[common::SHADOW_SIZE, common::EMITTER_LIGHTS, common::num_lights(256), common::RSM_SIZE],
        common::SAMPLING_OPTIONS,
        &[common::VPL_CLAMP, common::interleave(1)],
        common::DENOISE_OPTIONS,
        common::VISIBILITY_OPTIONS,
        common::IMPORTANCE_OPTIONS,
        common::RSM_OPTIONS,
    ],
    direct_light: DirectLight::ShadowMapped,
    indirect: true,
    extra_aovs: &[],
    ground_truth: false,
    area_emitters: false,
    configure: |o| Ok(Box::new(Vpl::new(o)?)),
};

struct Vpl {
    visibility: VisibilityMode,
    num_lights: u32,
    rsm: RsmSettings,
    sampling: TexelSampling,
    vpl_clamp: f32,
    interleave: InterleaveSettings,
    importance: Importance,
}

impl Vpl {
    fn new(o: &mut Options) -> Result<Self> {
        resolve_rsm_size_for_num_lights(o)?;
        let num_lights = o.u32("num_lights")?;
        Ok(Self {
            visibility: VisibilityMode::from_options(o)?,
            num_lights,
            rsm: RsmSettings::from_options(o, true, num_lights)?,
            sampling: TexelSampling::from_options(o)?,
            vpl_clamp: o.f32("vpl_clamp")?,
            interleave: InterleaveSettings::from_options(o)?,
            importance: Importance::from_options(o)?,
        })
    }
}

impl Method for Vpl {
    fn check(&self, gpu: &Gpu) -> Result<()> {
        check_rsm_size(gpu, self.rsm.size)
    }

    fn record(&self, ctx: &mut FrameContext<'_>) -> Result<()> {
        let (pdf_mips, sample, shading) = (ctx.passes.get::<PdfMipsPass>()?, ctx.passes.get::<VplSamplePass>()?, ctx.passes.get::<VplShadingPass>()?);
        let vpls = ctx.rec.storage("vpl_buffer", self.num_lights as u64 * VPL_BYTES);
        // Distances below the clamp count as the clamp (0: unbiased).
        let min_distance2 = (self.vpl_clamp as f64 * ctx.extent).powi(2) as f32;
        let shading_out = InterleavedShading::new(ctx, self.interleave);
        let vis = VirtualLightVisibility::new(ctx, self.visibility, self.num_lights)?;
        let metropolis = MetropolisSampling { method: INFO.name, num_lights: self.num_lights, rsm_size: self.rsm.size, seed: self.sampling.seed, space: self.sampling.chain_space, importance: self.importance };
        // Metropolis chains keep one view seed while they live (`target_seed` says why).
        let view_seed = if self.sampling.sampling == Sampling::Metropolis { metropolis.target_seed(ctx) } else { self.sampling.seed };
        let view = match self.importance {
            Importance::Brsm { view_lights, interleave } => Some(ViewImportance::new(ctx, view_lights, interleave, view_seed, None)?),
            Importance::Rsm => None,
        };
        let lit = for_each_light(ctx, &self.rsm, |ctx, light| {
            let feat = ctx.features;
            pdf_mips.record(&mut ctx.rec, light.rsm);
            // Sampled by the RSM's weights, or by its importance to the view (brsm).
            let reweighted = match &view {
                Some(view) => Some(view.pyramid(ctx, light)?),
                None => None,
            };
            let pdf = reweighted.as_ref().unwrap_or(&light.rsm.pyramid);
            // This RSM's share of num_lights (split over lights and cube faces by reflected
            // power, `power_budgets`); the buffer holds num_lights, the largest share.
            // The chains target the density the VPLs are then weighted by (`pdf`).
            let samples = match self.sampling.sampling {
                Sampling::Metropolis => Some(metropolis.step(ctx, light, pdf)?),
                _ => None,
            };
            let source = VplSource { light: light.light, rsm: light.rsm, out: &vpls, features: feat };
            let draw = ImportanceDraw { count: light.budget, pdf, sampling: self.sampling.sampling, seed: self.sampling.seed, samples: samples.as_ref() };
            sample.record_importance(&mut ctx.rec, &source, &draw);
            vis.build_maps(ctx, &vpls, light.budget, VPL_RECORD_WORDS)?;
            let target = shading_out.target(ctx.indirect);
            let io = ShadingInputs { frame_uniforms: ctx.frame_uniforms, gbuffer: ctx.gbuffer, out: target, features: feat, size: ctx.size, visibility: &vis };
            shading.record(&mut ctx.rec, &io, VirtualLightList { records: &vpls, count: light.budget, interleave: self.interleave.interleave }, min_distance2);
            Ok(())
        })?;
        if lit {
            shading_out.resolve(ctx)?;
        }
        Ok(())
    }
}

