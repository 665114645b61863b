//! Geometry-aware denoising of interleaved indirect light (compute): two separable
//! cross-bilateral passes (x, then y) over 2k + 1 taps each with weights symmetric in each pixel
//! pair: a normalised gather, or with `denoise_form="exchange"` an exchange of light between the
//! pairs that keeps the image's total (see `wgsl/passes/denoise.wgsl`).

use crate::error::Result;
use crate::frame::{GBuffer, IndirectTargets};
use crate::gpu::{groups, Gpu, PipelineVariants, Recorder};
use crate::plan::ShaderFeatures;

// Pixels per workgroup along the filter's axis (`TILE` in the shader); a workgroup is one line of
// them, so the x pass dispatches ceil(W/TILE) × H workgroups and the y pass ceil(H/TILE) × W.
use crate::shader_lib::constants::denoise::TILE;
// The largest radius the shader's workgroup span holds (`MAX_RADIUS`), and so the largest
// interleave tile side a method may take (its `interleave` option's bound).
pub use crate::shader_lib::constants::denoise::MAX_RADIUS;

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct DenoiseParamsRaw {
    radius: i32,
    direction: u32,
    keep_light: u32,
    _pad: u32,
}

pub struct DenoisePass {
    pipelines: PipelineVariants,
}

/// The frame the filter reads its edge-stopping weights from.
#[derive(Clone, Copy)]
pub struct DenoiseScreen<'a> {
    /// The frame's uniforms (camera).
    pub frame: &'a wgpu::Buffer,
    pub gbuffer: &'a GBuffer,
    pub features: ShaderFeatures,
    pub size: (u32, u32),
}

impl DenoisePass {
    pub fn new(gpu: &Gpu) -> Result<Self> {
        Ok(Self { pipelines: PipelineVariants::new(gpu, "passes/denoise.wgsl", "main")? })
    }

    /// Filters `noisy` into `out` through an intermediate (demodulated, x-filtered) pair;
    /// `keep_light`: by exchanges that keep the total light (`denoise_form="exchange"`), else as
    /// a normalised gather.
    pub fn record(&self, rec: &mut Recorder<'_>, screen: &DenoiseScreen<'_>, radius: u32, keep_light: bool, noisy: &IndirectTargets, out: &IndirectTargets) {
        let DenoiseScreen { frame, gbuffer, features, size } = *screen;
        debug_assert!(radius <= MAX_RADIUS, "denoise radius {radius} > {MAX_RADIUS}: the interleave option's bound");
        let gpu = rec.gpu;
        let pipeline = self.pipelines.get(gpu, &features.specular_flags());
        let bytes = size.0 as u64 * size.1 as u64 * 16;
        let across = IndirectTargets {
            // The x pass writes every pixel of both.
            diffuse: rec.storage_written("denoise_x_diffuse_buffer", bytes),
            specular: rec.storage_written("denoise_x_specular_buffer", bytes),
        };
        for (direction, input, output) in [(0u32, noisy, &across), (1u32, &across, out)] {
            let uniform = rec.uniform("denoise_params_uniform_buffer", &DenoiseParamsRaw { radius: radius as i32, direction, keep_light: u32::from(keep_light), _pad: 0 });
            rec.compute(
                "denoise",
                &pipeline,
                &[
                    &[frame.as_entire_binding()],
                    &[
                        uniform.as_entire_binding(),
                        gbuffer.position.as_entire_binding(),
                        gbuffer.normal.as_entire_binding(),
                        gbuffer.geo_normal.as_entire_binding(),
                        gbuffer.base_color.as_entire_binding(),
                        input.diffuse.as_entire_binding(),
                        input.specular.as_entire_binding(),
                        output.diffuse.as_entire_binding(),
                        output.specular.as_entire_binding(),
                    ],
                ],
                if direction == 0 { (groups(size.0, TILE), size.1, 1) } else { (groups(size.1, TILE), size.0, 1) },
            );
        }
    }
}
