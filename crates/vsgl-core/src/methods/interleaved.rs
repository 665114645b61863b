//! Interleaved shading and its filter, shared by `vpl` and `vsgl` (the papers compare both with
//! 8×8 interleaving [Tok15 §5]): with interleave k > 1 and denoise on, the shading passes write
//! noisy targets that the geometry-aware filter resolves into the frame's indirect targets.

use super::FrameContext;
use crate::error::Result;
use crate::frame::IndirectTargets;
use crate::passes::denoise::{DenoisePass, DenoiseScreen};

/// `interleave`, `denoise` and `denoise_form` (`options::common::DENOISE_OPTIONS` and the
/// method's own `interleave`), parsed once.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct InterleaveSettings {
    pub interleave: u32,
    pub denoise: bool,
    /// `denoise_form="exchange"`: the filter keeps the image's total light.
    pub keep_light: bool,
}

impl InterleaveSettings {
    pub fn from_options(o: &super::Options) -> Result<Self> {
        let keep_light = o.choice::<super::choices::DenoiseForm>("denoise_form")? == super::choices::DenoiseForm::Exchange;
        Ok(Self { interleave: o.u32("interleave")?, denoise: o.bool("denoise")?, keep_light })
    }
}

/// Where a method's shading writes, and whether the filter runs after it.
pub struct InterleavedShading {
    pub interleave: u32,
    pub denoise: bool,
    /// `denoise_form="exchange"`: the filter keeps the image's total light.
    pub keep_light: bool,
    /// The shading's targets when filtered (else placeholders of 16 bytes, so the bind group
    /// layouts of every variant stay the same).
    noisy: IndirectTargets,
}

impl InterleavedShading {
    /// Takes the noisy targets the frame needs (placeholders when it shades straight into the
    /// indirect targets).
    pub fn new(ctx: &mut FrameContext<'_>, settings: InterleaveSettings) -> Self {
        let InterleaveSettings { interleave, denoise, keep_light } = settings;
        let filtered = interleave > 1 && denoise;
        let pixel_bytes = ctx.size.0 as u64 * ctx.size.1 as u64 * 16;
        // Without specular materials the specular targets are never written.
        let specular_bytes = if ctx.features.specular { pixel_bytes } else { 16 };
        let noisy = IndirectTargets {
            diffuse: ctx.rec.storage("indirect_noisy_diffuse_buffer", if filtered { pixel_bytes } else { 16 }),
            specular: ctx.rec.storage("indirect_noisy_specular_buffer", if filtered { specular_bytes } else { 16 }),
        };
        Self { interleave, denoise, keep_light, noisy }
    }

    /// Interleaved shading goes into a noisy target that the filter resolves.
    pub fn filtered(&self) -> bool {
        self.interleave > 1 && self.denoise
    }

    /// The targets the shading passes add into.
    pub fn target<'t>(&'t self, indirect: &'t IndirectTargets) -> &'t IndirectTargets {
        if self.filtered() { &self.noisy } else { indirect }
    }

    /// Runs the filter, or notes why it is left out.
    pub fn resolve(&self, ctx: &mut FrameContext<'_>) -> Result<()> {
        if self.filtered() {
            let denoise = ctx.passes.get::<DenoisePass>()?;
            let screen = DenoiseScreen { frame: ctx.frame_uniforms, gbuffer: ctx.gbuffer, features: ctx.features, size: ctx.size };
            denoise.record(&mut ctx.rec, &screen, self.interleave, self.keep_light, &self.noisy, ctx.indirect);
        } else if self.interleave == 1 {
            ctx.skip("denoise", "interleave=1: every pixel evaluates every virtual light");
        } else {
            ctx.skip("denoise", "denoise=False");
        }
        Ok(())
    }
}
