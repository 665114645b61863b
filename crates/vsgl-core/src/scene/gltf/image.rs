//! Images and textures: an image is read from a file, data: URI or bufferView, its size is
//! checked from the header against the limits and the texture memory budget
//! (`LoadOptions::max_texture_bytes`) before it is decoded (PNG and JPEG only) to RGBA8, and
//! each (image, colour or data use) pair becomes one scene texture.

use std::borrow::Cow;
use std::io::Cursor;

use image::ImageDecoder;

use super::uri::uri_scheme;
use super::{
    Builder, Ctx, MAX_IMAGE_FILE_BYTES, MAX_IMAGE_SIDE, MAX_TOTAL_IMAGE_FILE_BYTES,
};
use crate::error::Result;
use crate::scene::{Texture, TextureUsage};

impl Ctx<'_> {
    /// Reads an image (file, data URI or bufferView), checks its size from the header and
    /// decodes it to RGBA8.
    fn decode_image(&self, i: usize) -> Result<(u32, u32, Vec<u8>)> {
        let el = format!("images[{i}]");
        let image = self
            .root
            .images
            .get(i)
            .ok_or_else(|| self.err(el.clone(), "image does not exist"))?;
        let bytes: Cow<[u8]> = match (&image.uri, image.buffer_view) {
            (Some(uri), _) => {
                let used = self.image_file_bytes.get();
                if used >= MAX_TOTAL_IMAGE_FILE_BYTES {
                    return Err(self.err(
                        el,
                        format!("the scene's image files exceed the limit of {MAX_TOTAL_IMAGE_FILE_BYTES} bytes"),
                    ));
                }
                let cap = MAX_IMAGE_FILE_BYTES.min(MAX_TOTAL_IMAGE_FILE_BYTES - used);
                let data = self.fetch_uri(uri, &format!("{el}.uri"), None, cap)?;
                self.image_file_bytes.set(used + data.len() as u64);
                Cow::Owned(data)
            }
            (None, Some(v)) => {
                let vi = v.value();
                let view = *self.views.get(vi).ok_or_else(|| {
                    self.err(
                        format!("{el}.bufferView"),
                        format!("bufferViews[{vi}] does not exist"),
                    )
                })?;
                if view.len as u64 > MAX_IMAGE_FILE_BYTES {
                    return Err(self.err(
                        el,
                        format!("image data is larger than {MAX_IMAGE_FILE_BYTES} bytes"),
                    ));
                }
                Cow::Borrowed(
                    self.view_bytes(view)
                        .ok_or_else(|| self.err(el.clone(), "bufferView out of range"))?,
                )
            }
            (None, None) => return Err(self.err(el, "image has neither uri nor bufferView")),
        };
        let reader = || -> Result<image::ImageReader<Cursor<&[u8]>>> {
            let r = image::ImageReader::new(Cursor::new(&bytes[..]))
                .with_guessed_format()
                .map_err(|e| self.err(el.clone(), format!("cannot read image: {e}")))?;
            match r.format() {
                Some(image::ImageFormat::Png | image::ImageFormat::Jpeg) => Ok(r),
                Some(f) => Err(self.err(
                    el.clone(),
                    format!("image format {f:?} is not supported (PNG and JPEG only)"),
                )),
                None => Err(self.err(el.clone(), "unrecognised image format (PNG and JPEG only)")),
            }
        };
        // Everything the checks need comes from the header; nothing is decoded yet.
        let probe = reader()?
            .into_decoder()
            .map_err(|e| self.err(el.clone(), format!("cannot read the image header: {e}")))?;
        let (w, h) = probe.dimensions();
        let native = probe.total_bytes();
        let converts = probe.color_type() != image::ColorType::Rgba8;
        drop(probe);
        if w == 0 || h == 0 || w > MAX_IMAGE_SIDE || h > MAX_IMAGE_SIDE {
            return Err(self.err(
                el,
                format!(
                    "image is {w}×{h} pixels; sides of 1 to {MAX_IMAGE_SIDE} pixels are accepted"
                ),
            ));
        }
        // The budget: while an image is converted, the decoder's output
        // in the file's own format (1 to 8 bytes a pixel) and the RGBA8 copy kept for the GPU
        // exist together, on top of the textures kept so far. Counting both makes the budget
        // a bound on the loader's peak texel memory, not only on what it returns.
        let rgba8 = u64::from(w) * u64::from(h) * 4;
        let transient = if converts { native } else { 0 };
        let kept = self.texture_bytes.get();
        let peak = kept.saturating_add(rgba8).saturating_add(transient);
        if peak > self.max_texture_bytes {
            let what = match &image.uri {
                Some(u) if uri_scheme(u).is_none() => format!("\"{u}\" "),
                _ => String::new(),
            };
            let decoding = if converts {
                format!(" plus {transient} while it is decoded")
            } else {
                String::new()
            };
            return Err(self.err(
                el,
                format!(
                    "image {what}is {w}×{h} pixels: {rgba8} bytes as RGBA8{decoding}; with the \
                     {kept} bytes of textures loaded before it, that exceeds the texture memory \
                     budget of {} bytes. If the file is trusted, raise the budget with \
                     max_texture_bytes= (vsgl.Scene.load; LoadOptions::max_texture_bytes in Rust)",
                    self.max_texture_bytes
                ),
            ));
        }
        let mut r = reader()?;
        let mut limits = image::Limits::default();
        limits.max_image_width = Some(MAX_IMAGE_SIDE);
        limits.max_image_height = Some(MAX_IMAGE_SIDE);
        // The decoder's output buffer (already within the budget) plus room for its scratch.
        limits.max_alloc = Some(native.saturating_add(64 << 20));
        r.limits(limits);
        let img = r
            .decode()
            .map_err(|e| self.err(el.clone(), format!("cannot decode image: {e}")))?;
        // `into_rgba8` keeps an RGBA8 image's own buffer instead of copying it.
        let rgba = img.into_rgba8();
        let (w, h) = rgba.dimensions();
        self.texture_bytes.set(kept.saturating_add(u64::from(w) * u64::from(h) * 4));
        Ok((w, h, rgba.into_raw()))
    }
}

pub(super) fn texture_index(
    ctx: &Ctx,
    b: &mut Builder,
    ti: usize,
    tex_coord: u32,
    usage: TextureUsage,
    element: String,
) -> Result<Option<usize>> {
    if tex_coord != 0 {
        b.warn(format!(
            "{element}: texCoord {tex_coord} is not supported (TEXCOORD_0 only); texture ignored"
        ));
        return Ok(None);
    }
    let texture = ctx.root.textures.get(ti).ok_or_else(|| {
        ctx.err(
            format!("{element}.index"),
            format!("textures[{ti}] does not exist"),
        )
    })?;
    let ii = texture.source.value();
    let image = ctx.root.images.get(ii).ok_or_else(|| {
        ctx.err(
            format!("textures[{ti}].source"),
            format!("images[{ii}] does not exist"),
        )
    })?;
    let key = (ii, usage == TextureUsage::Color);
    if let Some(&s) = b.texture_map.get(&key) {
        return Ok(Some(s));
    }
    let (width, height, rgba8) = ctx.decode_image(ii)?;
    let name = image
        .name
        .clone()
        .or_else(|| image.uri.clone().filter(|u| uri_scheme(u).is_none()))
        .unwrap_or_else(|| format!("images[{ii}]"));
    b.scene.textures.push(Texture {
        name,
        width,
        height,
        rgba8,
        usage,
    });
    let s = b.scene.textures.len() - 1;
    b.texture_map.insert(key, s);
    Ok(Some(s))
}
