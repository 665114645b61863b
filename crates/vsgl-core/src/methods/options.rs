//! Keyword options of the methods: each method declares the options it takes as
//! [`OptionSpec`]s (name, type, range, default, one line of help), and [`Options::parse`]
//! validates what a caller gave against them, once, in one place. An option the chosen method
//! does not take is an error that names it and lists what the method does take.

use crate::error::{Error, Result};
use crate::setting::Setting;
use std::borrow::Cow;

/// A value of a keyword option, as a caller gives it (Python int, float, bool or str).
#[derive(Clone, Debug, PartialEq)]
pub enum OptionValue {
    Int(i64),
    Float(f64),
    Bool(bool),
    Str(Cow<'static, str>),
}

impl OptionValue {
    /// The value as written in errors and `describe_method`.
    pub fn display(&self) -> String {
        match self {
            OptionValue::Int(v) => v.to_string(),
            OptionValue::Float(v) => v.to_string(),
            OptionValue::Bool(v) => v.to_string(),
            OptionValue::Str(v) => v.to_string(),
        }
    }

    fn type_name(&self) -> &'static str {
        match self {
            OptionValue::Int(_) => "an integer",
            OptionValue::Float(_) => "a float",
            OptionValue::Bool(_) => "a bool",
            OptionValue::Str(_) => "a string",
        }
    }
}

impl From<&OptionValue> for Setting {
    fn from(v: &OptionValue) -> Self {
        match v {
            OptionValue::Int(v) => Setting::Int(*v),
            OptionValue::Float(v) => Setting::Float(*v),
            OptionValue::Bool(v) => Setting::Bool(*v),
            OptionValue::Str(v) => Setting::Text(v.clone()),
        }
    }
}

impl From<i64> for OptionValue {
    fn from(v: i64) -> Self {
        OptionValue::Int(v)
    }
}
impl From<u32> for OptionValue {
    fn from(v: u32) -> Self {
        OptionValue::Int(v as i64)
    }
}
impl From<f64> for OptionValue {
    fn from(v: f64) -> Self {
        OptionValue::Float(v)
    }
}
impl From<bool> for OptionValue {
    fn from(v: bool) -> Self {
        OptionValue::Bool(v)
    }
}
impl From<&'static str> for OptionValue {
    fn from(v: &'static str) -> Self {
        OptionValue::Str(Cow::Borrowed(v))
    }
}
impl From<String> for OptionValue {
    fn from(v: String) -> Self {
        OptionValue::Str(Cow::Owned(v))
    }
}

/// The type and the allowed values of an option.
#[derive(Clone, Copy, Debug)]
pub enum OptionKind {
    /// An integer in `min..=max`, a power of two when `power_of_two`.
    Int { min: i64, max: i64, power_of_two: bool },
    /// A finite float `> min` (`min_exclusive`) or `>= min`.
    Float { min: f64, min_exclusive: bool },
    Bool,
    /// One of these strings.
    Choice(&'static [&'static str]),
}

/// One keyword option of a method.
#[derive(Clone, Debug)]
pub struct OptionSpec {
    pub name: &'static str,
    pub kind: OptionKind,
    pub default: OptionValue,
    /// One line for `describe_method` and the docstrings.
    pub help: &'static str,
    /// Said after a rejected value (e.g. which values are planned).
    pub note: &'static str,
}

impl OptionSpec {
    /// The allowed values in words, as error messages and `describe_method` give them.
    pub fn allowed(&self) -> String {
        match self.kind {
            OptionKind::Int { min, max, power_of_two: false } => format!("in {min}..={max}"),
            OptionKind::Int { min, max, power_of_two: true } => format!("a power of two in {min}..={max}"),
            OptionKind::Float { min, min_exclusive: true } => format!("finite and > {min}"),
            OptionKind::Float { min, min_exclusive: false } => format!("finite and >= {min}"),
            OptionKind::Bool => "True or False".into(),
            OptionKind::Choice(c) => match c {
                [one] => format!("{one:?}"),
                _ => format!("one of {}", c.iter().map(|s| format!("{s:?}")).collect::<Vec<_>>().join(", ")),
            },
        }
    }

    /// `value` converted to this option's type and checked against its range.
    fn check(&self, value: &OptionValue) -> Result<OptionValue> {
        let bad = |got: String| {
            let note = if self.note.is_empty() { String::new() } else { format!(" ({})", self.note) };
            Error::invalid(self.name, format!("must be {}{note}, got {got}", self.allowed()))
        };
        let wrong_type = || Error::invalid(self.name, format!("must be {}, got {} ({})", self.allowed(), value.type_name(), value.display()));
        match (self.kind, value) {
            (OptionKind::Int { min, max, power_of_two }, OptionValue::Int(v)) => {
                if (min..=max).contains(v) && (!power_of_two || (*v as u64).is_power_of_two()) {
                    Ok(OptionValue::Int(*v))
                } else {
                    Err(bad(v.to_string()))
                }
            }
            (OptionKind::Float { min, min_exclusive }, OptionValue::Float(_) | OptionValue::Int(_)) => {
                let v = match value {
                    OptionValue::Float(f) => *f,
                    OptionValue::Int(i) => *i as f64,
                    _ => unreachable!("matched above"),
                };
                let above = if min_exclusive { v > min } else { v >= min };
                if v.is_finite() && above { Ok(OptionValue::Float(v)) } else { Err(bad(v.to_string())) }
            }
            (OptionKind::Bool, OptionValue::Bool(b)) => Ok(OptionValue::Bool(*b)),
            (OptionKind::Choice(choices), OptionValue::Str(s)) => {
                if choices.contains(&s.as_ref()) { Ok(value.clone()) } else { Err(bad(format!("{s:?}"))) }
            }
            _ => Err(wrong_type()),
        }
    }
}

/// A method's options after validation: every option it takes, given or defaulted.
#[derive(Clone, Debug)]
pub struct Options {
    values: Vec<(&'static str, OptionValue)>,
    /// The names the caller gave (the rest took their defaults).
    given: Vec<&'static str>,
}

impl Options {
    /// Validates `given` against `specs` (the options of `method`): unknown names, types and
    /// ranges; options not given take their defaults. `every_option` is the union over all
    /// methods, so an option of another method is named as such.
    pub fn parse(method: &str, specs: &[&OptionSpec], given: &[(String, OptionValue)], every_option: &[&str]) -> Result<Self> {
        for (name, _) in given {
            if !specs.iter().any(|s| s.name == name) {
                let takes: Vec<&str> = specs.iter().map(|s| s.name).collect();
                let takes = if takes.is_empty() { "no options".to_string() } else { format!("only {}", takes.join(", ")) };
                let what = if every_option.contains(&name.as_str()) { "is not an option of" } else { "is no option of any method, nor of" };
                return Err(Error::invalid(name.clone(), format!("{name:?} {what} method={method:?}, which takes {takes}")));
            }
            if given.iter().filter(|(n, _)| n == name).count() > 1 {
                return Err(Error::invalid(name.clone(), "given more than once"));
            }
        }
        let mut values = Vec::with_capacity(specs.len());
        let mut names = Vec::new();
        for spec in specs {
            let value = match given.iter().find(|(n, _)| n == spec.name) {
                Some((_, v)) => {
                    names.push(spec.name);
                    spec.check(v)?
                }
                None => spec.default.clone(),
            };
            values.push((spec.name, value));
        }
        Ok(Self { values, given: names })
    }

    /// Whether the caller gave `name` (false: it has its default).
    pub fn was_given(&self, name: &str) -> bool {
        self.given.iter().any(|n| *n == name)
    }

    /// Replaces the default of an option the caller did not give by one that depends on other
    /// options (e.g. the RSM side that grows with num_lights), so `frame.settings` shows the
    /// value used. A given value is kept.
    pub fn resolve_default(&mut self, name: &str, value: OptionValue) {
        if self.was_given(name) {
            return;
        }
        if let Some((_, v)) = self.values.iter_mut().find(|(n, _)| *n == name) {
            *v = value;
        }
    }

    fn get(&self, name: &str) -> Result<&OptionValue> {
        self.values
            .iter()
            .find(|(n, _)| *n == name)
            .map(|(_, v)| v)
            .ok_or_else(|| Error::invalid(name.to_string(), "is not an option of this method (a method read an option it does not declare)"))
    }

    pub fn u32(&self, name: &str) -> Result<u32> {
        match self.get(name)? {
            OptionValue::Int(v) => u32::try_from(*v).map_err(|_| Error::invalid(name.to_string(), format!("does not fit 32 bits: {v}"))),
            v => Err(Error::invalid(name.to_string(), format!("expected an integer, got {}", v.display()))),
        }
    }

    pub fn f32(&self, name: &str) -> Result<f32> {
        match self.get(name)? {
            OptionValue::Float(v) => Ok(*v as f32),
            OptionValue::Int(v) => Ok(*v as f32),
            v => Err(Error::invalid(name.to_string(), format!("expected a float, got {}", v.display()))),
        }
    }

    pub fn bool(&self, name: &str) -> Result<bool> {
        match self.get(name)? {
            OptionValue::Bool(v) => Ok(*v),
            v => Err(Error::invalid(name.to_string(), format!("expected a bool, got {}", v.display()))),
        }
    }

    /// A choice option as its enum. Parse checked the string against the option's `Choice`
    /// list; an option declared with another list than `T::NAMES` is an error here, naming it.
    pub fn choice<T: ChoiceEnum>(&self, name: &str) -> Result<T> {
        let text = self.str(name)?;
        T::from_name(text).ok_or_else(|| Error::invalid(name.to_string(), format!("must be one of {:?}, got {text:?}", T::NAMES)))
    }

    pub fn str(&self, name: &str) -> Result<&str> {
        match self.get(name)? {
            OptionValue::Str(v) => Ok(v.as_ref()),
            v => Err(Error::invalid(name.to_string(), format!("expected a string, got {}", v.display()))),
        }
    }

    /// (name, value) as `frame.settings` shows them, in declaration order.
    pub fn rows(&self) -> Vec<(String, Setting)> {
        self.values.iter().map(|(n, v)| (n.to_string(), v.into())).collect()
    }
}

/// A choice option's values as a Rust enum: each variant and its string are declared once, by
/// [`choice_names!`](crate::choice_names), which makes the option's `Choice` list ([`NAMES`](Self::NAMES))
/// and the name of each variant from that one list. The name is an exhaustive `match`, so a
/// variant without a string does not compile, and [`Options::choice`] parses through `NAMES`, so
/// a string is a variant or an error naming the option: no `_ =>` can hand a new string a
/// default.
pub trait ChoiceEnum: Copy + PartialEq + 'static {
    /// The option's strings, in the order `describe_method` and errors list them.
    const NAMES: &'static [&'static str];
    /// The variants, in the order of `NAMES`.
    const VALUES: &'static [Self];
    /// The option's string for this variant.
    fn name(self) -> &'static str;
    /// The variant of `text`, if it is one of `NAMES`.
    fn from_name(text: &str) -> Option<Self> {
        Self::NAMES.iter().position(|n| *n == text).map(|i| Self::VALUES[i])
    }
}

/// Declares an enum's option strings: `choice_names!(Kernel { Integral => "integral", … })`
/// implements [`ChoiceEnum`](crate::methods::options::ChoiceEnum) for an enum declared
/// elsewhere; `choice_names!(#[doc] pub enum NearField { Texels => "texels", … })` declares the
/// enum too (Clone, Copy, Debug, PartialEq, Eq).
#[macro_export]
macro_rules! choice_names {
    ($(#[$meta:meta])* $vis:vis enum $ty:ident { $($variant:ident => $text:literal),+ $(,)? }) => {
        $(#[$meta])*
        #[derive(Clone, Copy, Debug, PartialEq, Eq)]
        $vis enum $ty {
            $($variant),+
        }
        $crate::choice_names!($ty { $($variant => $text),+ });
    };
    ($ty:ident { $($variant:ident => $text:literal),+ $(,)? }) => {
        impl $crate::methods::options::ChoiceEnum for $ty {
            const NAMES: &'static [&'static str] = &[$($text),+];
            const VALUES: &'static [Self] = &[$($ty::$variant),+];
            fn name(self) -> &'static str {
                match self {
                    $($ty::$variant => $text),+
                }
            }
        }
    };
}

/// Options that several methods take, defined once so a name means the same everywhere.
pub mod common {
    use super::super::choices::{DenoiseForm, ImportanceChoice, VisibilityChoice};
    use super::{ChoiceEnum, OptionKind, OptionSpec, OptionValue};
    use crate::frame::uniforms::RsmFit;
    use crate::methods::metropolis::ChainSpace;
    use crate::passes::vpl_sample::Sampling;
    use crate::methods::sg_lighting::BlendDiffuse;
    use crate::passes::vsgl_shading::{DiffuseMode, LambertLobe, LightingMode};
    use std::borrow::Cow;

    const fn int(name: &'static str, min: i64, max: i64, default: i64, help: &'static str) -> OptionSpec {
        OptionSpec { name, kind: OptionKind::Int { min, max, power_of_two: false }, default: OptionValue::Int(default), help, note: "" }
    }
    /// A choice option whose default is its first choice.
    pub const fn choice(name: &'static str, choices: &'static [&'static str], help: &'static str) -> OptionSpec {
        OptionSpec { name, kind: OptionKind::Choice(choices), default: OptionValue::Str(Cow::Borrowed(choices[0])), help, note: "" }
    }

    pub const SHADOW_SIZE: OptionSpec = int("shadow_size", 16, 8192, 1024, "side of each light's shadow map in texels");
    /// How many lights the emissive surfaces become in the methods that light with lights'
    /// shadow and reflective shadow maps (`upload/emitters.rs`, `emitter_lights`). Default 1, a
    /// point light's cost (experiments/emitter_cost.md): on the shared CornellBox lit by its
    /// ceiling its direct light is 1.004 of the path tracer's (4 lights: 1.001, with softer
    /// shadows: block error 0.024 → 0.0075, at four times the cost).
    pub const EMITTER_LIGHTS: OptionSpec = int(
        "emitter_lights",
        1,
        64,
        1,
        "lights the emissive surfaces become (clusters of emissive triangles, each with a point light's cube of shadow and reflective shadow maps and a cosine lobe, its direct light summed over 64 points of its area; at least one per normal direction that emits; more give softer shadows); ignored without emissive surfaces",
    );
    /// The virtual-light budget; the default differs by method: 1024 VSGLs, the papers' own
    /// setting (with 8×8 interleaving, 16 per pixel), chosen on the real-scene corpus
    /// (experiments/vsgl_defaults_on_the_corpus.md); 256 VPLs, `vpl`'s default since it
    /// was built (each pixel shades all of them).
    pub const fn num_lights(default: i64) -> OptionSpec {
        int("num_lights", 1, 1 << 20, default, "virtual lights in all: one light's whole budget, or with several lights or a point light's cube faces, split by the power each reflects")
    }
    /// The RSM side of the methods that build mip pyramids over it (a power of two).
    pub const RSM_SIZE: OptionSpec = OptionSpec {
        name: "rsm_size",
        kind: OptionKind::Int { min: 32, max: 4096, power_of_two: true },
        default: OptionValue::Int(256),
        help: "side of each light's reflective shadow map in texels",
        note: "",
    };

    /// The RSM side `vpl` and `vsgl` use when `rsm_size` is not given: at least
    /// four texels per virtual light, so clusters keep several texels and quadtree-node VSGLs
    /// (`kernel="node"`) reach single texels only where the light is concentrated:
    /// max(256, 2^⌈log2(2√N)⌉), at most 1024 (whose six moment chains take 134 MB). 256 up to
    /// N = 16384, 512 up to 65536, 1024 beyond.
    pub fn rsm_size_for(num_lights: u32) -> u32 {
        let side = (2.0 * (num_lights as f64).sqrt()).ceil() as u32;
        side.next_power_of_two().clamp(256, 1024)
    }
    pub const SAMPLING: OptionSpec = choice(
        "sampling",
        Sampling::NAMES,
        "how RSM texels are drawn: hierarchical warping of a stratified lattice or of independent random numbers, or \"metropolis\": Markov chains kept across the frames of a Renderer, one Metropolis-Hastings step per frame (temporally coherent)",
    );
    pub const CHAIN_SPACE: OptionSpec = choice(
        "chain_space",
        ChainSpace::NAMES,
        "with sampling=\"metropolis\", where a chain's state lives between frames: \"world\" (the surface point, reprojected into each frame's RSM: it stays put when the light moves, and restarts when it leaves the light's view or its surface) or \"rsm\" (the RSM position: it moves with the light's view)",
    );
    pub const SEED: OptionSpec = int("seed", 0, u32::MAX as i64, 0, "seed of the random numbers (same seed, same image)");
    pub const VPL_CLAMP: OptionSpec = OptionSpec {
        name: "vpl_clamp",
        kind: OptionKind::Float { min: 0.0, min_exclusive: false },
        default: OptionValue::Float(0.0),
        help: "lower bound of the VPL distance as a fraction of the scene's bounds diagonal (0 = unbiased)",
        note: "",
    };
    pub const VISIBILITY: OptionSpec = OptionSpec {
        name: "visibility",
        kind: OptionKind::Choice(VisibilityChoice::NAMES),
        default: OptionValue::Str(Cow::Borrowed("none")),
        help: "visibility of virtual lights: \"none\" (unshadowed, the papers' accuracy setting), \"ism\" (an imperfect shadow map per virtual light, splatted from the scene's point set, as the papers do) or \"raytrace\" (a shadow ray per pixel and virtual light through the scene's BVH; to the mean position of a VSGL)",
        note: "",
    };
    /// Imperfect shadow maps (`visibility="ism"`; docs/methods/visibility.md, "Visibility of virtual
    /// lights"). The papers' 64² maps and 8192 points per map are the defaults.
    pub const ISM_SIZE: OptionSpec = OptionSpec {
        name: "ism_size",
        kind: OptionKind::Int { min: 8, max: 256, power_of_two: true },
        default: OptionValue::Int(64),
        help: "side of each virtual light's imperfect shadow map (octahedral, the whole sphere) with visibility=\"ism\"",
        note: "",
    };
    pub const ISM_POINTS: OptionSpec = int("ism_points", 1024, 1 << 22, 65536, "points of the scene's point set for imperfect shadow maps (spread over the triangles by area; each map splats a subset)");
    pub const ISM_POINTS_PER_MAP: OptionSpec = int("ism_points_per_map", 64, 1 << 20, 8192, "points each imperfect shadow map splats (at most ism_points)");
    pub const ISM_BIAS: OptionSpec = OptionSpec {
        name: "ism_bias",
        kind: OptionKind::Float { min: 0.0, min_exclusive: false },
        default: OptionValue::Float(0.08),
        help: "depth bias of the imperfect shadow map test as a fraction of the receiver's distance to the virtual light (the receiver is also lifted off its surface by 1.5 texels' width)",
        note: "",
    };
    pub const ISM_PCF: OptionSpec = int("ism_pcf", 0, 2, 0, "percentage-closer filter radius of the imperfect shadow map lookup in texels (0: one texel; 1: 3×3, softer and a few % darker where nothing occludes)");
    /// Bidirectional RSM importance (docs/methods/brsm.md, "Bidirectional RSM
    /// importance"): the RSM's sampling density from the camera's view.
    pub const IMPORTANCE: OptionSpec = OptionSpec {
        name: "importance",
        kind: OptionKind::Choice(ImportanceChoice::NAMES),
        default: OptionValue::Str(Cow::Borrowed("rsm")),
        help: "sampling density of RSM texels: \"rsm\" (reflected power Φ·(R_d + R_s), the papers' default) or \"brsm\" (bidirectional: that power times the texel's importance to the view, estimated with importance_lights VSGLs of the camera's G-buffer, mixed with 1/11 of the \"rsm\" density; unbiased for vpl)",
        note: "",
    };
    /// Interleaved importance map (docs/methods/brsm.md, "Bidirectional RSM importance"): RSM
    /// texel (x, y) evaluates only the view VSGLs of its class, as `interleave` does for pixels.
    /// Default 4: on lavapipe it cut brsm's extra cost 13× and kept its error gain (measured in
    /// the docs).
    pub const IMPORTANCE_INTERLEAVE: OptionSpec = int("importance_interleave", 1, 16, 4, "with importance=\"brsm\", the interleave tile side k of the importance map: RSM texel (x, y) evaluates only the view VSGLs j ≡ (y mod k)·k + (x mod k) (mod k²), scaled by k², the classes then recombined by a k×k box filter (k² times cheaper; 1: every view VSGL at every texel; default 4, docs/methods/brsm.md)");
    pub const IMPORTANCE_LIGHTS: OptionSpec = int("importance_lights", 1, 65536, 2048, "VSGLs of the camera's view that estimate each RSM texel's importance with importance=\"brsm\" (the 2016 paper: 2048, the 2015 paper: 4096)");
    /// How a spot light's RSM frames the scene (docs/methods/rsm.md, "Fitting a spot light's RSM
    /// to the scene"): "scene" since 2026-12-02, "cone" the frame before it, bit for bit.
    pub const RSM_FIT: OptionSpec = choice(
        "rsm_fit",
        RsmFit::NAMES,
        "what a spot light's reflective shadow map covers: \"scene\" (the narrowest square frustum that holds the scene's bounds and no more than the cone, so its texels land on geometry) or \"cone\" (the whole outer cone, as the papers do; point and directional lights are not fitted)",
    );
    pub const CAPTURE_RSM: OptionSpec = OptionSpec {
        name: "capture_rsm",
        kind: OptionKind::Bool,
        default: OptionValue::Bool(false),
        help: "keep the first light's RSM for Frame.rsm(name)",
        note: "",
    };
    /// How the emitter lights' direct light is shaded (docs/scenes.md, "Emission";
    /// `methods/emitter_direct.rs`): their 64-point sum shadowed by the cluster's cube, or each
    /// point as a VSGL shaded with the SG lighting and shadowed by `visibility`.
    pub const EMITTER_DIRECT: OptionSpec = choice(
        "emitter_direct",
        &["points", "sg"],
        "direct light of emissive surfaces: \"points\" (each emitter light's 64 points summed, shadowed by its cube of shadow maps as seen from its centre: hard shadows) or \"sg\" (each point a VSGL of its patch's area and spread, shaded with the SG lighting and shadowed by the method's visibility, \"raytrace\" or \"ism\": penumbrae); ignored without emissive surfaces",
    );
    /// The option groups several methods take, each declared once here and parsed once into a
    /// typed value: visibility of virtual lights (`VisibilityMode::from_options`)…
    pub const VISIBILITY_OPTIONS: &[OptionSpec] = &[VISIBILITY, ISM_SIZE, ISM_POINTS, ISM_POINTS_PER_MAP, ISM_BIAS, ISM_PCF, EMITTER_DIRECT];
    /// …how RSM texels are drawn (`TexelSampling::from_options`)…
    pub const SAMPLING_OPTIONS: &[OptionSpec] = &[SAMPLING, CHAIN_SPACE, SEED];
    /// …the RSM's sampling density (`Importance::from_options`)…
    pub const IMPORTANCE_OPTIONS: &[OptionSpec] = &[IMPORTANCE, IMPORTANCE_LIGHTS, IMPORTANCE_INTERLEAVE];
    /// …the interleaved shading's filter (`InterleaveSettings::from_options`, with the method's
    /// own `interleave`)…
    pub const DENOISE_OPTIONS: &[OptionSpec] = &[DENOISE, DENOISE_FORM];
    /// …and the RSM's frame and readback (`RsmSettings::from_options`, with the method's own
    /// `rsm_size`).
    pub const RSM_OPTIONS: &[OptionSpec] = &[RSM_FIT, CAPTURE_RSM];

    /// The largest interleave tile side: the denoiser's (its workgroup span holds 2·this taps).
    pub const INTERLEAVE_MAX: i64 = crate::passes::denoise::MAX_RADIUS as i64;
    /// Interleaved sampling (`wgsl/common/interleave.wgsl`); the default differs by method
    /// (8 for VSGLs as in the papers, 1 for VPLs so `vpl` stays the every-pixel baseline).
    pub const fn interleave(default: i64) -> OptionSpec {
        int("interleave", 1, INTERLEAVE_MAX, default, "interleaved sampling tile side k: each pixel evaluates num_lights/k² virtual lights")
    }
    pub const DENOISE: OptionSpec = OptionSpec {
        name: "denoise",
        kind: OptionKind::Bool,
        default: OptionValue::Bool(true),
        help: "run the geometry-aware filter after interleaved shading",
        note: "",
    };
    // "gather" with symmetric weights (docs/methods/vsgl.md, "A denoiser that keeps the light"):
    // the gather before 2026-12-02, whose weights were the centre's alone, took 27% of
    // FlightHelmet's diffuse light out of the box (seed 0), this one 5%, "exchange" none, at a
    // block error 3-20% higher on the corpus.
    pub const DENOISE_FORM: OptionSpec = choice(
        "denoise_form",
        DenoiseForm::NAMES,
        "how the filter averages: \"gather\" (each pixel the normalised average of its taps, by weights symmetric in the pair) or \"exchange\" (each pixel trades light with its taps, so the image keeps its total light per channel exactly; noisier where the taps stop, at creases and silhouettes)",
    );
    pub const DIFFUSE: OptionSpec = choice(
        "diffuse",
        DiffuseMode::NAMES,
        "diffuse SG shading: the papers' clamped form, the unclamped SG-cosine product, or an SG product",
    );
    /// Normalization and shape of the Lambert lobe's SG (docs/methods/vsgl.md, "VSGLs": the
    /// hemisphere gain, and "The real-scene corpus" for the default).
    pub const LAMBERT_LOBE: OptionSpec = choice(
        "lambert_lobe",
        LambertLobe::NAMES,
        "each cluster's Lambert lobe: \"exact_compact\" (the default: the hemisphere-normalized SG blended with an exact Lambertian point emitter where the cluster is compact as seen from the receiver; closer to the reference on every corpus scene and built-in, worse where a wide lit floor lights a wall at grazing angles), \"hemisphere\" (the SG normalized over each texel's hemisphere, so all its diffuse power reaches where a Lambertian texel can light; the default until 2026-12-01) or \"papers\" (normalized over the sphere: 9.2% of it lies below the texel and is lost)",
    );
    /// The cluster's tangent-plane fade for the papers' diffuse form too (docs/methods/vsgl.md,
    /// "The cluster's tangent plane"); the other diffuse forms always fade. The default differs
    /// by method: a VSGL of `vsgl` is one cluster, `vsgl2`'s plane spans the whole RSM.
    pub const fn plane_fade(default: bool) -> OptionSpec {
        OptionSpec {
            name: "plane_fade",
            kind: OptionKind::Bool,
            default: OptionValue::Bool(default),
            help: "with diffuse=\"papers\", also fade each VSGL's diffuse light out below its cluster's mean tangent plane, as the \"accurate\" and \"sg_product\" forms always do (False: the papers' formula, whose SG product lights the back of a lit surface and the surface itself next to a light)",
            note: "",
        }
    }
    /// SG lighting forms (docs/methods/vsgl.md, "SG lighting"): the papers' (ASG specular, `diffuse=`),
    /// the accurate ones (filtered-NDF specular and the clamped-cosine diffuse), or the blend of
    /// the two specular forms (with the clamped-cosine diffuse). The default differs by method:
    /// `vsgl`'s is "blend", chosen on the real-scene corpus and the built-ins (docs/methods/vsgl.md,
    /// "The real-scene corpus"); `vsgl2` keeps the papers'.
    pub const fn lighting(default: &'static str, blend: BlendDiffuse) -> OptionSpec {
        OptionSpec {
            name: "lighting",
            kind: OptionKind::Choice(LightingMode::NAMES),
            default: OptionValue::Str(Cow::Borrowed(default)),
            help: match blend {
                BlendDiffuse::ClampedCosine => "SG lighting: \"asg\" (the papers' SG–ASG specular, diffuse as diffuse= says), \"accurate\" (GGX with its NDF widened by the light's spread, after Tokuyoshi et al. 2024, and the clamped-cosine diffuse) or \"blend\" (the two specular forms weighted by the receiver's share α/α' of the widened lobe: accurate for lights narrower than the lobe, the papers' for broad lights on sharp receivers; the clamped-cosine diffuse)",
                BlendDiffuse::AsDiffuseSays => "SG lighting: \"asg\" (the papers' SG–ASG specular), \"accurate\" (GGX with its NDF widened by the light's spread, after Tokuyoshi et al. 2024, and the clamped-cosine diffuse) or \"blend\" (the two specular forms weighted by the receiver's share α/α' of the widened lobe: accurate for lights narrower than the lobe, the papers' for broad lights on sharp receivers); with \"asg\" and \"blend\" diffuse as diffuse= says",
            },
            note: "",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::common::rsm_size_for;

    /// At least four texels per virtual light up to the cap, never below the old default.
    #[test]
    fn rsm_size_grows_with_num_lights() {
        assert_eq!(rsm_size_for(1), 256);
        assert_eq!(rsm_size_for(16384), 256);
        assert_eq!(rsm_size_for(16385), 512);
        assert_eq!(rsm_size_for(65536), 512);
        assert_eq!(rsm_size_for(65537), 1024);
        assert_eq!(rsm_size_for(1 << 20), 1024);
        for n in [1u32, 7, 256, 4096, 20000, 65536, 262144] {
            let side = rsm_size_for(n) as u64;
            assert!(side * side >= 4 * n as u64 || side == 1024, "{n}: {side}");
        }
    }
}
