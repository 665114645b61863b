//! Reading a frame's AOVs back: the GPU packs the asked-for AOVs in NumPy's layout into one
//! buffer (`passes/aov_pack.rs`), which is copied in the frame's own submission into a staging
//! buffer of the frame's readback slot (kept from frame to frame, never shared by two frames in
//! flight); the CPU then only splits the mapped bytes into the AOVs.

use super::options::{RenderOptions, AOV_NAMES};
use crate::error::{Error, Result};
use crate::gpu::{kept_staging_buffer, read_staging_with, Gpu, Recorder};
use crate::methods::MethodInfo;
use crate::passes::aov_pack::{AovPackPass, PackEntry, PackSources, LDR_KIND, MAX_ENTRIES};

/// Float AOVs (name, channels, data) and the 8-bit `ldr` image (RGBA per pixel) if asked for.
pub(super) struct Aovs {
    pub float: Vec<(String, usize, Vec<f32>)>,
    pub ldr: Option<Vec<u8>>,
    /// Pixels that see a surface and pixels whose image is not black (`None` when nothing was
    /// packed, i.e. `aovs=[]`).
    pub coverage: Option<(u32, u32)>,
}

/// Channels of a float AOV (4-byte words per pixel of any AOV).
fn words_per_pixel(name: &str) -> usize {
    match name {
        "depth" | "ldr" => 1,
        _ => 3,
    }
}

/// The packed AOVs of a frame: where each lies in the staging buffer, to read after submission.
pub(super) struct PendingAovs {
    layout: Vec<(&'static str, usize, u64)>,
    staging: Option<wgpu::Buffer>,
    /// The packed AOVs themselves when the frame keeps them on the GPU (no staging copy).
    kept: Option<wgpu::Buffer>,
    pixels: usize,
    /// Where the per-AOV counts of non-finite values lie in the staging buffer.
    counts_offset: u64,
}

/// Bytes of the counts after the packed AOVs: non-finite values per pack entry, then pixels
/// that see a surface, then pixels whose image is not black (`wgsl/passes/aov_pack.wgsl`).
const COUNTS_BYTES: u64 = (MAX_ENTRIES as u64 + 2) * 4;

/// Records the packing of the AOVs `opts` asks for (all float AOVs the method makes when it
/// names none) and their copy into the staging buffer `kept` (made or resized as needed).
pub(super) fn record_aovs(rec: &mut Recorder<'_>, pack: &AovPackPass, opts: &RenderOptions, info: &MethodInfo, src: &PackSources<'_>, size: (u32, u32), kept: &mut Option<wgpu::Buffer>) -> PendingAovs {
    let pixels = size.0 as usize * size.1 as usize;
    let mut layout = Vec::new();
    let mut entries = Vec::new();
    let mut words = 0u64;
    for (kind, name) in AOV_NAMES.iter().enumerate() {
        let wanted = opts.wants_aov(info, name) && (*name != "stderr" || src.stderr.is_some());
        if !wanted {
            continue;
        }
        let kind = if *name == "ldr" { LDR_KIND } else { kind as u32 };
        entries.push(PackEntry { kind, first_word: words as u32 });
        layout.push((*name, words_per_pixel(name), words * 4));
        words += (words_per_pixel(name) * pixels) as u64;
    }
    debug_assert!(entries.len() <= MAX_ENTRIES);
    if entries.is_empty() {
        return PendingAovs { layout, staging: None, kept: None, pixels, counts_offset: 0 };
    }
    let bytes = words * 4;
    // Every word is written by the pack pass: no clear needed on reuse.
    let packed = rec.storage_written("aov_pack_buffer", bytes);
    // Zeroed for every frame (storage() clears a kept buffer).
    let counts = rec.storage("aov_count_buffer", COUNTS_BYTES);
    pack.record(rec, src, &entries, &packed, &counts, size);
    if opts.keep_on_gpu {
        return PendingAovs { layout, staging: None, kept: Some(packed), pixels, counts_offset: bytes };
    }
    let staging = kept_staging_buffer(rec.gpu, kept, "aov_readback_staging_buffer", bytes + COUNTS_BYTES);
    rec.enc.copy_buffer_to_buffer(&packed, 0, &staging, 0, bytes);
    rec.enc.copy_buffer_to_buffer(&counts, 0, &staging, bytes, COUNTS_BYTES);
    PendingAovs { layout, staging: Some(staging), kept: None, pixels, counts_offset: bytes }
}

impl PendingAovs {
    /// The buffer and byte offset of AOV `name` of a frame that keeps its AOVs on the GPU
    /// (`ldr`: one RGBA8 word a pixel, rows top to bottom).
    pub(super) fn kept(&self, name: &str) -> Option<(&wgpu::Buffer, u64)> {
        let buffer = self.kept.as_ref()?;
        self.layout.iter().find(|(n, _, _)| *n == name).map(|(_, _, offset)| (buffer, *offset))
    }

    /// Waits for the frame's submission (not for later ones) and splits the staging buffer
    /// into the AOVs; an AOV with a NaN or Inf value is an [`Error::NonFinite`] naming it.
    pub(super) fn read(self, gpu: &Gpu, submission: &wgpu::SubmissionIndex) -> Result<Aovs> {
        let mut out = Aovs { float: Vec::new(), ldr: None, coverage: None };
        let Some(staging) = self.staging else { return Ok(out) };
        let mut nonfinite: Vec<(&str, u32)> = Vec::new();
        // One copy of each AOV, straight out of the mapped memory.
        read_staging_with(gpu, &staging, staging.size(), Some(submission), "readback", |bytes| {
            let counts: Vec<u32> = bytemuck::pod_collect_to_vec(&bytes[self.counts_offset as usize..(self.counts_offset + COUNTS_BYTES) as usize]);
            nonfinite = self.layout.iter().zip(&counts).filter(|(_, c)| **c > 0).map(|((name, _, _), c)| (*name, *c)).collect();
            out.coverage = Some((counts[MAX_ENTRIES], counts[MAX_ENTRIES + 1]));
            if !nonfinite.is_empty() {
                return;
            }
            for (name, words, offset) in &self.layout {
                let start = *offset as usize;
                let data = &bytes[start..start + words * self.pixels * 4];
                if *name == "ldr" {
                    out.ldr = Some(data.to_vec());
                } else {
                    out.float.push((name.to_string(), *words, bytemuck::pod_collect_to_vec::<u8, f32>(data)));
                }
            }
        })?;
        if !nonfinite.is_empty() {
            let what: Vec<String> = nonfinite.iter().map(|(name, c)| format!("{c} in {name:?}")).collect();
            return Err(Error::NonFinite { message: format!("non-finite values (NaN or Inf) in the frame: {}", what.join(", ")) });
        }
        Ok(out)
    }
}
