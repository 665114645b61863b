//! Stable LSD radix sort of (key, value) `u32` pairs (compute), 8 bits a digit: histogram,
//! scan and scatter per digit (`wgsl/passes/radix_sort.wgsl` says how each works). k-means
//! sorts its centres by grid cell and its texels by cluster id with it.

use crate::error::Result;
use crate::gpu::{storage_binding, uniform_binding, Gpu, Recorder};

use crate::shader_lib::constants::radix_sort::{BLOCK, RADIX};

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct SortParamsRaw {
    count: u32,
    shift: u32,
    blocks: u32,
    _pad: u32,
}

/// Bits of one digit (RADIX = 2^DIGIT_BITS).
const DIGIT_BITS: u32 = RADIX.trailing_zeros();
const _: () = assert!(1 << DIGIT_BITS == RADIX);

/// Two key and two value buffers: the pairs start in `keys[0]`/`values[0]` and end in the
/// pair [`RadixSortPass::record`] returns the index of.
pub struct SortBuffers<'a> {
    pub keys: [&'a wgpu::Buffer; 2],
    pub values: [&'a wgpu::Buffer; 2],
}

pub struct RadixSortPass {
    histogram: wgpu::ComputePipeline,
    scan: wgpu::ComputePipeline,
    scatter: wgpu::ComputePipeline,
}

impl RadixSortPass {
    pub fn new(gpu: &Gpu) -> Result<Self> {
        let module = gpu.shader("passes/radix_sort.wgsl")?;
        let bindings = [uniform_binding(), storage_binding(true), storage_binding(true), storage_binding(false), storage_binding(false), storage_binding(false)];
        let pipeline = |entry: &str| gpu.compute_pipeline_explicit(&format!("radix_sort_{entry}_pipeline"), &module, entry, &bindings);
        Ok(Self { histogram: pipeline("histogram"), scan: pipeline("scan"), scatter: pipeline("scatter") })
    }

    /// Dispatches per sort of keys below 2^`key_bits`: three per digit.
    pub fn dispatches(key_bits: u32) -> u32 {
        3 * key_bits.div_ceil(DIGIT_BITS).max(1)
    }

    /// Sorts the first `count` pairs by their keys' low `key_bits` bits (every key must be
    /// below 2^key_bits), timed as `label`; returns which of the two buffer pairs holds the result.
    pub fn record(&self, rec: &mut Recorder<'_>, label: &str, count: u32, key_bits: u32, buffers: &SortBuffers<'_>) -> usize {
        let blocks = count.div_ceil(BLOCK).max(1);
        let table = rec.storage_written("radix_sort_table_buffer", u64::from(RADIX * blocks) * 4);
        let mut from = 0;
        for digit in 0..key_bits.div_ceil(DIGIT_BITS).max(1) {
            let params = SortParamsRaw { count, shift: digit * DIGIT_BITS, blocks, _pad: 0 };
            let uniform = rec.uniform("radix_sort_params_uniform_buffer", &params);
            let to = 1 - from;
            let resources = [
                uniform.as_entire_binding(),
                buffers.keys[from].as_entire_binding(),
                buffers.values[from].as_entire_binding(),
                buffers.keys[to].as_entire_binding(),
                buffers.values[to].as_entire_binding(),
                table.as_entire_binding(),
            ];
            rec.compute(label, &self.histogram, &[&resources], (blocks, 1, 1));
            rec.compute(label, &self.scan, &[&resources], (1, 1, 1));
            rec.compute(label, &self.scatter, &[&resources], (blocks, 1, 1));
            from = to;
        }
        from
    }
}
