//! k-means centres (compute): N texels drawn from the RSM's weight pyramid as the filtered
//! importance sampling draws its kernel centres, placed in the clustering space
//! (`wgsl/passes/kmeans_centres.wgsl`).

use crate::error::Result;
use crate::frame::{MomentChains, Rsm};
use crate::gpu::{groups, Gpu, Recorder};

use crate::shader_lib::constants::kmeans_centres::WORKGROUP;

/// Where k-means measures distances [Tok16 Appendix D].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum KmeansSpace {
    /// RSM texel coordinates ("kmeans2d").
    Texels,
    /// World positions ("kmeans3d").
    World,
}

impl KmeansSpace {
    /// The shaders' `space` code.
    pub fn shader_code(self) -> u32 {
        match self {
            KmeansSpace::Texels => 0,
            KmeansSpace::World => 1,
        }
    }
}

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct CentreParamsRaw {
    count: u32,
    rsm_size: u32,
    levels: u32,
    chain_len: u32,
    seed: u32,
    stratified: u32,
    space: u32,
    _pad: u32,
}

/// Bytes of one centre (a vec4f: position in the clustering space, sample density).
pub const CENTRE_BYTES: u64 = 16;

/// How the centres are drawn.
#[derive(Clone, Copy)]
pub struct CentreDraw<'a> {
    /// The density they are drawn by: a pyramid in the layout of `rsm.pyramid` (the RSM's own
    /// weights, or with `importance="brsm"` the re-weighted ones).
    pub density: &'a wgpu::Buffer,
    pub count: u32,
    pub seed: u32,
    /// The Fibonacci lattice (`sampling="stratified"`) rather than random points.
    pub stratified: bool,
    pub space: KmeansSpace,
}

pub struct KmeansCentresPass {
    pipeline: wgpu::ComputePipeline,
}

impl KmeansCentresPass {
    pub fn new(gpu: &Gpu) -> Result<Self> {
        let module = gpu.shader("passes/kmeans_centres.wgsl")?;
        Ok(Self { pipeline: gpu.compute_pipeline("kmeans_centres_pipeline", &module, "main") })
    }

    pub fn record(&self, rec: &mut Recorder<'_>, rsm: &Rsm, chains: &MomentChains, draw: &CentreDraw<'_>, centres: &wgpu::Buffer) {
        let params = CentreParamsRaw {
            count: draw.count,
            rsm_size: rsm.size,
            levels: rsm.levels,
            chain_len: chains.chain_len,
            seed: draw.seed,
            stratified: u32::from(draw.stratified),
            space: draw.space.shader_code(),
            _pad: 0,
        };
        let uniform = rec.uniform("kmeans_centres_params_uniform_buffer", &params);
        rec.compute(
            "kmeans_centres",
            &self.pipeline,
            &[&[uniform.as_entire_binding(), draw.density.as_entire_binding(), rsm.level_offsets.as_entire_binding(), chains.buffer.as_entire_binding(), centres.as_entire_binding()]],
            (groups(draw.count, WORKGROUP), 1, 1),
        );
    }
}
