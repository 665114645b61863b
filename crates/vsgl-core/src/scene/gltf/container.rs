//! The GLB container: splits a `.glb` file into its JSON chunk and optional BIN chunk,
//! checking the header and every chunk length against the file.

use std::path::Path;

use crate::error::{Error, Result};

fn le_u32(data: &[u8], offset: usize) -> Option<u32> {
    let end = offset.checked_add(4)?;
    let b: [u8; 4] = data.get(offset..end)?.try_into().ok()?;
    Some(u32::from_le_bytes(b))
}

const CHUNK_JSON: u32 = 0x4E4F_534A;
const CHUNK_BIN: u32 = 0x004E_4942;

/// Splits a GLB file into its JSON chunk and optional BIN chunk, checking every length.
pub(super) fn parse_glb<'b>(file: &Path, data: &'b [u8]) -> Result<(&'b [u8], Option<&'b [u8]>)> {
    let bad = |element: &str, msg: String| Error::scene(file, element, msg);
    let version = le_u32(data, 4).ok_or_else(|| {
        bad(
            "GLB header",
            "file is shorter than the 12-byte header".into(),
        )
    })?;
    let length = le_u32(data, 8).ok_or_else(|| {
        bad(
            "GLB header",
            "file is shorter than the 12-byte header".into(),
        )
    })?;
    if version != 2 {
        return Err(bad(
            "GLB header",
            format!("unsupported GLB version {version} (only 2)"),
        ));
    }
    let length = length as usize;
    if length < 12 || length > data.len() {
        return Err(bad(
            "GLB header",
            format!(
                "declared length {length} does not fit the file ({} bytes)",
                data.len()
            ),
        ));
    }
    let data = data.get(..length).unwrap_or(data);

    let mut pos = 12usize;
    let mut json: Option<&[u8]> = None;
    let mut bin: Option<&[u8]> = None;
    let mut index = 0usize;
    while pos < data.len() {
        let el = format!("GLB chunk {index}");
        let (Some(len), Some(ty)) = (le_u32(data, pos), le_u32(data, pos + 4)) else {
            return Err(bad(&el, "truncated chunk header".into()));
        };
        let start = pos + 8;
        let end = start
            .checked_add(len as usize)
            .filter(|&e| e <= data.len())
            .ok_or_else(|| {
                bad(
                    &el,
                    format!("chunk length {len} runs past the end of the file"),
                )
            })?;
        let body = data.get(start..end).unwrap_or_default();
        match (index, ty) {
            (0, CHUNK_JSON) => json = Some(body),
            (0, _) => return Err(bad(&el, "the first chunk must be the JSON chunk".into())),
            (_, CHUNK_JSON) => return Err(bad(&el, "more than one JSON chunk".into())),
            (_, CHUNK_BIN) if bin.is_none() => bin = Some(body),
            (_, CHUNK_BIN) => return Err(bad(&el, "more than one BIN chunk".into())),
            _ => {} // unknown chunk types are skipped (glTF 2.0 §4.4.3.1)
        }
        pos = end;
        index += 1;
    }
    let json = json.ok_or_else(|| bad("GLB chunk 0", "missing JSON chunk".into()))?;
    Ok((json, bin))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn glb_lengths_never_panic() {
        let f = Path::new("x.glb");
        for data in [
            &b"glTF"[..],
            b"glTF\x02\0\0\0\x00\0\0\0",
            b"glTF\x02\0\0\0\x0c\0\0\0",
            b"glTF\x02\0\0\0\x14\0\0\0\xff\xff\xff\xffJSON",
            b"glTF\x01\0\0\0\x0c\0\0\0",
        ] {
            assert!(parse_glb(f, data).is_err());
        }
    }
}
