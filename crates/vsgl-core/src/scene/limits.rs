//! Bounds on the values a scene may hold, set by the products the renderer forms from them
//! in f32 (max 3.4e38), so that a value is refused where it is given, with the real cause,
//! instead of overflowing later into an Inf pixel or a misleading error (docs/security.md,
//! "Values").
//!
//! - Positions: squared distances between any two points are formed in f32, so coordinates
//!   stay within ±[`MAX_COORDINATE`] = 1e18 m (distances ≤ 3.5e18 m, squares ≤ 1.2e37).
//! - Intensities: radiance ~ I·ρ/π / d² and an RSM texel's flux ~ 4π·I; [`MAX_INTENSITY`] =
//!   1e32 leaves six decades of headroom below f32's maximum for distances down to 1 mm.
//!   Scenes that combine extreme intensities with extreme scales can still overflow; the frame
//!   path then refuses the frame (`Error::NonFinite`) rather than hand out NaN or Inf.

use crate::error::{Error, Result};
use glam::DVec3;

/// Largest |coordinate| of a position, in metres (a light-year is 9.5e15 m).
pub const MAX_COORDINATE: f64 = 1e18;
/// Largest light intensity (candela, or lux for a directional light).
pub const MAX_INTENSITY: f64 = 1e32;

/// Largest emitted radiance of a material (glTF emissiveFactor × emissiveStrength): the image
/// adds it to reflected light, so it keeps the same headroom below f32's maximum as
/// [`MAX_INTENSITY`].
pub const MAX_EMITTED_RADIANCE: f64 = 1e32;

/// `p` if every coordinate is finite and within ±[`MAX_COORDINATE`].
pub fn position(arg: &str, p: DVec3) -> Result<DVec3> {
    if !p.is_finite() || p.abs().max_element() > MAX_COORDINATE {
        return Err(Error::invalid(arg, format!(
            "coordinates must be finite and within ±{MAX_COORDINATE:e} m (squared distances are formed in f32), got {:?}",
            p.to_array()
        )));
    }
    Ok(p)
}

/// `d` scaled to unit length without overflow or underflow (a vector such as
/// (0, −1e300, 1e300) is divided by its largest component first, so its square never forms).
pub fn unit_direction(arg: &str, d: DVec3) -> Result<DVec3> {
    let m = d.abs().max_element();
    if !d.is_finite() || !(m > 0.0) {
        return Err(Error::invalid(arg, format!("must be a finite non-zero vector, got {:?}", d.to_array())));
    }
    let scaled = d / m;
    // Components far below the largest vanish in f64 (a ratio under 1e-308): still a direction.
    Ok(scaled / scaled.length())
}

/// A light intensity (`unit`: "candela" or "lux") as the GPU takes it, if in (0, [`MAX_INTENSITY`]].
pub fn intensity(arg: &str, unit: &str, v: f64) -> Result<f32> {
    if !(v.is_finite() && v > 0.0 && v <= MAX_INTENSITY) {
        return Err(Error::invalid(arg, format!(
            "must be positive and at most {MAX_INTENSITY:e} ({unit}; larger values overflow f32 radiance), got {v}"
        )));
    }
    Ok(v as f32)
}

/// An emitted radiance (`KHR_materials_emissive_strength` × factor) if finite, >= 0 and at
/// most [`MAX_EMITTED_RADIANCE`].
pub fn emitted_radiance(arg: &str, v: f64) -> Result<f32> {
    if !(v.is_finite() && v >= 0.0 && v <= MAX_EMITTED_RADIANCE) {
        return Err(Error::invalid(arg, format!(
            "must be finite, >= 0 and at most {MAX_EMITTED_RADIANCE:e} (emitted radiance; larger values overflow f32 images), got {v}"
        )));
    }
    Ok(v as f32)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn directions_normalise_without_overflow_or_underflow() {
        let d = unit_direction("d", DVec3::new(0.0, -1e300, 1e300)).unwrap();
        assert!((d - DVec3::new(0.0, -1.0, 1.0).normalize()).length() < 1e-15, "{d:?}");
        let tiny = unit_direction("d", DVec3::new(1e-310, 0.0, 0.0)).unwrap();
        assert_eq!(tiny, DVec3::X);
        assert!(unit_direction("d", DVec3::ZERO).is_err());
        assert!(unit_direction("d", DVec3::new(f64::NAN, 0.0, 1.0)).is_err());
    }

    #[test]
    fn positions_and_intensities_are_bounded() {
        assert!(position("p", DVec3::splat(1e18)).is_ok());
        let e = position("eye", DVec3::new(0.0, 1.0, 1e300)).unwrap_err().to_string();
        assert!(e.starts_with("eye: coordinates must be finite and within"), "{e}");
        assert_eq!(intensity("i", "candela", 1e32).unwrap(), 1e32);
        assert!(intensity("i", "candela", 3e38).unwrap_err().to_string().contains("at most 1e32"));
        assert!(intensity("i", "candela", 0.0).is_err());
    }
}
