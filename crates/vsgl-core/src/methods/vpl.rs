//! `method="vpl"`: N virtual point lights, importance-sampled from the lights' RSMs by
//! hierarchical sample warping over the weight pyramid (the papers' baseline; Dachsbacher and
//! Stamminger 2005 for the RSM), optionally interleaved and denoised like `vsgl`.

use super::brsm::{Importance, ViewImportance};
use super::interleaved::InterleavedShading;
use super::metropolis::{ChainSpace, MetropolisSampling};
use super::rsm_lights::{check_rsm_size, for_each_light, rsm_fit, with_rsm_size_for_num_lights, RsmSettings};
use crate::frame::uniforms::RsmFit;
use super::{options::common, DirectLight, FrameContext, Method, MethodInfo, OptionSpec, Options};
use super::visibility::{VirtualLightVisibility, VisibilityMode, VPL_RECORD_WORDS};
use crate::error::Result;
use crate::gpu::Gpu;
use crate::passes::pdf_mips::PdfMipsPass;
use crate::passes::vpl_sample::{Sampling, VplSamplePass, VPL_BYTES};
use crate::frame::{ShadingInputs, VirtualLightList};
use crate::passes::vpl_shading::VplShadingPass;

pub const INFO: MethodInfo = MethodInfo {
    name: "vpl",
    summary: "num_lights virtual point lights importance-sampled from the lights' reflective shadow maps (the papers' baseline)",
    options: OPTIONS,
    direct_light: DirectLight::ShadowMapped,
    indirect: true,
    extra_aovs: &[],
    configure: |o| Ok(Box::new(Vpl::new(o)?)),
};

const OPTIONS: &[OptionSpec] = &[
    common::SHADOW_SIZE,
    common::num_lights(256),
    common::RSM_SIZE,
    common::SAMPLING,
    common::CHAIN_SPACE,
    common::SEED,
    common::VPL_CLAMP,
    common::interleave(1),
    common::DENOISE,
    common::DENOISE_FORM,
    common::VISIBILITY,
    common::ISM_SIZE,
    common::ISM_POINTS,
    common::ISM_POINTS_PER_MAP,
    common::ISM_BIAS,
    common::ISM_PCF,
    common::IMPORTANCE,
    common::IMPORTANCE_LIGHTS,
    common::IMPORTANCE_INTERLEAVE,
    common::RSM_FIT,
    common::CAPTURE_RSM,
];

struct Vpl {
    options: Options,
    visibility: VisibilityMode,
    num_lights: u32,
    rsm_size: u32,
    sampling: Sampling,
    chain_space: ChainSpace,
    seed: u32,
    vpl_clamp: f32,
    interleave: u32,
    denoise: bool,
    /// `denoise_form="exchange"`.
    denoise_keeps_light: bool,
    importance: Importance,
    capture_rsm: bool,
    rsm_fit: RsmFit,
}

impl Vpl {
    fn new(given: &Options) -> Result<Self> {
        let o = &with_rsm_size_for_num_lights(given)?;
        Ok(Self {
            options: o.clone(),
            visibility: VisibilityMode::from_options(o)?,
            num_lights: o.u32("num_lights")?,
            rsm_size: o.u32("rsm_size")?,
            sampling: o.choice("sampling")?,
            chain_space: ChainSpace::from_options(o)?,
            seed: o.u32("seed")?,
            vpl_clamp: o.f32("vpl_clamp")?,
            interleave: o.u32("interleave")?,
            denoise: o.bool("denoise")?,
            denoise_keeps_light: super::interleaved::keeps_light(o)?,
            importance: Importance::from_options(o)?,
            capture_rsm: o.bool("capture_rsm")?,
            rsm_fit: rsm_fit(o)?,
        })
    }
}

impl Method for Vpl {
    fn check(&self, gpu: &Gpu) -> Result<()> {
        check_rsm_size(gpu, self.rsm_size)
    }

    fn record(&self, ctx: &mut FrameContext<'_>) -> Result<()> {
        let (pdf_mips, sample, shading) = (ctx.passes.get::<PdfMipsPass>()?, ctx.passes.get::<VplSamplePass>()?, ctx.passes.get::<VplShadingPass>()?);
        let vpls = ctx.rec.storage("vpl_buffer", self.num_lights as u64 * VPL_BYTES);
        // Distances below the clamp count as the clamp (0: unbiased).
        let min_distance2 = (self.vpl_clamp as f64 * ctx.extent).powi(2) as f32;
        let shading_out = InterleavedShading::new(ctx, self.interleave, self.denoise, self.denoise_keeps_light);
        let rsm = RsmSettings { size: self.rsm_size, sampling: true, capture: self.capture_rsm, budget: self.num_lights, fit: self.rsm_fit };
        let vis = VirtualLightVisibility::new(ctx, self.visibility, self.num_lights)?;
        let metropolis = MetropolisSampling { method: INFO.name, num_lights: self.num_lights, rsm_size: self.rsm_size, seed: self.seed, space: self.chain_space, importance: self.importance };
        // Metropolis chains keep one view seed while they live (`target_seed` says why).
        let view_seed = if self.sampling == Sampling::Metropolis { metropolis.target_seed(ctx) } else { self.seed };
        let view = match self.importance {
            Importance::Brsm { view_lights, interleave } => Some(ViewImportance::new(ctx, view_lights, interleave, view_seed)?),
            Importance::Rsm => None,
        };
        let lit = for_each_light(ctx, &rsm, |ctx, light| {
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
            let samples = match self.sampling {
                Sampling::Metropolis => Some(metropolis.step(ctx, light, pdf)?),
                _ => None,
            };
            sample.record_importance(&mut ctx.rec, light.light.as_entire_binding(), light.rsm, pdf, light.budget, self.sampling, self.seed, &vpls, feat, samples.as_ref());
            vis.build_maps(ctx, &vpls, light.budget, VPL_RECORD_WORDS)?;
            let target = shading_out.target(ctx.indirect);
            let io = ShadingInputs { frame_uniforms: ctx.frame_uniforms, gbuffer: ctx.gbuffer, out: target, features: feat, size: ctx.size, visibility: &vis };
            shading.record(&mut ctx.rec, &io, VirtualLightList { records: &vpls, count: light.budget, interleave: self.interleave }, min_distance2);
            Ok(())
        })?;
        if lit {
            shading_out.resolve(ctx)?;
        }
        Ok(())
    }

    fn settings(&self, _gpu: &Gpu) -> Result<Vec<(String, String)>> {
        Ok(self.options.rows())
    }
}

