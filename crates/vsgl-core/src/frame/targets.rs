//! Per-frame targets that several passes share: the visibility buffer, the G-buffer and the
//! indirect radiance targets. A pass that reads or writes one takes it as an argument; none of
//! them belongs to a pass.

use crate::gpu::Recorder;

/// Formats of the visibility buffer: depth (reverse-Z) and the visible triangle id.
pub const VISIBILITY_DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
pub const VISIBILITY_ID_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R32Uint;

/// The visibility buffer: depth and the visible triangle id per pixel (raster output).
pub struct VisibilityTargets {
    pub ids: wgpu::TextureView,
    pub depth: wgpu::TextureView,
}

impl VisibilityTargets {
    /// Depth and triangle-id targets of `width`×`height`.
    pub fn new(rec: &mut Recorder<'_>, width: u32, height: u32) -> Self {
        let mut make = |label, format, usage| {
            let desc = wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d { width, height, depth_or_array_layers: 1 },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage,
                view_formats: &[],
            };
            // Both formats are 4 bytes a texel (r32uint ids, depth32float).
            let texture = rec.texture(&desc, width as u64 * height as u64 * 4);
            rec.texture_view(&texture, &Default::default())
        };
        let usage = wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING;
        Self {
            ids: make("visibility_id_texture", VISIBILITY_ID_FORMAT, usage),
            depth: make("visibility_depth_texture", VISIBILITY_DEPTH_FORMAT, usage),
        }
    }
}

/// The G-buffer: four vec4f storage buffers (layout in `wgsl/common/gbuffer.wgsl`), and the
/// emitted radiance the camera sees.
pub struct GBuffer {
    pub position: wgpu::Buffer,
    pub normal: wgpu::Buffer,
    pub geo_normal: wgpu::Buffer,
    pub base_color: wgpu::Buffer,
    /// Emitted radiance (rgb) per pixel when `has_emission`, else a 16-byte placeholder that
    /// keeps the bind group layouts (the material pass then compiles the write out).
    pub emission: wgpu::Buffer,
    pub has_emission: bool,
    /// Width and height in texels (what the passes writing it dispatch over).
    pub size: (u32, u32),
}

impl GBuffer {
    /// The four buffers in layout order (position, normal, geo_normal, base_color), as the
    /// passes that read the G-buffer bind them.
    pub fn bindings(&self) -> [wgpu::BindingResource<'_>; 4] {
        [
            self.position.as_entire_binding(),
            self.normal.as_entire_binding(),
            self.geo_normal.as_entire_binding(),
            self.base_color.as_entire_binding(),
        ]
    }
}

impl GBuffer {
    /// A G-buffer without emission: a light's view (emissive surfaces light nothing, so an RSM
    /// never needs them) or a scene where nothing emits.
    pub fn new(rec: &mut Recorder<'_>, width: u32, height: u32) -> Self {
        Self::with_emission(rec, width, height, false)
    }

    /// `emission`: whether the material pass writes the emitted radiance of every pixel.
    pub fn with_emission(rec: &mut Recorder<'_>, width: u32, height: u32, emission: bool) -> Self {
        let texels = width as u64 * height as u64 * 16;
        // The material pass writes every texel (background ones too): nothing to clear.
        let mut make = |label, bytes| rec.storage_written(label, bytes);
        Self {
            position: make("gbuffer_position_buffer", texels),
            normal: make("gbuffer_normal_buffer", texels),
            geo_normal: make("gbuffer_geo_normal_buffer", texels),
            base_color: make("gbuffer_base_color_buffer", texels),
            emission: make("gbuffer_emission_buffer", if emission { texels } else { 16 }),
            has_emission: emission,
            size: (width, height),
        }
    }
}

/// Diffuse and specular indirect radiance (vec4f per pixel each).
pub struct IndirectTargets {
    pub diffuse: wgpu::Buffer,
    pub specular: wgpu::Buffer,
}

impl IndirectTargets {
    /// What a shading pass binds (group 1): its parameters, its light list, the G-buffer and
    /// both targets, in the order of vpl_shading.wgsl and vsgl_shading.wgsl.
    pub fn shading_bindings<'a>(&'a self, params: &'a wgpu::Buffer, lights: &'a wgpu::Buffer, gbuffer: &'a GBuffer) -> Vec<wgpu::BindingResource<'a>> {
        let mut b = vec![params.as_entire_binding(), lights.as_entire_binding()];
        b.extend(gbuffer.bindings());
        b.extend([self.diffuse.as_entire_binding(), self.specular.as_entire_binding()]);
        b
    }
}
