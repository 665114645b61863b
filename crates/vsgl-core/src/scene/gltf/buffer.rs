//! Buffers and bufferViews: every buffer is read (from the GLB BIN chunk, a data: URI or a
//! file) with its byteLength checked against the limits, and every bufferView is checked
//! against its buffer once, so that accessors and images slice only checked ranges.

use std::borrow::Cow;

use super::{Ctx, MAX_BUFFER_BYTES, MAX_TOTAL_BUFFER_BYTES};
use crate::error::Result;

/// A bufferView checked against its buffer.
#[derive(Clone, Copy)]
pub(super) struct ViewInfo {
    buffer: usize,
    offset: usize,
    pub(super) len: usize,
    pub(super) stride: Option<usize>,
}

impl<'a> Ctx<'a> {
    pub(super) fn load_buffers(&mut self, bin: Option<&'a [u8]>) -> Result<()> {
        let mut buffers = Vec::with_capacity(self.root.buffers.len());
        let mut total = 0u64;
        for (i, buffer) in self.root.buffers.iter().enumerate() {
            let el = format!("buffers[{i}]");
            let len = buffer.byte_length.0;
            if len > MAX_BUFFER_BYTES {
                return Err(self.err(
                    el,
                    format!("byteLength {len} exceeds the limit of {MAX_BUFFER_BYTES} bytes"),
                ));
            }
            total = total.saturating_add(len);
            if total > MAX_TOTAL_BUFFER_BYTES {
                return Err(self.err(
                    el,
                    format!("the buffers' byteLengths add up to more than {MAX_TOTAL_BUFFER_BYTES} bytes"),
                ));
            }
            let data: Cow<'a, [u8]> = match &buffer.uri {
                None => {
                    let chunk =
                        match (i, bin) {
                            (0, Some(chunk)) => chunk,
                            _ => return Err(self.err(
                                el,
                                "buffer has no uri (only the first buffer of a .glb may omit it, \
                                 and this file has no BIN chunk for it)",
                            )),
                        };
                    let n = usize::try_from(len).unwrap_or(usize::MAX);
                    let slice = chunk.get(..n).ok_or_else(|| {
                        self.err(
                            el.clone(),
                            format!(
                                "truncated: byteLength is {len} but the GLB BIN chunk has {} bytes",
                                chunk.len()
                            ),
                        )
                    })?;
                    Cow::Borrowed(slice)
                }
                Some(uri) => {
                    let el = format!("{el}.uri");
                    let mut data = self.fetch_uri(uri, &el, Some(len), MAX_BUFFER_BYTES)?;
                    data.truncate(usize::try_from(len).unwrap_or(usize::MAX));
                    Cow::Owned(data)
                }
            };
            buffers.push(data);
        }
        self.buffers = buffers;
        Ok(())
    }

    pub(super) fn check_views(&mut self) -> Result<()> {
        let mut views = Vec::with_capacity(self.root.buffer_views.len());
        for (i, view) in self.root.buffer_views.iter().enumerate() {
            let el = format!("bufferViews[{i}]");
            let b = view.buffer.value();
            let buffer = self.buffers.get(b).ok_or_else(|| {
                self.err(
                    format!("{el}.buffer"),
                    format!("buffers[{b}] does not exist"),
                )
            })?;
            let offset = view.byte_offset.map_or(0, |o| o.0);
            let len = view.byte_length.0;
            let end = offset.checked_add(len).filter(|&e| e <= buffer.len() as u64).ok_or_else(|| {
                self.err(
                    el.clone(),
                    format!(
                        "byteOffset {offset} + byteLength {len} runs past the end of buffers[{b}] ({} bytes)",
                        buffer.len()
                    ),
                )
            })?;
            let stride = match view.byte_stride {
                Some(s) if !(4..=252).contains(&s.0) => {
                    return Err(self.err(
                        format!("{el}.byteStride"),
                        format!("byteStride {} is not in 4..=252", s.0),
                    ))
                }
                Some(s) => Some(s.0),
                None => None,
            };
            // end <= buffer.len(), so both fit in usize.
            views.push(ViewInfo {
                buffer: b,
                offset: offset as usize,
                len: (end - offset) as usize,
                stride,
            });
        }
        self.views = views;
        Ok(())
    }

    pub(super) fn view_bytes(&self, v: ViewInfo) -> Option<&[u8]> {
        self.buffers
            .get(v.buffer)?
            .get(v.offset..v.offset.checked_add(v.len)?)
    }
}
