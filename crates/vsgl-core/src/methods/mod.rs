//! The methods of a render (`method=`), one module each, behind one trait and one registry.
//!
//! A method declares what it is ([`MethodInfo`]: name, one line of description, the keyword
//! options it takes, the AOVs it makes, whether the frame's shadow-mapped direct pass runs for
//! it) and records its part of the frame ([`Method::record`]) into a [`FrameContext`] that the
//! frame script (`crate::renderer`) has filled with the shared targets. Adding a method is one
//! new module here plus one line in [`REGISTRY`]; nothing else names methods.

pub mod choices;
pub mod options;
mod brsm;
mod interleaved;
mod kmeans;
pub mod metropolis;
mod rsm_lights;
mod sg_lighting;

mod direct;
pub mod emitter_direct;
mod lpv;
mod pathtrace;
mod reference;
mod vpl;
mod vsgl;
mod vsgl2;
pub mod visibility;

use crate::error::{Error, Result};
use crate::frame::uniforms::LightRaw;
use crate::frame::{GBuffer, IndirectTargets, VisibilityTargets};
use crate::gpu::{Gpu, PassCache, Recorder};
use crate::plan::ShaderFeatures;
use crate::scene::Scene;
use crate::setting::Setting;
use crate::upload::GpuScene;
pub use options::{OptionKind, OptionSpec, OptionValue, Options};

/// Every method, in the order `vsgl.METHODS` lists them.
pub const REGISTRY: &[&MethodInfo] = &[&direct::INFO, &vpl::INFO, &vsgl::INFO, &vsgl2::INFO, &lpv::INFO, &reference::INFO, &pathtrace::INFO];

/// How a method's frame gets its direct light.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DirectLight {
    /// The frame's shadow maps and direct pass (rasterized visibility).
    ShadowMapped,
    /// The method computes direct light itself (e.g. shadow rays) into the direct target.
    ByMethod,
}

/// What a method is, for the registry, validation, `describe_method` and the docs.
pub struct MethodInfo {
    pub name: &'static str,
    /// One line for `vsgl.describe_method` and `--help`.
    pub summary: &'static str,
    /// The keyword options it takes (besides the frame's `plan` and `aovs`), in groups: its own
    /// and the groups several methods share (`options::common::VISIBILITY_OPTIONS`, …), each
    /// declared once. [`Self::options`] lists them in order.
    pub option_groups: &'static [&'static [OptionSpec]],
    pub direct_light: DirectLight,
    /// Whether it makes the indirect AOVs (indirect, indirect_diffuse, indirect_specular).
    pub indirect: bool,
    /// AOVs only some methods make (e.g. `stderr`).
    pub extra_aovs: &'static [&'static str],
    /// A converged answer that other methods' error is measured against (`bench --reference`,
    /// the CLI's error line), not an estimate to be judged itself.
    pub ground_truth: bool,
    /// Whether it samples emissive triangles as area lights itself (`pathtrace`); else, where it
    /// takes `emitter_lights`, they light the scene as clusters of lights ([`Self::emitter_lighting`]).
    pub area_emitters: bool,
    /// Parses validated options into the method's typed settings, once. It may resolve a
    /// default that depends on other options in place ([`Options::resolve_default`]), so
    /// `frame.settings`, which the frame script makes from these options, shows what ran.
    pub configure: fn(&mut Options) -> Result<Box<dyn Method>>,
}

impl MethodInfo {
    /// Whether a frame of this method makes AOV `name` (one of `renderer::AOV_NAMES`).
    pub fn makes_aov(&self, name: &str) -> bool {
        match name {
            "indirect" | "indirect_diffuse" | "indirect_specular" => self.indirect,
            _ if OPTIONAL_AOVS.contains(&name) => self.extra_aovs.contains(&name),
            _ => true,
        }
    }

    /// How emissive surfaces light the scene in it: "area" (their triangles sampled as area
    /// lights), "clusters" (as `emitter_lights` lights with shadow and reflective shadow maps)
    /// or "none" (they only show).
    pub fn emitter_lighting(&self) -> &'static str {
        if self.area_emitters {
            "area"
        } else if self.takes("emitter_lights") {
            "clusters"
        } else {
            "none"
        }
    }

    /// Every option it takes, in declaration order.
    pub fn options(&self) -> impl Iterator<Item = &'static OptionSpec> {
        self.option_groups.iter().flat_map(|group| group.iter())
    }

    /// Whether it takes option `name`.
    pub fn takes(&self, name: &str) -> bool {
        self.options().any(|o| o.name == name)
    }

    /// Several lines: the summary, then each option with its allowed values and default.
    pub fn describe(&self) -> String {
        let mut s = format!("{}: {}", self.name, self.summary);
        if self.options().next().is_none() {
            s.push_str("\n  (no options)");
        }
        for o in self.options() {
            s.push_str(&format!("\n  {}={} ({}): {}", o.name, python_literal(&o.default), o.allowed(), o.help));
        }
        s
    }

    /// Validated options of a frame of this method (see [`Options::parse`]).
    pub fn parse_options(&self, given: &[(String, OptionValue)]) -> Result<Options> {
        let specs: Vec<&OptionSpec> = self.options().collect();
        Options::parse(self.name, &specs, given, &every_option_name())
    }
}

/// AOVs that only the methods listing them in `extra_aovs` make.
const OPTIONAL_AOVS: &[&str] = &["stderr"];

fn python_literal(v: &OptionValue) -> String {
    match v {
        OptionValue::Bool(true) => "True".into(),
        OptionValue::Bool(false) => "False".into(),
        OptionValue::Str(s) => format!("{s:?}"),
        v => v.display(),
    }
}

/// The method called `name`, or an error listing the valid ones.
pub fn info(name: &str) -> Result<&'static MethodInfo> {
    REGISTRY.iter().copied().find(|m| m.name == name).ok_or_else(|| {
        Error::invalid("method", format!("unknown method {name:?}; valid methods: {}", names().join(", ")))
    })
}

/// The method names, in registry order.
pub fn names() -> Vec<&'static str> {
    REGISTRY.iter().map(|m| m.name).collect()
}

/// Every option any method takes, once each, in first-declared order.
pub fn every_option_name() -> Vec<&'static str> {
    let mut all: Vec<&'static str> = Vec::new();
    for o in REGISTRY.iter().flat_map(|m| m.options()) {
        if !all.contains(&o.name) {
            all.push(o.name);
        }
    }
    all
}

/// Which methods make AOV `name`, in words ("every method but \"direct\"", "method=\"pathtrace\"").
pub fn aov_makers(name: &str) -> String {
    let makers: Vec<&str> = REGISTRY.iter().filter(|m| m.makes_aov(name)).map(|m| m.name).collect();
    let others: Vec<String> = REGISTRY.iter().filter(|m| !m.makes_aov(name)).map(|m| format!("{:?}", m.name)).collect();
    match (makers.len(), others.len()) {
        (_, 0) => "every method".into(),
        (m, o) if o < m => format!("every method but {}", others.join(", ")),
        _ => makers.iter().map(|m| format!("method={m:?}")).collect::<Vec<_>>().join(", "),
    }
}

/// One frame of a method, configured from its options.
pub trait Method: Send + Sync {
    /// Checks what depends on the adapter (limits, features) before anything is recorded.
    fn check(&self, _gpu: &Gpu) -> Result<()> {
        Ok(())
    }

    /// Records the method's passes: indirect light into `ctx.indirect` (and, for
    /// [`DirectLight::ByMethod`], direct light into `ctx.direct`), with a reason in
    /// `ctx.skipped` for each pass it leaves out.
    fn record(&self, ctx: &mut FrameContext<'_>) -> Result<()>;

    /// `frame.settings` rows beyond the method's options, or in place of one where what ran
    /// differs from what was asked (an "auto" resolved for the adapter). The frame script lists
    /// every option as [`MethodInfo::configure`] left it; most methods add nothing.
    fn settings(&self, _gpu: &Gpu) -> Result<Vec<(String, Setting)>> {
        Ok(Vec::new())
    }
}

/// The volumes of `method="lpv"` read back for `Frame.lpv`: (name, shape, data).
pub type CapturedLpv = Vec<(String, Vec<usize>, Vec<f32>)>;

/// The RSM of the first light, read back for `Frame.rsm`: side and (name, channels, data).
pub type CapturedRsm = (u32, Vec<(String, usize, Vec<f32>)>);

/// What the frame script hands a method, and what the method leaves for the readback.
pub struct FrameContext<'a> {
    pub gpu: &'a Gpu,
    /// Every pass, created on first use and kept by the renderer.
    pub passes: &'a PassCache,
    /// Where the method records its passes (device, encoder, timer).
    pub rec: Recorder<'a>,
    pub scene: &'a Scene,
    pub gpu_scene: &'a GpuScene,
    /// World position of the frame's origin (the camera); GPU positions are relative to it.
    pub origin: glam::DVec3,
    /// The scene's bounds diagonal: the length scale of every bias and clamp.
    pub extent: f64,
    pub features: ShaderFeatures,
    pub size: (u32, u32),
    pub frame_uniforms: &'a wgpu::Buffer,
    /// The frame's light sources: the scene's lights, then, in the methods that take
    /// `emitter_lights`, the clusters of its emissive triangles ([`crate::scene::EmitterLight`]).
    /// `lights` holds their GPU twins in the same order.
    pub light_sources: &'a [crate::scene::Light],
    /// The lights as the GPU sees them, and the storage buffer holding all of them.
    pub lights: &'a [LightRaw],
    pub light_buffer: &'a wgpu::Buffer,
    pub visibility: &'a VisibilityTargets,
    pub gbuffer: &'a GBuffer,
    pub direct: &'a wgpu::Buffer,
    pub indirect: &'a IndirectTargets,
    /// (pass or part, reason) for what the method leaves out.
    pub skipped: Vec<(String, String)>,
    /// The VSGLs of the first RSM that has any (`Frame.vsgls`: the first light's, or its first
    /// cube face's that reflects light).
    pub vsgls: Option<wgpu::Buffer>,
    pub captured_rsm: Option<CapturedRsm>,
    /// `capture_lpv`: the light propagation volumes.
    pub captured_lpv: Option<CapturedLpv>,
    /// The pyramid the current RSM view's virtual lights were drawn from when it is not the
    /// RSM's own (`importance="brsm"`), for `capture_rsm`'s "sampling_weight".
    pub sampling_pyramid: Option<wgpu::Buffer>,
    /// Per-pixel standard error (`stderr` AOV).
    pub stderr: Option<wgpu::Buffer>,
    /// Extra `frame.settings` rows the method learnt while recording.
    pub settings: Vec<(String, Setting)>,
    /// Asked between the GPU batches of long renders; an error stops the render.
    pub stop: Option<&'a crate::progress::StopCheck>,
    /// Kept from frame to frame (in the frame's readback slot) for the RSM powers that split
    /// the virtual-light budget over several lights or cube faces (`rsm_lights`).
    pub power_staging: &'a mut Option<wgpu::Buffer>,
    /// `plan="full"`: leave nothing out, even where a rule proves it unneeded.
    pub plan_full: bool,
    /// The Metropolis–Hastings chains of `sampling="metropolis"`, kept by the renderer.
    pub chains: &'a mut Option<metropolis::MetropolisChains>,
}

impl FrameContext<'_> {
    /// Submits what is recorded so far (long work is split so no submission trips a watchdog,
    /// and readbacks in the middle of a frame need it) and continues in a fresh encoder.
    pub fn submit_so_far(&mut self) -> wgpu::SubmissionIndex {
        self.rec.submit_so_far()
    }

    pub fn skip(&mut self, what: &str, why: impl Into<String>) {
        self.skipped.push((what.to_string(), why.into()));
    }
}

#[cfg(test)]
mod tests {
    use super::REGISTRY;

    /// Option groups are shared: a method that lists a group twice, or an option both alone and
    /// in a group, would take one name twice (and `Options::parse` would keep the first).
    #[test]
    fn no_method_takes_an_option_twice() {
        for method in REGISTRY {
            let names: Vec<&str> = method.options().map(|o| o.name).collect();
            for (i, name) in names.iter().enumerate() {
                assert!(!names[..i].contains(name), "{} takes {name:?} twice", method.name);
            }
        }
    }
}
