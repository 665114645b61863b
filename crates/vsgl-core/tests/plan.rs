//! The pass plan's shader variants are compiled on first use and then reused: rendering the
//! same scene again compiles nothing, a scene that needs other variants compiles only those.
//! Skips, with a message, only when there is no adapter at all (under CI that is a failure).

mod common;

use std::sync::atomic::Ordering;
use vsgl_core::renderer::{RenderOptions, Renderer};
use vsgl_core::scene::builtin;

#[test]
fn variants_are_compiled_once_and_only_when_a_plan_needs_them() {
    let Some(gpu) = common::gpu_or_skip("the plan test") else { return };
    let renderer = Renderer::new(gpu.clone(), 16, 16).expect("renderer");
    let compiled = || gpu.variants_compiled.load(Ordering::Relaxed);
    assert_eq!(compiled(), 0, "no variant is compiled before a frame asks for one");
    let opts = RenderOptions::new("vsgl").set("num_lights", 16u32).set("rsm_size", 32u32);
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

/// Every pipeline a frame binds runs the variant its plan asked for: each leave-out override a
/// pass's shader declares (`override HAS_SPECULAR`, …) is set, to the plan's value. A pass that
/// ignored its features (hard-coded a flag, or left one at its default of true) would still
/// render the same image — the unused buffers are placeholders whose writes are dropped — so
/// only this check sees it.
#[test]
fn every_pass_binds_the_variant_its_plan_asks_for() {
    use vsgl_core::plan::Plan;
    use vsgl_core::shader_lib;
    let Some(gpu) = common::gpu_or_skip("the plan test") else { return };
    let renderer = Renderer::new(gpu, 16, 16).expect("renderer");
    let mut checked = 0;
    for scene_name in ["diffuse_cornell", "cornell_box"] {
        let scene = builtin::by_name(scene_name).unwrap();
        for method in vsgl_core::methods::names() {
            for plan in ["auto", "full"] {
                // Each method gets the small settings it takes.
                let info = vsgl_core::methods::info(method).expect("registered method");
                let mut opts = RenderOptions::new(method);
                opts.plan = vsgl_core::renderer::PlanMode::parse(plan).expect("a plan mode");
                for (name, value) in [("num_lights", 16u32), ("rsm_size", 32), ("spp", 2)] {
                    if info.takes(name) {
                        opts = opts.set(name, value);
                    }
                }
                let frame = renderer.render(&scene, None, &opts).expect("frame");
                let features = Plan::new(&scene, plan == "full").features;
                let wanted = [("HAS_SPECULAR", features.specular), ("HAS_TEXTURES", features.textures), ("HAS_NORMAL_MAPS", features.normal_maps)];
                assert!(!frame.variants.is_empty(), "{scene_name}/{method}/{plan}: no variant logged");
                // HAS_EMISSION follows the G-buffer, not the plan's features: the built-ins emit
                // nothing, so every material pass of an automatic plan compiles emission out,
                // and plan="full" writes it for the camera (a light's view never needs it).
                let emission: Vec<bool> = frame.variants.iter()
                    .filter(|(shader, _, _)| shader_lib::compose(shader).expect("shader composes").contains("override HAS_EMISSION"))
                    .map(|(shader, entry, flags)| {
                        flags.iter().find(|(n, _)| *n == "HAS_EMISSION").map(|(_, v)| *v)
                            .unwrap_or_else(|| panic!("{scene_name}/{method}/plan={plan}: {shader}:{entry} ran without setting HAS_EMISSION: {flags:?}"))
                    })
                    .collect();
                assert!(!emission.is_empty(), "{scene_name}/{method}/plan={plan}: no material pass logged");
                assert_eq!(emission.contains(&true), plan == "full", "{scene_name}/{method}/plan={plan}: HAS_EMISSION {emission:?}");
                for (shader, entry, flags) in &frame.variants {
                    let src = shader_lib::compose(shader).expect("shader composes");
                    for (name, value) in wanted {
                        if src.contains(&format!("override {name}")) {
                            assert!(
                                flags.contains(&(name, value)),
                                "{scene_name}/{method}/plan={plan}: {shader}:{entry} ran with {flags:?}, the plan asks {name}={value}"
                            );
                            checked += 1;
                        }
                    }
                }
            }
        }
    }
    assert!(checked > 50, "only {checked} flags checked: the test would pass vacuously");
}
