//! What a frame needs from the device that grows with the scene's lights, checked at the start
//! of a render against the adapter's limits, so a scene too large for the device is refused
//! with the limit, the numbers and how to stay within it (`Error::ResourceLimit`), not with
//! "GPU out of memory" halfway through recording (docs/security.md, "GPU resources").
//!
//! - Shadow-map layers: one depth array holds every light's layers (1 per spot or directional
//!   light, 6 per point light), at most `max_texture_array_layers`.
//! - Shadow-map memory: that array is one texture, so one allocation of layers × side² × 4 bytes
//!   (Depth32Float). wgpu exposes no allocation limit for textures; its `max_buffer_size` is the
//!   device's largest single allocation (Vulkan `maxMemoryAllocationSize`, and below 2 GiB on
//!   Mesa drivers), the same bound that the driver applies to the texture: on lavapipe 600
//!   spot lights at 1024² (2.3 GiB) failed with "GPU out of memory", 511 (2.0 GiB) rendered.
//!   Drivers pad a layer's rows and columns (lavapipe refused 1001 layers of 732², 2.0 GiB
//!   unpadded), so the side is counted rounded up to a multiple of [`SIDE_PADDING`] and the
//!   side suggested in the error is such a multiple (1001 layers of 704² rendered).
//! - The light list: 128 bytes a light in one storage binding, at most
//!   `max_storage_buffer_binding_size`.

use crate::error::{Error, Result};
use crate::frame::uniforms::{shadow_layer_count, LightRaw};
use crate::scene::Light;

/// Bytes of one shadow-map texel (Depth32Float).
const SHADOW_TEXEL_BYTES: u64 = 4;
/// A layer's side as the memory estimate counts it: rounded up to a multiple of this, an upper
/// bound on the tiling and row alignment of the drivers met so far.
pub const SIDE_PADDING: u64 = 64;

/// Shadow layers the lights take: 1 per spot or directional light, 6 per point light.
pub fn shadow_layers(lights: &[Light]) -> u64 {
    lights.iter().map(|l| shadow_layer_count(l) as u64).sum()
}

/// Bytes of a shadow-map array of `layers` layers of `side`² texels, each side counted padded
/// to a multiple of [`SIDE_PADDING`].
pub fn shadow_map_bytes(layers: u64, side: u32) -> u64 {
    let padded = (side as u64).div_ceil(SIDE_PADDING) * SIDE_PADDING;
    layers.saturating_mul(padded * padded * SHADOW_TEXEL_BYTES)
}

/// Checks what `lights` need against `limits`; `shadow_size` is the side of the maps when the
/// method renders shadow maps, `None` when it does not (then only the light list counts).
pub fn check_lights(lights: &[Light], shadow_size: Option<u32>, limits: &wgpu::Limits) -> Result<()> {
    let count = lights.len() as u64;
    let list_bytes = count * std::mem::size_of::<LightRaw>() as u64;
    let list_max = limits.max_storage_buffer_binding_size as u64;
    if list_bytes > list_max {
        let fit = list_max / std::mem::size_of::<LightRaw>() as u64;
        return Err(Error::ResourceLimit(format!(
            "max_storage_buffer_binding_size: the {count} lights take {list_bytes} bytes in the light list, \
             more than this adapter's {list_max}; use at most {fit} lights"
        )));
    }
    let Some(side) = shadow_size else { return Ok(()) };
    let layers = shadow_layers(lights);
    let max_layers = limits.max_texture_array_layers as u64;
    if layers > max_layers {
        return Err(Error::ResourceLimit(format!(
            "max_texture_array_layers: the {count} lights need {layers} shadow-map layers (1 per spot or \
             directional light, 6 per point light), more than this adapter's {max_layers}; use fewer lights \
             (at most {max_layers} spot or directional lights, or {} point lights)",
            max_layers / 6
        )));
    }
    let bytes = shadow_map_bytes(layers, side);
    let budget = limits.max_buffer_size;
    if bytes > budget {
        let per_layer = shadow_map_bytes(1, side);
        let fit_layers = budget / per_layer;
        // The largest padded side at which these layers fit: side² ≤ budget / (4 · layers).
        let fit_side = ((budget / (SHADOW_TEXEL_BYTES * layers)) as f64).sqrt().floor() as u64 / SIDE_PADDING * SIDE_PADDING;
        let smaller = if fit_side > 0 {
            format!("or shadow_size={fit_side} or less for these lights")
        } else {
            format!("no shadow_size fits {layers} layers (a layer takes at least {} bytes)", shadow_map_bytes(1, 1))
        };
        return Err(Error::ResourceLimit(format!(
            "shadow-map memory: the {count} lights' {layers} shadow-map layers of {side}² texels need \
             {layers} × {per_layer} = {bytes} bytes ({:.2} GiB) in one texture, more than this adapter's \
             largest allocation of {budget} bytes ({:.2} GiB, max_buffer_size); use at most {fit_layers} \
             layers at shadow_size={side} (spot or directional lights take 1, point lights 6), {smaller}",
            bytes as f64 / GIB,
            budget as f64 / GIB,
        )));
    }
    Ok(())
}

const GIB: f64 = (1u64 << 30) as f64;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{PointLight, SpotLight};
    use glam::{DVec3, Vec3};

    fn spot() -> Light {
        Light::Spot(SpotLight { position: DVec3::Y, direction: -DVec3::Y, intensity: 1.0, color: Vec3::ONE, inner_cone: 0.5, outer_cone: 0.6 })
    }

    fn point() -> Light {
        Light::Point(PointLight { position: DVec3::Y, intensity: 1.0, color: Vec3::ONE })
    }

    /// Lavapipe's limits as wgpu reports them (2048 layers, i32::MAX bytes, 128 MiB bindings).
    fn limits() -> wgpu::Limits {
        wgpu::Limits { max_texture_array_layers: 2048, max_buffer_size: i32::MAX as u64, max_storage_buffer_binding_size: 1 << 27, ..Default::default() }
    }

    #[test]
    fn layers_are_limited_by_the_array_and_name_the_limit() {
        let lights = vec![spot(); 2049];
        let e = check_lights(&lights, Some(16), &limits()).unwrap_err().to_string();
        assert!(e.starts_with("max_texture_array_layers: the 2049 lights need 2049 shadow-map layers"), "{e}");
        assert!(e.contains("at most 2048 spot or directional lights, or 341 point lights"), "{e}");
        // Point lights count six layers each: 342 of them need 2052.
        let e = check_lights(&vec![point(); 342], Some(16), &limits()).unwrap_err().to_string();
        assert!(e.contains("need 2052 shadow-map layers"), "{e}");
        check_lights(&vec![point(); 341], Some(16), &limits()).expect("2046 layers fit");
        // Without shadow maps the layers do not count.
        check_lights(&lights, None, &limits()).expect("no shadow maps, no layer limit");
    }

    #[test]
    fn shadow_memory_is_limited_and_the_limit_scales_with_the_side() {
        // 1001 spot lights at the default 1024²: 4.2 GB, which failed as "GPU out of memory" before this bound.
        let e = check_lights(&vec![spot(); 1001], Some(1024), &limits()).unwrap_err().to_string();
        assert!(e.starts_with("shadow-map memory: the 1001 lights' 1001 shadow-map layers of 1024² texels need 1001 × 4194304 = 4198498304 bytes"), "{e}");
        assert!(e.contains("use at most 511 layers at shadow_size=1024"), "{e}");
        // 732² would fit unpadded; the suggestion is the multiple of 64 below it.
        assert!(e.contains("or shadow_size=704 or less for these lights"), "{e}");
        check_lights(&vec![spot(); 1001], Some(704), &limits()).expect("the suggested side fits");
        assert!(check_lights(&vec![spot(); 1001], Some(705), &limits()).is_err(), "705 counts as 768");
        // Halving the side quarters the bytes a layer takes: four times the layers fit.
        check_lights(&vec![spot(); 511], Some(1024), &limits()).expect("511 layers at 1024²");
        assert!(check_lights(&vec![spot(); 512], Some(1024), &limits()).is_err());
        check_lights(&vec![spot(); 2047], Some(512), &limits()).expect("2047 layers at 512²");
        // At the largest side only 7 layers fit, and no side fits a huge count of layers.
        assert!(check_lights(&vec![spot(); 8], Some(8192), &limits()).unwrap_err().to_string().contains("at most 7 layers"));
        let tiny = wgpu::Limits { max_buffer_size: 1 << 20, ..limits() };
        let e = check_lights(&vec![spot(); 2000], Some(64), &tiny).unwrap_err().to_string();
        assert!(e.contains("no shadow_size fits 2000 layers"), "{e}");
    }

    #[test]
    fn the_light_list_is_limited_by_the_storage_binding() {
        let small = wgpu::Limits { max_storage_buffer_binding_size: 128 * 10, ..limits() };
        let e = check_lights(&vec![spot(); 11], None, &small).unwrap_err().to_string();
        assert!(e.starts_with("max_storage_buffer_binding_size: the 11 lights take 1408 bytes") && e.contains("at most 10 lights"), "{e}");
    }
}
