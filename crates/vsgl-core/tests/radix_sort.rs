//! The GPU radix sort k-means sorts with (`passes::radix_sort`): stable, by the asked key bits,
//! against the standard library's stable sort of the same pairs.

mod common;

use vsgl_core::gpu::{FrameResources, PassTimer, Recorder};
use vsgl_core::passes::radix_sort::{RadixSortPass, SortBuffers};

/// A fixed pseudo-random sequence (xorshift), so a failure reproduces.
fn keys(count: usize, below: u32) -> Vec<u32> {
    let mut x = 0x9e37_79b9u32;
    (0..count)
        .map(|_| {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            x % below
        })
        .collect()
}

fn sort_on_gpu(keys: &[u32], key_bits: u32) -> Option<(Vec<u32>, Vec<u32>)> {
    let gpu = common::gpu_or_skip("the radix sort test")?;
    let pass = RadixSortPass::new(&gpu).unwrap();
    let (mut timer, mut resources) = (PassTimer::new_disabled(), FrameResources::default());
    let mut rec = Recorder::new(&gpu, &mut timer, &mut resources);
    let values: Vec<u32> = (0..keys.len() as u32).collect();
    let bytes = keys.len() as u64 * 4;
    let key_buffers = [rec.storage_written("keys", bytes), rec.storage_written("keys", bytes)];
    let value_buffers = [rec.storage_written("values", bytes), rec.storage_written("values", bytes)];
    gpu.queue.write_buffer(&key_buffers[0], 0, bytemuck::cast_slice(keys));
    gpu.queue.write_buffer(&value_buffers[0], 0, bytemuck::cast_slice(&values));
    let at = pass.record(&mut rec, "sort", keys.len() as u32, key_bits, &SortBuffers { keys: [&key_buffers[0], &key_buffers[1]], values: [&value_buffers[0], &value_buffers[1]] });
    let submitted = gpu.queue.submit([rec.finish().finish()]);
    gpu.wait_for(Some(&submitted), "sort").unwrap();
    let out = gpu.read_buffers(&[&key_buffers[at], &value_buffers[at]]).unwrap();
    Some((bytemuck::cast_slice(&out[0]).to_vec(), bytemuck::cast_slice(&out[1]).to_vec()))
}

#[test]
fn sorts_pairs_stably_by_their_keys() {
    // Sizes that end mid-block and keys of one, two and three digits (17 bits: three passes,
    // the result in the second buffer pair).
    for (count, below, bits) in [(1000usize, 7u32, 3u32), (4099, 1025, 11), (70_000, 1 << 17, 17), (1, 1, 1)] {
        let keys = keys(count, below);
        let Some((got_keys, got_values)) = sort_on_gpu(&keys, bits) else { return };
        let mut want: Vec<(u32, u32)> = keys.iter().copied().zip(0..).collect();
        want.sort_by_key(|&(k, _)| k);
        let want_keys: Vec<u32> = want.iter().map(|p| p.0).collect();
        let want_values: Vec<u32> = want.iter().map(|p| p.1).collect();
        assert_eq!(got_keys[..count], want_keys[..], "keys, {count} pairs below {below}");
        assert_eq!(got_values[..count], want_values[..], "values (stable order), {count} pairs below {below}");
    }
}
