//! k-means assignment (compute): each lit RSM texel to its nearest centre, searched in the
//! centre grid (`wgsl/passes/kmeans_assign.wgsl`), as (cluster id, texel) pairs to sort.

use super::kmeans_centres::KmeansSpace;
use crate::error::Result;
use crate::frame::MomentChains;
use crate::gpu::{groups, Gpu, Recorder};

use crate::shader_lib::constants::kmeans_assign::WORKGROUP;

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct AssignParamsRaw {
    count: u32,
    rsm_size: u32,
    space: u32,
    chain_len: u32,
}

/// The centres and their grid, as `KmeansGridPass` left them.
#[derive(Clone, Copy)]
pub struct CentreGrid<'a> {
    pub count: u32,
    pub centres: &'a wgpu::Buffer,
    pub grid: &'a wgpu::Buffer,
    pub sorted_centres: &'a wgpu::Buffer,
    pub ranges: &'a wgpu::Buffer,
}

pub struct KmeansAssignPass {
    pipeline: wgpu::ComputePipeline,
}

impl KmeansAssignPass {
    pub fn new(gpu: &Gpu) -> Result<Self> {
        let module = gpu.shader("passes/kmeans_assign.wgsl")?;
        Ok(Self { pipeline: gpu.compute_pipeline("kmeans_assign_pipeline", &module, "main") })
    }

    /// Writes one (cluster id, texel) pair per texel of the `rsm_size`² RSM into `pairs`
    /// (keys, values).
    pub fn record(&self, rec: &mut Recorder<'_>, rsm_size: u32, space: KmeansSpace, chains: &MomentChains, centres: &CentreGrid<'_>, pairs: [&wgpu::Buffer; 2]) {
        let [keys, values] = pairs;
        let params = AssignParamsRaw { count: centres.count, rsm_size, space: space.shader_code(), chain_len: chains.chain_len };
        let uniform = rec.uniform("kmeans_assign_params_uniform_buffer", &params);
        rec.compute(
            "kmeans_assign",
            &self.pipeline,
            &[&[
                uniform.as_entire_binding(),
                chains.buffer.as_entire_binding(),
                centres.centres.as_entire_binding(),
                centres.grid.as_entire_binding(),
                centres.sorted_centres.as_entire_binding(),
                centres.ranges.as_entire_binding(),
                keys.as_entire_binding(),
                values.as_entire_binding(),
            ]],
            (groups(rsm_size * rsm_size, WORKGROUP), 1, 1),
        );
    }
}
