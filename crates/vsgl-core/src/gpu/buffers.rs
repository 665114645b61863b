//! Buffers: uniforms from `Pod` twins of WGSL structs, logged storage buffers, and readback.

use super::frame_log::{note_allocation, note_use};
use super::Gpu;
use crate::error::{Error, Result};

impl Gpu {
    /// Reads back whole buffers (each must have COPY_SRC) as f32/u32 words, waiting for the GPU.
    pub fn read_buffers(&self, buffers: &[&wgpu::Buffer]) -> Result<Vec<Vec<u8>>> {
        let mut enc = self.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("readback_encoder") });
        let staging: Vec<wgpu::Buffer> = buffers
            .iter()
            .map(|b| {
                let s = self.device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("readback_staging_buffer"),
                    size: b.size(),
                    usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                });
                enc.copy_buffer_to_buffer(b, 0, &s, 0, b.size());
                s
            })
            .collect();
        self.queue.submit([enc.finish()]);
        for s in &staging {
            s.slice(..).map_async(wgpu::MapMode::Read, |_| {});
        }
        self.wait("readback")?;
        let mut out = Vec::with_capacity(staging.len());
        for s in &staging {
            let view = s
                .slice(..)
                .get_mapped_range()
                .map_err(|e| Error::Validation { context: "readback".into(), message: e.to_string() })?;
            out.push(view.to_vec());
            drop(view);
            s.unmap();
        }
        Ok(out)
    }
}

/// A uniform buffer holding `value` (a `#[repr(C)]` twin of a WGSL struct).
pub fn uniform_buffer<T: bytemuck::Pod>(gpu: &Gpu, label: &str, value: &T) -> wgpu::Buffer {
    wgpu::util::DeviceExt::create_buffer_init(
        &gpu.device,
        &wgpu::util::BufferInitDescriptor { label: Some(label), contents: bytemuck::bytes_of(value), usage: wgpu::BufferUsages::UNIFORM },
    )
}

/// A storage buffer of `size` bytes (at least 16, as wgpu rejects empty bindings), created now
/// (frames get theirs from [`super::Recorder::storage`], which keeps them across frames).
pub fn storage_buffer(gpu: &Gpu, label: &str, size: u64) -> wgpu::Buffer {
    note_allocation(label, size.max(16));
    note_use(label, size.max(16));
    gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: size.max(16),
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}
