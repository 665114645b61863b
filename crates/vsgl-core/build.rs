//! Embeds every file under `wgsl/` into the binary (so a wheel is self-contained): writes a
//! table `(relative path, contents)` that `shader_lib` composes at run time.
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
}
