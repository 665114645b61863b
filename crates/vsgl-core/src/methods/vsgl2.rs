//! `method="vsgl2"`: two VSGLs per light (one diffuse, one specular) from a parallel sum over
//! the whole RSM (Tokuyoshi 2015 poster): no pyramid, no sampling, no interleaving.

use super::sg_lighting::BlendDiffuse;
use super::rsm_lights::{check_rsm_size, for_each_light, rsm_fit, RsmSettings};
use super::options::ChoiceEnum;
use crate::frame::uniforms::RsmFit;
use super::{options::common, DirectLight, FrameContext, Method, MethodInfo, OptionKind, OptionSpec, OptionValue, Options};
use super::visibility::{VirtualLightVisibility, VisibilityMode, VSGL_RECORD_WORDS};
use crate::error::Result;
use crate::gpu::Gpu;
use crate::passes::vsgl2_reduce::{Vsgl2Reduce, Vsgl2Reduction, VSGL2_COUNT};
use crate::passes::vsgl_gen::VSGL_BYTES;
use crate::frame::{ShadingInputs, VirtualLightList};
use crate::passes::vsgl_shading::{DiffuseMode, LambertLobe, LightingMode, VsglShadingForm, VsglShadingPass};
use std::borrow::Cow;

pub const INFO: MethodInfo = MethodInfo {
    name: "vsgl2",
    summary: "two VSGLs per light (diffuse + specular) by a parallel sum over the whole RSM (2015 poster)",
    options: OPTIONS,
    direct_light: DirectLight::ShadowMapped,
    indirect: true,
    extra_aovs: &[],
    configure: |o| Ok(Box::new(Vsgl2::new(o)?)),
};

/// `lighting="blend"` (the default) takes only its specular form and shades diffuse as
/// `diffuse=` says: one plane for the whole RSM would fade most of the light out.
const BLEND_DIFFUSE: BlendDiffuse = BlendDiffuse::AsDiffuseSays;

const OPTIONS: &[OptionSpec] = &[
    common::SHADOW_SIZE,
    // The parallel sum tiles any side; only the mip-based methods need a power of two.
    OptionSpec { kind: OptionKind::Int { min: 32, max: 4096, power_of_two: false }, ..common::RSM_SIZE },
    common::DIFFUSE,
    // "blend" since it was measured on the real-scene corpus: the papers' SG–ASG form delivered
    // 0.07–0.28 of the reference's specular there, blend more on every scene at the same
    // diffuse (docs/methods/vsgl2.md, "Two VSGLs").
    common::lighting("blend", BLEND_DIFFUSE),
    common::LAMBERT_LOBE,
    // Off by default: vsgl2's one plane spans the whole RSM, and on the Cornell boxes fading by
    // it loses light (docs/methods/vsgl.md, "The cluster's tangent plane").
    common::plane_fade(false),
    OptionSpec {
        name: "vsgl2_reduction",
        kind: OptionKind::Choice(Vsgl2Reduction::NAMES),
        default: OptionValue::Str(Cow::Borrowed("auto")),
        help: "how workgroups add: subgroup arithmetic where the adapter has it (auto), or a shared-memory tree",
        note: "",
    },
    common::VISIBILITY,
    common::ISM_SIZE,
    common::ISM_POINTS,
    common::ISM_POINTS_PER_MAP,
    common::ISM_BIAS,
    common::ISM_PCF,
    common::RSM_FIT,
    common::CAPTURE_RSM,
];

struct Vsgl2 {
    options: Options,
    visibility: VisibilityMode,
    rsm_size: u32,
    diffuse: DiffuseMode,
    lighting: LightingMode,
    lambert_lobe: LambertLobe,
    plane_fade: bool,
    reduction: Vsgl2Reduction,
    capture_rsm: bool,
    rsm_fit: RsmFit,
}

impl Vsgl2 {
    fn new(given: &Options) -> Result<Self> {
        let o = &super::sg_lighting::with_resolved_diffuse_form(given.clone(), BLEND_DIFFUSE)?;
        let reduction = o.choice("vsgl2_reduction")?;
        Ok(Self { options: o.clone(), visibility: VisibilityMode::from_options(o)?, rsm_size: o.u32("rsm_size")?, diffuse: super::sg_lighting::diffuse_mode(o, BLEND_DIFFUSE)?, lighting: super::sg_lighting::lighting_mode(o)?, lambert_lobe: o.choice("lambert_lobe")?, plane_fade: super::sg_lighting::plane_fade(o, BLEND_DIFFUSE)?, reduction, capture_rsm: o.bool("capture_rsm")?, rsm_fit: rsm_fit(o)? })
    }
}

impl Method for Vsgl2 {
    fn check(&self, gpu: &Gpu) -> Result<()> {
        Vsgl2Reduce::resolve(gpu, self.reduction)?;
        check_rsm_size(gpu, self.rsm_size)
    }

    fn record(&self, ctx: &mut FrameContext<'_>) -> Result<()> {
        let (reduce, shading) = (ctx.passes.get::<Vsgl2Reduce>()?, ctx.passes.get::<VsglShadingPass>()?);
        let reduction = Vsgl2Reduce::resolve(ctx.gpu, self.reduction)?;
        let rsm = RsmSettings { size: self.rsm_size, sampling: false, capture: self.capture_rsm, budget: 0, fit: self.rsm_fit };
        let vis = VirtualLightVisibility::new(ctx, self.visibility, VSGL2_COUNT)?;
        let lit = for_each_light(ctx, &rsm, |ctx, light| {
            let feat = ctx.features;
            let buf = ctx.rec.storage("vsgl2_buffer", VSGL2_COUNT as u64 * VSGL_BYTES);
            reduce.record(&mut ctx.rec, light.rsm, light.raw.position, light.raw.rsm_light_dir(), light.texel_footprint(), &buf, feat, reduction)?;
            vis.build_maps(ctx, &buf, VSGL2_COUNT, VSGL_RECORD_WORDS)?;
            let io = ShadingInputs { frame_uniforms: ctx.frame_uniforms, gbuffer: ctx.gbuffer, out: ctx.indirect, features: feat, size: ctx.size, visibility: &vis };
            // One record per lobe, never a single texel: nothing to shade exactly.
            let form = VsglShadingForm { diffuse: self.diffuse, lighting: self.lighting, lambert_lobe: self.lambert_lobe, exact_texels: false, plane_fade: self.plane_fade };
            shading.record(&mut ctx.rec, &io, VirtualLightList { records: &buf, count: VSGL2_COUNT, interleave: 1 }, form, None);
            if ctx.vsgls.is_none() {
                ctx.vsgls = Some(buf);
            }
            Ok(())
        })?;
        if lit {
            let why = "method=\"vsgl2\": two VSGLs from a parallel sum over the whole RSM";
            ctx.skip("pdf_mips", format!("{why}, no importance sampling"));
            ctx.skip("moment_mips", format!("{why}, no mipmapped moments"));
            ctx.skip("vsgl_sampling", format!("{why}, no kernels to place"));
            ctx.skip("denoise", format!("{why}: every pixel evaluates both VSGLs (no interleaving)"));
        }
        Ok(())
    }

    fn settings(&self, gpu: &Gpu) -> Result<Vec<(String, String)>> {
        let resolved = Vsgl2Reduce::resolve(gpu, self.reduction)?;
        let mut rows = self.options.rows();
        for (name, value) in rows.iter_mut() {
            if name == "vsgl2_reduction" {
                // What ran, not what was asked ("auto" resolves per adapter).
                *value = resolved.name().into();
            }
        }
        rows.push(("vsgl2_temporary_bytes".into(), Vsgl2Reduce::temporary_bytes(self.rsm_size).to_string()));
        Ok(rows)
    }
}
