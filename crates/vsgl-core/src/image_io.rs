//! Writing frames: PNG (tone-mapped sRGB) and NumPy `.npy` (linear float32).
//!
//! Tone mapping happens here on the CPU rather than in a GPU pass: frames are read back as
//! linear floats anyway (NumPy is the product), so a GPU pass would add a second readback.

use crate::error::{Error, Result};
use std::io::Write;
use std::path::Path;

/// sRGB encoding of a linear value in [0, 1] (IEC 61966-2-1).
fn srgb_encode(x: f32) -> f32 {
    if x <= 0.003_130_8 { 12.92 * x } else { 1.055 * x.powf(1.0 / 2.4) - 0.055 }
}

/// Linear RGB (H·W·3) → 8-bit sRGB after multiplying by `exposure`; NaN/Inf never occur in
/// frames, but would map to black rather than poison the image.
pub fn tonemap_srgb8(rgb: &[f32], exposure: f32) -> Vec<u8> {
    rgb.iter()
        .map(|&v| {
            let x = if v.is_finite() { (v * exposure).clamp(0.0, 1.0) } else { 0.0 };
            (srgb_encode(x) * 255.0 + 0.5) as u8
        })
        .collect()
}

pub fn encode_png(rgb: &[f32], width: u32, height: u32, exposure: f32) -> Result<Vec<u8>> {
    let pixels = tonemap_srgb8(rgb, exposure);
    let mut out = Vec::new();
    image::ImageEncoder::write_image(
        image::codecs::png::PngEncoder::new(&mut out),
        &pixels,
        width,
        height,
        image::ExtendedColorType::Rgb8,
    )
    .map_err(|e| Error::invalid("path", format!("PNG encoding failed: {e}")))?;
    Ok(out)
}

/// OpenEXR, linear float32 RGB (for HDR viewers and compositing tools).
pub fn encode_exr(rgb: &[f32], width: u32, height: u32) -> Result<Vec<u8>> {
    let mut out = std::io::Cursor::new(Vec::new());
    image::ImageEncoder::write_image(
        image::codecs::openexr::OpenExrEncoder::new(&mut out),
        bytemuck::cast_slice(rgb),
        width,
        height,
        image::ExtendedColorType::Rgb32F,
    )
    .map_err(|e| Error::invalid("path", format!("EXR encoding failed: {e}")))?;
    Ok(out.into_inner())
}

/// NumPy format 1.0: magic, header dict padded to a multiple of 64 bytes, little-endian f32.
pub fn encode_npy(data: &[f32], shape: &[usize]) -> Vec<u8> {
    let dims: Vec<String> = shape.iter().map(|d| d.to_string()).collect();
    let shape_str = if dims.len() == 1 { format!("({},)", dims[0]) } else { format!("({})", dims.join(", ")) };
    let mut header = format!("{{'descr': '<f4', 'fortran_order': False, 'shape': {shape_str}, }}");
    let total = 10 + header.len() + 1;
    header.push_str(&" ".repeat((64 - total % 64) % 64));
    header.push('\n');
    let mut out = Vec::with_capacity(10 + header.len() + data.len() * 4);
    out.extend_from_slice(b"\x93NUMPY\x01\x00");
    out.extend_from_slice(&(header.len() as u16).to_le_bytes());
    out.extend_from_slice(header.as_bytes());
    for v in data {
        out.extend_from_slice(&v.to_le_bytes());
    }
    out
}

/// Writes `bytes` to `path`. The error is the operating system's, unchanged: a path that
/// cannot be written is not a bad argument value but an I/O failure, and the caller (the
/// Python binding raises `OSError`) names the path with it.
pub fn write_file(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let mut f = std::fs::File::create(path)?;
    f.write_all(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn npy_header_is_aligned_and_parsable() {
        let b = encode_npy(&[1.0, 2.0, 3.0, 4.0, 5.0, 6.0], &[1, 2, 3]);
        let hlen = u16::from_le_bytes([b[8], b[9]]) as usize;
        assert_eq!((10 + hlen) % 64, 0);
        let header = std::str::from_utf8(&b[10..10 + hlen]).unwrap();
        assert!(header.contains("'shape': (1, 2, 3)"), "{header}");
        assert_eq!(b.len(), 10 + hlen + 24);
    }

    #[test]
    fn exr_round_trips_linear_floats() {
        let rgb: Vec<f32> = (0..2 * 3 * 3).map(|i| i as f32 * 0.37 + 1e-3).collect();
        let bytes = encode_exr(&rgb, 3, 2).unwrap();
        let img = image::load_from_memory_with_format(&bytes, image::ImageFormat::OpenExr).unwrap().to_rgb32f();
        assert_eq!((img.width(), img.height()), (3, 2));
        assert_eq!(img.as_raw(), &rgb);
    }

    #[test]
    fn srgb_endpoints() {
        assert_eq!(tonemap_srgb8(&[0.0, 1.0, 2.0, f32::NAN], 1.0), vec![0, 255, 255, 0]);
        // Mid-grey 0.18 linear encodes to ≈ 118 in sRGB.
        assert_eq!(tonemap_srgb8(&[0.18], 1.0)[0], 118);
    }
}
