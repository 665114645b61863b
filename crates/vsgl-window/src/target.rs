//! The window's target: the frame as presented (composition and panel), kept so a screenshot
//! copies what was shown.

use vsgl_core::gpu::Gpu;

/// RGBA8 unorm holding sRGB-encoded bytes: the frame's `ldr` words land in it unchanged.
pub const TARGET_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;

pub struct FrameTarget {
    pub texture: wgpu::Texture,
    pub view: wgpu::TextureView,
    pub size: (u32, u32),
}

impl FrameTarget {
    pub fn new(device: &wgpu::Device, size: (u32, u32)) -> Self {
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("window_target_texture"),
            size: wgpu::Extent3d { width: size.0, height: size.1, depth_or_array_layers: 1 },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: TARGET_FORMAT,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        });
        let view = texture.create_view(&Default::default());
        Self { texture, view, size }
    }

    /// The target's pixels, RGBA8 rows top to bottom (waits for the GPU).
    pub fn read(&self, gpu: &Gpu) -> vsgl_core::Result<Vec<u8>> {
        let (w, h) = self.size;
        let row = 4 * w;
        let padded = row.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
        let staging = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("window_screenshot_staging_buffer"),
            size: padded as u64 * h as u64,
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        encoder.copy_texture_to_buffer(
            self.texture.as_image_copy(),
            wgpu::TexelCopyBufferInfo { buffer: &staging, layout: wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(padded), rows_per_image: Some(h) } },
            wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 },
        );
        let submission = gpu.queue.submit([encoder.finish()]);
        let mut out = Vec::with_capacity((row * h) as usize);
        vsgl_core::gpu::read_staging_with(gpu, &staging, staging.size(), Some(&submission), "screenshot", |bytes| {
            for y in 0..h as usize {
                out.extend_from_slice(&bytes[y * padded as usize..y * padded as usize + row as usize]);
            }
        })?;
        Ok(out)
    }
}
