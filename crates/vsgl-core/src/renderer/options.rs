//! The settings of one render: the method, the frame's own options (`plan`, `aovs`) and the
//! method's keyword options, validated once against the method registry.

use crate::error::{Error, Result};
use crate::methods::options::ChoiceEnum;
use crate::methods::{self, MethodInfo, OptionValue, Options};
pub use crate::progress::{Progress, StopCheck};

/// Every AOV a frame can hold, in the order a frame lists them (and the kinds of
/// `wgsl/passes/aov_pack.wgsl`).
pub const AOV_NAMES: &[&str] = &["image", "indirect", "indirect_diffuse", "indirect_specular", "direct", "albedo", "normal", "depth", "stderr", "ldr"];

/// AOVs read back only when asked for by name (not by `aovs=None`): `ldr` is a display copy of
/// `image`, (H, W, 4) uint8 sRGB tone-mapped on the GPU as `Frame.save(".png")` does.
pub const ON_REQUEST_AOVS: &[&str] = &["ldr"];

crate::choice_names!(
    /// `plan=`: what a frame runs. `Auto` leaves out what the scene does not need (the passes,
    /// shader variants and targets of features no material or light has); `Full` runs every
    /// variant (for checking that leaving things out changes nothing).
    pub enum PlanMode { Auto => "auto", Full => "full" }
);

impl PlanMode {
    /// The mode called `text`, or an error naming `plan` and the choices.
    pub fn parse(text: &str) -> Result<Self> {
        Self::from_name(text).ok_or_else(|| Error::invalid("plan", format!("must be {}, got {text:?}", Self::NAMES.iter().map(|n| format!("{n:?}")).collect::<Vec<_>>().join(" or "))))
    }
}

/// Settings of one render (the keyword arguments of `Renderer.render`).
#[derive(Clone, Debug)]
pub struct RenderOptions {
    /// A name from [`methods::REGISTRY`].
    pub method: String,
    /// What the frame runs ([`PlanMode`]).
    pub plan: PlanMode,
    /// The AOVs to read back (names from [`AOV_NAMES`]); `None`: every AOV the method makes.
    /// Readback and the RGB conversion are most of a frame's wall time at high resolution, so
    /// a loop that only shows `image` should ask for it alone.
    pub aovs: Option<Vec<String>>,
    /// The method's keyword options as given (validated by [`RenderOptions::resolve`]).
    pub options: Vec<(String, OptionValue)>,
    /// Asked between the GPU batches of long renders (`pathtrace`, `reference`): an error
    /// stops the render there (Python: Ctrl-C raises `KeyboardInterrupt` within a batch).
    pub stop: Option<StopCheck>,
    /// The asked-for AOVs stay on the GPU, packed, for a presenter (the desktop window): no
    /// staging copy and no readback. [`super::SubmittedFrame::packed_aov`] says where each lies;
    /// the frame `finish` returns then holds no AOV.
    pub keep_on_gpu: bool,
}

impl Default for RenderOptions {
    fn default() -> Self {
        Self::new("direct")
    }
}

impl RenderOptions {
    pub fn new(method: &str) -> Self {
        Self { method: method.into(), plan: PlanMode::Auto, aovs: None, options: Vec::new(), stop: None, keep_on_gpu: false }
    }

    /// Sets one keyword option of the method (`RenderOptions::new("vsgl").set("num_lights", 64u32)`).
    pub fn set(mut self, name: &str, value: impl Into<OptionValue>) -> Self {
        self.options.retain(|(n, _)| n != name);
        self.options.push((name.into(), value.into()));
        self
    }

    /// The method and its validated options, after checking the frame's own settings.
    pub fn resolve(&self) -> Result<(&'static MethodInfo, Options)> {
        let info = methods::info(&self.method)?;
        for name in self.aovs.iter().flatten() {
            if !AOV_NAMES.contains(&name.as_str()) {
                return Err(Error::invalid("aovs", format!("unknown AOV {name:?}; valid: {}", AOV_NAMES.join(", "))));
            }
            if !info.makes_aov(name) {
                return Err(Error::invalid("aovs", format!("{name:?} is not made by method={:?}, only by {}", self.method, methods::aov_makers(name))));
            }
        }
        let options = info.parse_options(&self.options)?;
        Ok((info, options))
    }

    /// Whether the frame reads back AOV `name` (asked for, or all asked for and made).
    pub fn wants_aov(&self, info: &MethodInfo, name: &str) -> bool {
        let asked = match &self.aovs {
            Some(a) => a.iter().any(|n| n == name),
            None => !ON_REQUEST_AOVS.contains(&name),
        };
        info.makes_aov(name) && asked
    }
}

#[cfg(test)]
mod tests {
    use super::AOV_NAMES;
    use crate::shader_lib::constants::aov_pack as shader;

    /// `aov_pack.wgsl` numbers the AOV kinds as AOV_NAMES orders them, and packs them all.
    #[test]
    fn aov_kinds_are_the_shaders() {
        let kinds = [
            shader::AOV_IMAGE,
            shader::AOV_INDIRECT,
            shader::AOV_INDIRECT_DIFFUSE,
            shader::AOV_INDIRECT_SPECULAR,
            shader::AOV_DIRECT,
            shader::AOV_ALBEDO,
            shader::AOV_NORMAL,
            shader::AOV_DEPTH,
            shader::AOV_STDERR,
            shader::AOV_LDR,
        ];
        assert_eq!(kinds.len(), AOV_NAMES.len());
        for (i, kind) in kinds.iter().enumerate() {
            assert_eq!(*kind as usize, i, "{}", AOV_NAMES[i]);
        }
        assert_eq!(shader::MAX_ENTRIES as usize, AOV_NAMES.len());
    }
}
