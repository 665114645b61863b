//! The layers of vsgl-core (docs/architecture.md, "Layers") hold: every source file refers only
//! to its own top-level module and to modules of lower layers, and no method module reaches into
//! another. References are read from the source text with comments removed: `crate::x` paths
//! anywhere (`use` lines and inline paths alike), `super::` chains that climb to the crate root,
//! and `vsgl_core::x` paths, grouped imports (`use crate::{a::X, b::Y}`) and the names the crate
//! root re-exports (`crate::Renderer` is the renderer layer). Within a group of one layer the
//! modules may use each other, but not in a circle. The layer order is written once, here; the
//! method modules are read from the registry's files (those that declare a method's `INFO`).

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// Top-level modules from the bottom up; a module may use its own layer's other modules only
/// where they share a group (one entry).
const LAYERS: &[&[&str]] = &[
    &["error", "rng", "progress", "setting"],
    &["shader_lib", "image_io"],
    &["gpu"],
    &["scene"],
    &["plan"],
    &["upload"],
    &["frame"],
    &["passes"],
    &["methods"],
    &["renderer"],
    &["verify"],
];

/// Macros exported at the crate root, by the module that defines them.
const ROOT_MACROS: &[(&str, &str)] = &[("choice_names", "methods")];

/// The method modules of `methods/` (its registry: the files that declare a method's
/// `pub const INFO: MethodInfo`): each is self-contained, sharing code through the helper
/// modules beside them, never through another method.
fn method_modules(src: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(src.join("methods"))
        .expect("read methods/")
        .map(|e| e.expect("dir entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "rs") && std::fs::read_to_string(p).unwrap().contains("pub const INFO: MethodInfo"))
        .map(|p| p.file_stem().unwrap().to_string_lossy().to_string())
        .collect();
    names.sort();
    names
}

/// The names `lib.rs` re-exports at the crate root (`pub use renderer::{Frame, …};`), by the
/// top-level module they come from.
fn root_reexports(src: &Path) -> Vec<(String, String)> {
    let lib = without_comments(&std::fs::read_to_string(src.join("lib.rs")).unwrap());
    let mut out = Vec::new();
    for line in lib.lines().filter_map(|l| l.trim().strip_prefix("pub use ")) {
        let line = line.trim_end_matches(';');
        let module = line.split("::").next().unwrap_or("").to_string();
        let names = match (line.find('{'), line.rfind('}')) {
            (Some(a), Some(b)) => line[a + 1..b].split(',').map(|n| n.trim().to_string()).collect(),
            _ => vec![line.rsplit("::").next().unwrap_or("").to_string()],
        };
        out.extend(names.into_iter().filter(|n| !n.is_empty()).map(|n| (n, module.clone())));
    }
    out
}

fn layer_of(module: &str) -> Option<usize> {
    LAYERS.iter().position(|group| group.contains(&module))
}

fn source_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).expect("read src dir") {
        let path = entry.expect("dir entry").path();
        if path.is_dir() {
            source_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The text with `//` comments removed (doc comments name other layers in prose and links).
fn without_comments(text: &str) -> String {
    text.lines().map(|line| line.split("//").next().unwrap_or("")).collect::<Vec<_>>().join("\n")
}

fn identifier(text: &str) -> String {
    text.trim_start().chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect()
}

/// Identifiers that follow `prefix` in `text` (e.g. `crate::` → `frame`, `gpu`, …), and for a
/// grouped path (`crate::{frame::X, gpu::{Y, Z}}`) the first identifier of each item of the
/// group.
fn after(text: &str, prefix: &str) -> Vec<String> {
    let mut found = Vec::new();
    let mut rest = text;
    while let Some(i) = rest.find(prefix) {
        let boundary = rest[..i].chars().next_back().is_none_or(|c| !(c.is_alphanumeric() || c == '_'));
        let tail = &rest[i + prefix.len()..];
        if boundary {
            if let Some(group) = tail.strip_prefix('{') {
                // The items at brace depth 0 of the group.
                let (mut depth, mut item_start) = (0usize, 0usize);
                for (j, c) in group.char_indices() {
                    match c {
                        '{' => depth += 1,
                        '}' if depth == 0 => {
                            found.push(identifier(&group[item_start..j]));
                            break;
                        }
                        '}' => depth -= 1,
                        ',' if depth == 0 => {
                            found.push(identifier(&group[item_start..j]));
                            item_start = j + 1;
                        }
                        _ => {}
                    }
                }
            } else {
                found.push(identifier(tail));
            }
        }
        rest = tail;
    }
    found.retain(|n| !n.is_empty());
    found
}

/// (file's top-level module, file's module path below it, the top-level modules it refers to).
fn references(src: &Path, file: &Path) -> (String, Vec<String>, BTreeSet<String>) {
    let rel = file.strip_prefix(src).unwrap();
    let mut path: Vec<String> = rel.iter().map(|c| c.to_string_lossy().trim_end_matches(".rs").to_string()).collect();
    if path.last().is_some_and(|l| l == "mod") {
        path.pop();
    }
    let top = path.first().cloned().unwrap_or_default();
    let text = without_comments(&std::fs::read_to_string(file).unwrap());
    let mut refs: BTreeSet<String> = after(&text, "crate::").into_iter().collect();
    refs.extend(after(&text, "vsgl_core::"));
    // `super::` × k from a file at module depth d climbs to the crate root when k ≥ d (inline
    // `mod` blocks only add depth, so this can only miss a climb, never invent one).
    let depth = path.len();
    for k in (1..=4).rev() {
        let chain = "super::".repeat(k);
        if k >= depth && depth > 0 {
            refs.extend(after(&text, &chain));
        }
    }
    for (name, module) in ROOT_MACROS {
        if refs.remove(*name) {
            refs.insert((*module).to_string());
        }
    }
    for (name, module) in root_reexports(src) {
        if refs.remove(&name) {
            refs.insert(module);
        }
    }
    let modules: BTreeSet<String> = refs.into_iter().filter(|r| layer_of(r).is_some()).collect();
    (top, path, modules)
}

fn violations(src: &Path) -> Vec<String> {
    let mut files = Vec::new();
    source_files(src, &mut files);
    files.sort();
    let methods = method_modules(src);
    let mut bad = Vec::new();
    // Same-layer references between top-level modules, for the circle check below.
    let mut same_layer: BTreeSet<(String, String)> = BTreeSet::new();
    for file in &files {
        let (top, path, refs) = references(src, file);
        let name = file.strip_prefix(src).unwrap().display().to_string();
        if top == "lib" || top == "main" {
            continue;
        }
        let Some(own) = layer_of(&top) else {
            bad.push(format!("{name}: top-level module {top:?} is in no layer (add it to LAYERS)"));
            continue;
        };
        for r in &refs {
            let theirs = layer_of(r).unwrap();
            if theirs > own {
                bad.push(format!("{name} ({top}, layer {own}) uses crate::{r} (layer {theirs}): an upward reference"));
            } else if theirs == own && *r != top {
                same_layer.insert((top.clone(), r.clone()));
            }
        }
        // Method modules do not use each other.
        if top == "methods" && path.len() == 2 && methods.contains(&path[1]) {
            let text = without_comments(&std::fs::read_to_string(file).unwrap());
            for other in methods.iter().filter(|m| **m != path[1]) {
                for prefix in [format!("super::{other}::"), format!("crate::methods::{other}::")] {
                    if text.contains(&prefix) {
                        bad.push(format!("{name}: the method module {:?} uses {prefix}…: share it through a helper module of methods/", path[1]));
                    }
                }
            }
        }
    }
    // Two modules of one layer that use each other, directly or through others, are a circle.
    for (a, b) in &same_layer {
        let mut reached: BTreeSet<&str> = BTreeSet::new();
        let mut stack = vec![b.as_str()];
        while let Some(m) = stack.pop() {
            if reached.insert(m) {
                stack.extend(same_layer.iter().filter(|(from, _)| from == m).map(|(_, to)| to.as_str()));
            }
        }
        if reached.contains(a.as_str()) {
            bad.push(format!("{a} uses {b} and {b} reaches {a}: a circle within one layer"));
        }
    }
    bad
}

fn src_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

#[test]
fn every_module_uses_only_its_own_and_lower_layers() {
    let bad = violations(&src_dir());
    assert!(bad.is_empty(), "layer violations:\n  {}", bad.join("\n  "));
}

/// The checker sees every form of an upward reference, a method module using another and a
/// circle within a layer: the same tree with a planted `use` line, an inline path, a grouped
/// import, a crate-root re-export, a method-to-method call (in the newest method too) and a
/// same-layer circle each fails.
#[test]
fn the_check_fails_on_planted_upward_references() {
    let planted: [(&str, &str); 7] = [
        ("passes/denoise.rs", "\nuse crate::methods::options::Options;\n"),
        ("frame/rsm.rs", "\nfn planted() -> usize { crate::renderer::AOV_NAMES.len() }\n"),
        ("gpu/timer.rs", "\nuse crate::{error::Result, renderer::AOV_NAMES};\n"),
        ("scene/mod.rs", "\nfn planted(_: &crate::Renderer) {}\n"),
        ("methods/vsgl2.rs", "\nfn planted() { let _ = super::vsgl::INFO; }\n"),
        ("methods/lpv.rs", "\nfn planted() { let _ = super::vpl::INFO; }\n"),
        // progress uses error already: error using progress closes a circle.
        ("error.rs", "\nfn planted(_: &crate::progress::StopCheck) {}\n"),
    ];
    for (file, line) in planted {
        let tmp = std::env::temp_dir().join(format!("vsgl-layers-{}-{}", std::process::id(), file.replace('/', "_")));
        let _ = std::fs::remove_dir_all(&tmp);
        copy_tree(&src_dir(), &tmp);
        let target = tmp.join(file);
        let mut text = std::fs::read_to_string(&target).unwrap();
        text.push_str(line);
        std::fs::write(&target, text).unwrap();
        let bad = violations(&tmp);
        let _ = std::fs::remove_dir_all(&tmp);
        let circle = file == "error.rs";
        assert!(bad.iter().any(|b| b.starts_with(file) || (circle && b.contains("a circle"))), "{file}: planted {line:?} not caught: {bad:?}");
    }
}

fn copy_tree(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for entry in std::fs::read_dir(from).unwrap() {
        let path = entry.unwrap().path();
        let dest = to.join(path.file_name().unwrap());
        if path.is_dir() {
            copy_tree(&path, &dest);
        } else {
            std::fs::copy(&path, &dest).unwrap();
        }
    }
}
