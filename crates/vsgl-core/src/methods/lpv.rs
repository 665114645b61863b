//! `method="lpv"`: light propagation volumes [Kaplanyan & Dachsbacher 2010], the baseline of the
//! 2015 VSGL poster's Table 1 (diffuse light only, as the poster compares them). Every lit RSM
//! texel is injected into a grid of two-band SH intensities, optionally with a geometry volume
//! of blocking potentials from the same texels, the light is propagated cell to cell for a
//! number of iterations, and every pixel reads its irradiance from the summed iterations.

use super::rsm_lights::{check_rsm_size, for_each_light, RsmSettings};
use super::{options::common, DirectLight, FrameContext, Method, MethodInfo, OptionKind, OptionSpec, OptionValue, Options};
use crate::error::Result;
use crate::frame::lpv::{grid_raw, place_cascades, Cascade, LpvVolumes, GEOMETRY_CELL_BYTES, MAX_CASCADES};
use crate::passes::lpv_geometry::LpvGeometryPass;
use crate::passes::lpv_geometry_merge::LpvGeometryMergePass;
use crate::passes::lpv_inject::LpvInjectPass;
use crate::passes::lpv_lookup::LpvLookupPass;
use crate::passes::lpv_propagate::LpvPropagatePass;
use crate::setting::Setting;

pub const INFO: MethodInfo = MethodInfo {
    name: "lpv",
    summary: "light propagation volumes: RSM texels injected as SH into a grid and propagated cell to cell (Kaplanyan & Dachsbacher 2010; diffuse only)",
    option_groups: OPTION_GROUPS,
    direct_light: DirectLight::ShadowMapped,
    indirect: true,
    extra_aovs: &[],
    ground_truth: false,
    area_emitters: false,
    configure: |o| Ok(Box::new(Lpv::new(o)?)),
};

const OPTION_GROUPS: &[&[OptionSpec]] = &[OPTIONS, common::RSM_OPTIONS];

const fn int(name: &'static str, min: i64, max: i64, default: i64, help: &'static str) -> OptionSpec {
    OptionSpec { name, kind: OptionKind::Int { min, max, power_of_two: false }, default: OptionValue::Int(default), help, note: "" }
}

const OPTIONS: &[OptionSpec] = &[
    common::SHADOW_SIZE,
    common::EMITTER_LIGHTS,
    // Injection reads every texel once: any side, no pyramid.
    OptionSpec { kind: OptionKind::Int { min: 32, max: 4096, power_of_two: false }, ..common::RSM_SIZE },
    int("lpv_grid", 4, 64, 32, "cells per side of each cascade's grid (the poster compared 32³)"),
    int("lpv_cascades", 1, MAX_CASCADES as i64, 1, "nested grids, each half the size of the one before and centred on the camera (1: one grid over the whole scene)"),
    // Light travels one cell per iteration: by default far enough to cross the grid once
    // (the sum over iterations grows slowly long after; docs/methods/lpv.md, "Iterations").
    int("lpv_iterations", 0, 256, 32, "propagation iterations, light moving one cell each (default: lpv_grid, enough to cross the grid)"),
    OptionSpec {
        name: "lpv_occlusion",
        kind: OptionKind::Bool,
        default: OptionValue::Bool(true),
        help: "attenuate propagation (from the second iteration on) by a geometry volume of the RSM texels' blocking potentials",
        note: "",
    },
    OptionSpec {
        name: "capture_lpv",
        kind: OptionKind::Bool,
        default: OptionValue::Bool(false),
        help: "read the volumes back into frame.lpv(name): \"injected\", \"total\", \"geometry\"",
        note: "",
    },
];

struct Lpv {
    rsm: RsmSettings,
    side: u32,
    cascades: u32,
    iterations: u32,
    occlusion: bool,
    capture: bool,
}

impl Lpv {
    fn new(o: &mut Options) -> Result<Self> {
        let side = o.u32("lpv_grid")?;
        o.resolve_default("lpv_iterations", OptionValue::Int(side as i64));
        Ok(Self {
            // No sampling, no budget: every texel is injected.
            rsm: RsmSettings::from_options(o, false, 0)?,
            side,
            cascades: o.u32("lpv_cascades")?,
            iterations: o.u32("lpv_iterations")?,
            occlusion: o.bool("lpv_occlusion")?,
            capture: o.bool("capture_lpv")?,
        })
    }
}

impl Method for Lpv {
    fn check(&self, gpu: &crate::gpu::Gpu) -> Result<()> {
        check_rsm_size(gpu, self.rsm.size)
    }

    fn record(&self, ctx: &mut FrameContext<'_>) -> Result<()> {
        let (anchor, half_size) = (ctx.gpu_scene.anchor, ctx.gpu_scene.half_size);
        if !half_size.is_finite() {
            ctx.skip("indirect", "the scene has no geometry");
            return Ok(());
        }
        let (inject, geometry, propagate, lookup) = (ctx.passes.get::<LpvInjectPass>()?, ctx.passes.get::<LpvGeometryPass>()?, ctx.passes.get::<LpvPropagatePass>()?, ctx.passes.get::<LpvLookupPass>()?);
        // Occlusion applies from the second iteration on: with fewer the geometry volume is
        // never read. (A convex room has no occluders either, but there the volume is not a
        // no-op: its two-band lobes also block light running along a lit wall, so leaving it
        // out would change the image, which a leave-out must not; docs/methods/lpv.md.)
        let occlusion = self.occlusion && (self.iterations > 1 || ctx.plan_full);
        if self.occlusion && !occlusion {
            ctx.skip("lpv_geometry", "one propagation iteration or none: occlusion applies from the second on");
        }
        let cascades = place_cascades(anchor, half_size, ctx.origin, self.side, self.cascades);
        let grid = ctx.rec.uniform("lpv_grid_uniform_buffer", &grid_raw(&cascades, ctx.origin, self.side));
        let volumes = LpvVolumes::new(&mut ctx.rec, self.side, self.cascades, occlusion);
        // With several lights each one's surfels go to a volume of their own, folded into the
        // frame's by `lpv_geometry_merge` once its last RSM (cube face) is in: every light sees
        // the same occluders again, and a sum would block once per light.
        let merge = occlusion && ctx.light_sources.len() > 1;
        let geometry_cells = (LpvVolumes::geometry_bytes(self.side, self.cascades) / GEOMETRY_CELL_BYTES) as u32;
        let merge_with = if merge { Some((ctx.rec.storage("lpv_light_geometry_volume_buffer", volumes.geometry.size()), ctx.passes.get::<LpvGeometryMergePass>()?)) } else { None };
        let mut open_light = None;
        let lit = for_each_light(ctx, &self.rsm, |ctx, light| {
            inject.record(&mut ctx.rec, &grid, light.rsm, light.raw.position, &volumes.current);
            if occlusion {
                let target = match &merge_with {
                    Some((scratch, pass)) => {
                        if open_light.is_some_and(|open| open != light.light_index) {
                            pass.record(&mut ctx.rec, geometry_cells, scratch, &volumes.geometry);
                            ctx.rec.enc.clear_buffer(scratch, 0, None);
                        }
                        open_light = Some(light.light_index);
                        scratch
                    }
                    None => &volumes.geometry,
                };
                geometry.record(&mut ctx.rec, &grid, light.rsm, &light.rsm_light(), target);
            }
            Ok(())
        })?;
        if let (Some((scratch, pass)), Some(_)) = (&merge_with, open_light) {
            pass.record(&mut ctx.rec, geometry_cells, scratch, &volumes.geometry);
        }
        if !lit {
            return Ok(());
        }
        // The injected volume is overwritten by the ping-pong: copy it out first.
        let injected = self.capture.then(|| {
            let copy = ctx.rec.storage_written("lpv_captured_injected_buffer", volumes.current.size());
            ctx.rec.enc.copy_buffer_to_buffer(&volumes.current, 0, &copy, 0, copy.size());
            copy
        });
        propagate.record(&mut ctx.rec, &grid, &volumes, self.iterations, occlusion);
        lookup.record(&mut ctx.rec, &grid, &volumes.total, ctx.gbuffer, ctx.indirect, ctx.size);
        ctx.skip("indirect_specular", "method=\"lpv\": two SH bands hold diffuse light only (the poster compares LPVs on the light–diffuse–diffuse–eye path)");
        ctx.settings.push(("lpv_cascade_grids".into(), cascade_rows(&cascades)));
        if let Some(injected) = injected {
            ctx.submit_so_far();
            ctx.captured_lpv = Some(read_volumes(ctx, &injected, &volumes)?);
        }
        Ok(())
    }
}

/// Each cascade's grid in world space, for `frame.settings["lpv_cascade_grids"]`.
fn cascade_rows(cascades: &[Cascade]) -> Setting {
    Setting::List(
        cascades
            .iter()
            .map(|c| Setting::Record(vec![("min", Setting::List(c.min.to_array().iter().map(|&v| v.into()).collect())), ("cell", c.cell.into())]))
            .collect(),
    )
}

/// The volumes as `frame.lpv` names them: (name, shape, data).
fn read_volumes(ctx: &FrameContext<'_>, injected: &wgpu::Buffer, volumes: &LpvVolumes) -> Result<super::CapturedLpv> {
    let b = ctx.gpu.read_buffers(&[injected, &volumes.total, &volumes.geometry])?;
    let f = |x: &Vec<u8>| -> Vec<f32> { bytemuck::cast_slice::<u8, f32>(x).to_vec() };
    let (c, s) = (volumes.cascades as usize, volumes.side as usize);
    // (cascade, z, y, x, colour, SH coefficient); the geometry volume (cascade, z, y, x, SH).
    let light = vec![c, s, s, s, 3, 4];
    let mut out = vec![("injected".to_string(), light.clone(), f(&b[0])), ("total".to_string(), light, f(&b[1]))];
    if volumes.geometry.size() > 16 {
        out.push(("geometry".to_string(), vec![c, s + 1, s + 1, s + 1, 4], f(&b[2])));
    }
    Ok(out)
}
