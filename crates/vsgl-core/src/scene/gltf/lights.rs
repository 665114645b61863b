//! Lights: every KHR_lights_punctual light on a reachable node becomes a scene light (spot,
//! point or directional; checked intensity, colour and cone angles). A light's `range` is
//! ignored with a warning (docs/scenes.md, "Lights": every method uses the physical
//! inverse-square law, so none of them could honour the window consistently with the others).

use glam::{DMat4, DVec3, Vec3};
use gltf::json;
use json::validation::Checked;

use super::{finite_all, Builder, Ctx};
use crate::error::Result;
use crate::scene::{DirectionalLight, Light, PointLight, SpotLight};

pub(super) fn add_light(
    ctx: &Ctx,
    b: &mut Builder,
    node: usize,
    li: usize,
    light: &json::extensions::scene::khr_lights_punctual::Light,
    world: DMat4,
) -> Result<()> {
    use json::extensions::scene::khr_lights_punctual::Type;
    let el = format!("extensions.KHR_lights_punctual.lights[{li}]");
    let kind = match light.type_ {
        Checked::Valid(t) => t,
        Checked::Invalid => return Err(ctx.err(format!("{el}.type"), "invalid light type")),
    };
    if !(light.intensity.is_finite() && light.intensity >= 0.0) {
        return Err(ctx.err(
            format!("{el}.intensity"),
            format!("intensity {} is not a finite value ≥ 0", light.intensity),
        ));
    }
    if light.intensity as f64 > crate::scene::limits::MAX_INTENSITY {
        return Err(ctx.err(
            format!("{el}.intensity"),
            format!("intensity {} is above {:e} (larger values overflow f32 radiance)", light.intensity, crate::scene::limits::MAX_INTENSITY),
        ));
    }
    if !finite_all(&light.color) || light.color.iter().any(|&c| c < 0.0) {
        return Err(ctx.err(
            format!("{el}.color"),
            "color must be finite and non-negative",
        ));
    }
    if let (Some(range), Type::Spot | Type::Point) = (light.range, kind) {
        b.warn(format!(
            "nodes[{node}]: {el}.range = {range} is ignored: lights fall off by the inverse-square \
             law without a cut-off window (docs/scenes.md, \"Lights\")"
        ));
    }
    // KHR_lights_punctual: a light sits at its node's origin and points along the node's −Z.
    let position = world.transform_point3(DVec3::ZERO);
    let direction = world.transform_vector3(DVec3::NEG_Z);
    let len = direction.length();
    let degenerate = match kind {
        Type::Point => !position.is_finite(),
        Type::Directional => !(len.is_finite() && len > 1e-12),
        Type::Spot => !(len.is_finite() && len > 1e-12 && position.is_finite()),
    };
    if kind != Type::Directional && position.is_finite() && position.abs().max_element() > crate::scene::limits::MAX_COORDINATE {
        return Err(ctx.err(
            format!("nodes[{node}]"),
            format!("light {el} at {:?} is beyond ±{:e} m (squared distances are formed in f32)", position.to_array(), crate::scene::limits::MAX_COORDINATE),
        ));
    }
    if degenerate {
        b.warn(format!(
            "nodes[{node}]: light {el} has a degenerate transform; skipped"
        ));
        return Ok(());
    }
    let color = Vec3::from_array(light.color);
    let intensity = light.intensity;
    let out: Light = match kind {
        // Intensity in candela (KHR_lights_punctual), radiating equally in all directions.
        Type::Point => PointLight { position, intensity, color }.into(),
        // Illuminance in lux on a surface facing the light; position-free.
        Type::Directional => DirectionalLight { direction: direction / len, intensity, color }.into(),
        Type::Spot => {
            let (inner, outer) = light
                .spot
                .as_ref()
                .map_or((0.0, std::f32::consts::FRAC_PI_4), |s| {
                    (s.inner_cone_angle, s.outer_cone_angle)
                });
            if !(inner.is_finite() && outer.is_finite()) {
                return Err(ctx.err(format!("{el}.spot"), "non-finite cone angle"));
            }
            let half_pi = std::f32::consts::FRAC_PI_2;
            let outer_c = outer.clamp(1e-4, half_pi);
            let inner_c = inner.clamp(0.0, outer_c * 0.999);
            if outer_c != outer || inner_c != inner {
                b.warn(format!(
                    "{el}: cone angles inner {inner}, outer {outer} are outside 0 ≤ inner < outer ≤ π/2; \
                     clamped to {inner_c}, {outer_c}"
                ));
            }
            SpotLight {
                position,
                direction: direction / len,
                intensity,
                color,
                inner_cone: inner_c,
                outer_cone: outer_c,
            }
            .into()
        }
    };
    b.scene.add_light(out);
    Ok(())
}
