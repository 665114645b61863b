//! k-means clustering of an RSM into VSGLs, the 2016 paper's baseline [Tok16 Appendix D, §5]
//! (`kernel="kmeans2d"` and `"kmeans3d"` of `method="vsgl"`): centres drawn from the same
//! density as the filtered importance sampling, every lit texel assigned to its nearest centre
//! (RSM texel coordinates or world positions), the texels sorted by cluster id, and one thread
//! per cluster turning its sums into a VSGL. The paper does not iterate ("we do not update
//! iteratively"); `kmeans_iterations` > 0 adds Lloyd's updates (centres moved to their clusters'
//! w-weighted means, texels assigned again). Where the paper keeps its centres in a binary
//! radix tree, the nearest-centre search here walks a uniform grid of cells (passes::kmeans_grid).

use super::FrameContext;
use crate::error::Result;
use crate::frame::{MomentChains, Rsm};
use crate::passes::kmeans_assign::{CentreGrid, KmeansAssignPass};
use crate::passes::kmeans_centres::{CentreDraw, KmeansCentresPass, KmeansSpace, CENTRE_BYTES};
use crate::passes::kmeans_grid::{max_cells, GridBuffers, KmeansGridPass, GRID_BYTES};
use crate::passes::kmeans_sums::{partial_bytes, ClusterOutputs, KmeansSumsPass, SortedClusters};
use crate::passes::radix_sort::{RadixSortPass, SortBuffers};

/// Bits of the keys below `limit` (at least 1).
fn key_bits(limit: u32) -> u32 {
    (32 - limit.leading_zeros()).max(1)
}

/// What k-means clusters and where its VSGLs go.
pub struct KmeansJob<'a> {
    pub rsm: &'a Rsm,
    /// The pyramid the centres are drawn from (`rsm.pyramid`, or the importance-weighted one of
    /// `importance="brsm"`): the clusters' sums are exact whatever draws their centres.
    pub centre_density: &'a wgpu::Buffer,
    pub chains: &'a MomentChains,
    /// Clusters (this RSM's share of `num_lights`).
    pub count: u32,
    pub seed: u32,
    pub stratified: bool,
    pub light_offset: [f32; 3],
    pub vsgls: &'a wgpu::Buffer,
    /// Candidate shadow targets: the buffer and how many per VSGL.
    pub shadow_candidates: Option<(&'a wgpu::Buffer, u32)>,
}

#[derive(Clone, Copy, Debug)]
pub struct KmeansClustering {
    pub space: KmeansSpace,
    pub iterations: u32,
}

impl KmeansClustering {
    /// Compute dispatches one clustering of `count` clusters records: the paper counts 39 for
    /// its k-means against 2 for filtered importance sampling [Tok16 Table 1].
    pub fn dispatches(&self, count: u32) -> u32 {
        let cell_sort = RadixSortPass::dispatches(key_bits(max_cells(self.space) - 1));
        let texel_sort = RadixSortPass::dispatches(key_bits(count));
        // centres, then per round: grid cells, the cell sort, cell ranges, assign, the texel
        // sort, and the two levels of sums.
        1 + (self.iterations + 1) * (1 + cell_sort + 1 + 1 + texel_sort + 2)
    }

    pub fn record(&self, ctx: &mut FrameContext<'_>, job: &KmeansJob<'_>) -> Result<()> {
        let passes = ctx.passes;
        let (centre_pass, grid_pass, assign_pass) = (passes.get::<KmeansCentresPass>()?, passes.get::<KmeansGridPass>()?, passes.get::<KmeansAssignPass>()?);
        let (sort_pass, sums_pass) = (passes.get::<RadixSortPass>()?, passes.get::<KmeansSumsPass>()?);
        let rec = &mut ctx.rec;
        let (n, size, space) = (job.count, job.rsm.size, self.space);
        let texels = size * size;
        let centres = rec.storage_written("kmeans_centre_buffer", u64::from(n) * CENTRE_BYTES);
        let next_centres = rec.storage_written("kmeans_next_centre_buffer", u64::from(n) * CENTRE_BYTES);
        let grid = rec.storage_written("kmeans_grid_buffer", GRID_BYTES);
        let ranges = rec.storage("kmeans_cell_range_buffer", u64::from(max_cells(space)) * 8);
        let pair = |rec: &mut crate::gpu::Recorder<'_>, label: &str, len: u32| [rec.storage_written(label, u64::from(len) * 4), rec.storage_written(label, u64::from(len) * 4)];
        let (centre_keys, centre_ids) = (pair(rec, "kmeans_centre_key_buffer", n), pair(rec, "kmeans_centre_id_buffer", n));
        let (texel_keys, texel_ids) = (pair(rec, "kmeans_texel_key_buffer", texels), pair(rec, "kmeans_texel_id_buffer", texels));
        let partials = rec.storage_written("kmeans_partial_sum_buffer", partial_bytes(size, n));
        centre_pass.record(rec, job.rsm, job.chains, &CentreDraw { density: job.centre_density, count: n, seed: job.seed, stratified: job.stratified, space }, &centres);
        for round in 0..=self.iterations {
            if round > 0 {
                rec.enc.copy_buffer_to_buffer(&next_centres, 0, &centres, 0, u64::from(n) * CENTRE_BYTES);
                rec.enc.clear_buffer(&ranges, 0, None);
            }
            let cells = GridBuffers { centres: &centres, grid: &grid, keys: &centre_keys[0], values: &centre_ids[0], ranges: &ranges };
            grid_pass.record_cells(rec, n, size, space, &cells);
            let sorted = sort_pass.record(rec, "kmeans_sort", n, key_bits(max_cells(space) - 1), &SortBuffers { keys: [&centre_keys[0], &centre_keys[1]], values: [&centre_ids[0], &centre_ids[1]] });
            grid_pass.record_ranges(rec, n, size, space, &GridBuffers { keys: &centre_keys[sorted], values: &centre_ids[sorted], ..cells });
            let search = CentreGrid { count: n, centres: &centres, grid: &grid, sorted_centres: &centre_ids[sorted], ranges: &ranges };
            assign_pass.record(rec, size, space, job.chains, &search, [&texel_keys[0], &texel_ids[0]]);
            let sorted = sort_pass.record(rec, "kmeans_sort", texels, key_bits(n), &SortBuffers { keys: [&texel_keys[0], &texel_keys[1]], values: [&texel_ids[0], &texel_ids[1]] });
            let clusters = SortedClusters { count: n, space, keys: &texel_keys[sorted], texels: &texel_ids[sorted], centres: &centres };
            let out = ClusterOutputs { partials: &partials, next_centres: &next_centres, vsgls: job.vsgls, shadow_candidates: job.shadow_candidates, seed: job.seed, light_offset: job.light_offset };
            sums_pass.record(rec, job.rsm, job.chains, &clusters, &out);
        }
        Ok(())
    }
}
