//! What every virtual-light method shares: the reflective shadow maps of each light (the
//! light's views through the visibility, material and flux passes: one for a spot light, six
//! cube faces for a point light, one orthographic view for a directional light), handed to the method one RSM at a time with its share of the
//! virtual-light budget, and the first light's RSM(s) read back when the frame asked for it
//! (`capture_rsm`).

use super::{CapturedRsm, FrameContext};
use crate::error::Result;
use crate::frame::uniforms::{directional_rsm_origin, rsm_views, views_seeing_scene, LightRaw, RsmFit};
use crate::scene::Light;
use crate::setting::Setting;
use crate::frame::{Rsm, VisibilityTargets};
use crate::gpu::{kept_staging_buffer, read_staging};
use std::sync::Arc;
use crate::passes::{material::{MaterialPass, RasterView}, pdf_mips::PdfMipsPass, rsm_flux::RsmFluxPass, visibility::VisibilityPass};

/// How the RSMs of a frame are made.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RsmSettings {
    /// Side in texels.
    pub size: u32,
    /// Whether the method samples texels by weight (then the weight pyramid is allocated).
    pub sampling: bool,
    /// Read the first light's RSM back into the frame.
    pub capture: bool,
    /// Virtual lights per light source (`num_lights`; 0 for methods without a budget).
    pub budget: u32,
    /// How a spot light's RSM frames the scene (`rsm_fit`).
    pub fit: RsmFit,
}

/// Splits the virtual-light budget `n` over a frame's RSMs (every light's views: one for a
/// spot or directional light, six cube faces for a point light) in proportion to the power each
/// reflects, `powers` (the sum of its texels' sampling weights, Φ·(R_d + R_s) over rgb).
///
/// - A view that reflects nothing (power 0: it sees no geometry, or only black or unlit
///   geometry) gets no virtual lights and is left out: it contributes nothing to any estimate.
/// - Every view that reflects something gets at least one, so no reflected light is dropped
///   (each RSM's estimate is unbiased only if it is sampled); the other `n − lit` are shared
///   in proportion to power by largest remainder (Hamilton), so the shares add up to exactly
///   `n` whenever `n ≥ lit`. With fewer than `lit` the frame uses `lit` virtual lights.
/// - Powers that are not finite (which `NumericsError` reports later) or all zero fall back to
///   equal shares over the views, so the split never hides or makes a problem.
///
/// Any split keeps VPLs unbiased (each view's VPLs carry that view's power over its count);
/// proportional shares give each view the same power per virtual light, which is what
/// minimises the variance of a sum of independent per-view estimates for a fixed total.
pub fn power_budgets(n: u32, powers: &[f64]) -> Vec<u32> {
    let views = powers.len();
    if views == 0 {
        return Vec::new();
    }
    let usable = powers.iter().all(|p| p.is_finite() && *p >= 0.0) && powers.iter().any(|p| *p > 0.0);
    let powers: Vec<f64> = if usable { powers.to_vec() } else { vec![1.0; views] };
    let lit = powers.iter().filter(|p| **p > 0.0).count() as u32;
    let rest = n.saturating_sub(lit) as f64;
    let total: f64 = powers.iter().sum();
    let quotas: Vec<f64> = powers.iter().map(|p| rest * p / total).collect();
    let mut shares: Vec<u32> = quotas.iter().map(|q| q.floor() as u32).collect();
    let given: u32 = shares.iter().sum();
    // Largest remainders first (ties: the earlier view), among lit views only.
    let mut order: Vec<usize> = (0..views).filter(|&v| powers[v] > 0.0).collect();
    order.sort_by(|&a, &b| (quotas[b] - quotas[b].floor()).total_cmp(&(quotas[a] - quotas[a].floor())).then(a.cmp(&b)));
    for &v in order.iter().take((rest as u32).saturating_sub(given) as usize) {
        shares[v] += 1;
    }
    for (share, p) in shares.iter_mut().zip(&powers) {
        if *p > 0.0 {
            *share += 1;
        }
    }
    shares
}

impl RsmSettings {
    /// `rsm_size`, `rsm_fit` and `capture_rsm` (`options::common::RSM_OPTIONS` but the
    /// method's own `rsm_size`); `sampling` and `budget` are the method's.
    pub fn from_options(o: &super::Options, sampling: bool, budget: u32) -> Result<Self> {
        Ok(Self { size: o.u32("rsm_size")?, sampling, capture: o.bool("capture_rsm")?, budget, fit: o.choice("rsm_fit")? })
    }
}

/// One light's RSM as a method sees it.
pub struct LightRsm<'a> {
    /// Virtual lights to make from this RSM (its [`power_budgets`] share of
    /// `RsmSettings::budget`; never 0: views without a share are not handed to the method).
    pub budget: u32,
    /// The light as the RSM passes see it: `position` is the origin its RSM positions are
    /// relative to, relative to the frame origin (the light itself for a spot or point light;
    /// for a directional light, the centre of its RSM's image plane, [`directional_rsm_origin`]).
    pub raw: &'a LightRaw,
    /// A storage buffer holding this light alone (what the RSM passes bind).
    pub light: &'a wgpu::Buffer,
    pub rsm: &'a Rsm,
    /// The RSM's view (`rsm_views`): what gives a texel its footprint (`texel_footprint`).
    pub view: &'a crate::frame::uniforms::FrameUniforms,
    /// Index of the view among all lights' views, in order (what `metropolis` keys chains by).
    pub slot: usize,
    /// Index of the light among the frame's light sources (`FrameContext::light_sources`): a
    /// point light's cube faces share it.
    pub light_index: usize,
}

impl LightRsm<'_> {
    /// The light as the passes that read this RSM's texels need it.
    pub fn rsm_light(&self) -> crate::frame::RsmLight {
        crate::frame::RsmLight { offset: self.raw.position, dir: self.raw.rsm_light_dir(), texel_footprint: self.texel_footprint() }
    }

    /// What `vsgl_moments.wgsl` needs to give each RSM texel its area on the surface: for a
    /// perspective RSM (spot light, point light face) the view
    /// axis and t²·(2/N)², so that a texel at angle α to the axis spans the solid angle
    /// Δω = t²(2/N)²cos³α (as in rsm_flux.wgsl) and a cross-section Δω·d² at distance d;
    /// for an orthographic RSM (directional light) w is the cross-section (2R/N)² itself and
    /// xyz = 0.
    pub fn texel_footprint(&self) -> [f32; 4] {
        let v = self.view;
        let n = v.size[0] as f32;
        let len = |a: [f32; 4]| (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
        let texel = 2.0 / n;
        if v.orthographic != 0 {
            [0.0, 0.0, 0.0, len(v.cam_right) * len(v.cam_up) * texel * texel]
        } else {
            let t2 = len(v.cam_up) * len(v.cam_up);
            let f = v.cam_forward;
            [f[0], f[1], f[2], t2 * texel * texel]
        }
    }
}

/// What renders one RSM: the shared targets and the three passes.
struct RsmPasses {
    rsm: Rsm,
    visibility_targets: VisibilityTargets,
    visibility: Arc<VisibilityPass>,
    material: Arc<MaterialPass>,
    flux: Arc<RsmFluxPass>,
}

impl RsmPasses {
    /// Renders `view` of the light in `light` into the shared RSM (`what`: the pass-name
    /// prefix, `rsm` or `rsm_power`).
    fn record(&self, ctx: &mut FrameContext<'_>, what: &str, view: &crate::frame::uniforms::FrameUniforms, light: &wgpu::Buffer) {
        let view_buf = ctx.rec.uniform("rsm_view_uniform_buffer", view);
        let gs = ctx.gpu_scene;
        self.visibility.record(&mut ctx.rec, &format!("{what}_visibility"), &view_buf, &gs.raster_vertices, gs.raster_vertex_count, &self.visibility_targets);
        let view = RasterView { label: &format!("{what}_material"), frame_uniforms: &view_buf, ids: &self.visibility_targets.ids };
        self.material.record(&mut ctx.rec, &view, gs, ctx.features, &self.rsm.gbuffer);
        self.flux.record(&mut ctx.rec, &view_buf, light.as_entire_binding(), &self.rsm, ctx.features);
    }
}

/// Light `index` as its RSM passes see it. A directional light's RSM positions are relative to
/// its image plane's centre (its view_origin, anchor-relative): that point, relative to the
/// frame origin (computed in f64), takes the place of the light's position, so VPL and VSGL
/// positions come out relative to the eye like a spot light's (`pos + light.position`,
/// `light_offset`).
fn rsm_light(ctx: &FrameContext<'_>, index: usize) -> LightRaw {
    let mut raw = ctx.lights[index];
    if let Light::Directional(dir) = &ctx.light_sources[index] {
        raw.position = (ctx.gpu_scene.anchor + directional_rsm_origin(dir, ctx.extent) - ctx.origin).as_vec3().to_array();
    }
    raw
}

/// The power each view's RSM reflects (the top of its weight pyramid), in `views` order:
/// every RSM rendered once more before the method's own pass over them, and read back in the
/// middle of the frame (a wait for the GPU: frames with one view skip this).
fn measure_rsm_powers(ctx: &mut FrameContext<'_>, passes: &RsmPasses, views: &[Vec<crate::frame::uniforms::FrameUniforms>], seeing: &[Vec<bool>]) -> Result<Vec<f64>> {
    let pdf_mips = ctx.passes.get::<PdfMipsPass>()?;
    let count = seeing.iter().flatten().filter(|s| **s).count();
    let bytes = count as u64 * 4;
    let staging = kept_staging_buffer(ctx.gpu, ctx.power_staging, "rsm_power_staging_buffer", bytes);
    let (_, texels) = crate::frame::pyramid_layout(passes.rsm.size);
    let top = (texels as u64 - 1) * 4;
    let mut slot = 0u64;
    for (index, (light_views, light_seeing)) in views.iter().zip(seeing).enumerate() {
        let raw = rsm_light(ctx, index);
        let light = ctx.rec.storage_init("light_rsm_storage_buffer", bytemuck::bytes_of(&raw));
        for (view, _) in light_views.iter().zip(light_seeing).filter(|(_, sees)| **sees) {
            passes.record(ctx, "rsm_power", view, &light);
            pdf_mips.record(&mut ctx.rec, &passes.rsm);
            ctx.rec.enc.copy_buffer_to_buffer(&passes.rsm.pyramid, top, &staging, slot * 4, 4);
            slot += 1;
        }
    }
    let submission = ctx.submit_so_far();
    let measured = read_staging::<f32>(ctx.gpu, &staging, bytes, Some(&submission), "RSM power readback")?;
    // Views that miss the scene reflect nothing (power 0) without being measured.
    let mut measured = measured.into_iter();
    Ok(seeing.iter().flatten().map(|&sees| if sees { measured.next().map_or(0.0, f64::from) } else { 0.0 }).collect())
}

/// Renders the RSM of each light in turn and calls `per_light` after each view that gets
/// virtual lights; `false` (and a reason in `ctx.skipped`) when the scene has no light, so
/// there is no indirect light.
///
/// With a budget (`vpl`, `vsgl`) and more than one RSM in the frame (several lights, or a
/// point light's six faces), the budget is split over the RSMs by [`power_budgets`], from
/// powers measured first ([`measure_rsm_powers`]), and RSMs that reflect nothing are left out
/// (`frame.skipped`). One RSM takes the whole budget with no measuring.
pub fn for_each_light(ctx: &mut FrameContext<'_>, s: &RsmSettings, mut per_light: impl FnMut(&mut FrameContext<'_>, &LightRsm<'_>) -> Result<()>) -> Result<bool> {
    if ctx.lights.is_empty() {
        ctx.skip("indirect", "the scene has no light");
        return Ok(false);
    }
    let (anchor, half_size, extent, layer_size) = (ctx.gpu_scene.anchor, ctx.gpu_scene.half_size, ctx.extent, ctx.gpu_scene.texture_layer_size);
    let views: Vec<_> = ctx.light_sources.iter().map(|l| rsm_views(l, anchor, half_size, extent, s.size, layer_size, s.fit)).collect();
    if ctx.light_sources.iter().any(|l| matches!(l, Light::Spot(_))) {
        // Each spot light's RSM frame (`rsm_fit`), for a model of its texels' footprints: per
        // light {forward: [x, y, z], tan: t} (t = tan of the half field of view), or nothing
        // for other lights.
        let rows: Vec<Setting> = views.iter().zip(ctx.light_sources).map(|(v, l)| match l {
            Light::Spot(_) => {
                let (f, u) = (v[0].cam_forward, v[0].cam_up);
                let tan = (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]).sqrt();
                Setting::Record(vec![("forward", f[..3].to_vec().into()), ("tan", tan.into())])
            }
            _ => Setting::Absent,
        }).collect();
        ctx.settings.push(("rsm_view".into(), Setting::List(rows)));
    }
    let n = s.size;
    let passes = RsmPasses {
        rsm: Rsm::new(&mut ctx.rec, n, ctx.features.specular, s.sampling),
        visibility_targets: VisibilityTargets::new(&mut ctx.rec, n, n),
        visibility: ctx.passes.get::<VisibilityPass>()?,
        material: ctx.passes.get::<MaterialPass>()?,
        flux: ctx.passes.get::<RsmFluxPass>()?,
    };
    // Views that miss the scene's bounds reflect nothing: never rendered (nor measured).
    let seeing: Vec<Vec<bool>> = ctx.light_sources.iter().map(|l| views_seeing_scene(l, anchor, extent)).collect();
    let view_count = seeing.iter().flatten().filter(|s| **s).count();
    let budgets: Vec<Vec<u32>> = if s.budget > 0 && view_count > 1 && s.sampling {
        let shares = power_budgets(s.budget, &measure_rsm_powers(ctx, &passes, &views, &seeing)?);
        let mut shares = shares.into_iter();
        views.iter().map(|v| shares.by_ref().take(v.len()).collect()).collect()
    } else {
        seeing.iter().map(|v| v.iter().map(|&sees| if sees { s.budget } else { 0 }).collect()).collect()
    };
    if s.budget > 0 {
        // What each light's RSMs got, per light: [256] for a spot light, [43, 43, 43, 43, 42, 42]
        // for a point light's cube faces (`frame.settings["virtual_lights_per_light"]`).
        ctx.settings.push(("virtual_lights_per_light".into(), budgets.clone().into()));
    }
    let mut first_slot = 0;
    for (index, (light_views, light_budgets)) in views.iter().zip(&budgets).enumerate() {
        let slot_base = first_slot;
        first_slot += light_views.len();
        let raw = rsm_light(ctx, index);
        let raw = &raw;
        let light = ctx.rec.storage_init("light_rsm_storage_buffer", bytemuck::bytes_of(raw));
        for (view_index, (view, &budget)) in light_views.iter().zip(light_budgets).enumerate() {
            let misses = !seeing[index][view_index];
            let dark = misses || (s.budget > 0 && budget == 0);
            let capture = index == 0 && s.capture;
            if dark {
                let what = if light_views.len() > 1 { format!("light {index} view {view_index}") } else { format!("light {index}") };
                let why = if misses { "its view misses the scene's bounds" } else { "its RSM reflects no light (it sees no lit, non-black geometry)" };
                ctx.skip(&format!("virtual lights of {what}"), why);
                if !capture {
                    continue;
                }
            }
            passes.record(ctx, "rsm", view, &light);
            ctx.sampling_pyramid = None;
            if !dark {
                per_light(ctx, &LightRsm { budget, raw, light: &light, rsm: &passes.rsm, view, slot: slot_base + view_index, light_index: index })?;
            }
            if capture {
                // Read back before the next view overwrites the shared RSM buffers; a point
                // light's six faces are stacked (CUBE_FACES order) along the first axis.
                ctx.submit_so_far();
                let face = read_rsm(ctx, &passes.rsm, ctx.sampling_pyramid.as_ref())?;
                match &mut ctx.captured_rsm {
                    Some((_, stacked)) if view_index > 0 => {
                        for ((_, _, all), (_, _, more)) in stacked.iter_mut().zip(face.1) {
                            all.extend(more);
                        }
                    }
                    slot => *slot = Some(face),
                }
            }
        }
    }
    Ok(true)
}

/// The RSM's buffers as `Frame.rsm` names them; `sampling`: the pyramid the view's virtual
/// lights were drawn from when it is not the RSM's own (brsm).
fn read_rsm(ctx: &FrameContext<'_>, rsm: &Rsm, sampling: Option<&wgpu::Buffer>) -> Result<CapturedRsm> {
    let mut buffers = vec![&rsm.gbuffer.position, &rsm.gbuffer.normal, &rsm.flux_diffuse, &rsm.flux_specular];
    buffers.extend(sampling);
    let b = ctx.gpu.read_buffers(&buffers)?;
    let f = |x: &Vec<u8>| -> Vec<f32> { bytemuck::cast_slice::<u8, f32>(x).to_vec() };
    let rgb = |v: Vec<f32>| -> Vec<f32> { v.chunks_exact(4).flat_map(|p| [p[0], p[1], p[2]]).collect() };
    let n = rsm.size;
    let texels = n as usize * n as usize;
    let fs = if ctx.features.specular { f(&b[3]) } else { vec![0.0; texels * 4] };
    let (pos, nrm, fd) = (f(&b[0]), f(&b[1]), f(&b[2]));
    let roughness: Vec<f32> = nrm.chunks_exact(4).map(|p| p[3]).collect();
    let weight: Vec<f32> = fd.chunks_exact(4).map(|p| p[3]).collect();
    // Level 0 of the sampling pyramid: what the warp and the estimators use as the texel's
    // (unnormalised) probability; the RSM's own weight unless brsm re-weighted it.
    let sampling_weight: Vec<f32> = if sampling.is_some() { f(&b[4])[..texels].to_vec() } else { weight.clone() };
    Ok((n, vec![
        ("position".into(), 3, rgb(pos)),
        ("normal".into(), 3, rgb(nrm)),
        ("roughness".into(), 1, roughness),
        ("flux_diffuse".into(), 3, rgb(fd)),
        ("flux_specular".into(), 3, rgb(fs)),
        ("weight".into(), 1, weight),
        ("sampling_weight".into(), 1, sampling_weight),
    ]))
}

/// Checks that an RSM of side `n` fits the adapter's storage binding limit.
pub fn check_rsm_size(gpu: &crate::gpu::Gpu, n: u32) -> Result<()> {
    let n = n as u64;
    let limit = gpu.limits.max_storage_buffer_binding_size as u64;
    if n * n * 16 > limit {
        return Err(crate::error::Error::invalid("rsm_size", format!("{n}² texels exceed this adapter's storage binding limit of {limit} bytes")));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::power_budgets;

    #[test]
    fn power_budgets_add_up_and_follow_power() {
        // Six equal faces: equal shares adding up to n (the remainder to the first faces).
        for n in [6, 7, 16, 255, 256, 1 << 20] {
            let b = power_budgets(n, &[1.0; 6]);
            assert_eq!(b.iter().sum::<u32>(), n, "n = {n}: {b:?}");
            assert!(b.iter().max().unwrap() - b.iter().min().unwrap() <= 1, "equal shares: {b:?}");
        }
        assert_eq!(power_budgets(256, &[3.5]), vec![256], "one RSM keeps the whole budget");
        // In proportion to power: 1 each, then 97 shared 1:2:3 (16.17, 32.33, 48.5 → 16, 32, 49).
        assert_eq!(power_budgets(100, &[1.0, 2.0, 3.0]), vec![17, 33, 50]);
        // Dark views get nothing; every lit view at least one, even a very dim one.
        let b = power_budgets(64, &[0.0, 1e-9, 5.0, 0.0]);
        assert_eq!(b, vec![0, 1, 63, 0]);
        // Fewer virtual lights than lit views: one each (the frame uses more than asked).
        assert_eq!(power_budgets(2, &[1.0, 1.0, 0.0, 1.0]), vec![1, 1, 0, 1]);
        // No usable power (all dark, NaN, infinite): equal shares over every view.
        assert_eq!(power_budgets(12, &[0.0; 3]), vec![4, 4, 4]);
        assert_eq!(power_budgets(12, &[f64::NAN, 1.0, 1.0]), vec![4, 4, 4]);
        assert_eq!(power_budgets(12, &[f64::INFINITY, 1.0, 1.0]), vec![4, 4, 4]);
        for (n, powers) in [(1000u32, vec![0.3, 7.0, 0.001, 2.0, 0.0, 9.0]), (7, vec![1.0, 1e6, 1.0])] {
            let b = power_budgets(n, &powers);
            assert_eq!(b.iter().sum::<u32>(), n, "{powers:?}: {b:?}");
        }
    }
}

/// `rsm_size`, when not given, grown with `num_lights`
/// ([`common::rsm_size_for`](super::options::common::rsm_size_for)); shared by `vpl` and `vsgl`.
pub(super) fn resolve_rsm_size_for_num_lights(o: &mut super::Options) -> Result<()> {
    let side = super::options::common::rsm_size_for(o.u32("num_lights")?);
    o.resolve_default("rsm_size", super::options::OptionValue::Int(side as i64));
    Ok(())
}
