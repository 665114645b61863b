//! `method="vsgl2"`: two VSGLs per light (one diffuse, one specular) from a parallel sum over
//! the whole RSM (Tokuyoshi 2015 poster): no pyramid, no sampling, no interleaving.

use super::sg_lighting::{BlendDiffuse, SgLighting};
use super::rsm_lights::{check_rsm_size, for_each_light, RsmSettings};
use super::options::ChoiceEnum;
use crate::setting::Setting;
use super::{options::common, DirectLight, FrameContext, Method, MethodInfo, OptionKind, OptionSpec, OptionValue, Options};
use super::visibility::{VirtualLightVisibility, VisibilityMode, VSGL_RECORD_WORDS};
use crate::error::Result;
use crate::gpu::Gpu;
use crate::passes::vsgl2_reduce::{Vsgl2Reduce, Vsgl2Reduction, VSGL2_COUNT};
use crate::passes::vsgl_gen::VSGL_BYTES;
use crate::frame::{ShadingInputs, VirtualLightList};
use crate::passes::vsgl_shading::VsglShadingPass;
use std::borrow::Cow;

pub const INFO: MethodInfo = MethodInfo {
    name: "vsgl2",
    summary: "two VSGLs per light (diffuse + specular) by a parallel sum over the whole RSM (2015 poster)",
    option_groups: OPTION_GROUPS,
    direct_light: DirectLight::ShadowMapped,
    indirect: true,
    extra_aovs: &[],
    ground_truth: false,
    area_emitters: false,
    configure: |o| Ok(Box::new(Vsgl2::new(o)?)),
};

/// `lighting="blend"` (the default) takes only its specular form and shades diffuse as
/// `diffuse=` says: one plane for the whole RSM would fade most of the light out.
const BLEND_DIFFUSE: BlendDiffuse = BlendDiffuse::AsDiffuseSays;

const OPTION_GROUPS: &[&[OptionSpec]] = &[OPTIONS, common::VISIBILITY_OPTIONS, common::RSM_OPTIONS];

const OPTIONS: &[OptionSpec] = &[
    common::SHADOW_SIZE,
    common::EMITTER_LIGHTS,
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
];

struct Vsgl2 {
    visibility: VisibilityMode,
    rsm: RsmSettings,
    lighting: SgLighting,
    reduction: Vsgl2Reduction,
}

impl Vsgl2 {
    fn new(o: &mut Options) -> Result<Self> {
        Ok(Self {
            lighting: SgLighting::from_options(o, BLEND_DIFFUSE)?,
            visibility: VisibilityMode::from_options(o)?,
            // No sampling, no budget: every texel goes into the two sums.
            rsm: RsmSettings::from_options(o, false, 0)?,
            reduction: o.choice("vsgl2_reduction")?,
        })
    }
}

impl Method for Vsgl2 {
    fn check(&self, gpu: &Gpu) -> Result<()> {
        Vsgl2Reduce::resolve(gpu, self.reduction)?;
        check_rsm_size(gpu, self.rsm.size)
    }

    fn record(&self, ctx: &mut FrameContext<'_>) -> Result<()> {
        let (reduce, shading) = (ctx.passes.get::<Vsgl2Reduce>()?, ctx.passes.get::<VsglShadingPass>()?);
        let reduction = Vsgl2Reduce::resolve(ctx.gpu, self.reduction)?;
        let vis = VirtualLightVisibility::new(ctx, self.visibility, VSGL2_COUNT)?;
        let lit = for_each_light(ctx, &self.rsm, |ctx, light| {
            let feat = ctx.features;
            let buf = ctx.rec.storage("vsgl2_buffer", VSGL2_COUNT as u64 * VSGL_BYTES);
            let reduced = light.rsm_light();
            reduce.record(&mut ctx.rec, light.rsm, &reduced, &buf, feat, reduction)?;
            vis.build_maps(ctx, &buf, VSGL2_COUNT, VSGL_RECORD_WORDS)?;
            let io = ShadingInputs { frame_uniforms: ctx.frame_uniforms, gbuffer: ctx.gbuffer, out: ctx.indirect, features: feat, size: ctx.size, visibility: &vis };
            // One record per lobe, never a single texel: nothing to shade exactly.
            let form = self.lighting.shading_form(false);
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

    fn settings(&self, gpu: &Gpu) -> Result<Vec<(String, Setting)>> {
        // What ran, not what was asked ("auto" resolves per adapter).
        let resolved = Vsgl2Reduce::resolve(gpu, self.reduction)?;
        Ok(vec![("vsgl2_reduction".into(), resolved.name().into()), ("vsgl2_temporary_bytes".into(), Vsgl2Reduce::temporary_bytes(self.rsm.size).into())])
    }
}
