//! The small built-ins: Cornell boxes, the caustics ring, the mirror panel and the cave, a few
//! hundred to a few thousand triangles each.

use super::*;

/// The classic diffuse Cornell box with two white blocks.
pub fn cornell_box() -> Scene {
    let mut s = Scene { source: "builtin:cornell_box".into(), ..Default::default() };
    cornell_walls(&mut s, Material::dielectric("white", WHITE, 1.0));
    add(&mut s, "tall_block", Material::dielectric("white", WHITE, 1.0), |b| {
        b.cuboid(DVec3::new(-0.65, 0.0, -0.6), DVec3::new(-0.05, 1.2, 0.0), false, Some(2))
    });
    add(&mut s, "short_block", Material::dielectric("white", WHITE, 1.0), |b| {
        b.cuboid(DVec3::new(0.1, 0.0, 0.0), DVec3::new(0.7, 0.6, 0.6), false, Some(2))
    });
    s
}

/// The Cornell box with purely Lambertian materials (`KHR_materials_specular` factor 0, so
/// R_s = 0): the diffuse-only scene on which a frame leaves out every specular lobe.
pub fn diffuse_cornell() -> Scene {
    let mut s = cornell_box();
    s.source = "builtin:diffuse_cornell".into();
    for m in &mut s.materials {
        *m = Material::lambertian(&m.name, [m.base_color_factor[0], m.base_color_factor[1], m.base_color_factor[2]]);
    }
    s
}

/// The Cornell box with GGX objects of roughness 0.05–0.3 (a gold sphere, a glossy block and
/// a glossy floor): glossy indirect light, the papers' subject.
pub fn glossy_cornell() -> Scene {
    let mut s = Scene { source: "builtin:glossy_cornell".into(), ..Default::default() };
    cornell_walls(&mut s, Material::dielectric("glossy_floor", WHITE, 0.3));
    add(&mut s, "gold_sphere", Material::metal("gold", [1.0, 0.78, 0.34], 0.05), |b| {
        b.sphere(DVec3::new(0.4, 0.4, 0.2), 0.4, 32, 64)
    });
    add(&mut s, "glossy_block", Material::metal("steel", [0.8, 0.8, 0.85], 0.15), |b| {
        b.cuboid(DVec3::new(-0.7, 0.0, -0.6), DVec3::new(-0.1, 1.2, -0.1), false, Some(2))
    });
    // The sphere rolls to the front left (0.5 m left, 0.4 m forward, clear of the block) and
    // back over 4 s: a moving glossy object, which re-uploads the geometry every frame.
    let sphere = s.nodes.iter().position(|n| n.name == "gold_sphere").expect("the sphere was just added");
    s.rest_poses.insert(sphere, Trs::default());
    s.animations.push(Animation {
        name: "sphere_roll".into(),
        channels: vec![Channel {
            node: sphere,
            property: AnimatedProperty::Translation,
            keys: builtin_keys(&[0.0, 2.0, 4.0], &[0.0, 0.0, 0.0, -0.5, 0.0, 0.4, 0.0, 0.0, 0.0], 3),
        }],
    });
    s
}

/// A polished metal ring (roughness 0.02) on a diffuse floor under a spot light: the papers'
/// caustics case, where glossy VSGLs matter most.
pub fn caustics_ring() -> Scene {
    let mut s = Scene { source: "builtin:caustics_ring".into(), ..Default::default() };
    add(&mut s, "floor", Material::dielectric("floor", [0.8, 0.8, 0.8], 1.0), |b| {
        b.quad(DVec3::new(-2.0, 0.0, 2.0), DVec3::X * 4.0, DVec3::NEG_Z * 4.0)
    });
    add(&mut s, "ring", Material::metal("polished_gold", [1.0, 0.86, 0.57], 0.02), |b| {
        b.ring(DVec3::ZERO, 0.6, 0.03, 0.35, 128)
    });
    s.add_light(spot(DVec3::new(0.0, 2.2, 2.0), DVec3::new(0.0, 0.0, -0.3), 30.0, 20.0, 30.0));
    s.cameras.push(camera(DVec3::new(0.0, 2.4, -2.2), DVec3::new(0.0, 0.0, 0.0), 45.0));
    s
}

/// A polished metal panel (roughness 0.02) tilted 45° on a diffuse floor in front of a diffuse
/// wall, lit from straight above by a narrow spot: the panel throws the beam sideways onto the
/// wall as a sharp bright patch (a planar caustic). Unlike the
/// ring, every texel of the panel reflects the same way, so the caustic is one coherent lobe
/// that VSGL clusters of the panel can represent exactly, and the wall around the patch should
/// stay dark: light that VSGLs spread there is their bias.
pub fn mirror_panel() -> Scene {
    let mut s = Scene { source: "builtin:mirror_panel".into(), ..Default::default() };
    add(&mut s, "floor", Material::dielectric("floor", [0.8, 0.8, 0.8], 1.0), |b| {
        b.quad(DVec3::new(-3.0, 0.0, 1.5), DVec3::X * 6.0, DVec3::NEG_Z * 3.5)
    });
    add(&mut s, "wall", Material::dielectric("wall", [0.8, 0.8, 0.8], 1.0), |b| {
        b.quad(DVec3::new(-3.0, 0.0, -2.0), DVec3::X * 6.0, DVec3::Y * 2.5)
    });
    // The panel's normal (0, 1, −1)/√2 reflects light falling straight down into −z, onto the
    // wall 1.5 m behind it. Its edges: 0.8 m along x and 0.8 m up the 45° slope.
    let center = DVec3::new(0.0, 0.5, -0.5);
    let (across, up_slope) = (DVec3::X * 0.8, DVec3::new(0.0, 1.0, 1.0).normalize() * 0.8);
    let corner = center - 0.5 * across - 0.5 * up_slope;
    add(&mut s, "panel", Material::metal("polished_silver", [0.97, 0.96, 0.91], 0.02), |b| {
        // Front (mirror side, facing up and towards the wall) and back as two one-sided quads,
        // 1 cm apart so that no ray leaving one face meets the other at distance zero.
        b.quad(corner, up_slope, across);
        b.quad(corner - 0.01 * up_slope.cross(across).normalize(), across, up_slope);
    });
    s.add_light(spot(DVec3::new(0.0, 2.6, -0.5), center, 30.0, 10.0, 14.0));
    s.cameras.push(camera(DVec3::new(1.3, 1.4, 1.5), DVec3::new(-0.3, 0.55, -1.3), 50.0));
    s
}

/// An enclosed room lit only by a narrow spot light (a flashlight) with a glossy floor: all
/// indirect light comes from a small lit spot, the two-VSGL poster's case.
pub fn cave_flashlight() -> Scene {
    let mut s = Scene { source: "builtin:cave_flashlight".into(), ..Default::default() };
    add(&mut s, "floor", Material::dielectric("wet_stone", [0.35, 0.33, 0.3], 0.15), |b| {
        b.quad(DVec3::new(-3.0, 0.0, 3.0), DVec3::X * 6.0, DVec3::NEG_Z * 6.0)
    });
    add(&mut s, "walls", Material::dielectric("rock", [0.55, 0.5, 0.45], 0.8), |b| {
        b.cuboid(DVec3::new(-3.0, 0.0, -3.0), DVec3::new(3.0, 2.5, 3.0), true, Some(2))
    });
    add(&mut s, "boulder", Material::dielectric("boulder", [0.6, 0.45, 0.3], 0.5), |b| {
        b.sphere(DVec3::new(0.8, 0.5, -1.2), 0.5, 24, 48)
    });
    let light = spot(DVec3::new(-0.3, 1.5, 2.2), DVec3::new(0.3, 0.0, -1.5), 40.0, 8.0, 12.0);
    s.add_light(light);
    s.cameras.push(camera(DVec3::new(0.0, 1.6, 2.6), DVec3::new(0.0, 0.6, -1.0), 60.0));
    // The flashlight sits on a node whose rotation sweeps it left and right about the vertical
    // (yaw 0 → +35° → −35° → 0 over 4 s): the light slides across floor, boulder and walls.
    let aim = DQuat::from_rotation_arc(DVec3::NEG_Z, light.direction);
    let rest = Trs { translation: light.position, rotation: aim, scale: DVec3::ONE };
    s.nodes.push(Node { name: "flashlight".into(), local: rest.matrix(), parent: None, mesh: None });
    let node = s.nodes.len() - 1;
    s.attach_light(0, node);
    s.rest_poses.insert(node, rest);
    let yaws_deg = [0.0, 35.0, -35.0, 0.0];
    let rotations: Vec<f64> = yaws_deg
        .iter()
        .flat_map(|&y: &f64| (DQuat::from_rotation_y(y.to_radians()) * aim).to_array())
        .collect();
    s.animations.push(Animation {
        name: "flashlight_sweep".into(),
        channels: vec![Channel {
            node,
            property: AnimatedProperty::Rotation,
            keys: builtin_keys(&[0.0, 1.0, 3.0, 4.0], &rotations, 4),
        }],
    });
    s
}
