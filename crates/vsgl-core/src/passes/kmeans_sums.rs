//! k-means cluster sums and VSGLs (compute): each cluster's run of the texels sorted by cluster
//! id summed in two levels, the VSGL built from the sums as the sampled kernels build theirs,
//! candidate shadow targets, and Lloyd's next centres (`wgsl/passes/kmeans_sums.wgsl`).

use super::kmeans_centres::KmeansSpace;
use crate::error::Result;
use crate::frame::{MomentChains, Rsm};
use crate::gpu::{groups, storage_binding, uniform_binding, Gpu, Recorder};

use crate::shader_lib::constants::kmeans_sums::{PART, PARTIAL_ROWS, WORKGROUP};

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct SumParamsRaw {
    count: u32,
    rsm_size: u32,
    space: u32,
    chain_len: u32,
    light_offset: [f32; 3],
    planes: u32,
    levels: u32,
    shadow_candidates: u32,
    seed: u32,
    _pad: u32,
}

/// Bytes of the run sums of an `rsm_size`² RSM cut into `count` clusters.
pub fn partial_bytes(rsm_size: u32, count: u32) -> u64 {
    let texels = u64::from(rsm_size) * u64::from(rsm_size);
    (texels.div_ceil(u64::from(PART)) + u64::from(count) + 1) * u64::from(PARTIAL_ROWS) * 16
}

/// The sorted texels and the clusters' centres.
#[derive(Clone, Copy)]
pub struct SortedClusters<'a> {
    pub count: u32,
    pub space: KmeansSpace,
    pub keys: &'a wgpu::Buffer,
    pub texels: &'a wgpu::Buffer,
    pub centres: &'a wgpu::Buffer,
}

/// What the sums write.
#[derive(Clone, Copy)]
pub struct ClusterOutputs<'a> {
    pub partials: &'a wgpu::Buffer,
    pub next_centres: &'a wgpu::Buffer,
    pub vsgls: &'a wgpu::Buffer,
    /// `candidates` rows per VSGL (vsgl_gen's layout), or none.
    pub shadow_candidates: Option<(&'a wgpu::Buffer, u32)>,
    pub seed: u32,
    pub light_offset: [f32; 3],
}

pub struct KmeansSumsPass {
    parts: wgpu::ComputePipeline,
    clusters: wgpu::ComputePipeline,
}

impl KmeansSumsPass {
    pub fn new(gpu: &Gpu) -> Result<Self> {
        let module = gpu.shader("passes/kmeans_sums.wgsl")?;
        let (read, write) = (storage_binding(true), storage_binding(false));
        let bindings = [uniform_binding(), read, read, read, write, read, write, write, write, read, read];
        Ok(Self {
            parts: gpu.compute_pipeline_explicit("kmeans_sums_parts_pipeline", &module, "parts", &bindings),
            clusters: gpu.compute_pipeline_explicit("kmeans_sums_clusters_pipeline", &module, "clusters", &bindings),
        })
    }

    pub fn record(&self, rec: &mut Recorder<'_>, rsm: &Rsm, chains: &MomentChains, sorted: &SortedClusters<'_>, out: &ClusterOutputs<'_>) {
        let per_vsgl = out.shadow_candidates.map_or(0, |(_, n)| n);
        // Unwritten without candidates: a small placeholder of its own.
        let placeholder;
        let candidates = match out.shadow_candidates {
            Some((b, _)) => b,
            None => {
                placeholder = rec.storage("kmeans_shadow_candidates_placeholder_buffer", 32);
                &placeholder
            }
        };
        let params = SumParamsRaw {
            count: sorted.count,
            rsm_size: rsm.size,
            space: sorted.space.shader_code(),
            chain_len: chains.chain_len,
            light_offset: out.light_offset,
            planes: u32::from(chains.has_planes()),
            levels: rsm.levels,
            shadow_candidates: per_vsgl,
            seed: out.seed,
            _pad: 0,
        };
        let uniform = rec.uniform("kmeans_sums_params_uniform_buffer", &params);
        let resources = [
            uniform.as_entire_binding(),
            chains.buffer.as_entire_binding(),
            sorted.keys.as_entire_binding(),
            sorted.texels.as_entire_binding(),
            out.partials.as_entire_binding(),
            sorted.centres.as_entire_binding(),
            out.next_centres.as_entire_binding(),
            out.vsgls.as_entire_binding(),
            candidates.as_entire_binding(),
            rsm.pyramid.as_entire_binding(),
            rsm.level_offsets.as_entire_binding(),
        ];
        rec.compute("kmeans_sum", &self.parts, &[&resources], (groups(rsm.size * rsm.size, WORKGROUP), 1, 1));
        rec.compute("kmeans_sum", &self.clusters, &[&resources], (groups(sorted.count, WORKGROUP), 1, 1));
    }
}
