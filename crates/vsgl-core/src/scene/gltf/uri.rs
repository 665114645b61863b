//! URIs of buffers and images: `data:` URIs (base64 or percent-encoded) and relative file
//! names, which must resolve to a regular file inside the scene's own folder (no scheme, no
//! absolute path, no `..` above the folder, no symbolic link out of it). Sizes are checked
//! before anything is read.

use std::io::Read;
use std::path::{Path, PathBuf};

use super::Ctx;
use crate::error::Result;

/// Whether `uri` starts with an RFC 3986 scheme (`http:`, `file:`, `data:`, `C:` ...).
pub(super) fn uri_scheme(uri: &str) -> Option<&str> {
    let colon = uri.find(':')?;
    let scheme = uri.get(..colon)?;
    let mut chars = scheme.chars();
    let first = chars.next()?;
    if first.is_ascii_alphabetic() && chars.all(|c| c.is_ascii_alphanumeric() || "+-.".contains(c))
    {
        Some(scheme)
    } else {
        None
    }
}

fn hex_value(c: u8) -> Option<u8> {
    match c {
        b'0'..=b'9' => Some(c - b'0'),
        b'a'..=b'f' => Some(c - b'a' + 10),
        b'A'..=b'F' => Some(c - b'A' + 10),
        _ => None,
    }
}

/// Decodes `%XX` escapes. `None` on a malformed escape.
fn percent_decode(s: &[u8]) -> Option<Vec<u8>> {
    let mut out = Vec::with_capacity(s.len());
    let mut i = 0;
    while let Some(&c) = s.get(i) {
        if c == b'%' {
            let hi = hex_value(*s.get(i + 1)?)?;
            let lo = hex_value(*s.get(i + 2)?)?;
            out.push(hi << 4 | lo);
            i += 3;
        } else {
            out.push(c);
            i += 1;
        }
    }
    Some(out)
}

/// Standard (and URL-safe) base64 with optional padding; ASCII whitespace is skipped.
fn base64_decode(s: &[u8]) -> Option<Vec<u8>> {
    let mut out = Vec::with_capacity(s.len() / 4 * 3 + 3);
    let mut acc: u32 = 0;
    let mut bits = 0u32;
    let mut padding = 0;
    for &c in s {
        let v = match c {
            b'A'..=b'Z' => c - b'A',
            b'a'..=b'z' => c - b'a' + 26,
            b'0'..=b'9' => c - b'0' + 52,
            b'+' | b'-' => 62,
            b'/' | b'_' => 63,
            b'=' => {
                padding += 1;
                continue;
            }
            b' ' | b'\t' | b'\r' | b'\n' => continue,
            _ => return None,
        };
        if padding > 0 {
            return None; // data after padding
        }
        acc = (acc << 6) | u32::from(v);
        bits += 6;
        if bits >= 8 {
            bits -= 8;
            out.push((acc >> bits) as u8);
            acc &= (1 << bits) - 1;
        }
    }
    // 6 leftover bits means a lone sextet, which encodes no byte.
    if padding > 2 || bits >= 6 {
        return None;
    }
    Some(out)
}

impl Ctx<'_> {
    /// Bytes named by a buffer or image URI: a `data:` URI or a file inside the scene folder.
    /// `exact` is a buffer's byteLength: the file must hold at least that many bytes, and
    /// only those are read. Without it the whole file is read, up to `cap` bytes.
    pub(super) fn fetch_uri(&self, uri: &str, element: &str, exact: Option<u64>, cap: u64) -> Result<Vec<u8>> {
        if let Some(scheme) = uri_scheme(uri) {
            if scheme.eq_ignore_ascii_case("data") {
                return self.decode_data_uri(uri.get(5..).unwrap_or_default(), element, exact, cap);
            }
            return Err(self.err(
                element,
                format!(
                    "URI scheme \"{scheme}:\" is not allowed; only relative file names inside the \
                     scene folder and data: URIs are accepted"
                ),
            ));
        }
        let path = self.resolve_relative(uri, element)?;
        let meta = std::fs::metadata(&path)
            .map_err(|e| self.err(element, format!("cannot open \"{uri}\": {e}")))?;
        if !meta.is_file() {
            return Err(self.err(element, format!("\"{uri}\" is not a regular file")));
        }
        let want = match exact {
            Some(n) => {
                if meta.len() < n {
                    return Err(self.err(
                        element,
                        format!(
                            "file \"{uri}\" is truncated: it has {} bytes but byteLength is {n}",
                            meta.len()
                        ),
                    ));
                }
                n
            }
            None => {
                if meta.len() > cap {
                    return Err(self.err(
                        element,
                        format!(
                            "file \"{uri}\" is {} bytes; at most {cap} are accepted",
                            meta.len()
                        ),
                    ));
                }
                meta.len()
            }
        };
        let want_usize =
            usize::try_from(want).map_err(|_| self.err(element, "too large for this machine"))?;
        let file = std::fs::File::open(&path)
            .map_err(|e| self.err(element, format!("cannot open \"{uri}\": {e}")))?;
        let mut data = Vec::with_capacity(want_usize);
        file.take(want)
            .read_to_end(&mut data)
            .map_err(|e| self.err(element, format!("cannot read \"{uri}\": {e}")))?;
        if (data.len() as u64) < want {
            return Err(self.err(
                element,
                format!(
                    "file \"{uri}\" is truncated: read {} of {want} bytes",
                    data.len()
                ),
            ));
        }
        Ok(data)
    }

    fn decode_data_uri(
        &self,
        rest: &str,
        element: &str,
        exact: Option<u64>,
        cap: u64,
    ) -> Result<Vec<u8>> {
        let comma = rest
            .find(',')
            .ok_or_else(|| self.err(element, "malformed data: URI (no comma)"))?;
        let header = rest.get(..comma).unwrap_or_default();
        let payload = rest.get(comma + 1..).unwrap_or_default().as_bytes();
        let is_base64 = header.to_ascii_lowercase().ends_with(";base64");
        // Upper bound of the decoded size, to refuse an impossible byteLength before decoding.
        let bound = if is_base64 {
            payload.len() as u64 / 4 * 3 + 3
        } else {
            payload.len() as u64
        };
        if let Some(n) = exact {
            if n > bound {
                return Err(self.err(
                    element,
                    format!("data: URI is truncated: it holds at most {bound} bytes but byteLength is {n}"),
                ));
            }
        }
        let data = if is_base64 {
            base64_decode(payload)
                .ok_or_else(|| self.err(element, "malformed base64 in data: URI"))?
        } else {
            percent_decode(payload)
                .ok_or_else(|| self.err(element, "malformed percent-encoding in data: URI"))?
        };
        match exact {
            Some(n) if (data.len() as u64) < n => Err(self.err(
                element,
                format!(
                    "data: URI is truncated: it holds {} bytes but byteLength is {n}",
                    data.len()
                ),
            )),
            None if data.len() as u64 > cap => Err(self.err(
                element,
                format!(
                    "data: URI holds {} bytes; at most {cap} are accepted",
                    data.len()
                ),
            )),
            _ => Ok(data),
        }
    }

    /// Resolves a relative URI to a canonical path under the scene folder, or refuses it.
    fn resolve_relative(&self, uri: &str, element: &str) -> Result<PathBuf> {
        let decoded = percent_decode(uri.as_bytes()).ok_or_else(|| {
            self.err(
                element,
                format!("malformed percent-encoding in URI \"{uri}\""),
            )
        })?;
        let decoded = String::from_utf8(decoded)
            .map_err(|_| self.err(element, format!("URI \"{uri}\" is not UTF-8")))?;
        if decoded.is_empty() {
            return Err(self.err(element, "empty URI"));
        }
        if decoded.contains('\0') {
            return Err(self.err(element, "URI contains a NUL byte"));
        }
        if decoded.starts_with('/')
            || decoded.starts_with('\\')
            || Path::new(&decoded).is_absolute()
        {
            return Err(self.err(
                element,
                format!("absolute path \"{decoded}\" is not allowed; URIs must be relative to the scene folder"),
            ));
        }
        let mut rel = PathBuf::new();
        let mut depth = 0usize;
        for part in decoded.split(['/', '\\']) {
            match part {
                "" | "." => {}
                ".." => {
                    if depth == 0 {
                        return Err(self.err(
                            element,
                            format!("\"{decoded}\" escapes the scene folder with \"..\""),
                        ));
                    }
                    depth -= 1;
                    rel.pop();
                }
                p => {
                    depth += 1;
                    rel.push(p);
                }
            }
        }
        if depth == 0 {
            return Err(self.err(element, format!("\"{decoded}\" does not name a file")));
        }
        let full = self.base.join(&rel);
        let canonical = full
            .canonicalize()
            .map_err(|e| self.err(element, format!("cannot open \"{decoded}\": {e}")))?;
        if !canonical.starts_with(&self.base) {
            return Err(self.err(
                element,
                format!("\"{decoded}\" resolves outside the scene folder (symbolic link?)"),
            ));
        }
        Ok(canonical)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_round_trips() {
        assert_eq!(base64_decode(b"").as_deref(), Some(&b""[..]));
        assert_eq!(base64_decode(b"TQ==").as_deref(), Some(&b"M"[..]));
        assert_eq!(base64_decode(b"TWE=").as_deref(), Some(&b"Ma"[..]));
        assert_eq!(base64_decode(b"TWFu").as_deref(), Some(&b"Man"[..]));
        assert_eq!(base64_decode(b"TWFuTWE").as_deref(), Some(&b"ManMa"[..]));
        assert_eq!(base64_decode(b"TWFu!"), None);
        assert_eq!(base64_decode(b"TQ==TQ=="), None);
        assert_eq!(base64_decode(b"TWFuT"), None);
    }

    #[test]
    fn percent_and_scheme() {
        assert_eq!(percent_decode(b"a%20b").as_deref(), Some(&b"a b"[..]));
        assert_eq!(percent_decode(b"a%2"), None);
        assert_eq!(percent_decode(b"a%zz"), None);
        assert_eq!(uri_scheme("http://x"), Some("http"));
        assert_eq!(
            uri_scheme("data:application/octet-stream;base64,AA=="),
            Some("data")
        );
        assert_eq!(uri_scheme("file.bin"), None);
        assert_eq!(uri_scheme("./a:b.bin"), None);
    }
}
