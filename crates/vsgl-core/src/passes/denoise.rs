//! Geometry-aware denoising of interleaved indirect light (compute), (2k)² window.

use super::run_compute;
use crate::error::Result;
use crate::gpu::{groups, Gpu, PassTimer};
use crate::passes::material::GBuffer;
use crate::passes::vpl_shading::IndirectTargets;
use wgpu::util::DeviceExt;

const WORKGROUP: u32 = 8;

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct DenoiseParamsRaw {
    radius: i32,
    _pad: [u32; 3],
}

pub struct DenoisePass {
    pipeline: wgpu::ComputePipeline,
}

impl DenoisePass {
    pub fn new(gpu: &Gpu) -> Result<Self> {
        let module = gpu.shader("passes/denoise.wgsl")?;
        Ok(Self { pipeline: gpu.compute_pipeline("denoise_pipeline", &module, "main") })
    }

    #[allow(clippy::too_many_arguments)]
    pub fn record(&self, gpu: &Gpu, enc: &mut wgpu::CommandEncoder, timer: &mut PassTimer, frame: &wgpu::Buffer, radius: u32, gbuffer: &GBuffer, noisy: &IndirectTargets, out: &IndirectTargets, size: (u32, u32)) {
        let uniform = gpu.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("denoise_params_uniform_buffer"),
            contents: bytemuck::bytes_of(&DenoiseParamsRaw { radius: radius as i32, _pad: [0; 3] }),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        run_compute(
            gpu,
            enc,
            timer,
            "denoise",
            &self.pipeline,
            &[
                &[frame.as_entire_binding()],
                &[
                    uniform.as_entire_binding(),
                    gbuffer.position.as_entire_binding(),
                    gbuffer.normal.as_entire_binding(),
                    gbuffer.geo_normal.as_entire_binding(),
                    gbuffer.base_color.as_entire_binding(),
                    noisy.diffuse.as_entire_binding(),
                    noisy.specular.as_entire_binding(),
                    out.diffuse.as_entire_binding(),
                    out.specular.as_entire_binding(),
                ],
            ],
            (groups(size.0, WORKGROUP), groups(size.1, WORKGROUP), 1),
        );
    }
}
