//! The uniform grid over the k-means centres that the assignment searches
//! (`wgsl/passes/kmeans_grid.wgsl`): the grid and each centre's cell as a sort key, then, once
//! the centres are sorted by cell, each cell's run of them.

use super::kmeans_centres::KmeansSpace;
use crate::error::Result;
use crate::gpu::{groups, storage_binding, uniform_binding, Gpu, Recorder};

use crate::shader_lib::constants::kmeans_grid::{MAX_DIM_2D, MAX_DIM_3D, WORKGROUP};

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct GridParamsRaw {
    count: u32,
    rsm_size: u32,
    space: u32,
    _pad: u32,
}

/// Bytes of the grid record (`KmeansGrid` of `wgsl/common/kmeans_grid.wgsl`).
pub const GRID_BYTES: u64 = 32;

/// The most cells a grid of `space` has.
pub fn max_cells(space: KmeansSpace) -> u32 {
    match space {
        KmeansSpace::Texels => MAX_DIM_2D * MAX_DIM_2D,
        KmeansSpace::World => MAX_DIM_3D * MAX_DIM_3D * MAX_DIM_3D,
    }
}

/// What the two entry points read and write.
#[derive(Clone, Copy)]
pub struct GridBuffers<'a> {
    pub centres: &'a wgpu::Buffer,
    pub grid: &'a wgpu::Buffer,
    /// `cells` writes (cell, centre id) pairs here; `ranges` reads the sorted cells here.
    pub keys: &'a wgpu::Buffer,
    pub values: &'a wgpu::Buffer,
    /// Each cell's [start, end) in the sorted centres; zero (empty) when handed out.
    pub ranges: &'a wgpu::Buffer,
}

pub struct KmeansGridPass {
    cells: wgpu::ComputePipeline,
    ranges: wgpu::ComputePipeline,
}

impl KmeansGridPass {
    pub fn new(gpu: &Gpu) -> Result<Self> {
        let module = gpu.shader("passes/kmeans_grid.wgsl")?;
        let bindings = [uniform_binding(), storage_binding(true), storage_binding(false), storage_binding(false), storage_binding(false), storage_binding(false)];
        Ok(Self {
            cells: gpu.compute_pipeline_explicit("kmeans_grid_cells_pipeline", &module, "cells", &bindings),
            ranges: gpu.compute_pipeline_explicit("kmeans_grid_ranges_pipeline", &module, "ranges_of_cells", &bindings),
        })
    }

    fn resources<'b>(uniform: &'b wgpu::Buffer, b: &GridBuffers<'b>) -> [wgpu::BindingResource<'b>; 6] {
        [uniform.as_entire_binding(), b.centres.as_entire_binding(), b.grid.as_entire_binding(), b.keys.as_entire_binding(), b.values.as_entire_binding(), b.ranges.as_entire_binding()]
    }

    /// The grid over `count` centres and their cells as (key, value) pairs to sort.
    pub fn record_cells(&self, rec: &mut Recorder<'_>, count: u32, rsm_size: u32, space: KmeansSpace, b: &GridBuffers<'_>) {
        let uniform = rec.uniform("kmeans_grid_params_uniform_buffer", &GridParamsRaw { count, rsm_size, space: space.shader_code(), _pad: 0 });
        rec.compute("kmeans_grid", &self.cells, &[&Self::resources(&uniform, b)], (1, 1, 1));
    }

    /// Each cell's run of the centres sorted by cell (`b.keys`: the sorted cells).
    pub fn record_ranges(&self, rec: &mut Recorder<'_>, count: u32, rsm_size: u32, space: KmeansSpace, b: &GridBuffers<'_>) {
        let uniform = rec.uniform("kmeans_grid_params_uniform_buffer", &GridParamsRaw { count, rsm_size, space: space.shader_code(), _pad: 0 });
        rec.compute("kmeans_grid", &self.ranges, &[&Self::resources(&uniform, b)], (groups(count, WORKGROUP), 1, 1));
    }
}
