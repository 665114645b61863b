//! AOV packing (compute): the AOVs a frame reads back, in NumPy's layout, into one buffer
//! (`wgsl/passes/aov_pack.wgsl`), so the readback moves only those bytes and the CPU converts
//! nothing.

use crate::error::Result;
use crate::frame::{GBuffer, IndirectTargets};
use crate::gpu::{groups, Gpu, Recorder};

use crate::shader_lib::constants::aov_pack::WORKGROUP;
/// Most AOVs one frame packs (`MAX_ENTRIES` in the shader).
pub const MAX_ENTRIES: usize = crate::shader_lib::constants::aov_pack::MAX_ENTRIES as usize;

/// An AOV to pack: its kind (index in `renderer::AOV_NAMES`, or [`LDR_KIND`]) and its first
/// 4-byte word in the packed buffer.
#[derive(Clone, Copy, Debug)]
pub struct PackEntry {
    pub kind: u32,
    pub first_word: u32,
}

/// The kind of the 8-bit tone-mapped AOV (`AOV_LDR` in the shader).
pub const LDR_KIND: u32 = crate::shader_lib::constants::aov_pack::AOV_LDR;

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct PackParamsRaw {
    width: u32,
    height: u32,
    count: u32,
    flags: u32,
    entries: [[u32; 4]; MAX_ENTRIES],
}
const _: () = assert!(std::mem::size_of::<PackParamsRaw>() == 16 + 16 * MAX_ENTRIES);

/// What the AOVs are made from.
pub struct PackSources<'a> {
    pub direct: &'a wgpu::Buffer,
    pub indirect: &'a IndirectTargets,
    pub gbuffer: &'a GBuffer,
    /// The path tracer's standard error (another buffer stands in when there is none).
    pub stderr: Option<&'a wgpu::Buffer>,
    /// The method makes indirect light (else the image is the direct light).
    pub indirect_light: bool,
    /// The specular target exists (else it is a placeholder that reads as zero).
    pub specular: bool,
    /// The emitter VSGLs' direct light (`emitter_direct="sg"`), added to `direct`; `None`
    /// leaves every value as it was without (the buffers are not read).
    pub emitter_direct: Option<&'a IndirectTargets>,
}

pub struct AovPackPass {
    pipeline: wgpu::ComputePipeline,
}

impl AovPackPass {
    pub fn new(gpu: &Gpu) -> Result<Self> {
        let module = gpu.shader("passes/aov_pack.wgsl")?;
        Ok(Self { pipeline: gpu.compute_pipeline("aov_pack_pipeline", &module, "main") })
    }

    /// Packs `entries` (at most [`MAX_ENTRIES`]) of a `size` frame into `out`, and counts into
    /// `counts` (zero before the pass) each entry's non-finite values, then the pixels that see
    /// a surface and those whose image is not black.
    pub fn record(&self, rec: &mut Recorder<'_>, src: &PackSources<'_>, entries: &[PackEntry], out: &wgpu::Buffer, counts: &wgpu::Buffer, size: (u32, u32)) {
        let mut raw = PackParamsRaw {
            width: size.0,
            height: size.1,
            count: entries.len().min(MAX_ENTRIES) as u32,
            flags: src.indirect_light as u32 | (src.specular as u32) << 1 | (src.gbuffer.has_emission as u32) << 2 | (src.emitter_direct.is_some() as u32) << 3,
            entries: [[0; 4]; MAX_ENTRIES],
        };
        for (slot, e) in raw.entries.iter_mut().zip(entries) {
            *slot = [e.kind, e.first_word, 0, 0];
        }
        let uniform = rec.uniform("aov_pack_params_uniform_buffer", &raw);
        let stderr = src.stderr.unwrap_or(src.direct);
        // Without emitter VSGLs the indirect targets stand in for their bindings (not read).
        let emitters = src.emitter_direct.unwrap_or(src.indirect);
        rec.compute(
            "aov_pack",
            &self.pipeline,
            &[&[
                uniform.as_entire_binding(),
                src.direct.as_entire_binding(),
                src.indirect.diffuse.as_entire_binding(),
                src.indirect.specular.as_entire_binding(),
                src.gbuffer.position.as_entire_binding(),
                src.gbuffer.normal.as_entire_binding(),
                src.gbuffer.base_color.as_entire_binding(),
                stderr.as_entire_binding(),
                out.as_entire_binding(),
                counts.as_entire_binding(),
                src.gbuffer.emission.as_entire_binding(),
                emitters.diffuse.as_entire_binding(),
                emitters.specular.as_entire_binding(),
            ]],
            (groups(size.0, WORKGROUP), groups(size.1, WORKGROUP), 1),
        );
    }
}
