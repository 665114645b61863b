//! Per-pass GPU timestamps: two queries per pass, resolved once per frame.

use super::Gpu;
use crate::error::Result;

/// Per-pass GPU timestamps: two queries per pass, resolved once per frame.
pub struct PassTimer {
    pub query_set: Option<wgpu::QuerySet>,
    resolve: Option<wgpu::Buffer>,
    /// Where `resolve` copies the timestamps in the frame's own submission, so reading them
    /// needs no second submission and no buffer made per frame.
    staging: Option<wgpu::Buffer>,
    names: Vec<String>,
    capacity: u32,
    period_ns: f32,
}

impl PassTimer {
    pub fn new(gpu: &Gpu, capacity: u32) -> Self {
        let (query_set, resolve) = if gpu.timestamps {
            let qs = gpu.device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("frame_timestamp_query_set"),
                ty: wgpu::QueryType::Timestamp,
                count: capacity * 2,
            });
            let rb = gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("frame_timestamp_resolve_buffer"),
                size: capacity as u64 * 2 * 8,
                usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            });
            (Some(qs), Some(rb))
        } else {
            (None, None)
        };
        let staging = resolve.as_ref().map(|rb| {
            gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("frame_timestamp_staging_buffer"),
                size: rb.size(),
                usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        });
        Self { query_set, resolve, staging, names: Vec::new(), capacity, period_ns: gpu.queue.get_timestamp_period() }
    }

    /// A timer that records nothing (for work that is not a pass of its own).
    pub fn new_disabled() -> Self {
        Self { query_set: None, resolve: None, staging: None, names: Vec::new(), capacity: 0, period_ns: 1.0 }
    }

    /// Forgets the passes of the previous frame (the queries are reused).
    pub fn reset(&mut self) {
        self.names.clear();
    }

    /// Registers a pass; returns the (begin, end) query indices when timestamps are on.
    /// `name` may carry the variant in brackets (`"vpl_sample[every_texel]"`): the frame log
    /// records it as is (`frame.passes`: what ran, reported by the code that ran it), the
    /// timings under the bare pass name.
    pub fn begin(&mut self, name: &str) -> Option<(u32, u32)> {
        if self.capacity > 0 {
            super::frame_log::note_pass(name);
        }
        self.query_set.as_ref()?;
        let i = self.names.len() as u32;
        if i >= self.capacity {
            return None;
        }
        self.names.push(name.split('[').next().unwrap_or(name).to_string());
        Some((2 * i, 2 * i + 1))
    }

    pub fn compute_writes(&self, q: Option<(u32, u32)>) -> Option<wgpu::ComputePassTimestampWrites<'_>> {
        let (b, e) = q?;
        Some(wgpu::ComputePassTimestampWrites {
            query_set: self.query_set.as_ref()?,
            beginning_of_pass_write_index: Some(b),
            end_of_pass_write_index: Some(e),
        })
    }

    pub fn render_writes(&self, q: Option<(u32, u32)>) -> Option<wgpu::RenderPassTimestampWrites<'_>> {
        let (b, e) = q?;
        Some(wgpu::RenderPassTimestampWrites {
            query_set: self.query_set.as_ref()?,
            beginning_of_pass_write_index: Some(b),
            end_of_pass_write_index: Some(e),
        })
    }

    /// Resolves this frame's queries and copies them to the staging buffer (in `enc`, the
    /// frame's last encoder).
    pub fn resolve(&self, enc: &mut wgpu::CommandEncoder) {
        if let (Some(qs), Some(rb), Some(st)) = (&self.query_set, &self.resolve, &self.staging) {
            if !self.names.is_empty() {
                let used = self.names.len() as u32 * 2;
                enc.resolve_query_set(qs, 0..used, rb, 0);
                enc.copy_buffer_to_buffer(rb, 0, st, 0, used as u64 * 8);
            }
        }
    }

    /// Milliseconds per pass (same name twice adds up), once `submission` (the frame's last,
    /// which resolved the queries) has finished.
    pub fn read(&self, gpu: &Gpu, submission: &wgpu::SubmissionIndex) -> Result<Vec<(String, f64)>> {
        let Some(st) = &self.staging else { return Ok(Vec::new()) };
        if self.names.is_empty() {
            return Ok(Vec::new());
        }
        let ticks: Vec<u64> = super::read_staging(gpu, st, self.names.len() as u64 * 16, Some(submission), "timestamp readback")?;
        let mut out: Vec<(String, f64)> = Vec::new();
        for (i, name) in self.names.iter().enumerate() {
            let dt = ticks[2 * i + 1].saturating_sub(ticks[2 * i]) as f64 * self.period_ns as f64 * 1e-6;
            match out.iter_mut().find(|(n, _)| n == name) {
                Some((_, t)) => *t += dt,
                None => out.push((name.clone(), dt)),
            }
        }
        Ok(out)
    }
}
