//! Two VSGLs by parallel summation (compute, `method="vsgl2"`, the 2015 poster): the per-texel
//! VSGL moments of the whole RSM summed (subgroup sums where the adapter has them, else a
//! shared-memory tree: [`Vsgl2Reduction`]) to one diffuse and one specular VSGL,
//! written as two `VsglRaw` records (record 0 diffuse, record 1 specular).
//!
//! Dispatches (all timed as `vsgl2_reduce`): `tiles` (one 8×8 workgroup per RSM tile, any RSM
//! side) writes ⌈n/8⌉² partials; `merge` (64 threads, 256 partials per workgroup) runs until
//! one workgroup is left, whose dispatch also writes the VSGLs. Temporary memory: two partial
//! buffers of 112 bytes per partial, ⌈n/8⌉² and ⌈⌈n/8⌉²/256⌉ partials (see [`Vsgl2Reduce::temporary_bytes`]).

use crate::error::Result;
use crate::frame::{Rsm, RsmLight};
use crate::gpu::{groups, storage_binding, uniform_binding, Gpu, PipelineVariants, Recorder};
use crate::plan::ShaderFeatures;

/// Side of an RSM tile summed by one `tiles` workgroup, and the partials one `merge` workgroup
/// sums (`wgsl/common/vsgl2_moments.wgsl`).
use crate::shader_lib::constants::vsgl2_reduce::{MERGE_SPAN, TILE};
/// Bytes of one partial: seven vec4 (`Moments2` in the shader).
pub const PARTIAL_BYTES: u64 = 112;
/// Records written: diffuse, specular.
pub const VSGL2_COUNT: u32 = 2;

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct ReduceParamsRaw {
    rsm_size: u32,
    count: u32,
    finish: u32,
    _pad0: u32,
    light_offset: [f32; 3],
    _pad1: f32,
    light_dir: [f32; 4],
    texel_footprint: [f32; 4],
}

/// How the workgroups of the reduction add their values.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Vsgl2Reduction {
    /// Subgroups where the adapter has them, else shared memory.
    Auto,
    /// `subgroupAdd` within subgroups, a shared-memory tree across them.
    Subgroup,
    /// A pairwise tree in workgroup memory only (every adapter).
    SharedMemory,
}

/// The `tiles` and `merge` entry points of one implementation.
struct ReducePipelines {
    tiles: PipelineVariants,
    merge: PipelineVariants,
}

impl ReducePipelines {
    fn new(gpu: &Gpu, path: &str) -> Result<Self> {
        let module = gpu.shader(path)?;
        let ro = storage_binding(true);
        let rw = storage_binding(false);
        let bindings = vec![uniform_binding(), ro, ro, ro, ro, ro, rw, rw];
        Ok(Self {
            tiles: PipelineVariants::from_module(module.clone(), path, "tiles", Some(bindings.clone())),
            merge: PipelineVariants::from_module(module, path, "merge", Some(bindings)),
        })
    }
}

pub struct Vsgl2Reduce {
    shared_memory: ReducePipelines,
    /// Compiled on first use, and only on adapters with wgpu's SUBGROUP feature (devices
    /// without it reject the subgroup built-ins).
    subgroup: std::sync::OnceLock<ReducePipelines>,
}

/// Partials after the tile pass for an RSM of side `rsm_size`.
fn tile_partials(rsm_size: u32) -> u64 {
    let t = groups(rsm_size, TILE) as u64;
    t * t
}

impl Vsgl2Reduce {
    pub fn new(gpu: &Gpu) -> Result<Self> {
        Ok(Self { shared_memory: ReducePipelines::new(gpu, "passes/vsgl2_reduce.wgsl")?, subgroup: Default::default() })
    }

    /// The implementation `asked` resolves to on this adapter; asking for subgroups on an
    /// adapter without them is an error naming the setting.
    pub fn resolve(gpu: &Gpu, asked: Vsgl2Reduction) -> Result<Vsgl2Reduction> {
        match (asked, gpu.adapter.subgroups) {
            (Vsgl2Reduction::Auto, true) => Ok(Vsgl2Reduction::Subgroup),
            (Vsgl2Reduction::Auto, false) => Ok(Vsgl2Reduction::SharedMemory),
            (Vsgl2Reduction::Subgroup, false) => Err(crate::error::Error::invalid(
                "vsgl2_reduction",
                format!("\"subgroup\" needs wgpu's SUBGROUP feature, which adapter {:?} lacks; use \"auto\" or \"shared_memory\"", gpu.adapter.name),
            )),
            (other, _) => Ok(other),
        }
    }

    fn pipelines(&self, gpu: &Gpu, reduction: Vsgl2Reduction) -> Result<&ReducePipelines> {
        match Self::resolve(gpu, reduction)? {
            Vsgl2Reduction::Subgroup => {
                if let Some(p) = self.subgroup.get() {
                    return Ok(p);
                }
                let p = ReducePipelines::new(gpu, "passes/vsgl2_reduce_subgroup.wgsl")?;
                Ok(self.subgroup.get_or_init(|| p))
            }
            _ => Ok(&self.shared_memory),
        }
    }

    /// Temporary bytes the reduction allocates for an RSM of side `rsm_size` (both partial
    /// buffers; the two 112-byte VSGL records are the output, not counted).
    pub fn temporary_bytes(rsm_size: u32) -> u64 {
        let p = tile_partials(rsm_size);
        (p * PARTIAL_BYTES).max(16) + (p.div_ceil(MERGE_SPAN as u64) * PARTIAL_BYTES).max(16)
    }

    /// Records the reduction of `rsm` into `out` (two VSGL records, means relative to the
    /// frame origin) for the light `light` says.
    pub fn record(&self, rec: &mut Recorder<'_>, rsm: &Rsm, light: &RsmLight, out: &wgpu::Buffer, features: ShaderFeatures, reduction: Vsgl2Reduction) -> Result<()> {
        let RsmLight { offset: light_offset, dir: light_dir, texel_footprint } = *light;
        let gpu = rec.gpu;
        let pipelines = self.pipelines(gpu, reduction)?;
        let (tiles, merge) = (pipelines.tiles.get(gpu, &features.specular_flags()), pipelines.merge.get(gpu, &features.specular_flags()));
        let n = rsm.size;
        let p = tile_partials(n);
        let a = rec.storage("vsgl2_partial_a_buffer", p * PARTIAL_BYTES);
        let b = rec.storage("vsgl2_partial_b_buffer", p.div_ceil(MERGE_SPAN as u64) * PARTIAL_BYTES);
        let params = |rec: &mut Recorder<'_>, count: u64, finish: bool| {
            let raw = ReduceParamsRaw { rsm_size: n, count: count as u32, finish: finish as u32, _pad0: 0, light_offset, _pad1: 0.0, light_dir, texel_footprint };
            rec.uniform("vsgl2_reduce_params_uniform_buffer", &raw)
        };
        let dispatch = |u: &wgpu::Buffer, input: &wgpu::Buffer, output: &wgpu::Buffer, pipeline: &wgpu::ComputePipeline, rec: &mut Recorder<'_>, workgroups: (u32, u32, u32)| {
            rec.compute(
                "vsgl2_reduce",
                pipeline,
                &[&[
                    u.as_entire_binding(),
                    rsm.gbuffer.position.as_entire_binding(),
                    rsm.gbuffer.normal.as_entire_binding(),
                    rsm.flux_diffuse.as_entire_binding(),
                    rsm.flux_specular.as_entire_binding(),
                    input.as_entire_binding(),
                    output.as_entire_binding(),
                    out.as_entire_binding(),
                ]],
                workgroups,
            );
        };
        let u = params(rec, 0, false);
        let t = groups(n, TILE);
        dispatch(&u, &b, &a, &tiles, rec, (t, t, 1));
        // Ping-pong: each merge reads `count` partials from one buffer and writes
        // ⌈count/256⌉ to the other (the first buffer is the larger, so both always fit).
        let (mut input, mut output) = (&a, &b);
        let mut count = p;
        loop {
            let wgs = count.div_ceil(MERGE_SPAN as u64);
            let finish = wgs == 1;
            let u = params(rec, count, finish);
            dispatch(&u, input, output, &merge, rec, (wgs as u32, 1, 1));
            if finish {
                break;
            }
            count = wgs;
            std::mem::swap(&mut input, &mut output);
        }
        Ok(())
    }
}
