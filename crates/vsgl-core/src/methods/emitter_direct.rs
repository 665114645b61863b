//! `emitter_direct="sg"`: the direct light of emissive surfaces as virtual spherical Gaussian
//! lights, shaded by the VSGL shading pass and shadowed by the method's `visibility`.
//!
//! Each of an emitter light's points (`upload::emitters::EmitterClusters::points`: its patches
//! split into 64 parts of equal standing) becomes one VSGL record: its positional Gaussian is the
//! part's centroid and spread (`point_variances`), its diffuse radiant-intensity lobe the
//! Lambertian emitter's cosine, I(ω) = L_e·A·max(n·ω, 0), written as the SG lobe of power
//! Φ = π·L_e·A [Tok16s Eq. 1], and it has no glossy lobe (emitters are Lambertian). The mean
//! tangent plane is the emitter's own, so nothing behind the emitting side is lit (the plane
//! fade), and the shadow target is the part's centroid on the surface: with
//! `visibility="raytrace"` each (pixel, point) pair casts one shadow ray there, so an occluder
//! between a receiver and part of a lamp casts a penumbra, where the cube of shadow maps of
//! `emitter_direct="points"` sees the lamp from its centre alone.
//!
//! The shading writes into targets of its own (`IndirectTargets` reused for its diffuse and
//! glossy halves), which `aov_pack` adds to the direct light; the direct pass then leaves the
//! emitter lights out. A frame whose method leaves `emitter_direct` at "points", or whose scene
//! has no emitter light, runs none of this.

use super::visibility::{VirtualLightVisibility, VisibilityMode, VSGL_RECORD_WORDS};
use super::FrameContext;
use crate::error::{Error, Result};
use crate::frame::{IndirectTargets, ShadingInputs, VirtualLightList};
use crate::passes::vsgl_gen::VSGL_BYTES;
use crate::passes::vsgl_shading::{DiffuseMode, LambertLobe, LightingMode, VsglShadingForm, VsglShadingPass};
use crate::scene::EmitterLight;
use crate::upload::emitters::{EmitterClusters, POINTS_PER_LIGHT};

/// Sharpness of the Lambert lobe's SG (`LAMBERT_LOBE_SG_SHARPNESS` in wgsl/common/sg.wgsl).
const LAMBERT_LOBE_SG_SHARPNESS: f32 = 2.2925;
const RECORD_FLOATS: usize = (VSGL_BYTES / 4) as usize;
const _: () = assert!(RECORD_FLOATS == 32, "VsglRaw in wgsl/common/vsgl_record.wgsl is 32 floats");

/// How the emitter lights' direct light is shaded (`emitter_direct=`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EmitterDirect {
    /// The direct pass's 64-point sum, shadowed by the cluster's cube of shadow maps.
    Points,
    /// Emitter VSGLs through the VSGL shading pass, shadowed by `visibility`.
    Sg,
}

impl EmitterDirect {
    /// The method's choice, with the visibility it shades with; "sg" without visibility would
    /// leave emitters unshadowed, which is refused.
    pub fn from_options(options: &super::Options, takes: bool) -> Result<(Self, VisibilityMode)> {
        if !takes {
            return Ok((Self::Points, VisibilityMode::None));
        }
        let visibility = VisibilityMode::from_options(options)?;
        match options.str("emitter_direct")? {
            "sg" if visibility == VisibilityMode::None => Err(Error::invalid(
                "emitter_direct",
                "\"sg\" shadows the emitter VSGLs with the method's virtual-light visibility, and visibility=\"none\" would leave emissive surfaces unshadowed: set visibility=\"raytrace\" or \"ism\", or keep emitter_direct=\"points\"",
            )),
            "sg" => Ok((Self::Sg, visibility)),
            _ => Ok((Self::Points, visibility)),
        }
    }
}

/// The VSGL records (`VsglRaw`, 32 floats each) of every emitter point with a share of its
/// light's intensity, positions relative to the frame origin `origin`.
pub fn emitter_vsgl_records(clusters: &EmitterClusters, origin: glam::DVec3) -> Vec<[f32; RECORD_FLOATS]> {
    let mut out = Vec::new();
    for (index, light) in clusters.lights.iter().enumerate() {
        let EmitterLight { normal, intensity, color, .. } = *light;
        let n = normal.as_vec3();
        for k in 0..POINTS_PER_LIGHT {
            let i = index * POINTS_PER_LIGHT + k;
            let (Some(&(position, share)), Some(&variance)) = (clusters.points.get(i), clusters.point_variances.get(i)) else { continue };
            if share <= 0.0 {
                continue;
            }
            let mean = (position - origin).as_vec3();
            // Φ = π·I along the normal: the Lambert lobe's SG carries power (wgsl/common/vsgl_record.wgsl).
            let power = color * (std::f32::consts::PI * intensity * share);
            let mut r = [0.0f32; RECORD_FLOATS];
            r[0..3].copy_from_slice(&mean.to_array());
            r[3] = variance as f32;
            r[4..7].copy_from_slice(&n.to_array());
            r[7] = LAMBERT_LOBE_SG_SHARPNESS;
            r[8..11].copy_from_slice(&power.to_array());
            r[12..15].copy_from_slice(&n.to_array());
            r[15] = LAMBERT_LOBE_SG_SHARPNESS;
            // specular_power (16..19) stays 0: an emitter has no glossy lobe.
            r[19] = 1.0;
            // The emitter's own plane through the part: coherent normal (length 1), offset 0.
            r[24..27].copy_from_slice(&n.to_array());
            r[28..31].copy_from_slice(&mean.to_array());
            out.push(r);
        }
    }
    out
}

/// The form emitter VSGLs are shaded with: the clamped cosine kept inside the diffuse integral
/// and the accurate glossy form, the Lambert lobe blended with an exact point emitter where a
/// part is compact as seen from the receiver (a part is a 64th of a lamp, compact everywhere
/// but at touching distance), and the plane fade, of the glossy reflection too, that keeps the
/// emitter's own plane and what lies behind it dark.
pub const EMITTER_SHADING_FORM: VsglShadingForm = VsglShadingForm {
    diffuse: DiffuseMode::Accurate,
    lighting: LightingMode::Accurate,
    lambert_lobe: LambertLobe::ExactCompact,
    exact_texels: false,
    plane_fade: true,
    fade_glossy: true,
};

/// Shades the emitter VSGLs of `clusters` into `out`, shadowed by `visibility`.
pub fn record(ctx: &mut FrameContext<'_>, clusters: &EmitterClusters, visibility: VisibilityMode, out: &IndirectTargets) -> Result<()> {
    let records = emitter_vsgl_records(clusters, ctx.origin);
    if records.is_empty() {
        return Ok(());
    }
    let count = records.len() as u32;
    let buffer = ctx.rec.storage_init("emitter_vsgl_buffer", bytemuck::cast_slice(&records));
    let vis = VirtualLightVisibility::new(ctx, visibility, count)?;
    vis.build_maps(ctx, &buffer, count, VSGL_RECORD_WORDS)?;
    let shading = ctx.passes.get::<VsglShadingPass>()?;
    let io = ShadingInputs { frame_uniforms: ctx.frame_uniforms, gbuffer: ctx.gbuffer, out, features: ctx.features, size: ctx.size, visibility: &vis };
    shading.record_as(&mut ctx.rec, "emitter_direct", &io, VirtualLightList { records: &buffer, count, interleave: 1 }, EMITTER_SHADING_FORM, None);
    Ok(())
}
