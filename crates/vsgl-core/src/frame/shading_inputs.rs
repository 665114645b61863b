//! What a virtual-light shading pass (`vpl_shading`, `vsgl_shading`) reads and writes for one
//! frame, and the list of virtual lights it shades: the arguments every such pass takes, named
//! once instead of passed one by one.

use super::{GBuffer, IndirectTargets, ShadingVisibility};
use crate::plan::ShaderFeatures;

/// The frame a shading pass adds its light into.
#[derive(Clone, Copy)]
pub struct ShadingInputs<'a> {
    /// The frame's uniforms (camera, output size).
    pub frame_uniforms: &'a wgpu::Buffer,
    pub gbuffer: &'a GBuffer,
    /// The targets the pass adds into: the frame's indirect targets, or the noisy ones the
    /// denoiser resolves when shading is interleaved and filtered.
    pub out: &'a IndirectTargets,
    pub features: ShaderFeatures,
    /// Output size in pixels.
    pub size: (u32, u32),
    /// Shadow rays or imperfect shadow maps for the virtual lights, or neither.
    pub visibility: &'a ShadingVisibility,
}

/// The virtual lights to shade: `count` records in `records`, split among the pixels of each
/// k × k block by interleaved sampling (`interleave` = k; 1 gives every pixel every light).
#[derive(Clone, Copy)]
pub struct VirtualLightList<'a> {
    pub records: &'a wgpu::Buffer,
    pub count: u32,
    pub interleave: u32,
}
