//! The stability suite on the default adapter (lavapipe in CI): every WGSL function of
//! wgsl/common/{math,sg,ggx,vsgl}.wgsl in f32 against its f64 oracle on grids with the extremes
//! (sharpness 1e-6…1e9, grazing cosines, zero variance and power). Every row must pass (no
//! NaN/Inf, every case within its stated bound); the table is
//! printed (`cargo test -p vsgl-core --release --test stability -- --nocapture`).
//! Skips, with a message, only when there is no adapter at all (under CI that is a failure).

mod common;

use std::time::Instant;
use vsgl_core::verify::stability::{self, StabilityRow};

fn print_table(rows: &[StabilityRow]) {
    println!(
        "{:<50} {:<58} {:>6} {:>10} {:>10} {:>9} {:>7} {:>5}",
        "function", "case family", "cases", "max rel", "bound", "err/bound", "NaN/Inf", "pass"
    );
    for r in rows {
        println!(
            "{:<50} {:<58} {:>6} {:>10.2e} {:>10.2e} {:>9.3} {:>7} {:>5}",
            r.function,
            r.family,
            r.cases,
            r.max_rel_error,
            r.bound,
            r.worst_ratio,
            r.nonfinite,
            if r.pass { "pass" } else { "FAIL" }
        );
    }
}

#[test]
fn every_function_is_within_its_bound_on_the_default_adapter() {
    let Some(gpu) = common::gpu_or_skip("the stability suite") else { return };
    let start = Instant::now();
    let rows = stability::run(&gpu, 1.0).expect("stability suite");
    let elapsed = start.elapsed();
    println!("adapter: {} ({}), {} rows in {:.2?}", gpu.adapter.name, gpu.adapter.device_type, rows.len(), elapsed);
    print_table(&rows);
    // Every harness function appears in the table.
    for f in vsgl_core::verify::harness::HarnessFunction::ALL {
        assert!(rows.iter().any(|r| r.function.starts_with(&format!("{}.", f.name()))), "{} missing", f.name());
    }
    let failed: Vec<&StabilityRow> = rows.iter().filter(|r| !r.pass).collect();
    for r in &failed {
        println!("FAIL {} / {}: max rel {:.3e}, err/bound {:.3}, NaN/Inf {}; worst case: {}", r.function, r.family, r.max_rel_error, r.worst_ratio, r.nonfinite, r.worst_case);
    }
    assert!(failed.is_empty(), "{} of {} rows failed (see above)", failed.len(), rows.len());
    assert_eq!(rows.iter().map(|r| r.nonfinite).sum::<usize>(), 0, "NaN or Inf");
    assert!(elapsed.as_secs_f64() < 120.0, "suite took {elapsed:.1?}");
}

/// The bounds are not vacuous: at 1/1000 of them, the GPU's real rounding errors fail many rows
/// (rows whose functions are exact, or that never round on this grid, still pass).
#[test]
fn the_suite_fails_when_the_bounds_are_too_tight() {
    let Some(gpu) = common::gpu_or_skip("the stability suite") else { return };
    let rows = stability::run(&gpu, 1e-3).expect("stability suite");
    let failed = rows.iter().filter(|r| !r.pass).count();
    println!("{failed} of {} rows fail at 1/1000 of the bounds", rows.len());
    assert!(failed * 2 > rows.len(), "only {failed} of {} rows fail with bounds / 1000", rows.len());
    for name in ["sg_evaluate.value", "sg_product.log_amplitude", "vsgl_incoming_radiance.amplitude", "vsgl_specular.value"] {
        assert!(rows.iter().any(|r| r.function == name && !r.pass), "{name} should fail at bounds / 1000");
    }
}
