//! The pass plan's shader variants are compiled on first use and then reused: rendering the
//! same scene again compiles nothing, a scene that needs other variants compiles only those.
//! Skips, with a message, only when there is no adapter at all.

use std::sync::atomic::Ordering;
use vsgl_core::gpu::Gpu;
use vsgl_core::renderer::{RenderOptions, Renderer};
use vsgl_core::scene::builtin;
use vsgl_core::Error;

#[test]
fn variants_are_compiled_once_and_only_when_a_plan_needs_them() {
    let gpu = match Gpu::new(None) {
        Ok(gpu) => gpu,
        Err(Error::NoAdapter(msg)) => {
            println!("SKIPPED: no GPU or CPU adapter: {msg}");
            return;
        }
        Err(e) => panic!("could not open the default adapter: {e}"),
    };
    let renderer = Renderer::new(gpu.clone(), 16, 16).expect("renderer");
    let compiled = || gpu.variants_compiled.load(Ordering::Relaxed);
    assert_eq!(compiled(), 0, "no variant is compiled before a frame asks for one");
    let opts = RenderOptions { method: "vsgl".into(), num_lights: 16, rsm_size: Some(32), ..Default::default() };
    let diffuse = builtin::by_name("diffuse_cornell").unwrap();
    let glossy = builtin::by_name("cornell_box").unwrap();

    renderer.render(&diffuse, None, &opts).expect("diffuse frame");
    let after_first = compiled();
    assert!(after_first > 0);
    renderer.render(&diffuse, None, &opts).expect("diffuse frame again");
    assert_eq!(compiled(), after_first, "the same plan recompiled a variant");

    // The box with R_s = 0.04 needs the specular variants of the same passes.
    renderer.render(&glossy, None, &opts).expect("specular frame");
    let after_specular = compiled();
    assert!(after_specular > after_first, "a plan with specular lobes used the diffuse-only variants");
    renderer.render(&diffuse, None, &opts).expect("diffuse frame after specular");
    renderer.render(&glossy, None, &opts).expect("specular frame again");
    assert_eq!(compiled(), after_specular, "switching between cached plans recompiled a variant");
}
