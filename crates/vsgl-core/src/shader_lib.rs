//! WGSL composition: a small include preprocessor over the shaders embedded from `wgsl/`.
//!
//! A line `#include "common/sg.wgsl"` (path relative to `wgsl/`) is replaced by that file,
//! once per composed shader (include guards are implicit), so shared modules can include each
//! other freely. Errors name the including file and line. `override` constants carry per-pass
//! settings, so there is no template logic here.

use crate::error::{Error, Result};
use std::collections::HashSet;

include!(concat!(env!("OUT_DIR"), "/wgsl_files.rs"));

/// The integer constants each pass shader declares at its top level, as Rust constants (written
/// by build.rs from `wgsl/passes/*.wgsl`): the workgroup sizes, tiles and radii the host
/// dispatches by are written once, in the shader. `tests::pass_constants_are_what_naga_reads`
/// checks them against naga's reading of each composed module.
#[allow(clippy::all)]
pub mod constants {
    include!(concat!(env!("OUT_DIR"), "/wgsl_constants.rs"));
}

/// The embedded source of `path` (relative to `wgsl/`).
pub fn source(path: &str) -> Option<&'static str> {
    WGSL_FILES.iter().find(|(p, _)| *p == path).map(|(_, s)| *s)
}

/// Every embedded shader path, for tests that validate them all.
pub fn paths() -> impl Iterator<Item = &'static str> {
    WGSL_FILES.iter().map(|(p, _)| *p)
}

/// `path` with its includes expanded.
pub fn compose(path: &str) -> Result<String> {
    let mut out = String::new();
    let mut seen = HashSet::new();
    expand(path, None, &mut seen, &mut out, 0)?;
    Ok(out)
}

/// Maps a 1-based line of a composed shader back to `(file, line)` using the
/// `// ---- begin <path>` / `// ---- end <path>` markers that `shader_lib::compose` writes and the
/// original sources: an `#include` of a file already included emits nothing, so each file's own
/// lines are followed with a cursor that skips such include lines.
pub fn original_location(composed: &str, composed_line: usize) -> Option<(String, usize)> {
    fn is_include(line: &str) -> bool {
        line.trim_start().starts_with("#include")
    }
    // Stack of (file, its source lines, cursor = index of the next unconsumed source line).
    let mut stack: Vec<(String, Vec<&'static str>, usize)> = Vec::new();
    for (i, line) in composed.lines().enumerate() {
        let here = if let Some(path) = line.strip_prefix("// ---- begin ") {
            if let Some(top) = stack.last_mut() {
                // Skip deduplicated includes up to the include line that produced this block.
                while top.2 < top.1.len() && !(is_include(top.1[top.2]) && top.1[top.2].contains(path)) {
                    top.2 += 1;
                }
                top.2 += 1;
            }
            let lines = source(path).map(|s| s.lines().collect()).unwrap_or_default();
            stack.push((path.to_string(), lines, 0));
            None
        } else if line.starts_with("// ---- end ") {
            stack.pop();
            None
        } else if let Some(top) = stack.last_mut() {
            while top.2 < top.1.len() && is_include(top.1[top.2]) {
                top.2 += 1;
            }
            top.2 += 1;
            Some((top.0.clone(), top.2))
        } else {
            None
        };
        if i + 1 == composed_line {
            return here;
        }
    }
    None
}

/// Parses and validates the composed shader `src` of `path` with naga (the WGSL front end wgpu
/// uses); an error names the original file and line of the composed line it points at.
pub fn validate(path: &str, src: &str) -> Result<()> {
    let at = |location: Option<naga::SourceLocation>| -> (String, u32) {
        location
            .and_then(|l| original_location(src, l.line_number as usize))
            .map(|(file, line)| (file, line as u32))
            .unwrap_or_else(|| (path.to_string(), 0))
    };
    let module = naga::front::wgsl::parse_str(src).map_err(|e| {
        let (file, line) = at(e.location(src));
        Error::ShaderCompile { file, line, message: format!("(composing {path}) {}", e.emit_to_string(src)) }
    })?;
    naga::valid::Validator::new(naga::valid::ValidationFlags::all(), naga::valid::Capabilities::all()).validate(&module).map_err(|e| {
        let (file, line) = at(e.location(src));
        Error::ShaderCompile { file, line, message: format!("(composing {path}) {}", e.emit_to_string(src)) }
    })?;
    Ok(())
}

fn expand(path: &str, from: Option<(&str, u32)>, seen: &mut HashSet<String>, out: &mut String, depth: u32) -> Result<()> {
    if !seen.insert(path.to_string()) {
        return Ok(());
    }
    let (file, line) = from.unwrap_or((path, 0));
    let src = source(path).ok_or_else(|| Error::ShaderCompile {
        file: file.into(),
        line,
        message: format!("included file {path:?} does not exist under wgsl/"),
    })?;
    if depth > 32 {
        return Err(Error::ShaderCompile { file: file.into(), line, message: "includes nested too deeply".into() });
    }
    out.push_str(&format!("// ---- begin {path}\n"));
    for (i, l) in src.lines().enumerate() {
        if let Some(rest) = l.trim_start().strip_prefix("#include") {
            let inc = rest.trim().trim_matches('"');
            expand(inc, Some((path, i as u32 + 1)), seen, out, depth + 1)?;
        } else {
            out.push_str(l);
            out.push('\n');
        }
    }
    out.push_str(&format!("// ---- end {path}\n"));
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The Rust constants build.rs writes are what naga reads from each composed pass module:
    /// the constant of that name, its initializer a literal of that value. (So the build
    /// script's line reading cannot drift from the WGSL a pipeline is built from.)
    #[test]
    fn pass_constants_are_what_naga_reads() {
        assert!(constants::ALL.len() >= 20, "{} constants", constants::ALL.len());
        assert_eq!(constants::denoise::TILE, 64);
        for (file, name, value) in constants::ALL {
            let module = naga::front::wgsl::parse_str(&compose(file).unwrap()).unwrap_or_else(|e| panic!("{file}: {e}"));
            let (_, constant) = module.constants.iter().find(|(_, c)| c.name.as_deref() == Some(*name)).unwrap_or_else(|| panic!("{file} has no constant {name}"));
            let read = match module.global_expressions[constant.init] {
                naga::Expression::Literal(naga::Literal::U32(v)) => v as i64,
                naga::Expression::Literal(naga::Literal::I32(v)) => v as i64,
                ref other => panic!("{file}: {name} is {other:?}, not an integer literal"),
            };
            assert_eq!(read, *value, "{file}: {name}");
        }
    }

    /// A syntax error inside an included file is reported at that file's own line, not at the
    /// line of the composed module.
    #[test]
    fn compile_errors_name_the_included_file_and_its_line() {
        let composed = compose("passes/vsgl_shading.wgsl").unwrap();
        let sg = source("common/sg.wgsl").unwrap();
        let (sg_line, target) = sg.lines().enumerate().find(|(_, l)| l.starts_with("fn ")).unwrap();
        assert!(validate("passes/vsgl_shading.wgsl", &composed).is_ok());
        let broken = composed.replacen(target, "fn this is not wgsl(", 1);
        match validate("passes/vsgl_shading.wgsl", &broken) {
            Err(Error::ShaderCompile { file, line, message }) => {
                assert_eq!((file.as_str(), line as usize), ("common/sg.wgsl", sg_line + 1), "{message}");
                assert!(message.contains("passes/vsgl_shading.wgsl"), "{message}");
            }
            other => panic!("expected a compile error, got {other:?}"),
        }
    }

    #[test]
    fn missing_include_names_file_and_line() {
        let mut seen = HashSet::new();
        let mut out = String::new();
        let err = expand("nope/missing.wgsl", Some(("passes/x.wgsl", 7)), &mut seen, &mut out, 0).unwrap_err();
        let msg = err.to_string();
        assert!(msg.contains("passes/x.wgsl:7") && msg.contains("missing.wgsl"), "{msg}");
    }
}
