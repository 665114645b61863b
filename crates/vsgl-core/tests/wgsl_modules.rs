//! Every embedded WGSL file, composed with its includes, parses and validates with naga; and the
//! shared math in `wgsl/common` contains no unjustified `1 − dot(…)` cancellation.
//!
//! GPU-free (STYLE.md §4 item 10a): naga is the WGSL front end wgpu itself uses.

use naga::valid::{Capabilities, ValidationFlags, Validator};
use vsgl_core::shader_lib;

fn describe(path: &str, composed: &str, location: Option<naga::SourceLocation>, report: String) -> String {
    let origin = location
        .and_then(|loc| shader_lib::original_location(composed, loc.line_number as usize).map(|(f, l)| (loc, f, l)))
        .map(|(loc, f, l)| format!("{f}:{l}:{} (composed line {})", loc.line_position, loc.line_number))
        .unwrap_or_else(|| "unknown location".to_string());
    format!("{path}: at {origin}\n{report}")
}

#[test]
fn every_composed_shader_parses_and_validates() {
    let paths: Vec<&str> = shader_lib::paths().collect();
    assert!(paths.contains(&"common/math.wgsl"), "embedded shaders: {paths:?}");
    assert!(paths.contains(&"common/sg.wgsl"), "embedded shaders: {paths:?}");
    assert!(paths.contains(&"common/vsgl.wgsl"), "embedded shaders: {paths:?}");
    let mut failures = Vec::new();
    for path in &paths {
        // A module that relies on bindings its includer declares (marked `vsgl:include-only`)
        // cannot validate alone; it is validated inside every shader that includes it, and
        // must have at least one.
        if shader_lib::source(path).is_some_and(|s| s.contains("// vsgl:include-only")) {
            let included = paths.iter().any(|p| {
                shader_lib::source(p).is_some_and(|s| s.lines().any(|l| l.trim_start().starts_with("#include") && l.contains(path)))
            });
            if !included {
                failures.push(format!("{path}: marked include-only but no shader includes it"));
            }
            continue;
        }
        let composed = match shader_lib::compose(path) {
            Ok(s) => s,
            Err(e) => {
                failures.push(format!("{path}: composition failed: {e}"));
                continue;
            }
        };
        let module = match naga::front::wgsl::parse_str(&composed) {
            Ok(m) => m,
            Err(e) => {
                let report = e.emit_to_string_with_path(&composed, path);
                failures.push(describe(path, &composed, e.location(&composed), report));
                continue;
            }
        };
        if let Err(e) = Validator::new(ValidationFlags::all(), Capabilities::all()).validate(&module) {
            let report = e.emit_to_string_with_path(&composed, path);
            failures.push(describe(path, &composed, e.location(&composed), report));
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {} shaders failed:\n\n{}",
        failures.len(),
        paths.len(),
        failures.join("\n\n")
    );
}

#[test]
fn composed_locations_map_back_to_files() {
    let composed = shader_lib::compose("common/vsgl.wgsl").expect("compose vsgl.wgsl");
    let sg = shader_lib::source("common/sg.wgsl").expect("sg.wgsl is embedded");
    let (sg_line, _) = sg
        .lines()
        .enumerate()
        .find(|(_, l)| l.starts_with("fn sg_product("))
        .expect("sg_product in sg.wgsl");
    let (composed_line, _) = composed
        .lines()
        .enumerate()
        .find(|(_, l)| l.starts_with("fn sg_product("))
        .expect("sg_product composed");
    assert_eq!(
        shader_lib::original_location(&composed, composed_line + 1),
        Some(("common/sg.wgsl".to_string(), sg_line + 1))
    );
    let vsgl = shader_lib::source("common/vsgl.wgsl").expect("vsgl.wgsl is embedded");
    let (vsgl_line, _) = vsgl
        .lines()
        .enumerate()
        .find(|(_, l)| l.starts_with("fn vsgl_specular("))
        .expect("vsgl_specular");
    let (composed_line, _) = composed
        .lines()
        .enumerate()
        .find(|(_, l)| l.starts_with("fn vsgl_specular("))
        .expect("vsgl_specular composed");
    assert_eq!(
        shader_lib::original_location(&composed, composed_line + 1),
        Some(("common/vsgl.wgsl".to_string(), vsgl_line + 1))
    );
}

/// STYLE.md §4 item 4: `1 − dot(a, b)` cancels for nearly parallel unit vectors (the SG code uses
/// ‖a − b‖² instead). Such a line in `wgsl/common` must say why it is fine, in a `//` comment on
/// the same line.
#[test]
fn no_unjustified_one_minus_dot_in_common() {
    let patterns = ["1.0 - dot(", "1.0-dot(", "1 - dot(", "1.0 - saturate(dot(", "1.0 - clamp(dot("];
    let mut offenders = Vec::new();
    for path in shader_lib::paths().filter(|p| p.starts_with("common/")) {
        let src = shader_lib::source(path).expect("embedded");
        for (i, line) in src.lines().enumerate() {
            let code = line.split("//").next().unwrap_or("");
            let compact: String = code.split_whitespace().collect::<Vec<_>>().join(" ");
            if patterns.iter().any(|p| compact.contains(p)) && !line.contains("//") {
                offenders.push(format!("{path}:{}: {}", i + 1, line.trim()));
            }
        }
    }
    assert!(
        offenders.is_empty(),
        "cancelling `1 - dot(` without a justification comment:\n{}",
        offenders.join("\n")
    );
}
