//! Animations: every channel that drives a node's translation, rotation or scale becomes a
//! [`Channel`] with checked keyframes (times finite, ≥ 0 and strictly increasing; as many
//! outputs as the interpolation needs; values finite), and every targeted node gets its rest
//! pose. Morph-target weights are skipped with a warning. Keyframe data is read through the
//! accessor reader, so it counts against the scene's geometry cap like vertex data.

use glam::{DQuat, DVec3};
use gltf::json;
use json::accessor::{ComponentType, Type as AccType};
use json::animation::{Interpolation as JsonInterpolation, Property};
use json::validation::Checked;

use super::{Builder, Ctx};
use crate::error::Result;
use crate::scene::animation::{AnimatedProperty, Animation, Channel, Interpolation, Keyframes, Trs};

pub(super) fn load_animations(ctx: &Ctx, b: &mut Builder) -> Result<()> {
    let node_count = ctx.root.nodes.len();
    let mut skipped_weights = 0usize;
    for (ai, anim) in ctx.root.animations.iter().enumerate() {
        let mut channels = Vec::with_capacity(anim.channels.len());
        for (ci, ch) in anim.channels.iter().enumerate() {
            let el = format!("animations[{ai}].channels[{ci}]");
            let property = match ch.target.path {
                Checked::Valid(Property::Translation) => AnimatedProperty::Translation,
                Checked::Valid(Property::Rotation) => AnimatedProperty::Rotation,
                Checked::Valid(Property::Scale) => AnimatedProperty::Scale,
                Checked::Valid(Property::MorphTargetWeights) => {
                    skipped_weights += 1;
                    continue;
                }
                Checked::Invalid => return Err(ctx.err(format!("{el}.target.path"), "invalid target path")),
            };
            let node = ch.target.node.value();
            if node >= node_count {
                return Err(ctx.err(format!("{el}.target.node"), format!("nodes[{node}] does not exist")));
            }
            let si = ch.sampler.value();
            let sampler = anim.samplers.get(si).ok_or_else(|| {
                ctx.err(format!("{el}.sampler"), format!("animations[{ai}].samplers[{si}] does not exist"))
            })?;
            let sel = format!("animations[{ai}].samplers[{si}]");
            let interpolation = match sampler.interpolation {
                Checked::Valid(JsonInterpolation::Linear) => Interpolation::Linear,
                Checked::Valid(JsonInterpolation::Step) => Interpolation::Step,
                Checked::Valid(JsonInterpolation::CubicSpline) => Interpolation::CubicSpline,
                Checked::Invalid => return Err(ctx.err(format!("{sel}.interpolation"), "invalid interpolation")),
            };
            let times: Vec<f32> = ctx.read_accessor(
                sampler.input.value(),
                AccType::Scalar,
                &format!("{sel}.input"),
                &[ComponentType::F32],
            )?;
            let (ty, allowed): (AccType, &[ComponentType]) = match property {
                // glTF 2.0 §3.11: translation and scale outputs are float; rotations may also
                // be normalised integers.
                AnimatedProperty::Rotation => {
                    use ComponentType::*;
                    (AccType::Vec4, &[F32, I8, U8, I16, U16])
                }
                _ => (AccType::Vec3, &[ComponentType::F32]),
            };
            let values: Vec<f32> = ctx.read_accessor(sampler.output.value(), ty, &format!("{sel}.output"), allowed)?;
            let keys = Keyframes::new(
                times.into_iter().map(f64::from).collect(),
                values.into_iter().map(f64::from).collect(),
                property.components(),
                interpolation,
            )
            .map_err(|(part, msg)| {
                let element = if part.is_empty() { sel.clone() } else { format!("{sel}.{part}") };
                ctx.err(element, msg)
            })?;
            if !b.scene.rest_poses.contains_key(&node) {
                let rest = rest_pose(ctx, b, node);
                b.scene.rest_poses.insert(node, rest);
            }
            channels.push(Channel { node, property, keys });
        }
        let name = anim.name.clone().unwrap_or_else(|| format!("animations[{ai}]"));
        b.scene.animations.push(Animation { name, channels });
    }
    if skipped_weights > 0 {
        b.warn(format!(
            "{skipped_weights} animation channel(s) drive morph-target weights, which are not supported; skipped"
        ));
    }
    Ok(())
}

/// The node's TRS as the file gives it. glTF 2.0 forbids `matrix` on an animated node; one
/// that has it anyway is decomposed (with a warning), so its other properties stay put.
fn rest_pose(ctx: &Ctx, b: &mut Builder, i: usize) -> Trs {
    let Some(node) = ctx.root.nodes.get(i) else { return Trs::default() };
    if let Some(local) = node.matrix.map(|m| glam::DMat4::from_cols_array(&m.map(f64::from))) {
        b.warn(format!(
            "nodes[{i}]: an animation targets a node with a matrix (glTF 2.0 allows only TRS there); \
             the matrix is decomposed into translation, rotation and scale"
        ));
        let (scale, rotation, translation) = local.to_scale_rotation_translation();
        // A singular matrix has no rotation to recover: keep the identity rather than NaN.
        let rotation = if rotation.is_finite() && rotation.length() > 1e-12 { rotation.normalize() } else { DQuat::IDENTITY };
        let scale = if scale.is_finite() { scale } else { DVec3::ONE };
        return Trs { translation, rotation, scale };
    }
    let t = node.translation.unwrap_or([0.0; 3]).map(f64::from);
    let s = node.scale.unwrap_or([1.0; 3]).map(f64::from);
    let r = node.rotation.map_or([0.0, 0.0, 0.0, 1.0], |q| q.0).map(f64::from);
    // `node_local` has already refused non-finite values and a zero quaternion.
    let q = DQuat::from_array(r);
    let q = if q.length() > 1e-12 { q.normalize() } else { DQuat::IDENTITY };
    Trs { translation: DVec3::from_array(t), rotation: q, scale: DVec3::from_array(s) }
}
