//! Same-run timing of vsgl2's two reductions (subgroup sums vs the shared-memory tree) on the
//! default adapter, with the per-frame noise taken out: each sample records `--repeats`
//! reductions of one synthetic RSM into a single command buffer and times submit → idle on
//! the CPU clock, so queue and driver overheads are paid once per sample, not per reduction.
//! Samples alternate between the implementations so both see the same machine state.
//!
//!     cargo run --release -p vsgl-core --example vsgl2_reduction_timing -- \
//!         --rsm-sizes 128,256,512,1024 --repeats 50 --samples 9
//!
//! Prints one line per RSM size and the JSON report on stdout's last line. On a CPU adapter
//! (lavapipe) only the ratio between the two implementations means anything.

use std::time::Instant;
use vsgl_core::gpu::{storage_buffer, FrameResources, Gpu, PassTimer, Recorder};
use vsgl_core::frame::Rsm;
use vsgl_core::passes::vsgl_gen::VSGL_BYTES;
use vsgl_core::frame::RsmLight;
use vsgl_core::passes::vsgl2_reduce::{Vsgl2Reduce, Vsgl2Reduction, VSGL2_COUNT};
use vsgl_core::plan::ShaderFeatures;
use vsgl_core::rng::SplitMix64;

fn arg(args: &[String], name: &str, default: &str) -> String {
    args.iter().position(|a| a == name).and_then(|i| args.get(i + 1)).cloned().unwrap_or_else(|| default.to_string())
}

/// An RSM of side `n` whose every texel reflects light: positions in a 10 m box in front of
/// the light, unit normals facing it, roughness in 0.05..1, positive diffuse and specular flux.
fn synthetic_rsm(gpu: &Gpu, n: u32, seed: u64) -> Rsm {
    let (mut timer, mut resources) = (PassTimer::new_disabled(), FrameResources::default());
    let rsm = Rsm::new(&mut Recorder::new(gpu, &mut timer, &mut resources), n, true, false);
    let mut rng = SplitMix64(seed);
    let texels = (n * n) as usize;
    let (mut position, mut normal, mut flux_d, mut flux_s) = (Vec::with_capacity(texels * 4), Vec::with_capacity(texels * 4), Vec::with_capacity(texels * 4), Vec::with_capacity(texels * 4));
    for _ in 0..texels {
        position.extend([rng.next_f32() * 10.0 - 5.0, rng.next_f32() * 10.0 - 5.0, -1.0 - rng.next_f32() * 9.0, 1.0]);
        let (x, y) = (rng.next_f32() - 0.5, rng.next_f32() - 0.5);
        let len = (x * x + y * y + 1.0f32).sqrt();
        normal.extend([x / len, y / len, 1.0 / len, 0.05 + 0.95 * rng.next_f32()]);
        flux_d.extend([rng.next_f32(), rng.next_f32(), rng.next_f32(), 0.0]);
        flux_s.extend([0.1 * rng.next_f32(), 0.1 * rng.next_f32(), 0.1 * rng.next_f32(), 0.0]);
    }
    for (buffer, data) in [(&rsm.gbuffer.position, &position), (&rsm.gbuffer.normal, &normal), (&rsm.flux_diffuse, &flux_d), (&rsm.flux_specular, &flux_s)] {
        gpu.queue.write_buffer(buffer, 0, bytemuck::cast_slice(data));
    }
    rsm
}

/// Wall-clock milliseconds of `repeats` reductions of `rsm` recorded into one submission.
fn time_sample(gpu: &Gpu, reduce: &Vsgl2Reduce, rsm: &Rsm, out: &wgpu::Buffer, reduction: Vsgl2Reduction, repeats: u32) -> f64 {
    let features = ShaderFeatures { textures: false, normal_maps: false, specular: true };
    let mut timer = PassTimer::new_disabled();
    let mut resources = FrameResources::default();
    let mut rec = Recorder::new(gpu, &mut timer, &mut resources);
    for _ in 0..repeats {
        reduce.record(&mut rec, rsm, &RsmLight::default(), out, features, reduction).expect("record the reduction");
    }
    let commands = rec.finish().finish();
    let start = Instant::now();
    gpu.queue.submit([commands]);
    gpu.device.poll(wgpu::PollType::wait_indefinitely()).expect("wait for the reductions");
    start.elapsed().as_secs_f64() * 1e3
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let sizes: Vec<u32> = arg(&args, "--rsm-sizes", "128,256,512").split(',').map(|s| s.trim().parse().expect("--rsm-sizes: comma-separated integers")).collect();
    let repeats: u32 = arg(&args, "--repeats", "50").parse().expect("--repeats: an integer");
    let samples: usize = arg(&args, "--samples", "9").parse().expect("--samples: an integer");
    let gpu = Gpu::new(None).expect("an adapter");
    if !gpu.adapter.subgroups {
        eprintln!("adapter {:?} has no subgroup operations: nothing to compare", gpu.adapter.name);
        std::process::exit(2);
    }
    let reduce = Vsgl2Reduce::new(&gpu).expect("reduction pipelines");
    let out = storage_buffer(&gpu, "vsgl2_buffer", VSGL2_COUNT as u64 * VSGL_BYTES);
    let variants = [Vsgl2Reduction::Subgroup, Vsgl2Reduction::SharedMemory];
    let mut rows = Vec::new();
    for &n in &sizes {
        let rsm = synthetic_rsm(&gpu, n, 7);
        for v in variants {
            time_sample(&gpu, &reduce, &rsm, &out, v, 1); // compile and warm
        }
        let mut times = [Vec::new(), Vec::new()];
        for _ in 0..samples {
            for (i, v) in variants.iter().enumerate() {
                times[i].push(time_sample(&gpu, &reduce, &rsm, &out, *v, repeats) / repeats as f64);
            }
        }
        let (sub, shared) = (median(times[0].clone()), median(times[1].clone()));
        println!("rsm {n:5}: subgroup {sub:.4} ms, shared_memory {shared:.4} ms per reduction, ratio {:.3}  ({})", sub / shared, gpu.adapter.name);
        rows.push(format!(
            "{{\"rsm_size\": {n}, \"subgroup_ms\": {sub:.6}, \"shared_memory_ms\": {shared:.6}, \"subgroup_over_shared\": {:.4}, \"subgroup_samples_ms\": {:?}, \"shared_memory_samples_ms\": {:?}}}",
            sub / shared,
            times[0],
            times[1]
        ));
    }
    println!("{{\"adapter\": {:?}, \"repeats\": {repeats}, \"samples\": {samples}, \"rows\": [{}]}}", gpu.adapter.name, rows.join(", "));
}
