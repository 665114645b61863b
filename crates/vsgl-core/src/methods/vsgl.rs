//! `method="vsgl"`: N virtual spherical Gaussian lights by filtered importance
//! sampling of the mipmapped RSM (Tokuyoshi 2015 with the 2016 integral kernel), shaded with
//! interleaving and a geometry-aware filter.

use super::brsm::{Importance, ViewImportance};
use super::choices::{NearField, ShadowTarget, VsglKernel};
use super::kmeans::{KmeansClustering, KmeansJob};
use super::options::ChoiceEnum;
use super::interleaved::{InterleaveSettings, InterleavedShading};
use super::metropolis::{MetropolisSampling, TexelSampling};
use super::rsm_lights::{check_rsm_size, for_each_light, resolve_rsm_size_for_num_lights, RsmSettings};
use super::sg_lighting::{BlendDiffuse, SgLighting};
use super::visibility::{VirtualLightVisibility, VisibilityMode, VSGL_RECORD_WORDS};
use super::{options::common, DirectLight, FrameContext, Method, MethodInfo, OptionKind, OptionSpec, OptionValue, Options};
use crate::error::{Error, Result};
use crate::frame::MomentChains;
use crate::gpu::Gpu;
use crate::passes::moment_mips::MomentMipsPass;
use crate::passes::pdf_mips::PdfMipsPass;
use crate::passes::vpl_sample::Sampling;
use crate::passes::vsgl_gen::{GenSettings, GenSource, Kernel, KernelFilter, VsglGenPass, SHADOW_CANDIDATES, SHADOW_CANDIDATE_BYTES, VSGL_BYTES};
use crate::setting::Setting;
use crate::passes::vsgl_moments::VsglMomentsPass;
use crate::frame::{ShadingInputs, VirtualLightList};
use crate::passes::vsgl_shading::{ShadingCandidates, VsglShadingPass};
use std::borrow::Cow;

pub const INFO: MethodInfo = MethodInfo {
    name: "vsgl",
    summary: "num_lights VSGLs by filtered importance sampling of the mipmapped RSM (2015/2016 papers), interleaved and denoised",
    option_groups: OPTION_GROUPS,
    direct_light: DirectLight::ShadowMapped,
    indirect: true,
    extra_aovs: &[],
    ground_truth: false,
    area_emitters: false,
    configure: |o| Ok(Box::new(Vsgl::new(o)?)),
};

/// `lighting="blend"` brings the clamped-cosine diffuse, faded below each cluster's plane.
const BLEND_DIFFUSE: BlendDiffuse = BlendDiffuse::ClampedCosine;

const OPTION_GROUPS: &[&[OptionSpec]] = &[
    &[common::SHADOW_SIZE, common::EMITTER_LIGHTS, common::num_lights(1024), common::RSM_SIZE],
    common::SAMPLING_OPTIONS,
    &[
        OptionSpec {
            name: "kernel",
            kind: OptionKind::Choice(VsglKernel::NAMES),
            default: OptionValue::Str(Cow::Borrowed("integral")),
            help: "kernel size rule: \"integral\" (2016, bisection to mass K/N), \"density\" (2015) or \"node\" (quadtree nodes of mass <= K/N read exactly: unbiased cluster totals, VPL-like as N reaches the texel count); or the 2016 paper's k-means baseline, \"kmeans2d\" (every lit texel to its nearest of N centres in RSM texel coordinates) or \"kmeans3d\" (in world positions), its clusters' exact sums as VSGLs",
            note: "",
        },
        OptionSpec {
            name: "kmeans_iterations",
            kind: OptionKind::Int { min: 0, max: 64, power_of_two: false },
            // 0 as the paper ("we do not update iteratively").
            default: OptionValue::Int(0),
            help: "with kernel=\"kmeans2d\"/\"kmeans3d\": Lloyd iterations after the first assignment (each centre moved to its cluster's weighted mean, the texels assigned again); 0 is the paper's single assignment",
            note: "",
        },
        // "nodes" (experiments/vsgl_defaults_on_the_corpus.md): FlightHelmet's indirect diffuse
        // 0.67 -> 0.98 of the every-texel reference at N = 1024, whatever K.
        common::choice(
            "kernel_filter",
            KernelFilter::NAMES,
            "how kernel=\"integral\" and \"density\" read the moment mips at a kernel's level: \"nodes\" (the quadtree nodes that hold its centre at the two levels either side, blended by the fraction, so a kernel of about a texel is that texel: a bilinear blend spreads it over 2x2 texels and moves its mean, across a depth jump into the gap, and the light it sends a texel or two away is lost) or \"trilinear\" (the papers' trilinear mip read, bilinear within a level; before 2026-12-02)",
        ),
        OptionSpec {
            name: "K",
            kind: OptionKind::Float { min: 0.0, min_exclusive: true },
            default: OptionValue::Float(1.0),
            help: "probability mass K/N of each kernel (2016 paper); larger K is smoother and more biased",
            note: "",
        },
        OptionSpec {
            name: "coherence",
            kind: OptionKind::Float { min: 0.0, min_exclusive: false },
            // 0.9 (docs/scenes.md, "The real-scene corpus"): out of the box it lifts
            // CornellBoxOriginal's indirect diffuse from 0.87 to 0.94 of the reference and
            // FlightHelmet's from 0.25 to 0.40, and no built-in's block error rises by 1%.
            default: OptionValue::Float(0.9),
            help: "smallest mean-normal length |Σw·n|/Σw of a cluster, in 0..1: each kernel shrinks until its texels' normals agree that well, so clusters do not straddle creases and depth discontinuities of the RSM (0: the papers' kernels, which grow by mass alone)",
            note: "",
        },
        OptionSpec {
            name: "bisection_steps",
            kind: OptionKind::Int { min: 1, max: 32, power_of_two: false },
            default: OptionValue::Int(12),
            help: "bisection iterations of the integral kernel",
            note: "",
        },
        common::interleave(8),
    ],
    common::DENOISE_OPTIONS,
    &[
        common::DIFFUSE,
        // "blend" by default (docs/scenes.md, "The real-scene corpus"): against the path tracer it
        // is closer than the papers' form on every corpus scene and built-in measured.
        common::lighting("blend", BLEND_DIFFUSE),
        common::LAMBERT_LOBE,
        // On by default (docs/methods/vsgl.md, "The cluster's tangent plane"): without it the papers'
        // form lights the back of a lit plane with about half its front's direct light.
        common::plane_fade(true),
    ],
    common::VISIBILITY_OPTIONS,
    &[
        // "resampled" (experiments/corpus_shadow_targets_and_bounds.md, "Which texel the shadow
        // ray aims at"): in a float64 model
        // on FlightHelmet the centre texel kept 0.69 of the every-texel reference's shadowed light
        // from 4-texel clusters, 8 resampled candidates 0.95-0.97.
        common::choice(
            "shadow_target",
            ShadowTarget::NAMES,
            "with visibility=\"raytrace\", where each VSGL's shadow ray aims: \"resampled\" (at one of 8 texels of its cluster, drawn by power and kept per receiver by its geometric term there, so the ray goes where the cluster's light at that receiver comes from) or \"centre\" (at the cluster's sampled centre texel, the same for every receiver; before 2026-12-02)",
        ),
        // "texels" (experiments/vsgl_defaults_on_the_corpus.md): lower block error against the
        // every-texel reference on 9 of 13 corpus scenes and built-ins, none higher by over 0.1%.
        common::choice(
            "near_field",
            NearField::NAMES,
            "diffuse light at receivers inside a VSGL's positional Gaussian or behind its mean tangent plane: \"texels\" (also from 8 of its texels shaded one by one as patches, weighted in where the Gaussian's form does not hold) or \"sg\" (the Gaussian's SG alone, before 2026-12-02)",
        ),
    ],
    common::IMPORTANCE_OPTIONS,
    common::RSM_OPTIONS,
];

struct Vsgl {
    visibility: VisibilityMode,
    num_lights: u32,
    rsm: RsmSettings,
    sampling: TexelSampling,
    kernel: VsglKernel,
    kernel_filter: KernelFilter,
    /// `kmeans_iterations=` (k-means kernels only).
    kmeans_iterations: u32,
    k: f32,
    /// Smallest mean-normal length of a cluster (`coherence=`, 0: off).
    coherence: f32,
    bisection_steps: u32,
    interleave: InterleaveSettings,
    lighting: SgLighting,
    importance: Importance,
    /// `shadow_target="resampled"`: candidate shadow targets with `visibility="raytrace"`.
    resampled_shadow_target: bool,
    /// `near_field="texels"`.
    near_field_texels: bool,
}

/// `kernel_filter=`: for the filtered kernels; `kernel="node"` reads its node exactly and
/// k-means sums its clusters exactly, so one given with them is an error rather than silently
/// ignored.
fn kernel_filter(o: &Options) -> Result<KernelFilter> {
    let filter = o.str("kernel_filter")?;
    let kernel = o.choice::<VsglKernel>("kernel")?;
    if o.was_given("kernel_filter") && kernel.sampled() != Some(Kernel::Integral) && kernel.sampled() != Some(Kernel::Density) {
        let kernel = kernel.name();
        return Err(Error::invalid("kernel_filter", format!("kernel_filter={filter:?} applies to kernel=\"integral\" and \"density\"; kernel={kernel:?} reads its clusters' moments exactly")));
    }
    o.choice("kernel_filter")
}

/// k-means' own option and the sampled kernels' options: each given with the other kind of
/// kernel is an error naming both, and k-means does not yet run with what it was not built for.
fn check_kmeans_options(o: &Options) -> Result<()> {
    let kernel = o.choice::<VsglKernel>("kernel")?;
    let name = kernel.name();
    if kernel.kmeans().is_none() {
        if o.was_given("kmeans_iterations") {
            return Err(Error::invalid("kmeans_iterations", format!("applies to kernel=\"kmeans2d\" and \"kmeans3d\", not kernel={name:?}")));
        }
        return Ok(());
    }
    for option in ["K", "coherence", "bisection_steps"] {
        if o.was_given(option) {
            return Err(Error::invalid(option, format!("applies to the sampled kernels (\"integral\", \"density\", \"node\"); kernel={name:?} assigns every lit texel to its nearest centre")));
        }
    }
    if o.choice::<Sampling>("sampling")? == Sampling::Metropolis {
        return Err(Error::invalid("sampling", format!("kernel={name:?} draws its centres once per frame; sampling=\"metropolis\" is for the sampled kernels (use \"stratified\" or \"random\")")));
    }
    Ok(())
}

/// `coherence=`: a length of a mean of unit vectors, so at most 1.
fn coherence(o: &Options) -> Result<f32> {
    let c = o.f32("coherence")?;
    if c > 1.0 {
        return Err(Error::invalid("coherence", format!("must be in 0..=1 (the length of a mean of unit normals), got {c}")));
    }
    Ok(c)
}

impl Vsgl {
    fn new(o: &mut Options) -> Result<Self> {
        resolve_rsm_size_for_num_lights(o)?;
        let num_lights = o.u32("num_lights")?;
        check_kmeans_options(o)?;
        Ok(Self {
            lighting: SgLighting::from_options(o, BLEND_DIFFUSE)?,
            visibility: VisibilityMode::from_options(o)?,
            num_lights,
            rsm: RsmSettings::from_options(o, true, num_lights)?,
            sampling: TexelSampling::from_options(o)?,
            kernel: o.choice("kernel")?,
            kernel_filter: kernel_filter(o)?,
            kmeans_iterations: o.u32("kmeans_iterations")?,
            k: o.f32("K")?,
            coherence: coherence(o)?,
            bisection_steps: o.u32("bisection_steps")?,
            interleave: InterleaveSettings::from_options(o)?,
            importance: Importance::from_options(o)?,
            resampled_shadow_target: o.choice::<ShadowTarget>("shadow_target")? == ShadowTarget::Resampled,
            near_field_texels: o.choice::<NearField>("near_field")? == NearField::Texels,
        })
    }
}

impl Vsgl {
    /// Chain F (each texel's w·n, w·(y·n)) serves the tangent-plane fade and the kernels'
    /// normal coherence.
    fn needs_planes(&self) -> bool {
        self.lighting.plane_fade || self.coherence > 0.0
    }

    fn kmeans(&self) -> Option<KmeansClustering> {
        self.kernel.kmeans().map(|space| KmeansClustering { space, iterations: self.kmeans_iterations })
    }

    fn metropolis(&self) -> MetropolisSampling {
        MetropolisSampling { method: INFO.name, num_lights: self.num_lights, rsm_size: self.rsm.size, seed: self.sampling.seed, space: self.sampling.chain_space, importance: self.importance }
    }
}

impl Method for Vsgl {
    fn check(&self, gpu: &Gpu) -> Result<()> {
        check_rsm_size(gpu, self.rsm.size)?;
        let limit = gpu.limits.max_storage_buffer_binding_size as u64;
        let bytes = MomentChains::bytes(self.rsm.size, self.needs_planes());
        if bytes > limit {
            let n = self.rsm.size;
            return Err(Error::invalid("rsm_size", format!("the VSGL moment mips of a {n}² RSM ({bytes} bytes) exceed this adapter's storage binding limit of {limit} bytes")));
        }
        Ok(())
    }

    fn settings(&self, _gpu: &Gpu) -> Result<Vec<(String, Setting)>> {
        // The paper's dispatch count of its k-means (39, both views with BRSM) has a row to
        // stand beside: one clustering of num_lights, and with importance="brsm" the view's.
        let view = match self.importance {
            Importance::Brsm { view_lights, .. } => Some(view_lights),
            Importance::Rsm => None,
        };
        Ok(self.kmeans().map(|k| ("kmeans_dispatches".to_string(), Setting::Int(i64::from(k.dispatches(self.num_lights) + view.map_or(0, |n| k.dispatches(n)))))).into_iter().collect())
    }

    fn record(&self, ctx: &mut FrameContext<'_>) -> Result<()> {
        let passes = ctx.passes;
        let (pdf_mips, moments, moment_mips) = (passes.get::<PdfMipsPass>()?, passes.get::<VsglMomentsPass>()?, passes.get::<MomentMipsPass>()?);
        let (gen, shading) = (passes.get::<VsglGenPass>()?, passes.get::<VsglShadingPass>()?);
        let shading_out = InterleavedShading::new(ctx, self.interleave);
        let mut chains: Option<MomentChains> = None;
        let vis = VirtualLightVisibility::new(ctx, self.visibility, self.num_lights)?;
        // Metropolis chains keep one view seed while they live (`target_seed` says why).
        let view_seed = if self.sampling.sampling == Sampling::Metropolis { self.metropolis().target_seed(ctx) } else { self.sampling.seed };
        let view = match self.importance {
            Importance::Brsm { view_lights, interleave } => Some(ViewImportance::new(ctx, view_lights, interleave, view_seed, self.kmeans())?),
            Importance::Rsm => None,
        };
        let lit = for_each_light(ctx, &self.rsm, |ctx, light| {
            let feat = ctx.features;
            let chains = chains.get_or_insert_with(|| MomentChains::new(&mut ctx.rec, self.rsm.size, self.needs_planes()));
            pdf_mips.record(&mut ctx.rec, light.rsm);
            // Sampled by the RSM's weights, or by its importance to the view (brsm).
            let reweighted = match &view {
                Some(view) => Some(view.pyramid(ctx, light)?),
                None => None,
            };
            moments.record(&mut ctx.rec, light.rsm, &light.rsm_light(), chains, feat);
            // k-means sums whole texels (level 0): the mips are for the sampled kernels.
            if self.kmeans().is_none() {
                moment_mips.record(&mut ctx.rec, self.rsm.size, chains);
            }
            // This RSM's share of num_lights (split over lights and cube faces by reflected
            // power, `power_budgets`).
            // The chains target the density the VSGLs' estimators then divide by (`pdf`).
            let pdf = reweighted.as_ref().unwrap_or(&light.rsm.pyramid);
            let samples = match self.sampling.sampling {
                Sampling::Metropolis => Some(self.metropolis().step(ctx, light, pdf)?),
                _ => None,
            };
            let buf = ctx.rec.storage("vsgl_buffer", light.budget as u64 * VSGL_BYTES);
            let resample_target = self.resampled_shadow_target && self.visibility == VisibilityMode::RayTraced;
            let candidates = (resample_target || self.near_field_texels)
                .then(|| ctx.rec.storage("vsgl_shadow_candidate_buffer", light.budget as u64 * SHADOW_CANDIDATE_BYTES));
            if let Some(kmeans) = self.kmeans() {
                let job = KmeansJob {
                    rsm: light.rsm,
                    centre_density: pdf,
                    chains,
                    count: light.budget,
                    seed: self.sampling.seed,
                    stratified: self.sampling.sampling == Sampling::Stratified,
                    light_offset: light.raw.position,
                    vsgls: &buf,
                    shadow_candidates: candidates.as_ref().map(|b| (b, SHADOW_CANDIDATES)),
                };
                kmeans.record(ctx, &job)?;
            } else {
                let settings = GenSettings {
                    count: light.budget,
                    sampling: self.sampling.sampling,
                    samples: samples.as_ref(),
                    seed: self.sampling.seed,
                    kernel: self.kernel.sampled().unwrap_or(Kernel::Integral),
                    k: self.k,
                    bisection_steps: self.bisection_steps,
                    light_offset: light.raw.position,
                    importance: reweighted.is_some(),
                    coherence: self.coherence,
                    shadow_candidates: candidates.as_ref(),
                    filter: self.kernel_filter,
                };
                gen.record_with_pdf(&mut ctx.rec, "vsgl_gen", &GenSource { rsm: light.rsm, pdf, chains }, &settings, &buf);
            }
            vis.build_maps(ctx, &buf, light.budget, VSGL_RECORD_WORDS)?;
            let target = shading_out.target(ctx.indirect);
            let io = ShadingInputs { frame_uniforms: ctx.frame_uniforms, gbuffer: ctx.gbuffer, out: target, features: feat, size: ctx.size, visibility: &vis };
            let form = self.lighting.shading_form(self.kernel == VsglKernel::Node || self.kmeans().is_some());
            let lights = VirtualLightList { records: &buf, count: light.budget, interleave: self.interleave.interleave };
            let candidates = candidates.as_ref().map(|buffer| ShadingCandidates { buffer, seed: self.sampling.seed, resample_target, near_field: self.near_field_texels });
            shading.record(&mut ctx.rec, &io, lights, form, candidates.as_ref());
            if ctx.vsgls.is_none() {
                ctx.vsgls = Some(buf);
            }
            Ok(())
        })?;
        if !lit {
            return Ok(());
        }
        if self.kmeans().is_some() {
            ctx.skip("moment_mips", "k-means sums its clusters' texels at level 0; the mips serve the sampled kernels");
        }
        shading_out.resolve(ctx)
    }
}
