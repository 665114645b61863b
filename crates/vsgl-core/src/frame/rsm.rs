//! The reflective shadow map of one light and what the VSGL methods derive from it: the
//! per-texel buffers, the layout of its mip pyramids, and the VSGL moment chains.

use super::targets::GBuffer;
use crate::gpu::Recorder;

/// Level start offsets (level 0 = size², …, top = 1) and the total texel count, for a
/// power-of-two `size`.
pub fn pyramid_layout(size: u32) -> (Vec<u32>, u32) {
    let mut offsets = Vec::new();
    let mut offset = 0u32;
    let mut s = size;
    loop {
        offsets.push(offset);
        offset += s * s;
        if s == 1 {
            break;
        }
        s /= 2;
    }
    (offsets, offset)
}

/// The light an RSM was rendered from, as the passes that read its texels need it.
#[derive(Clone, Copy, Debug, Default)]
pub struct RsmLight {
    /// The light's position relative to the frame origin (RSM positions are relative to it).
    pub offset: [f32; 3],
    /// [`LightRaw::rsm_light_dir`](super::uniforms::LightRaw::rsm_light_dir).
    pub dir: [f32; 4],
    /// `LightRsm::texel_footprint`, or zeros for texels taken as points.
    pub texel_footprint: [f32; 4],
}

/// The per-texel RSM data: the light-view G-buffer plus flux and the weight pyramid.
pub struct Rsm {
    pub size: u32,
    pub gbuffer: GBuffer,
    pub flux_diffuse: wgpu::Buffer,
    pub flux_specular: wgpu::Buffer,
    /// Sampling-weight pyramid, all levels (see `pdf_mips`).
    pub pyramid: wgpu::Buffer,
    pub level_offsets: wgpu::Buffer,
    pub levels: u32,
    /// Whether the weight pyramid exists (the method samples texels by weight).
    pub sampling: bool,
}

impl Rsm {
    /// `specular = false` (no specular material): the specular flux is never written or read,
    /// so it gets a 16-byte placeholder; `sampling = false` (nothing is sampled from the RSM):
    /// neither is the weight pyramid.
    pub fn new(rec: &mut Recorder<'_>, size: u32, specular: bool, sampling: bool) -> Self {
        let texels = size as u64 * size as u64;
        let (offsets, total) = pyramid_layout(size);
        Self {
            size,
            gbuffer: GBuffer::new(rec, size, size),
            // rsm_flux writes every texel of both (zero where nothing reflects).
            flux_diffuse: rec.storage_written("rsm_flux_diffuse_buffer", texels * 16),
            flux_specular: rec.storage_written("rsm_flux_specular_buffer", if specular { texels * 16 } else { 16 }),
            pyramid: rec.storage("rsm_weight_pyramid_buffer", if sampling { total as u64 * 4 } else { 16 }),
            level_offsets: rec.storage_init("rsm_level_offset_buffer", bytemuck::cast_slice(&offsets)),
            levels: offsets.len() as u32,
            sampling,
        }
    }
}

/// A, B, C, D, E of `wgsl/passes/vsgl_moments.wgsl`: what every VSGL needs.
pub const BASE_CHAINS: u32 = 5;
/// With F (Σw·n, Σw·(y·n)), the clusters' tangent planes, which only the shading modes that
/// fade light below them read; left out otherwise.
pub const PLANE_CHAINS: u32 = 6;

/// The moment mip chains in one buffer (chain c at c·chain_len vec4s).
pub struct MomentChains {
    pub buffer: wgpu::Buffer,
    pub chain_len: u32,
    /// BASE_CHAINS or PLANE_CHAINS.
    pub count: u32,
}

impl MomentChains {
    pub fn new(rec: &mut Recorder<'_>, rsm_size: u32, with_planes: bool) -> Self {
        Self::labelled(rec, "vsgl_moment_chain_buffer", rsm_size, with_planes)
    }

    /// The chains in a buffer called `label` (the view's chains of bidirectional importance).
    pub fn labelled(rec: &mut Recorder<'_>, label: &str, rsm_size: u32, with_planes: bool) -> Self {
        let (_, chain_len) = pyramid_layout(rsm_size);
        let count = if with_planes { PLANE_CHAINS } else { BASE_CHAINS };
        Self { buffer: rec.storage(label, Self::bytes(rsm_size, with_planes)), chain_len, count }
    }

    /// Whether chain F (tangent planes) is present.
    pub fn has_planes(&self) -> bool {
        self.count == PLANE_CHAINS
    }

    /// Bytes needed for an RSM of side `rsm_size`.
    pub fn bytes(rsm_size: u32, with_planes: bool) -> u64 {
        let count = if with_planes { PLANE_CHAINS } else { BASE_CHAINS };
        count as u64 * pyramid_layout(rsm_size).1 as u64 * 16
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn layout_of_8() {
        assert_eq!(super::pyramid_layout(8), (vec![0, 64, 80, 84], 85));
    }
}
