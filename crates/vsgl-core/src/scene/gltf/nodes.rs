//! Nodes and cameras: the node hierarchy (checked for missing children, second parents and
//! cycles; roots listed twice or that have a parent are warned about), the nodes reachable from the displayed scene, local and world transforms, and
//! the perspective cameras of reachable nodes. Meshes and lights are instanced from here.

use glam::{DMat4, DQuat, DVec3};
use gltf::json;
use json::validation::Checked;

use super::animation::load_animations;
use super::lights::add_light;
use super::mesh::load_mesh;
use super::raw::RawNode;
use super::{Builder, Ctx};
use crate::error::Result;
use crate::scene::{Camera, Node};

/// A node's local transform from its f64 values in the file (`raw`: the gltf crate keeps f32,
/// which would move a node 1e5 m from the origin by millimetres).
fn node_local(ctx: &Ctx, i: usize, node: &RawNode) -> Result<DMat4> {
    let finite = |v: &[f64]| v.iter().all(|x| x.is_finite());
    if let Some(m) = node.matrix {
        if !finite(&m) {
            return Err(ctx.err(format!("nodes[{i}].matrix"), "non-finite matrix element"));
        }
        return Ok(DMat4::from_cols_array(&m));
    }
    let t = node.translation.unwrap_or([0.0; 3]);
    let s = node.scale.unwrap_or([1.0; 3]);
    let r = node.rotation.unwrap_or([0.0, 0.0, 0.0, 1.0]);
    if !finite(&t) {
        return Err(ctx.err(format!("nodes[{i}].translation"), "non-finite translation"));
    }
    if !finite(&s) {
        return Err(ctx.err(format!("nodes[{i}].scale"), "non-finite scale"));
    }
    let q = DQuat::from_xyzw(r[0], r[1], r[2], r[3]);
    let len = q.length();
    if !(len.is_finite() && len > 1e-12) {
        return Err(ctx.err(
            format!("nodes[{i}].rotation"),
            "rotation is not a unit quaternion",
        ));
    }
    let q = q / len;
    Ok(DMat4::from_scale_rotation_translation(DVec3::from(s), q, DVec3::from(t)))
}

pub(super) fn build_scene(ctx: &Ctx, b: &mut Builder) -> Result<()> {
    let nodes = &ctx.root.nodes;
    let nn = nodes.len();

    // Parents from children lists: every node has at most one parent.
    let mut parent: Vec<Option<usize>> = vec![None; nn];
    for (i, node) in nodes.iter().enumerate() {
        for (k, c) in node.children.iter().flatten().enumerate() {
            let c = c.value();
            if c >= nn {
                return Err(ctx.err(
                    format!("nodes[{i}].children[{k}]"),
                    format!("nodes[{c}] does not exist"),
                ));
            }
            if c == i {
                return Err(ctx.err(
                    format!("nodes[{i}]"),
                    "node is its own child (cycle in the node hierarchy)",
                ));
            }
            if let Some(slot) = parent.get_mut(c) {
                if let Some(p) = *slot {
                    return Err(ctx.err(
                        format!("nodes[{c}]"),
                        format!("node has two parents (nodes[{p}] and nodes[{i}])"),
                    ));
                }
                *slot = Some(i);
            }
        }
    }
    // Cycles: follow parent links, colouring nodes (1 = on the current path, 2 = done).
    let mut state = vec![0u8; nn];
    for start in 0..nn {
        let mut path = Vec::new();
        let mut cur = Some(start);
        while let Some(c) = cur {
            match state.get(c).copied() {
                Some(0) => {
                    if let Some(s) = state.get_mut(c) {
                        *s = 1;
                    }
                    path.push(c);
                    cur = parent.get(c).copied().flatten();
                }
                Some(1) => {
                    return Err(ctx.err(format!("nodes[{c}]"), "cycle in the node hierarchy"));
                }
                _ => break,
            }
        }
        for c in path {
            if let Some(s) = state.get_mut(c) {
                *s = 2;
            }
        }
    }

    // Roots of the displayed scene.
    let roots: Vec<usize> = {
        let scene_index = match ctx.root.scene {
            Some(s) => Some((s.value(), "scene")),
            None if !ctx.root.scenes.is_empty() => Some((0, "scenes[0]")),
            None => None,
        };
        match scene_index {
            Some((s, el)) => {
                let scene = ctx
                    .root
                    .scenes
                    .get(s)
                    .ok_or_else(|| ctx.err(el, format!("scenes[{s}] does not exist")))?;
                let mut roots = Vec::with_capacity(scene.nodes.len());
                let mut listed_at: Vec<Option<usize>> = vec![None; nn];
                let (mut twice, mut not_root) = (FirstOf::default(), FirstOf::default());
                for (k, n) in scene.nodes.iter().enumerate() {
                    let n = n.value();
                    if n >= nn {
                        return Err(ctx.err(
                            format!("scenes[{s}].nodes[{k}]"),
                            format!("nodes[{n}] does not exist"),
                        ));
                    }
                    // glTF 2.0: `scene.nodes` lists root nodes, each once. Both rules
                    // can be broken without harm here (a node is instanced once however
                    // often it is reached, under its parent's transform), so the file loads,
                    // with a warning: other tools may show it differently.
                    if let Some(slot) = listed_at.get_mut(n) {
                        if let Some(first) = *slot {
                            twice.note(format!(
                                "scenes[{s}].nodes[{k}]: nodes[{n}] is listed twice as a root \
                                 of the scene (also at scenes[{s}].nodes[{first}]); it is \
                                 instanced once"
                            ));
                            continue;
                        }
                        *slot = Some(k);
                    }
                    if let Some(p) = parent.get(n).copied().flatten() {
                        not_root.note(format!(
                            "scenes[{s}].nodes[{k}]: nodes[{n}] is not a root node (it is a \
                             child of nodes[{p}]); it is instanced once, under its parent"
                        ));
                    }
                    roots.push(n);
                }
                twice.warn(b);
                not_root.warn(b);
                roots
            }
            None => (0..nn)
                .filter(|&i| parent.get(i).copied().flatten().is_none())
                .collect(),
        }
    };
    let mut reachable = vec![false; nn];
    let mut stack = roots;
    while let Some(i) = stack.pop() {
        match reachable.get_mut(i) {
            Some(r) if !*r => *r = true,
            _ => continue,
        }
        if let Some(node) = nodes.get(i) {
            stack.extend(node.children.iter().flatten().map(|c| c.value()));
        }
    }
    if nn == 0 && !ctx.root.meshes.is_empty() {
        b.warn("the file has meshes but no nodes; nothing is instanced".into());
    }

    // Nodes (all of them, so indices match the file); meshes only on reachable ones.
    for (i, node) in nodes.iter().enumerate() {
        let raw = ctx.raw.nodes.get(i).ok_or_else(|| ctx.err(format!("nodes[{i}]"), "node not found in the JSON's second reading"))?;
        let local = node_local(ctx, i, raw)?;
        let is_reachable = reachable.get(i).copied().unwrap_or(false);
        let mesh = match (node.mesh, is_reachable) {
            (Some(m), true) => Some(load_mesh(ctx, b, m.value(), i)?),
            _ => None,
        };
        if is_reachable && node.skin.is_some() {
            b.warn(format!(
                "nodes[{i}]: skinning is not supported; the mesh is shown unskinned"
            ));
        }
        b.scene.nodes.push(Node {
            name: node.name.clone().unwrap_or_else(|| format!("nodes[{i}]")),
            local,
            parent: parent.get(i).copied().flatten(),
            mesh,
        });
    }

    load_animations(ctx, b)?;

    // Lights and cameras of reachable nodes, in node order.
    let lights: &[json::extensions::scene::khr_lights_punctual::Light] = ctx
        .root
        .extensions
        .as_ref()
        .and_then(|e| e.khr_lights_punctual.as_ref())
        .map_or(&[], |l| &l.lights[..]);
    let mut world_memo: Vec<Option<DMat4>> = vec![None; nn];
    for (i, node) in nodes.iter().enumerate() {
        if !reachable.get(i).copied().unwrap_or(false) {
            continue;
        }
        let has_light = node
            .extensions
            .as_ref()
            .is_some_and(|e| e.khr_lights_punctual.is_some());
        if !has_light && node.camera.is_none() {
            continue;
        }
        let world = world_transform(&b.scene.nodes, &mut world_memo, i);
        if let Some(ext) = node
            .extensions
            .as_ref()
            .and_then(|e| e.khr_lights_punctual.as_ref())
        {
            let li = ext.light.value();
            let light = lights.get(li).ok_or_else(|| {
                ctx.err(
                    format!("nodes[{i}].extensions.KHR_lights_punctual.light"),
                    format!("KHR_lights_punctual.lights[{li}] does not exist"),
                )
            })?;
            let before = b.scene.lights.len();
            add_light(ctx, b, i, li, light, world)?;
            if b.scene.lights.len() > before {
                // The light follows its node when an animation or set_transform moves it.
                b.scene.attach_light(before, i);
            }
        }
        if let Some(c) = node.camera {
            let ci = c.value();
            let camera = ctx.root.cameras.get(ci).ok_or_else(|| {
                ctx.err(
                    format!("nodes[{i}].camera"),
                    format!("cameras[{ci}] does not exist"),
                )
            })?;
            add_camera(ctx, b, i, ci, camera, world)?;
        }
    }
    check_world_bounds(ctx, b, &mut world_memo)
}

/// Refuses a mesh node whose world-space geometry lies beyond ±`limits::MAX_COORDINATE` (or is
/// not finite): a node translated to 3e38 would otherwise load and fail at render with a
/// misleading message. The corners of each mesh's local bounds are transformed, once per node.
fn check_world_bounds(ctx: &Ctx, b: &Builder, world_memo: &mut [Option<DMat4>]) -> Result<()> {
    use crate::scene::limits::MAX_COORDINATE;
    let mut local_bounds: Vec<Option<(DVec3, DVec3)>> = vec![None; b.scene.meshes.len()];
    for i in 0..b.scene.nodes.len() {
        let Some(m) = b.scene.nodes[i].mesh else { continue };
        let Some(mesh) = b.scene.meshes.get(m) else { continue };
        let (lo, hi) = *local_bounds[m].get_or_insert_with(|| {
            let mut lo = DVec3::splat(f64::INFINITY);
            let mut hi = DVec3::splat(f64::NEG_INFINITY);
            for p in mesh.primitives.iter().flat_map(|p| &p.positions) {
                let v = DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64);
                lo = lo.min(v);
                hi = hi.max(v);
            }
            (lo, hi)
        });
        if !(lo.x <= hi.x) {
            continue; // no vertices
        }
        let world = world_transform(&b.scene.nodes, world_memo, i);
        for corner in 0..8 {
            let c = DVec3::new(
                if corner & 1 == 0 { lo.x } else { hi.x },
                if corner & 2 == 0 { lo.y } else { hi.y },
                if corner & 4 == 0 { lo.z } else { hi.z },
            );
            let w = world.transform_point3(c);
            if !w.is_finite() || w.abs().max_element() > MAX_COORDINATE {
                return Err(ctx.err(
                    format!("nodes[{i}]"),
                    format!(
                        "its mesh reaches world position {:?}, beyond ±{MAX_COORDINATE:e} m \
                         (squared distances are formed in f32)",
                        w.to_array()
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// The first of a kind of warning and how many more there were: one line per kind, so that
/// a file repeating a mistake a million times cannot make a million warnings.
#[derive(Default)]
struct FirstOf {
    first: Option<String>,
    more: usize,
}

impl FirstOf {
    fn note(&mut self, msg: String) {
        if self.first.is_none() {
            self.first = Some(msg);
        } else {
            self.more += 1;
        }
    }

    fn warn(self, b: &mut Builder) {
        match (self.first, self.more) {
            (Some(m), 0) => b.warn(m),
            (Some(m), n) => b.warn(format!("{m} (and {n} more like it)")),
            (None, _) => {}
        }
    }
}

/// World transform of node `i`, memoised so that a deep hierarchy costs O(nodes) in all
/// (the hierarchy is known to be acyclic here).
fn world_transform(nodes: &[Node], memo: &mut [Option<DMat4>], i: usize) -> DMat4 {
    let mut chain = Vec::new();
    let mut cur = Some(i);
    let mut m = DMat4::IDENTITY;
    while let Some(c) = cur {
        if let Some(w) = memo.get(c).copied().flatten() {
            m = w;
            break;
        }
        chain.push(c);
        cur = nodes.get(c).and_then(|n| n.parent);
    }
    for &c in chain.iter().rev() {
        m *= nodes.get(c).map_or(DMat4::IDENTITY, |n| n.local);
        if let Some(slot) = memo.get_mut(c) {
            *slot = Some(m);
        }
    }
    m
}

fn add_camera(
    ctx: &Ctx,
    b: &mut Builder,
    node: usize,
    ci: usize,
    camera: &json::Camera,
    world: DMat4,
) -> Result<()> {
    use json::camera::Type;
    let el = format!("cameras[{ci}]");
    match camera.type_ {
        Checked::Valid(Type::Perspective) => {}
        Checked::Valid(Type::Orthographic) => {
            b.warn(format!(
                "nodes[{node}]: orthographic camera {el} is not supported; skipped"
            ));
            return Ok(());
        }
        Checked::Invalid => return Err(ctx.err(format!("{el}.type"), "invalid camera type")),
    }
    let p = camera.perspective.as_ref().ok_or_else(|| {
        ctx.err(
            format!("{el}.perspective"),
            "perspective camera without perspective properties",
        )
    })?;
    if !(p.yfov.is_finite() && p.yfov > 0.0 && p.yfov < std::f32::consts::PI) {
        return Err(ctx.err(
            format!("{el}.perspective.yfov"),
            format!("yfov {} is not in (0, π)", p.yfov),
        ));
    }
    let eye = world.transform_point3(DVec3::ZERO);
    let forward = world.transform_vector3(DVec3::NEG_Z);
    let up = world.transform_vector3(DVec3::Y);
    if eye.is_finite() && eye.abs().max_element() > crate::scene::limits::MAX_COORDINATE {
        return Err(ctx.err(
            format!("nodes[{node}]"),
            format!("camera {el} at {:?} is beyond ±{:e} m", eye.to_array(), crate::scene::limits::MAX_COORDINATE),
        ));
    }
    let ok = eye.is_finite() && forward.length() > 1e-12 && forward.is_finite() && up.is_finite();
    let forward = forward.normalize_or_zero();
    let up = (up - forward * up.dot(forward)).normalize_or_zero();
    if !ok || up == DVec3::ZERO || forward == DVec3::ZERO {
        b.warn(format!(
            "nodes[{node}]: camera {el} has a degenerate transform; skipped"
        ));
        return Ok(());
    }
    b.scene.cameras.push(Camera {
        eye,
        forward,
        up,
        fov_y: p.yfov,
    });
    Ok(())
}
