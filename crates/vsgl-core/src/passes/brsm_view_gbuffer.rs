//! The camera side of bidirectional RSM importance (compute, `wgsl/passes/brsm_view_gbuffer.wgsl`): the
//! camera's G-buffer resampled onto a square power-of-two grid laid out like an RSM — the
//! papers' "additional G-buffer" [Tok15 §4.3; Tok16 Table 1] — so the VSGL passes build the
//! view's VSGLs from it as they build a light's from its RSM.

use crate::error::Result;
use crate::frame::{pyramid_layout, GBuffer, Rsm};
use crate::gpu::{groups, Gpu, PipelineVariants, Recorder};
use crate::plan::ShaderFeatures;

use crate::shader_lib::constants::brsm_view_gbuffer::WORKGROUP;

/// Largest side of the view grid: a 1920×1080 view is subsampled onto 512² texels (every 3.75th
/// column, every 2.1th row), which is plenty for an importance estimate and keeps the five
/// moment chains at 28 MB (and the grid buffers at 17 MB).
pub const VIEW_GRID_MAX: u32 = 512;

/// Side of the view grid for an image of `size`: the smallest power of two covering the longer
/// side, at most [`VIEW_GRID_MAX`] (and at least 2, so the pyramid has a level above 0).
pub fn view_grid_side(size: (u32, u32)) -> u32 {
    size.0.max(size.1).next_power_of_two().clamp(2, VIEW_GRID_MAX)
}

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct ViewParamsRaw {
    width: u32,
    height: u32,
    grid: u32,
    _pad: u32,
}

/// The view grid as an [`Rsm`]: positions relative to the camera, flux 1 per texel times the
/// pixel's reflectances, the weight pyramid (`brsm_*` labels so `frame.memory` tells them from
/// the light's).
pub fn view_grid(rec: &mut Recorder<'_>, side: u32, specular: bool) -> Rsm {
    let texels = side as u64 * side as u64;
    let (offsets, total) = pyramid_layout(side);
    let mut make = |label, bytes| rec.storage_written(label, bytes);
    let gbuffer = GBuffer {
        position: make("brsm_view_position_buffer", texels * 16),
        normal: make("brsm_view_normal_buffer", texels * 16),
        // Not read by the moments (positions, normals and fluxes only).
        geo_normal: make("brsm_view_unused_buffer", 16),
        base_color: make("brsm_view_unused_buffer", 16),
        emission: make("brsm_view_unused_buffer", 16),
        has_emission: false,
        size: (side, side),
    };
    Rsm {
        size: side,
        gbuffer,
        flux_diffuse: make("brsm_view_flux_diffuse_buffer", texels * 16),
        flux_specular: make("brsm_view_flux_specular_buffer", if specular { texels * 16 } else { 16 }),
        // Level 0 is written by the pass, the rest by pdf_mips.
        pyramid: make("brsm_view_weight_pyramid_buffer", total as u64 * 4),
        level_offsets: rec.storage_init("brsm_view_level_offset_buffer", bytemuck::cast_slice(&offsets)),
        levels: offsets.len() as u32,
        sampling: true,
    }
}

pub struct BrsmViewPass {
    pipelines: PipelineVariants,
}

impl BrsmViewPass {
    pub fn new(gpu: &Gpu) -> Result<Self> {
        Ok(Self { pipelines: PipelineVariants::new(gpu, "passes/brsm_view_gbuffer.wgsl", "main")? })
    }

    /// Fills `grid` (from [`view_grid`]) from the camera G-buffer of `size`.
    pub fn record(&self, rec: &mut Recorder<'_>, gbuffer: &GBuffer, size: (u32, u32), grid: &Rsm, features: ShaderFeatures) {
        let gpu = rec.gpu;
        let pipeline = self.pipelines.get(gpu, &features.specular_flags());
        let uniform = rec.uniform("brsm_view_params_uniform_buffer", &ViewParamsRaw { width: size.0, height: size.1, grid: grid.size, _pad: 0 });
        let [position, normal, geo_normal, base_color] = gbuffer.bindings();
        rec.compute(
            "brsm_view_gbuffer",
            &pipeline,
            &[&[
                uniform.as_entire_binding(),
                position,
                normal,
                geo_normal,
                base_color,
                grid.gbuffer.position.as_entire_binding(),
                grid.gbuffer.normal.as_entire_binding(),
                grid.flux_diffuse.as_entire_binding(),
                grid.flux_specular.as_entire_binding(),
                grid.pyramid.as_entire_binding(),
            ]],
            (groups(grid.size, WORKGROUP), groups(grid.size, WORKGROUP), 1),
        );
    }
}
