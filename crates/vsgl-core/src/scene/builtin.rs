//! Built-in procedural scenes (no files needed): `vsgl.scenes.names()`.
//!
//! Units are metres, +Y up. Every scene has a default camera and one spot light, so
//! `r.render(vsgl.scenes.cornell_box())` just works. Two are animated (`scene.set_time(t)`,
//! `scene.animations`), with the same machinery as glTF animations: `cave_flashlight`'s
//! flashlight sweeps the cave (its light sits on an animated node), `glossy_cornell`'s gold
//! sphere rolls to the front and back. Until `set_time` is called both show their rest pose.

use super::animation::{AnimatedProperty, Animation, Channel, Interpolation, Keyframes, Trs};
use super::{Camera, Material, Mesh, Node, Primitive, Scene, SpotLight};
use glam::{DMat4, DQuat, DVec3, Vec3};
use std::f64::consts::PI;

/// The names accepted by [`by_name`], in the order `vsgl.scenes.names()` lists them.
pub const NAMES: &[&str] =
    &["cornell_box", "glossy_cornell", "caustics_ring", "cave_flashlight", "diffuse_cornell", "mirror_panel", "helmet_shell"];

/// A built-in scene by name, or `None` for an unknown name.
pub fn by_name(name: &str) -> Option<Scene> {
    Some(match name {
        "cornell_box" => cornell_box(),
        "glossy_cornell" => glossy_cornell(),
        "caustics_ring" => caustics_ring(),
        "cave_flashlight" => cave_flashlight(),
        "diffuse_cornell" => diffuse_cornell(),
        "mirror_panel" => mirror_panel(),
        "helmet_shell" => helmet_shell(),
        _ => return None,
    })
}

/// Accumulates triangles with flat or smooth normals into one primitive.
#[derive(Default)]
struct MeshBuilder {
    prim: Primitive,
}

impl MeshBuilder {
    fn vertex(&mut self, p: DVec3, n: DVec3, uv: [f32; 2]) -> u32 {
        self.prim.positions.push(p.as_vec3().to_array());
        self.prim.normals.push(n.normalize().as_vec3().to_array());
        self.prim.uvs.push(uv);
        (self.prim.positions.len() - 1) as u32
    }

    /// A parallelogram `origin + s·e1 + t·e2`, s,t ∈ [0,1], facing `e1 × e2`.
    fn quad(&mut self, origin: DVec3, e1: DVec3, e2: DVec3) {
        let n = e1.cross(e2).normalize();
        let a = self.vertex(origin, n, [0.0, 0.0]);
        let b = self.vertex(origin + e1, n, [1.0, 0.0]);
        let c = self.vertex(origin + e1 + e2, n, [1.0, 1.0]);
        let d = self.vertex(origin + e2, n, [0.0, 1.0]);
        self.prim.indices.extend_from_slice(&[a, b, c, a, c, d]);
    }

    /// An axis-aligned box with outward normals (`inward` flips them, for rooms).
    fn cuboid(&mut self, min: DVec3, max: DVec3, inward: bool, skip_face: Option<usize>) {
        let s = max - min;
        let (x, y, z) = (DVec3::X * s.x, DVec3::Y * s.y, DVec3::Z * s.z);
        // Faces as (origin, e1, e2) with e1 × e2 pointing outward: −x, +x, −y, +y, −z, +z.
        let faces = [
            (min, z, y),
            (min + x, y, z),
            (min, x, z),
            (min + y, z, x),
            (min, y, x),
            (min + z, x, y),
        ];
        for (i, (o, e1, e2)) in faces.into_iter().enumerate() {
            if skip_face == Some(i) {
                continue;
            }
            if inward { self.quad(o, e2, e1) } else { self.quad(o, e1, e2) }
        }
    }

    /// A UV sphere with smooth normals.
    fn sphere(&mut self, center: DVec3, radius: f64, rings: u32, segments: u32) {
        let base = self.prim.positions.len() as u32;
        for i in 0..=rings {
            let theta = PI * i as f64 / rings as f64;
            for j in 0..=segments {
                let phi = 2.0 * PI * j as f64 / segments as f64;
                let n = DVec3::new(theta.sin() * phi.cos(), theta.cos(), theta.sin() * phi.sin());
                self.vertex(center + radius * n, n, [j as f32 / segments as f32, i as f32 / rings as f32]);
            }
        }
        let row = segments + 1;
        for i in 0..rings {
            for j in 0..segments {
                let (a, b) = (base + i * row + j, base + (i + 1) * row + j);
                self.prim.indices.extend_from_slice(&[a, a + 1, b, b, a + 1, b + 1]);
            }
        }
    }

    /// A thin ring (open cylinder shell with inner and outer wall and a top rim), axis +Y.
    fn ring(&mut self, center: DVec3, radius: f64, thickness: f64, height: f64, segments: u32) {
        let r_in = radius - 0.5 * thickness;
        let r_out = radius + 0.5 * thickness;
        let at = |r: f64, phi: f64, y: f64| center + DVec3::new(r * phi.cos(), y, r * phi.sin());
        let radial = |phi: f64| DVec3::new(phi.cos(), 0.0, phi.sin());
        for (r, sign) in [(r_out, 1.0), (r_in, -1.0)] {
            let base = self.prim.positions.len() as u32;
            for j in 0..=segments {
                let phi = 2.0 * PI * j as f64 / segments as f64;
                let u = j as f32 / segments as f32;
                self.vertex(at(r, phi, 0.0), sign * radial(phi), [u, 0.0]);
                self.vertex(at(r, phi, height), sign * radial(phi), [u, 1.0]);
            }
            for j in 0..segments {
                let (a, b, c, d) = (base + 2 * j, base + 2 * j + 1, base + 2 * j + 2, base + 2 * j + 3);
                // Winding so that the geometric normal agrees with the shading normal.
                if sign > 0.0 {
                    self.prim.indices.extend_from_slice(&[a, b, c, c, b, d]);
                } else {
                    self.prim.indices.extend_from_slice(&[a, c, b, c, d, b]);
                }
            }
        }
        // Top rim.
        let base = self.prim.positions.len() as u32;
        for j in 0..=segments {
            let phi = 2.0 * PI * j as f64 / segments as f64;
            self.vertex(at(r_in, phi, height), DVec3::Y, [0.0, 0.0]);
            self.vertex(at(r_out, phi, height), DVec3::Y, [1.0, 0.0]);
        }
        for j in 0..segments {
            let (a, b, c, d) = (base + 2 * j, base + 2 * j + 1, base + 2 * j + 2, base + 2 * j + 3);
            self.prim.indices.extend_from_slice(&[a, c, b, b, c, d]);
        }
    }

    /// A thin spherical cap (a shell of thickness `r_out − r_in`) around +Y from the pole down to
    /// the polar angle `theta_max`: the outer surface faces out, the inner one in (towards the
    /// centre), and a band at `theta_max` closes the rim.
    fn shell_cap(&mut self, center: DVec3, r_out: f64, r_in: f64, theta_max: f64, rings: u32, segments: u32) {
        let dir = |theta: f64, phi: f64| DVec3::new(theta.sin() * phi.cos(), theta.cos(), theta.sin() * phi.sin());
        let row = segments + 1;
        for (r, sign) in [(r_out, 1.0), (r_in, -1.0)] {
            let base = self.prim.positions.len() as u32;
            for i in 0..=rings {
                let theta = theta_max * i as f64 / rings as f64;
                for j in 0..=segments {
                    let phi = 2.0 * PI * j as f64 / segments as f64;
                    let n = dir(theta, phi);
                    self.vertex(center + r * n, sign * n, [j as f32 / segments as f32, i as f32 / rings as f32]);
                }
            }
            for i in 0..rings {
                for j in 0..segments {
                    let (a, b) = (base + i * row + j, base + (i + 1) * row + j);
                    // Winding so that the geometric normal agrees with the shading normal.
                    if sign > 0.0 {
                        self.prim.indices.extend_from_slice(&[a, a + 1, b, b, a + 1, b + 1]);
                    } else {
                        self.prim.indices.extend_from_slice(&[a, b, a + 1, b, b + 1, a + 1]);
                    }
                }
            }
        }
        // The rim band between the two surfaces, facing down and out along the cap's edge.
        let base = self.prim.positions.len() as u32;
        for j in 0..=segments {
            let phi = 2.0 * PI * j as f64 / segments as f64;
            let rim = dir(theta_max, phi);
            let n = DVec3::new(0.0, -1.0, 0.0).lerp(rim, 0.5);
            self.vertex(center + r_out * rim, n, [j as f32 / segments as f32, 0.0]);
            self.vertex(center + r_in * rim, n, [j as f32 / segments as f32, 1.0]);
        }
        for j in 0..segments {
            let (a, b, c, d) = (base + 2 * j, base + 2 * j + 1, base + 2 * j + 2, base + 2 * j + 3);
            self.prim.indices.extend_from_slice(&[a, c, b, b, c, d]);
        }
    }

    fn finish(self, name: &str, material: usize) -> Mesh {
        let mut prim = self.prim;
        prim.material = material;
        Mesh { name: name.into(), primitives: vec![prim] }
    }
}

fn add(scene: &mut Scene, name: &str, material: Material, build: impl FnOnce(&mut MeshBuilder)) {
    scene.materials.push(material);
    let mut b = MeshBuilder::default();
    build(&mut b);
    let mesh = b.finish(name, scene.materials.len() - 1);
    scene.add_mesh_node(name, mesh, DMat4::IDENTITY);
}

fn spot(position: DVec3, target: DVec3, intensity: f32, inner_deg: f32, outer_deg: f32) -> SpotLight {
    SpotLight {
        position,
        direction: (target - position).normalize(),
        intensity,
        color: Vec3::ONE,
        inner_cone: inner_deg.to_radians(),
        outer_cone: outer_deg.to_radians(),
    }
}

/// Keyframes made here are valid by construction (increasing times, matching counts).
fn builtin_keys(times: &[f64], values: &[f64], components: usize) -> Keyframes {
    Keyframes::new(times.to_vec(), values.to_vec(), components, Interpolation::Linear)
        .map_err(|(_, msg)| msg)
        .expect("built-in keyframes are valid")
}

fn camera(eye: DVec3, target: DVec3, fov_y_deg: f32) -> Camera {
    Camera::look_at(eye, target, DVec3::Y, fov_y_deg.to_radians()).expect("built-in camera is valid")
}

const WHITE: [f32; 3] = [0.73, 0.73, 0.73];
const RED: [f32; 3] = [0.63, 0.065, 0.05];
const GREEN: [f32; 3] = [0.14, 0.45, 0.091];

/// Walls of a 2 m Cornell box (x, z ∈ [−1, 1], y ∈ [0, 2]), open towards +z.
fn cornell_walls(scene: &mut Scene, floor: Material) {
    let lo = DVec3::new(-1.0, 0.0, -1.0);
    add(scene, "floor", floor, |b| b.quad(DVec3::new(-1.0, 0.0, 1.0), DVec3::X * 2.0, DVec3::NEG_Z * 2.0));
    add(scene, "ceiling", Material::dielectric("white", WHITE, 1.0), |b| {
        b.quad(DVec3::new(-1.0, 2.0, -1.0), DVec3::X * 2.0, DVec3::Z * 2.0)
    });
    add(scene, "back_wall", Material::dielectric("white", WHITE, 1.0), |b| {
        b.quad(lo, DVec3::X * 2.0, DVec3::Y * 2.0)
    });
    add(scene, "left_wall", Material::dielectric("red", RED, 1.0), |b| {
        b.quad(DVec3::new(-1.0, 0.0, 1.0), DVec3::NEG_Z * 2.0, DVec3::Y * 2.0)
    });
    add(scene, "right_wall", Material::dielectric("green", GREEN, 1.0), |b| {
        b.quad(DVec3::new(1.0, 0.0, -1.0), DVec3::Z * 2.0, DVec3::Y * 2.0)
    });
    scene.add_light(spot(DVec3::new(0.0, 1.95, 0.0), DVec3::new(0.0, 0.0, 0.0), 6.0, 40.0, 55.0));
    scene.cameras.push(camera(DVec3::new(0.0, 1.0, 3.9), DVec3::new(0.0, 1.0, 0.0), 40.0));
}

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
/// wall as a sharp bright patch (a planar caustic), issue 18's mirror-panel case. Unlike the
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

/// A helmet-like object at FlightHelmet's size (docs/rendering.md, "The real-scene corpus"): a
/// thin leather cap (a 5 mm spherical shell) over a head, a polished metal visor band around the
/// head at eye level under the cap's rim, a neck and a wooden pedestal, lit like FlightHelmet's
/// corpus light. What the boxes lack and the helmet has: a curved thin shell, and creases where
/// parts meet at close range (cap over forehead, visor on the face, head on neck, neck on
/// pedestal, rivets half sunk into the cap, a hose of touching beads, goggle lenses sunk into the
/// face), where much of the indirect light is exchanged between surfaces a few RSM texels apart.
/// No textures or normal maps yet.
pub fn helmet_shell() -> Scene {
    let mut s = Scene { source: "builtin:helmet_shell".into(), ..Default::default() };
    add(&mut s, "pedestal", Material::dielectric("wood", [0.45, 0.25, 0.12], 0.6), |b| {
        b.cuboid(DVec3::new(-0.15, 0.0, -0.15), DVec3::new(0.15, 0.1, 0.15), false, Some(2))
    });
    add(&mut s, "neck", Material::dielectric("rubber", [0.12, 0.12, 0.12], 0.8), |b| {
        b.cuboid(DVec3::new(-0.04, 0.1, -0.04), DVec3::new(0.04, 0.27, 0.04), false, Some(2))
    });
    let head = DVec3::new(0.0, 0.36, 0.0);
    add(&mut s, "head", Material::dielectric("skin", [0.6, 0.45, 0.35], 0.5), |b| b.sphere(head, 0.11, 24, 48));
    add(&mut s, "cap", Material::dielectric("leather", [0.35, 0.22, 0.12], 0.7), |b| {
        b.shell_cap(head, 0.125, 0.12, 1.75, 20, 48)
    });
    add(&mut s, "visor", Material::metal("steel", [0.9, 0.9, 0.92], 0.15), |b| {
        // Just below the cap's rim; its inner wall cuts into the face at the top, as exported
        // parts often interpenetrate.
        b.ring(head + DVec3::new(0.0, -0.055, 0.0), 0.108, 0.006, 0.03, 48)
    });
    // Rivets: 6 mm spheres half sunk into the cap along eight meridians.
    add(&mut s, "rivets", Material::metal("brass", [0.95, 0.78, 0.45], 0.3), |b| {
        for m in 0..8 {
            let phi = 2.0 * PI * m as f64 / 8.0 + 0.2;
            for k in 1..=5 {
                let theta = 1.6 * k as f64 / 5.5;
                let n = DVec3::new(theta.sin() * phi.cos(), theta.cos(), theta.sin() * phi.sin());
                b.sphere(head + 0.125 * n, 0.006, 6, 12);
            }
        }
    });
    // Goggle lenses: two glossy 18 mm spheres sunk into the face at eye level, inside the visor.
    add(&mut s, "lenses", Material::dielectric("glass", [0.2, 0.25, 0.2], 0.1), |b| {
        for x in [-0.04, 0.04] {
            b.sphere(head + DVec3::new(x, -0.04, 0.085), 0.018, 12, 24);
        }
    });
    // A hose of touching 9 mm beads from the chin down to the pedestal.
    add(&mut s, "hose", Material::dielectric("rubber", [0.15, 0.15, 0.15], 0.6), |b| {
        for k in 0..14 {
            let t = k as f64 / 13.0;
            let p = DVec3::new(0.02 + 0.06 * t, 0.27 - 0.16 * t, 0.09 + 0.02 * (PI * t).sin());
            b.sphere(p, 0.009, 8, 16);
        }
    });
    s.add_light(spot(DVec3::new(0.5, 0.9, 0.6), head, 3.0, 30.0, 40.0));
    s.cameras.push(camera(DVec3::new(0.0, 0.45, 0.95), DVec3::new(0.0, 0.3, 0.0), 40.0));
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_builtin_has_camera_light_and_triangles() {
        for name in NAMES {
            let s = by_name(name).unwrap();
            assert!(!s.cameras.is_empty() && !s.lights.is_empty(), "{name}");
            assert!(s.stats().triangles > 0, "{name}");
        }
        assert!(by_name("nope").is_none());
    }

    #[test]
    fn the_flashlight_sweeps_and_comes_back() {
        let mut s = by_name("cave_flashlight").unwrap();
        let rest = *s.lights[0].as_spot().unwrap();
        let v = s.geometry_version;
        s.set_time(1.0).unwrap();
        let swept = *s.lights[0].as_spot().unwrap();
        // +35° about +Y turns the beam; its position stays.
        let cos = swept.direction.dot(rest.direction);
        let horizontal = |d: DVec3| DVec3::new(d.x, 0.0, d.z).normalize();
        let yaw = horizontal(swept.direction).dot(horizontal(rest.direction)).acos().to_degrees();
        assert!((yaw - 35.0).abs() < 1e-6, "yaw {yaw}");
        assert!(cos < 0.9 && (swept.position - rest.position).length() < 1e-12);
        assert_eq!(s.geometry_version, v, "a light-only animation must keep the uploaded geometry");
        s.set_time(4.0).unwrap();
        let back = *s.lights[0].as_spot().unwrap();
        assert!((back.direction - rest.direction).length() < 1e-12);
        assert_eq!(s.animations[0].duration(), 4.0);
    }

    #[test]
    fn the_glossy_sphere_rolls_and_is_uploaded_again() {
        let mut s = by_name("glossy_cornell").unwrap();
        let sphere = s.nodes.iter().position(|n| n.name == "gold_sphere").unwrap();
        let v = s.geometry_version;
        s.set_time(1.0).unwrap(); // half way to (−0.5, 0, 0.4)
        let moved = s.world_transform(sphere).transform_point3(DVec3::ZERO);
        assert!((moved - DVec3::new(-0.25, 0.0, 0.2)).length() < 1e-12, "{moved}");
        assert_eq!(s.geometry_version, v + 1, "a moved mesh must be uploaded again");
        s.set_time(4.0).unwrap();
        assert!(s.world_transform(sphere).transform_point3(DVec3::ZERO).length() < 1e-12);
    }

    #[test]
    fn geometric_and_shading_normals_agree() {
        // Flat faces and spheres must be wound so the triangle normal points like the vertex
        // normals; the G-buffer pass relies on it to orient shading normals.
        for name in NAMES {
            let s = by_name(name).unwrap();
            for m in &s.meshes {
                for p in &m.primitives {
                    for t in p.indices.chunks(3) {
                        let v = |i: u32| glam::Vec3::from(p.positions[i as usize]);
                        let ng = (v(t[1]) - v(t[0])).cross(v(t[2]) - v(t[0]));
                        if ng.length() < 1e-9 {
                            continue;
                        }
                        let ns = glam::Vec3::from(p.normals[t[0] as usize]);
                        assert!(ng.dot(ns) > 0.0, "{name}/{}: triangle {t:?} wound against its normal", m.name);
                    }
                }
            }
        }
    }
}
