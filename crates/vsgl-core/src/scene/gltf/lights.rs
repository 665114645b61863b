//! Lights: a KHR_lights_punctual spot light on a reachable node becomes a scene `SpotLight`
//! (checked intensity, colour and cone angles); point and directional lights are skipped
//! with a warning.

use glam::{DMat4, DVec3, Vec3};
use gltf::json;
use json::validation::Checked;

use super::{finite_all, Builder, Ctx};
use crate::error::Result;
use crate::scene::SpotLight;

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
    let (inner, outer) = match kind {
        Type::Spot => light
            .spot
            .as_ref()
            .map_or((0.0, std::f32::consts::FRAC_PI_4), |s| {
                (s.inner_cone_angle, s.outer_cone_angle)
            }),
        Type::Point | Type::Directional => {
            let what = if kind == Type::Point {
                "point"
            } else {
                "directional"
            };
            b.warn(format!(
                "nodes[{node}]: {what} light {el} is not supported (spot lights only); skipped"
            ));
            return Ok(());
        }
    };
    if !(light.intensity.is_finite() && light.intensity >= 0.0) {
        return Err(ctx.err(
            format!("{el}.intensity"),
            format!("intensity {} is not a finite value ≥ 0", light.intensity),
        ));
    }
    if !finite_all(&light.color) || light.color.iter().any(|&c| c < 0.0) {
        return Err(ctx.err(
            format!("{el}.color"),
            "color must be finite and non-negative",
        ));
    }
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
    let position = world.transform_point3(DVec3::ZERO);
    let direction = world.transform_vector3(DVec3::NEG_Z);
    let len = direction.length();
    if !(len.is_finite() && len > 1e-12 && position.is_finite()) {
        b.warn(format!(
            "nodes[{node}]: light {el} has a degenerate transform; skipped"
        ));
        return Ok(());
    }
    b.scene.add_light(SpotLight {
        position,
        direction: direction / len,
        intensity: light.intensity,
        color: Vec3::from_array(light.color),
        inner_cone: inner_c,
        outer_cone: outer_c,
    });
    Ok(())
}
