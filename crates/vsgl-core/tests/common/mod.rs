//! Helpers the integration tests share: a fresh temporary folder, base64 for data URIs and a GLB
//! container around JSON and binary chunks (the loader's tests), and the default adapter for the
//! GPU tests (`plan.rs`, `stability.rs`).
#![allow(dead_code)]

pub mod gltf_fixtures;

use std::path::PathBuf;
use std::sync::Arc;
use vsgl_core::gpu::Gpu;
use vsgl_core::Error;

/// The default adapter. Without any adapter at all: `None` and a message, so the test returns
/// early, except under CI (`CI` set), where that is a failure, as it is for the pytest suite
/// (tests/conftest.py): CI must never pass by skipping the GPU tests. `what` says what needs it.
pub fn gpu_or_skip(what: &str) -> Option<Arc<Gpu>> {
    match Gpu::new(None) {
        Ok(gpu) => Some(gpu),
        Err(Error::NoAdapter(msg)) => {
            assert!(std::env::var_os("CI").is_none(), "CI has no GPU or CPU adapter, {what} needs one: {msg}");
            println!("SKIPPED: no GPU or CPU adapter, {what} needs one: {msg}");
            None
        }
        Err(e) => panic!("could not open the default adapter: {e}"),
    }
}

/// An empty folder of its own under the system temp dir (`prefix`, process id, `what`).
pub fn tmpdir(prefix: &str, what: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("vsgl-{prefix}-{}-{what}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Standard base64 with padding (RFC 4648), for `data:` URIs.
pub fn base64(data: &[u8]) -> String {
    const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::new();
    for c in data.chunks(3) {
        let n = (u32::from(c[0]) << 16) | (u32::from(*c.get(1).unwrap_or(&0)) << 8) | u32::from(*c.get(2).unwrap_or(&0));
        for k in 0..4 {
            if k <= c.len() {
                out.push(A[(n >> (18 - 6 * k) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

/// A GLB file (glTF 2.0 binary container): header, the JSON chunk padded with spaces, the
/// BIN chunk padded with zeros, every length as the spec defines it.
pub fn glb(json: &[u8], bin: &[u8]) -> Vec<u8> {
    let mut j = json.to_vec();
    while !j.len().is_multiple_of(4) {
        j.push(b' ');
    }
    let mut b = bin.to_vec();
    while !b.len().is_multiple_of(4) {
        b.push(0);
    }
    let total = 12 + 8 + j.len() + 8 + b.len();
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(j.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&j);
    out.extend_from_slice(&(b.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(&b);
    out
}
