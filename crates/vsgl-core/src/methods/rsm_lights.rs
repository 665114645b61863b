//! What every virtual-light method shares: one reflective shadow map per light (the light's
//! view through the visibility, material and flux passes), handed to the method light by
//! light, and the first light's RSM read back when the frame asked for it (`capture_rsm`).

use super::{CapturedRsm, FrameContext};
use crate::error::Result;
use crate::frame::uniforms::{light_view_uniforms, LightRaw};
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
}

/// One light's RSM as a method sees it.
pub struct LightRsm<'a> {
    /// Index of the light in the scene (and in `ctx.lights`).
    pub index: usize,
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
    // Only spot lights have an RSM so far (issue 16): refuse the others by name before
    // anything is recorded, rather than leaving their indirect light out of the image.
    if let Some((index, light)) = ctx.scene.lights.iter().enumerate().find(|(_, l)| l.as_spot().is_none()) {
        return Err(crate::error::Error::invalid(
            format!("scene.lights[{index}]"),
            format!(
                "{} lights have no reflective shadow map yet, so the virtual-light methods (vpl, vsgl, \
                 vsgl2, reference) take spot lights only; method=\"direct\" and method=\"pathtrace\" render \
                 spot, point and directional lights",
                light.kind()
            ),
        ));
    }
    let n = s.size;
    let rsm = Rsm::new(&mut ctx.rec, n, ctx.features.specular, s.sampling);
    let rsm_visibility = VisibilityTargets::new(&mut ctx.rec, n, n);
    let (visibility, material, flux) = (ctx.passes.get::<VisibilityPass>()?, ctx.passes.get::<MaterialPass>()?, ctx.passes.get::<RsmFluxPass>()?);
    let lights = ctx.lights;
    for (index, raw) in lights.iter().enumerate() {
        let Some(spot) = ctx.scene.lights[index].as_spot() else { continue }; // others refused above
        let view = light_view_uniforms(spot, ctx.gpu_scene.anchor, ctx.extent, n, ctx.gpu_scene.texture_layer_size);
        let view_buf = ctx.rec.uniform("rsm_view_uniform_buffer", &view);
        let light = ctx.rec.storage_init("spot_light_storage_buffer", bytemuck::bytes_of(raw));
        let gs = ctx.gpu_scene;
        visibility.record(&mut ctx.rec, "rsm_visibility", &view_buf, &gs.raster_vertices, gs.raster_vertex_count, &rsm_visibility);
        material.record(&mut ctx.rec, "rsm_material", &view_buf, &rsm_visibility.ids, gs, ctx.features, &rsm.gbuffer, (n, n));
        flux.record(&mut ctx.rec, &view_buf, light.as_entire_binding(), &rsm, ctx.features);
        per_light(ctx, &LightRsm { index, raw, light: &light, rsm: &rsm })?;
        if index == 0 && s.capture {
            // Read back before the next light overwrites the shared RSM buffers.
            ctx.submit_so_far();
            ctx.captured_rsm = Some(read_rsm(ctx, &rsm)?);
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
