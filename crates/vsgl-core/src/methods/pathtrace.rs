//! `method="pathtrace"`: the one-bounce ground truth with exact visibility — shadow rays for
//! direct light, `spp` BRDF-sampled bounces per pixel through the scene's BVH, progressive, with
//! the standard error of the mean as the `stderr` AOV.

use super::{options::common, DirectLight, FrameContext, Method, MethodInfo, OptionKind, OptionSpec, OptionValue};
use super::options::ChoiceEnum;
use crate::error::Result;
use crate::passes::pathtrace::{PathTraceInputs, PathTracePass, Strategy};

pub const INFO: MethodInfo = MethodInfo {
    name: "pathtrace",
    summary: "one-bounce ground truth by path tracing (exact visibility, progressive, stderr AOV)",
    option_groups: &[OPTIONS],
    direct_light: DirectLight::ByMethod,
    indirect: true,
    extra_aovs: &["stderr"],
    ground_truth: true,
    area_emitters: true,
    configure: |o| {
        let strategy = o.choice("strategy")?;
        Ok(Box::new(PathTrace { spp: o.u32("spp")?, seed: o.u32("seed")?, time_budget_s: o.f32("time_budget_s")? as f64, strategy }))
    },
};

const OPTIONS: &[OptionSpec] = &[
    OptionSpec {
        name: "spp",
        kind: OptionKind::Int { min: 1, max: 65536, power_of_two: false },
        default: OptionValue::Int(64),
        help: "bounce samples per pixel",
        note: "",
    },
    common::SEED,
    OptionSpec {
        name: "time_budget_s",
        kind: OptionKind::Float { min: 0.0, min_exclusive: false },
        default: OptionValue::Float(0.0),
        help: "stop adding samples after this many seconds (0: no budget); frame.settings['spp_done'] says how many were taken",
        note: "",
    },
    OptionSpec {
        name: "strategy",
        kind: OptionKind::Choice(Strategy::NAMES),
        // Bidirectional by default: camera paths alone do not converge on caustics (a polished
        // panel's beam on a wall), so the default is the strategy that converges everywhere.
        default: OptionValue::Str(std::borrow::Cow::Borrowed("bidirectional")),
        help: "\"bidirectional\" (the default): BRDF-sampled bounces from each pixel and light tracing (photons reflected once and splatted), combined by MIS over each pixel's area, so caustics converge; \"camera\": the camera paths alone (faster, but caustics off a near-mirror converge slowly or not at all); \"light\": light tracing alone (a check on the others)",
        note: "",
    },
];

struct PathTrace {
    spp: u32,
    seed: u32,
    time_budget_s: f64,
    strategy: Strategy,
}

impl Method for PathTrace {
    fn record(&self, ctx: &mut FrameContext<'_>) -> Result<()> {
        let pass = ctx.passes.get::<PathTracePass>()?;
        let input = PathTraceInputs {
            scene: ctx.scene,
            frame: ctx.frame_uniforms,
            lights: ctx.light_buffer,
            gscene: ctx.gpu_scene,
            gbuffer: ctx.gbuffer,
            ids: &ctx.visibility.ids,
            features: ctx.features,
            stop: ctx.stop,
            time_budget_s: (self.time_budget_s > 0.0).then_some(self.time_budget_s),
            strategy: self.strategy,
            spp: self.spp,
            seed: self.seed,
        };
        let out = pass.record(&mut ctx.rec, &input, ctx.indirect, ctx.direct, ctx.size)?;
        ctx.settings.push(("spp_done".into(), out.spp_done.into()));
        // Emissive triangles sampled as area lights (0: the emitter code is left out).
        ctx.settings.push(("emitters".into(), ctx.gpu_scene.emitter_count.into()));
        if !out.bvh_built {
            ctx.skip("bvh_build", "the BVH built for this scene upload is reused");
        }
        ctx.stderr = Some(out.stderr);
        ctx.skip("rsm", "method=\"pathtrace\" traces rays instead of virtual lights");
        Ok(())
    }
}
