//! What every virtual-light method shares: the reflective shadow maps of each light (the
//! light's views through the visibility, material and flux passes: one for a spot light, six
//! cube faces for a point light, one orthographic view for a directional light), handed to the method one RSM at a time with its share of the
//! virtual-light budget, and the first light's RSM(s) read back when the frame asked for it
//! (`capture_rsm`).

use super::{CapturedRsm, FrameContext};
use crate::error::Result;
use crate::frame::uniforms::{directional_rsm_origin, rsm_views, LightRaw};
use crate::scene::Light;
use crate::frame::{Rsm, VisibilityTargets};
use crate::passes::{material::MaterialPass, rsm_flux::RsmFluxPass, visibility::VisibilityPass};

/// How the RSMs of a frame are made.
pub struct RsmSettings {
    /// Side in texels.
    pub size: u32,
    /// Whether the method samples texels by weight (then the weight pyramid is allocated).
    pub sampling: bool,
    /// Read the first light's RSM back into the frame.
    pub capture: bool,
    /// Virtual lights per light source (`num_lights`; 0 for methods without a budget).
    pub budget: u32,
}

/// Splits a light's virtual-light budget `n` over its `views` RSMs: equal shares (a point
/// light's six cube faces receive equal power, 4π·I/6 each) that add up to `n`, the first
/// `n mod views` getting one more. Every view gets at least one, so no face's light is left
/// out (an unbiased estimate needs every RSM sampled): with n < views the light gets `views`.
pub fn view_budgets(n: u32, views: u32) -> Vec<u32> {
    let views = views.max(1);
    (0..views).map(|v| (n / views + u32::from(v < n % views)).max(1)).collect()
}

/// One light's RSM as a method sees it.
pub struct LightRsm<'a> {
    /// Index of the light in the scene (and in `ctx.lights`).
    pub index: usize,
    /// Which of the light's RSMs this is (a point light's cube face, `CUBE_FACES` order; 0
    /// for a spot light).
    pub view: usize,
    /// Virtual lights to make from this RSM ([`view_budgets`] of `RsmSettings::budget`).
    pub budget: u32,
    /// The light as the RSM passes see it: `position` is the origin its RSM positions are
    /// relative to, relative to the frame origin (the light itself for a spot or point light;
    /// for a directional light, the centre of its RSM's image plane, [`directional_rsm_origin`]).
    pub raw: &'a LightRaw,
    /// A storage buffer holding this light alone (what the RSM passes bind).
    pub light: &'a wgpu::Buffer,
    pub rsm: &'a Rsm,
}

/// Renders the RSM of each light in turn and calls `per_light` after each; `false` (and a
/// reason in `ctx.skipped`) when the scene has no light, so there is no indirect light.
pub fn for_each_light(ctx: &mut FrameContext<'_>, s: &RsmSettings, mut per_light: impl FnMut(&mut FrameContext<'_>, &LightRsm<'_>) -> Result<()>) -> Result<bool> {
    if ctx.lights.is_empty() {
        ctx.skip("indirect", "the scene has no light");
        return Ok(false);
    }
    let (anchor, extent, layer_size) = (ctx.gpu_scene.anchor, ctx.extent, ctx.gpu_scene.texture_layer_size);
    let views: Vec<_> = ctx.scene.lights.iter().map(|l| rsm_views(l, anchor, extent, s.size, layer_size)).collect();
    if s.budget > 0 {
        // What each light's RSMs got, e.g. "256" for a spot light, "43+43+43+43+42+42" for a
        // point light (`frame.settings["virtual_lights_per_light"]`, lights separated by ";").
        let rows: Vec<String> = views.iter().map(|v| view_budgets(s.budget, v.len() as u32).iter().map(u32::to_string).collect::<Vec<_>>().join("+")).collect();
        ctx.settings.push(("virtual_lights_per_light".into(), rows.join(";")));
    }
    let n = s.size;
    let rsm = Rsm::new(&mut ctx.rec, n, ctx.features.specular, s.sampling);
    let rsm_visibility = VisibilityTargets::new(&mut ctx.rec, n, n);
    let (visibility, material, flux) = (ctx.passes.get::<VisibilityPass>()?, ctx.passes.get::<MaterialPass>()?, ctx.passes.get::<RsmFluxPass>()?);
    let lights = ctx.lights;
    for ((index, raw), light_views) in lights.iter().enumerate().zip(&views) {
        let budgets = view_budgets(s.budget, light_views.len() as u32);
        // A directional light's RSM positions are relative to its image plane's centre (its
        // view_origin, anchor-relative): that point, relative to the frame origin (computed in
        // f64), takes the place of the light's position, so VPL and VSGL positions come out
        // relative to the eye like a spot light's (`pos + light.position`, `light_offset`).
        let mut raw = *raw;
        if let Light::Directional(dir) = &ctx.scene.lights[index] {
            raw.position = (anchor + directional_rsm_origin(dir, extent) - ctx.origin).as_vec3().to_array();
        }
        let raw = &raw;
        let light = ctx.rec.storage_init("light_rsm_storage_buffer", bytemuck::bytes_of(raw));
        for (view_index, (view, &budget)) in light_views.iter().zip(&budgets).enumerate() {
            let view_buf = ctx.rec.uniform("rsm_view_uniform_buffer", view);
            let gs = ctx.gpu_scene;
            visibility.record(&mut ctx.rec, "rsm_visibility", &view_buf, &gs.raster_vertices, gs.raster_vertex_count, &rsm_visibility);
            material.record(&mut ctx.rec, "rsm_material", &view_buf, &rsm_visibility.ids, gs, ctx.features, &rsm.gbuffer, (n, n));
            flux.record(&mut ctx.rec, &view_buf, light.as_entire_binding(), &rsm, ctx.features);
            per_light(ctx, &LightRsm { index, view: view_index, budget, raw, light: &light, rsm: &rsm })?;
            if index == 0 && s.capture {
                // Read back before the next view overwrites the shared RSM buffers; a point
                // light's six faces are stacked (CUBE_FACES order) along the first axis.
                ctx.submit_so_far();
                let face = read_rsm(ctx, &rsm)?;
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
    ctx.skip("vpl_shadow_maps", "visibility=\"none\": virtual lights are unshadowed");
    Ok(true)
}

/// The RSM's buffers as `Frame.rsm` names them.
fn read_rsm(ctx: &FrameContext<'_>, rsm: &Rsm) -> Result<CapturedRsm> {
    let b = ctx.gpu.read_buffers(&[&rsm.gbuffer.position, &rsm.gbuffer.normal, &rsm.flux_diffuse, &rsm.flux_specular])?;
    let f = |x: &Vec<u8>| -> Vec<f32> { bytemuck::cast_slice::<u8, f32>(x).to_vec() };
    let rgb = |v: Vec<f32>| -> Vec<f32> { v.chunks_exact(4).flat_map(|p| [p[0], p[1], p[2]]).collect() };
    let n = rsm.size;
    let texels = n as usize * n as usize;
    let fs = if ctx.features.specular { f(&b[3]) } else { vec![0.0; texels * 4] };
    let (pos, nrm, fd) = (f(&b[0]), f(&b[1]), f(&b[2]));
    let roughness: Vec<f32> = nrm.chunks_exact(4).map(|p| p[3]).collect();
    let weight: Vec<f32> = fd.chunks_exact(4).map(|p| p[3]).collect();
    Ok((n, vec![
        ("position".into(), 3, rgb(pos)),
        ("normal".into(), 3, rgb(nrm)),
        ("roughness".into(), 1, roughness),
        ("flux_diffuse".into(), 3, rgb(fd)),
        ("flux_specular".into(), 3, rgb(fs)),
        ("weight".into(), 1, weight),
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
    use super::view_budgets;

    #[test]
    fn view_budgets_add_up_to_the_light_budget() {
        for n in [6, 7, 16, 255, 256, 1 << 20] {
            let b = view_budgets(n, 6);
            assert_eq!(b.iter().sum::<u32>(), n, "n = {n}: {b:?}");
            assert!(b.iter().max().unwrap() - b.iter().min().unwrap() <= 1, "equal shares: {b:?}");
        }
        assert_eq!(view_budgets(256, 1), vec![256], "a spot light keeps its whole budget");
        // Fewer than one per face: every face still gets one (none of its light is dropped).
        assert_eq!(view_budgets(4, 6), vec![1; 6]);
    }
}
