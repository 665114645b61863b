//! Bidirectional RSM importance (`importance="brsm"`) [Tok15 §4.3; Tok16 §5
//! setup and Table 1]: VSGLs generated on the camera's G-buffer estimate what each RSM texel
//! adds to the view, and the RSM's VPLs or VSGLs are then sampled from that importance instead
//! of from the reflected power Φ·(R_d + R_s) alone. Shared by `vpl` and `vsgl`; the steps,
//! each its own timed pass (docs/methods/brsm.md, "Bidirectional RSM importance"):
//!
//! once per frame (the view's VSGLs): `brsm_view_gbuffer` (the camera G-buffer onto a square
//! grid, the papers' additional G-buffer), `brsm_view_moments`, `brsm_view_mips` (weight and
//! moment pyramids), `brsm_view_vsgl_gen` (integral kernel, K = 1, stratified);
//!
//! per RSM: `brsm_importance` (the importance map; with `importance_interleave` k > 1 each
//! texel evaluates 1/k² of the view VSGLs and `brsm_importance_filter` recombines the classes),
//! then the re-weighted pyramid:
//! `brsm_pdf_mips` (its total), `brsm_mix` (mixed with the RSM's weights), `brsm_pdf_mips`.

use super::options::Options;
use super::choices::ImportanceChoice;
use super::rsm_lights::LightRsm;
use super::kmeans::{KmeansClustering, KmeansJob};
use super::FrameContext;
use crate::error::Result;
use crate::frame::{pyramid_layout, MomentChains, RsmLight, VirtualLightList};
use crate::passes::brsm_importance::BrsmImportancePass;
use crate::passes::brsm_importance_filter::BrsmImportanceFilterPass;
use crate::passes::brsm_mix::BrsmMixPass;
use crate::passes::brsm_view_gbuffer::{view_grid, view_grid_side, BrsmViewPass};
use crate::passes::moment_mips::MomentMipsPass;
use crate::passes::pdf_mips::PdfMipsPass;
use crate::passes::vpl_sample::Sampling;
use crate::passes::vsgl_gen::{GenSettings, GenSource, Kernel, KernelFilter, VsglGenPass, VSGL_BYTES};
use crate::passes::vsgl_moments::VsglMomentsPass;

/// `importance=`: where the RSM's sampling density comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Importance {
    /// Φ·(R_d + R_s) of each texel (the papers' default).
    Rsm,
    /// Bidirectional: Φ·R of each texel shaded by `view_lights` VSGLs of the camera's view,
    /// each texel evaluating the 1/`interleave`² of them of its interleave class.
    Brsm { view_lights: u32, interleave: u32 },
}

impl Importance {
    pub fn from_options(o: &Options) -> Result<Self> {
        // With sampling="metropolis" the chains target the same re-weighted pyramid the
        // estimators divide by (`MetropolisSampling::step` is given it), so the pair combines.
        Ok(match o.choice("importance")? {
            ImportanceChoice::Brsm => Importance::Brsm { view_lights: o.u32("importance_lights")?, interleave: o.u32("importance_interleave")? },
            ImportanceChoice::Rsm => Importance::Rsm,
        })
    }
}

/// The view's VSGLs of one frame, from which each RSM's importance is estimated.
pub struct ViewImportance {
    vsgls: wgpu::Buffer,
    count: u32,
    /// Interleave tile side of the importance map (`importance_interleave`).
    interleave: u32,
}

impl ViewImportance {
    /// Builds `count` VSGLs of the camera's view (seeded by `seed`, as the frame's own
    /// sampling is, so estimates of different seeds stay independent), by the 2016 paper's
    /// filtered importance sampling or, with `clustering`, by k-means on the view's G-buffer
    /// (the paper ran its k-means baseline there too [Tok16 §5]); each RSM texel will evaluate
    /// those of its class of the `interleave`² classes.
    pub fn new(ctx: &mut FrameContext<'_>, count: u32, interleave: u32, seed: u32, clustering: Option<KmeansClustering>) -> Result<Self> {
        let p = ctx.passes;
        let (view, pdf_mips, moments, moment_mips, gen) =
            (p.get::<BrsmViewPass>()?, p.get::<PdfMipsPass>()?, p.get::<VsglMomentsPass>()?, p.get::<MomentMipsPass>()?, p.get::<VsglGenPass>()?);
        let features = ctx.features;
        let side = view_grid_side(ctx.size);
        let rec = &mut ctx.rec;
        let grid = view_grid(rec, side, features.specular);
        view.record(rec, ctx.gbuffer, ctx.size, &grid, features);
        pdf_mips.record_pyramid(rec, "brsm_view_mips", side, &grid.pyramid);
        let chains = MomentChains::labelled(rec, "brsm_view_moment_chain_buffer", side, false);
        // The eye is the grid's "light": positions relative to it (light_dir w = 0).
        moments.record_as(rec, "brsm_view_moments", &grid, &RsmLight::default(), &chains, features);
        let vsgls = rec.storage("brsm_view_vsgl_buffer", count as u64 * VSGL_BYTES);
        if let Some(kmeans) = clustering {
            // Positions relative to the frame origin, the eye; in "kmeans2d" the grid's texel
            // coordinates are the screen's.
            let job = KmeansJob { rsm: &grid, centre_density: &grid.pyramid, chains: &chains, count, seed, stratified: true, light_offset: [0.0; 3], vsgls: &vsgls, shadow_candidates: None };
            kmeans.record(ctx, &job)?;
            return Ok(Self { vsgls, count, interleave });
        }
        moment_mips.record_as(rec, "brsm_view_mips", side, &chains);
        // The 2016 paper's generation (integral kernel, K = 1, 12 bisection steps, Fibonacci
        // centres); positions relative to the frame origin, the eye.
        let settings = GenSettings { count, sampling: Sampling::Stratified, samples: None, seed, kernel: Kernel::Integral, k: 1.0, bisection_steps: 12, light_offset: [0.0; 3], importance: false, coherence: 0.0, shadow_candidates: None, filter: KernelFilter::Trilinear };
        gen.record_with_pdf(rec, "brsm_view_vsgl_gen", &GenSource { rsm: &grid, pdf: &grid.pyramid, chains: &chains }, &settings, &vsgls);
        Ok(Self { vsgls, count, interleave })
    }

    /// The re-weighted sampling pyramid of `light`'s RSM (whose own weight pyramid is already
    /// summed): the importance map mixed with the RSM's weights (`brsm_mix`), summed.
    pub fn pyramid(&self, ctx: &mut FrameContext<'_>, light: &LightRsm<'_>) -> Result<wgpu::Buffer> {
        let p = ctx.passes;
        let (importance, filter, mix, pdf_mips) = (p.get::<BrsmImportancePass>()?, p.get::<BrsmImportanceFilterPass>()?, p.get::<BrsmMixPass>()?, p.get::<PdfMipsPass>()?);
        let size = light.rsm.size;
        let rec = &mut ctx.rec;
        // Every texel of level 0 is written by brsm_importance (k = 1) or brsm_importance_filter
        // (k > 1, from brsm_importance's interleaved estimates), the levels above by pdf_mips.
        let pyramid = rec.storage_written("brsm_pdf_pyramid_buffer", pyramid_layout(size).1 as u64 * 4);
        if self.interleave > 1 {
            let interleaved = rec.storage_written("brsm_interleaved_importance_buffer", size as u64 * size as u64 * 4);
            importance.record(rec, light.light.as_entire_binding(), light.rsm, VirtualLightList { records: &self.vsgls, count: self.count, interleave: self.interleave }, &interleaved, ctx.features);
            filter.record(rec, light.rsm, self.interleave, &interleaved, &pyramid);
        } else {
            importance.record(rec, light.light.as_entire_binding(), light.rsm, VirtualLightList { records: &self.vsgls, count: self.count, interleave: 1 }, &pyramid, ctx.features);
        }
        pdf_mips.record_pyramid(rec, "brsm_pdf_mips", size, &pyramid);
        mix.record(rec, light.rsm, &pyramid);
        pdf_mips.record_pyramid(rec, "brsm_pdf_mips", size, &pyramid);
        ctx.sampling_pyramid = Some(pyramid.clone());
        Ok(pyramid)
    }
}
