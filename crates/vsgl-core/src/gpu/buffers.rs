//! Buffers made outside a frame (a frame gets its own from `Recorder`, which keeps them) and
//! readback of whole buffers.

use super::frame_log::{note_allocation, note_use};
use super::Gpu;
use crate::error::{Error, Result};

impl Gpu {
    /// Reads back whole buffers (each must have COPY_SRC) as f32/u32 words, waiting for the GPU.
    /// Staging buffers made here count as the frame's allocations (`allocated_bytes`): frame
    /// loops read back through staging buffers they keep instead (`read_staging`).
    pub fn read_buffers(&self, buffers: &[&wgpu::Buffer]) -> Result<Vec<Vec<u8>>> {
        let mut enc = self.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("readback_encoder") });
        let staging: Vec<wgpu::Buffer> = buffers
            .iter()
            .map(|b| {
                note_allocation("readback_staging_buffer", b.size());
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
        let submission = self.queue.submit([enc.finish()]);
        staging.iter().map(|s| read_staging::<u8>(self, s, s.size(), Some(&submission), "readback")).collect()
    }
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

/// A MAP_READ | COPY_DST buffer of `size` bytes (at least 16) for `kept`, which holds it from
/// frame to frame: reused when its size matches, else made now (and logged as the frame's
/// allocation). Whoever keeps it must not hand it to two frames in flight at once.
pub fn kept_staging_buffer(gpu: &Gpu, kept: &mut Option<wgpu::Buffer>, label: &str, size: u64) -> wgpu::Buffer {
    let size = size.max(16);
    note_use(label, size);
    if let Some(b) = kept.as_ref().filter(|b| b.size() == size) {
        return b.clone();
    }
    note_allocation(label, size);
    let usage = wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST;
    let b = gpu.device.create_buffer(&wgpu::BufferDescriptor { label: Some(label), size, usage, mapped_at_creation: false });
    *kept = Some(b.clone());
    b
}

/// Calls `f` on the first `bytes` of a MAP_READ `staging` buffer whose copy is already
/// submitted (in `submission`; `None`: anything submitted so far): maps it, waits for that
/// submission only, and unmaps it on every path, so a later frame can copy into it again.
/// `f` copies out what it keeps (the mapping may not be aligned).
pub fn read_staging_with<R>(gpu: &Gpu, staging: &wgpu::Buffer, bytes: u64, submission: Option<&wgpu::SubmissionIndex>, context: &str, f: impl FnOnce(&[u8]) -> R) -> Result<R> {
    let slice = staging.slice(..bytes);
    slice.map_async(wgpu::MapMode::Read, |_| {});
    gpu.wait_for(submission, context)?;
    let value = slice.get_mapped_range().map(|view| f(&view));
    staging.unmap();
    value.map_err(|e| Error::Validation { context: context.into(), message: e.to_string() })
}

/// [`read_staging_with`] copying the bytes out as `T`s.
pub fn read_staging<T: bytemuck::Pod>(gpu: &Gpu, staging: &wgpu::Buffer, bytes: u64, submission: Option<&wgpu::SubmissionIndex>, context: &str) -> Result<Vec<T>> {
    read_staging_with(gpu, staging, bytes, submission, context, |view| bytemuck::pod_collect_to_vec::<u8, T>(view))
}

/// Bytes of one page of a storage array that may outgrow one binding (the scene's vertices, the
/// BVH's nodes and triangle corners): 128 MiB, wgpu's default per-binding limit and lavapipe's
/// own. Such an array lives in one buffer (buffers may be far larger than a binding) and is
/// bound as [`STORAGE_PAGES`] ranges of this size; the shaders pick the page from the index
/// (`wgsl/common/storage_pages.wgsl`). Fixed, not the adapter's limit, so the shaders' page
/// shifts are constants.
pub const STORAGE_PAGE_BYTES: u64 = 1 << 27;
/// Pages bound per paged array: 512 MiB in all (8M vertices, 16M BVH nodes, 32M triangle
/// corners; the scene's 4-byte index array, bound whole, stops at 10.7M triangles first).
pub const STORAGE_PAGES: usize = 4;

/// The [`STORAGE_PAGES`] bindings of a paged storage array in `buffer`: page k is the range at
/// k·[`STORAGE_PAGE_BYTES`] (its last page shorter); pages past the end bind the first again
/// (read-only, so binding one range twice is allowed), which no index reaches.
pub fn storage_pages(buffer: &wgpu::Buffer) -> [wgpu::BindingResource<'_>; STORAGE_PAGES] {
    let bytes = buffer.size();
    std::array::from_fn(|k| {
        let start = k as u64 * STORAGE_PAGE_BYTES;
        let offset = if start < bytes { start } else { 0 };
        let size = (bytes - offset).min(STORAGE_PAGE_BYTES);
        wgpu::BindingResource::Buffer(wgpu::BufferBinding { buffer, offset, size: std::num::NonZeroU64::new(size) })
    })
}

/// The bindings of pages 1 … [`STORAGE_PAGES`] − 1 of each of `buffers`, array by array (the
/// shaders declare them in this order after their other bindings; page 0 keeps each array's own
/// binding).
pub fn later_storage_pages<'a>(buffers: &[&'a wgpu::Buffer]) -> Vec<wgpu::BindingResource<'a>> {
    buffers.iter().flat_map(|b| storage_pages(b).into_iter().skip(1)).collect()
}

/// Whether a paged array in `buffer` reaches past its first page: then the shaders that read it
/// run with `STORAGE_PAGED` (wgsl/common/storage_pages.wgsl), which tests each index's page.
pub fn spans_pages(buffer: &wgpu::Buffer) -> bool {
    buffer.size() > STORAGE_PAGE_BYTES
}

/// The most bytes of a paged array an adapter whose storage bindings hold at most
/// `binding_limit` bytes can bind: [`STORAGE_PAGES`] pages when a page fits in a binding (also
/// where a binding could hold more: the shaders' pages are fixed), else one shorter binding.
pub fn storage_pages_capacity(binding_limit: u64) -> u64 {
    if binding_limit >= STORAGE_PAGE_BYTES {
        STORAGE_PAGES as u64 * STORAGE_PAGE_BYTES
    } else {
        binding_limit
    }
}

// The shaders' page shifts are the page's element counts: 64-byte vertices, 32-byte BVH nodes,
// 16-byte triangle corners.
const _: () = {
    use crate::shader_lib::constants::pathtrace::{BVH_NODE_PAGE_SHIFT, CORNER_PAGE_SHIFT, VERTEX_PAGE_SHIFT};
    assert!(STORAGE_PAGE_BYTES == 64 << VERTEX_PAGE_SHIFT);
    assert!(STORAGE_PAGE_BYTES == 32 << BVH_NODE_PAGE_SHIFT);
    assert!(STORAGE_PAGE_BYTES == 16 << CORNER_PAGE_SHIFT);
};

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paged_arrays_hold_four_pages_where_a_page_fits_a_binding_and_one_binding_otherwise() {
        // lavapipe and wgpu's defaults: 128 MiB a binding, so four pages of it.
        assert_eq!(storage_pages_capacity(STORAGE_PAGE_BYTES), 4 * STORAGE_PAGE_BYTES);
        // A GPU whose bindings hold more still gets the shaders' fixed pages, not its limit.
        assert_eq!(storage_pages_capacity(1 << 32), 4 * STORAGE_PAGE_BYTES);
        // An adapter whose bindings hold less than a page: one binding, no paging.
        assert_eq!(storage_pages_capacity(64 << 20), 64 << 20);
    }
}
