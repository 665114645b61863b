//! WGSL composition: a small include preprocessor over the shaders embedded from `wgsl/`.
//!
//! A line `#include "common/sg.wgsl"` (path relative to `wgsl/`) is replaced by that file,
//! once per composed shader (include guards are implicit), so shared modules can include each
//! other freely. Errors name the including file and line. `override` constants carry per-pass
//! settings, so there is no template logic here.

use crate::error::{Error, Result};
use std::collections::HashSet;

include!(concat!(env!("OUT_DIR"), "/wgsl_files.rs"));

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

    #[test]
    fn missing_include_names_file_and_line() {
        let mut seen = HashSet::new();
        let mut out = String::new();
        let err = expand("nope/missing.wgsl", Some(("passes/x.wgsl", 7)), &mut seen, &mut out, 0).unwrap_err();
        let msg = err.to_string();
        assert!(msg.contains("passes/x.wgsl:7") && msg.contains("missing.wgsl"), "{msg}");
    }
}
