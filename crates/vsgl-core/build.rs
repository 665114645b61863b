//! Embeds every file under `wgsl/` into the binary (so a wheel is self-contained): writes a
//! table `(relative path, contents)` that `shader_lib` composes at run time. Also writes the
//! integer constants each pass shader declares at its top level (`const NAME: u32 = 8u;`), its
//! own and those of the files it includes, as Rust constants, one module per
//! `wgsl/passes/*.wgsl` and `wgsl/harness/*.wgsl` (`shader_lib::constants::denoise::TILE`), so
//! the numbers the host dispatches by are written once, in the shaders.
use std::{env, fs, path::Path};

fn collect(dir: &Path, root: &Path, out: &mut Vec<String>) {
    // Watching each folder notices files added or removed anywhere under wgsl/.
    println!("cargo:rerun-if-changed={}", dir.display());
    let mut entries: Vec<_> = fs::read_dir(dir).expect("read wgsl dir").flatten().collect();
    entries.sort_by_key(|e| e.path());
    for e in entries {
        let p = e.path();
        if p.is_dir() {
            collect(&p, root, out);
        } else if p.extension().is_some_and(|x| x == "wgsl") {
            println!("cargo:rerun-if-changed={}", p.display());
            let rel = p.strip_prefix(root).unwrap().to_string_lossy().replace('\\', "/");
            out.push(format!("    ({rel:?}, include_str!({:?})),\n", p.canonicalize().unwrap()));
        }
    }
}

/// `const NAME: u32 = 8u;` / `const NAME: i32 = -1i;` at the start of a line: (name, type, value).
fn top_level_integer_constant(line: &str) -> Option<(String, &'static str, String)> {
    let rest = line.strip_prefix("const ")?;
    let (name, rest) = rest.split_once(':')?;
    let (ty, rest) = rest.trim_start().split_once('=')?;
    let ty = match ty.trim() {
        "u32" => "u32",
        "i32" => "i32",
        _ => return None,
    };
    let value = rest.trim().strip_suffix(';')?.trim();
    let digits = value.trim_end_matches(['u', 'i']);
    let valid = !digits.is_empty() && digits.trim_start_matches('-').chars().all(|c| c.is_ascii_digit());
    let name = name.trim();
    if !valid || !name.chars().all(|c| c.is_ascii_uppercase() || c.is_ascii_digit() || c == '_') {
        return None;
    }
    Some((name.to_string(), ty, digits.to_string()))
}

/// The integer constants of `file` and of every file it includes (each file once), in order.
fn constants_with_includes(root: &Path, file: &Path, seen: &mut Vec<std::path::PathBuf>, out: &mut Vec<(String, &'static str, String)>) {
    if seen.iter().any(|s| s == file) {
        return;
    }
    seen.push(file.to_path_buf());
    let text = fs::read_to_string(file).unwrap();
    for line in text.lines() {
        if let Some(included) = line.trim().strip_prefix("#include").map(|r| r.trim().trim_matches('"')) {
            constants_with_includes(root, &root.join(included), seen, out);
        } else if let Some(c) = top_level_integer_constant(line) {
            out.push(c);
        }
    }
}

fn pass_constants(root: &Path) -> String {
    let mut files: Vec<_> = ["passes", "harness"]
        .iter()
        .flat_map(|d| fs::read_dir(root.join(d)).expect("read wgsl/passes and wgsl/harness").flatten().map(|e| e.path()))
        .collect();
    files.sort();
    let mut out = String::new();
    let mut table = String::from("/// Every (shader, constant, value) above, for the test that checks them against naga.\npub static ALL: &[(&str, &str, i64)] = &[\n");
    for p in files.iter().filter(|p| p.extension().is_some_and(|x| x == "wgsl")) {
        let stem = p.file_stem().unwrap().to_string_lossy().to_string();
        let rel = p.strip_prefix(root).unwrap().to_string_lossy().replace('\\', "/");
        let mut consts = Vec::new();
        constants_with_includes(root, p, &mut Vec::new(), &mut consts);
        if consts.is_empty() {
            continue;
        }
        out.push_str(&format!("/// The integer constants of `wgsl/{rel}` and the files it includes.\npub mod {stem} {{\n"));
        for (name, ty, value) in consts {
            out.push_str(&format!("    pub const {name}: {ty} = {value};\n"));
            table.push_str(&format!("    (\"{rel}\", \"{name}\", {value}),\n"));
        }
        out.push_str("}\n");
    }
    out.push_str(&table);
    out.push_str("];\n");
    out
}

fn main() {
    // Read at run time, not baked in with env!(): a build script compiled for another checkout
    // of the same crate (a git worktree sharing the target folder) must not read that one's wgsl/.
    let manifest_dir = env::var("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR");
    let root = Path::new(&manifest_dir).join("../../wgsl");
    println!("cargo:rerun-if-changed={}", root.display());
    let mut rows = Vec::new();
    collect(&root, &root, &mut rows);
    let src = format!("pub static WGSL_FILES: &[(&str, &str)] = &[\n{}];\n", rows.concat());
    fs::write(Path::new(&env::var("OUT_DIR").unwrap()).join("wgsl_files.rs"), src).unwrap();
    fs::write(Path::new(&env::var("OUT_DIR").unwrap()).join("wgsl_constants.rs"), pass_constants(&root)).unwrap();
}
