//! The SG lighting options the VSGL methods (`vsgl`, `vsgl2`) share: `lighting=`, `diffuse=`
//! and `plane_fade=`, read and checked against each other once, here.

use super::options::{ChoiceEnum, OptionValue, Options};
use crate::error::{Error, Result};
use crate::passes::vsgl_shading::{DiffuseMode, LambertLobe, LightingMode, VsglShadingForm};

/// Which diffuse form `lighting="blend"` shades by, a property of the method.
/// `lighting="accurate"` always brings the clamped cosine.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BlendDiffuse {
    /// The clamped-cosine integral (`diffuse="accurate"`), which fades below each VSGL's tangent
    /// plane: `vsgl`, whose VSGL is one cluster with one plane.
    ClampedCosine,
    /// The form `diffuse=` names: `vsgl2`, whose one diffuse VSGL spans the whole RSM, so that
    /// fading by its one plane removes most of the light (FlightHelmet's diffuse 0.24 -> 0.01 of
    /// the reference; docs/methods/vsgl2.md, "Two VSGLs").
    AsDiffuseSays,
}

/// Whether `lighting` shades diffuse by the clamped cosine whatever `diffuse=` says.
fn brings_clamped_cosine_diffuse(lighting: LightingMode, blend: BlendDiffuse) -> bool {
    match lighting {
        LightingMode::Asg => false,
        LightingMode::Accurate => true,
        LightingMode::Blend => blend == BlendDiffuse::ClampedCosine,
    }
}

/// `diffuse=` as the shading pass takes it. `lighting="accurate"` (and `"blend"` where the
/// method says so) brings its own diffuse form (the clamped cosine, `diffuse="accurate"`);
/// another one given with it is an error rather than silently replaced.
pub(super) fn diffuse_mode(o: &Options, blend: BlendDiffuse) -> Result<DiffuseMode> {
    let lighting = lighting_mode(o)?;
    let diffuse: DiffuseMode = o.choice("diffuse")?;
    if brings_clamped_cosine_diffuse(lighting, blend) {
        if o.was_given("diffuse") && diffuse != DiffuseMode::Accurate {
            let (diffuse, name) = (diffuse.name(), lighting.name());
            return Err(Error::invalid(
                "diffuse",
                format!("diffuse={diffuse:?} is a form of lighting=\"asg\"; lighting={name:?}{} shades diffuse by the clamped-cosine integral (diffuse=\"accurate\"): give lighting=\"asg\" with it, or leave diffuse out", lighting_default_note(o)),
            ));
        }
        return Ok(DiffuseMode::Accurate);
    }
    Ok(diffuse)
}

/// The options with `diffuse` resolved to the form `lighting` brings when it was left out, so
/// `frame.settings` shows the diffuse form the frame used (it had shown "papers" under
/// `lighting="accurate"`, which shades the clamped cosine), and `plane_fade` to True for the
/// forms that always fade.
pub(super) fn resolve_diffuse_form(o: &mut Options, blend: BlendDiffuse) -> Result<()> {
    if brings_clamped_cosine_diffuse(lighting_mode(o)?, blend) {
        o.resolve_default("diffuse", OptionValue::Str("accurate".into()));
    }
    if diffuse_mode(o, blend)?.fades_below_tangent_plane() {
        o.resolve_default("plane_fade", OptionValue::Bool(true));
    }
    Ok(())
}

/// `diffuse`, `lighting`, `lambert_lobe` and `plane_fade` of a VSGL method, resolved
/// ([`resolve_diffuse_form`]) and checked against each other once.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct SgLighting {
    pub diffuse: DiffuseMode,
    pub lighting: LightingMode,
    pub lambert_lobe: LambertLobe,
    /// Whether the diffuse term fades below each cluster's tangent plane: always for the forms
    /// that need it, and for the papers' with `plane_fade`.
    pub plane_fade: bool,
}

impl SgLighting {
    pub fn from_options(o: &mut Options, blend: BlendDiffuse) -> Result<Self> {
        resolve_diffuse_form(o, blend)?;
        Ok(Self { diffuse: diffuse_mode(o, blend)?, lighting: lighting_mode(o)?, lambert_lobe: o.choice("lambert_lobe")?, plane_fade: plane_fade(o, blend)? })
    }

    /// The shading pass's form; `exact_texels`: shade one-texel VSGLs as that texel.
    pub fn shading_form(&self, exact_texels: bool) -> VsglShadingForm {
        VsglShadingForm { diffuse: self.diffuse, lighting: self.lighting, lambert_lobe: self.lambert_lobe, exact_texels, plane_fade: self.plane_fade, fade_glossy: false }
    }
}

/// Whether the diffuse term fades below each VSGL's tangent plane: always for the forms that
/// need it, and for the papers' with `plane_fade`. `plane_fade=False` given with a form that
/// always fades is an error rather than silently ignored.
pub(super) fn plane_fade(o: &Options, blend: BlendDiffuse) -> Result<bool> {
    let diffuse = diffuse_mode(o, blend)?;
    if diffuse.fades_below_tangent_plane() {
        if o.was_given("plane_fade") && !o.bool("plane_fade")? {
            let name = diffuse.name();
            let lighting = lighting_mode(o)?.name();
            return Err(Error::invalid(
                "plane_fade",
                format!("the diffuse form {name:?}, which lighting={lighting:?}{} brings, always fades below each cluster's tangent plane (without it a lit plane lights itself); plane_fade=False applies to lighting=\"asg\" with diffuse=\"papers\" only", lighting_default_note(o)),
            ));
        }
        return Ok(true);
    }
    o.bool("plane_fade")
}

/// " (the method's default)" when `lighting` was left out: the errors above then name the
/// default as what brought the clamped-cosine diffuse, so a caller who asked only for a papers'
/// diffuse form learns to give lighting="asg" too.
fn lighting_default_note(o: &Options) -> &'static str {
    if o.was_given("lighting") {
        ""
    } else {
        " (the method's default)"
    }
}

/// `lighting=` as the shading pass takes it.
pub(super) fn lighting_mode(o: &Options) -> Result<LightingMode> {
    o.choice("lighting")
}
