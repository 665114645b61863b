//! Built-in procedural scenes (no files needed): `vsgl.scenes.names()`.
//!
//! Units are metres, +Y up. Every scene has a default camera and one spot light, so
//! `r.render(vsgl.scenes.cornell_box())` just works. Two are animated (`scene.set_time(t)`,
//! `scene.animations`), with the same machinery as glTF animations: `cave_flashlight`'s
//! flashlight sweeps the cave (its light sits on an animated node), `glossy_cornell`'s gold
//! sphere rolls to the front and back. Until `set_time` is called both show their rest pose.

use super::animation::{AnimatedProperty, Animation, Channel, Interpolation, Keyframes, Trs};
use super::{Camera, Material, Mesh, Node, Primitive, Scene, SpotLight, Texture, TextureUsage};
use glam::{DMat4, DQuat, DVec3, Vec3};
use std::f64::consts::PI;

/// The names accepted by [`by_name`], in the order `vsgl.scenes.names()` lists them.
pub const NAMES: &[&str] = &[
    "cornell_box",
    "glossy_cornell",
    "caustics_ring",
    "cave_flashlight",
    "diffuse_cornell",
    "mirror_panel",
    "helmet_shell",
    "furnished_room",
    "atrium",
];

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
        "furnished_room" => furnished_room(),
        "atrium" => atrium(),
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

    /// A parallelogram like [`Self::quad`] whose texture coordinates run 0…`uv_scale` (a texture
    /// repeated across a floor, not stretched over it).
    fn quad_tiled(&mut self, origin: DVec3, e1: DVec3, e2: DVec3, uv_scale: [f32; 2]) {
        let n = e1.cross(e2).normalize();
        let a = self.vertex(origin, n, [0.0, 0.0]);
        let b = self.vertex(origin + e1, n, [uv_scale[0], 0.0]);
        let c = self.vertex(origin + e1 + e2, n, [uv_scale[0], uv_scale[1]]);
        let d = self.vertex(origin + e2, n, [0.0, uv_scale[1]]);
        self.prim.indices.extend_from_slice(&[a, b, c, a, c, d]);
    }

    /// A triangle wound so that its geometric normal points like its first vertex's normal.
    fn oriented_triangle(&mut self, a: u32, b: u32, c: u32) {
        let p = |i: u32| DVec3::from(self.prim.positions[i as usize].map(f64::from));
        let ng = (p(b) - p(a)).cross(p(c) - p(a));
        let ns = DVec3::from(self.prim.normals[a as usize].map(f64::from));
        if ng.dot(ns) >= 0.0 {
            self.prim.indices.extend_from_slice(&[a, b, c]);
        } else {
            self.prim.indices.extend_from_slice(&[a, c, b]);
        }
    }

    /// A (nu × nv)-cell grid of vertices `surface(u, v) = (position, normal)`, u, v ∈ [0, 1],
    /// with texture coordinates (u·uv_scale[0], v·uv_scale[1]).
    fn grid(&mut self, nu: u32, nv: u32, uv_scale: [f32; 2], surface: impl Fn(f64, f64) -> (DVec3, DVec3)) {
        let base = self.prim.positions.len() as u32;
        for j in 0..=nv {
            for i in 0..=nu {
                let (u, v) = (i as f64 / nu as f64, j as f64 / nv as f64);
                let (p, n) = surface(u, v);
                self.vertex(p, n, [u as f32 * uv_scale[0], v as f32 * uv_scale[1]]);
            }
        }
        let row = nu + 1;
        for j in 0..nv {
            for i in 0..nu {
                let (a, b) = (base + j * row + i, base + (j + 1) * row + i);
                self.oriented_triangle(a, a + 1, b + 1);
                self.oriented_triangle(a, b + 1, b);
            }
        }
    }

    /// A closed upright cylinder from `base` up by `height`: smooth side, flat caps.
    fn cylinder(&mut self, base: DVec3, radius: f64, height: f64, segments: u32) {
        let radial = |phi: f64| DVec3::new(phi.cos(), 0.0, phi.sin());
        self.grid(segments, 1, [1.0, 1.0], |u, v| {
            let n = radial(2.0 * PI * u);
            (base + radius * n + DVec3::Y * (height * v), n)
        });
        for (y, n) in [(0.0, -DVec3::Y), (height, DVec3::Y)] {
            let centre = self.vertex(base + DVec3::Y * y, n, [0.5, 0.5]);
            let first = self.prim.positions.len() as u32;
            for j in 0..=segments {
                let phi = 2.0 * PI * j as f64 / segments as f64;
                self.vertex(base + radius * radial(phi) + DVec3::Y * y, n, [0.5 + 0.5 * phi.cos() as f32, 0.5 + 0.5 * phi.sin() as f32]);
            }
            for j in 0..segments {
                self.oriented_triangle(centre, first + j, first + j + 1);
            }
        }
    }

    /// A hanging curtain: a single sheet from `top_left` along `across` (horizontal, its
    /// length the width) and down by `height`, folded along its normal `n0` by
    /// `depth`·sin(2π·folds·u), with the normals of the folded sheet.
    #[allow(clippy::too_many_arguments)]
    fn curtain(&mut self, top_left: DVec3, across: DVec3, n0: DVec3, height: f64, folds: f64, depth: f64, nu: u32, nv: u32) {
        let width = across.length();
        let t = across / width;
        self.grid(nu, nv, [4.0, 4.0], |u, v| {
            let w = 2.0 * PI * folds;
            let offset = depth * (w * u).sin();
            // d(position)/du = width·t + depth·w·cos(w·u)·n0; the normal is (d/du × down) turned to face n0.
            let du = width * t + depth * w * (w * u).cos() * n0;
            let n = du.cross(DVec3::Y).normalize();
            let n = if n.dot(n0) < 0.0 { -n } else { n };
            (top_left + t * (width * u) + n0 * offset - DVec3::Y * (height * v), n)
        });
    }

    fn finish(self, name: &str, material: usize) -> Mesh {
        let mut prim = self.prim;
        prim.material = material;
        Mesh { name: name.into(), primitives: vec![prim] }
    }
}

fn add(scene: &mut Scene, name: &str, material: Material, build: impl FnOnce(&mut MeshBuilder)) {
    add_mesh(scene, name, material, false, build);
}

/// Adds a mesh of `material` built by `build` on a node of its own; `tangents`: generated from the
/// texture coordinates (what a normal map needs).
fn add_mesh(scene: &mut Scene, name: &str, material: Material, tangents: bool, build: impl FnOnce(&mut MeshBuilder)) {
    scene.materials.push(material);
    let mut b = MeshBuilder::default();
    build(&mut b);
    if tangents {
        let p = &mut b.prim;
        p.tangents = super::gltf::generate_tangents(&p.positions, &p.normals, &p.uvs, &p.indices);
    }
    let mesh = b.finish(name, scene.materials.len() - 1);
    scene.add_mesh_node(name, mesh, DMat4::IDENTITY);
}

/// Adds a `size`² RGBA8 texture whose texel (x, y) is `texel(x / size, y / size)` (u, v in
/// [0, 1)) and returns its index.
fn add_texture(scene: &mut Scene, name: &str, size: u32, usage: TextureUsage, texel: impl Fn(f64, f64) -> [u8; 4]) -> usize {
    let mut rgba8 = Vec::with_capacity((size * size * 4) as usize);
    for y in 0..size {
        for x in 0..size {
            rgba8.extend(texel(x as f64 / size as f64, y as f64 / size as f64));
        }
    }
    scene.textures.push(Texture { name: name.into(), width: size, height: size, rgba8, usage });
    scene.textures.len() - 1
}

/// A tangent-space normal map of the height field `height(u, v)` (periodic on [0, 1)²),
/// `strength` the slope scale, by central differences: n ∝ (−∂h/∂u, −∂h/∂v, 1).
fn add_normal_map(scene: &mut Scene, name: &str, size: u32, strength: f64, height: impl Fn(f64, f64) -> f64) -> usize {
    let e = 1.0 / size as f64;
    add_texture(scene, name, size, TextureUsage::Data, |u, v| {
        let du = (height(u + e, v) - height(u - e, v)) / (2.0 * e);
        let dv = (height(u, v + e) - height(u, v - e)) / (2.0 * e);
        let n = DVec3::new(-strength * du, -strength * dv, 1.0).normalize();
        let byte = |c: f64| ((c * 0.5 + 0.5) * 255.0).round().clamp(0.0, 255.0) as u8;
        [byte(n.x), byte(n.y), byte(n.z), 255]
    })
}

/// A deterministic hash of an integer to [0, 1) (texture and layout variation without a RNG).
fn hash01(k: u32) -> f64 {
    let mut x = k.wrapping_mul(0x9E37_79B9) ^ 0x85EB_CA6B;
    x ^= x >> 16;
    x = x.wrapping_mul(0x7FEB_352D);
    x ^= x >> 15;
    x = x.wrapping_mul(0x846C_A68B);
    x ^= x >> 16;
    f64::from(x) / 4_294_967_296.0
}

fn srgb8(c: f64) -> u8 {
    (c.clamp(0.0, 1.0) * 255.0).round() as u8
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

/// A helmet-like object at FlightHelmet's size (docs/scenes.md, "The real-scene corpus"): a
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

/// A furnished room (4 × 3 m, 2.6 m high), what real interiors have and the boxes lack: many
/// small objects on a textured parquet floor, touching and interpenetrating (table legs through
/// the top, books pressed together on a shelf, cushions sunk into a sofa, toy blocks in a heap,
/// a rug sunk into the floor), thin parts (shelf boards 2 cm thick, a floor lamp on a 12 mm
/// pole, a lampshade 3 mm thick), a normal-mapped plaster wall and a brushed-metal vase whose
/// roughness comes from a metallic-roughness texture. One spot light in a ceiling corner aims at
/// the table; the camera stands inside the room.
pub fn furnished_room() -> Scene {
    let mut s = Scene { source: "builtin:furnished_room".into(), ..Default::default() };
    let (hx, hz, h) = (2.0, 1.5, 2.6);
    // Parquet: 8 planks across a texture that repeats every 0.5 m, grain along the planks.
    let parquet = add_texture(&mut s, "parquet", 256, TextureUsage::Color, |u, v| {
        let plank = (u * 8.0).floor() as u32;
        let shade = 0.8 + 0.35 * hash01(plank * 7 + ((v * 2.0).floor() as u32) * 131);
        let grain = 0.9 + 0.1 * (v * 60.0 + 9.0 * hash01(plank)).sin();
        let seam = if (u * 8.0).fract() < 0.03 { 0.5 } else { 1.0 };
        let k = shade * grain * seam;
        [srgb8(0.62 * k), srgb8(0.42 * k), srgb8(0.24 * k), 255]
    });
    let plaster = add_normal_map(&mut s, "plaster_normal", 128, 0.02, |u, v| {
        let (x, y) = (2.0 * PI * u, 2.0 * PI * v);
        (3.0 * x).sin() * (2.0 * y).cos() + 0.5 * (7.0 * x + 5.0 * y).sin() + 0.25 * (13.0 * y - 11.0 * x).cos()
    });
    let brushed = add_texture(&mut s, "brushed_roughness", 64, TextureUsage::Data, |u, _| {
        // glTF: roughness in G, metallic in B. Stripes of roughness 0.25…0.6 around the vase.
        let r = 0.25 + 0.35 * (0.5 + 0.5 * (2.0 * PI * 12.0 * u).sin());
        [0, srgb8(r), 255, 255]
    });
    let mut floor = Material::dielectric("parquet", [1.0, 1.0, 1.0], 0.35);
    floor.base_color_texture = Some(parquet);
    add(&mut s, "floor", floor, |b| {
        b.quad_tiled(DVec3::new(-hx, 0.0, hz), DVec3::new(2.0 * hx, 0.0, 0.0), DVec3::new(0.0, 0.0, -2.0 * hz), [8.0, 6.0])
    });
    add(&mut s, "ceiling", Material::dielectric("ceiling", [0.8, 0.8, 0.78], 0.9), |b| {
        b.quad(DVec3::new(-hx, h, -hz), DVec3::new(2.0 * hx, 0.0, 0.0), DVec3::new(0.0, 0.0, 2.0 * hz))
    });
    let mut wall = Material::dielectric("plaster", [0.75, 0.72, 0.66], 0.8);
    wall.normal_texture = Some(plaster);
    add_mesh(&mut s, "walls", wall, true, |b| {
        b.quad_tiled(DVec3::new(-hx, 0.0, -hz), DVec3::new(2.0 * hx, 0.0, 0.0), DVec3::new(0.0, h, 0.0), [4.0, 2.6]); // back
        b.quad_tiled(DVec3::new(hx, 0.0, hz), DVec3::new(-2.0 * hx, 0.0, 0.0), DVec3::new(0.0, h, 0.0), [4.0, 2.6]); // front
        b.quad_tiled(DVec3::new(-hx, 0.0, hz), DVec3::new(0.0, 0.0, -2.0 * hz), DVec3::new(0.0, h, 0.0), [3.0, 2.6]); // left
    });
    add(&mut s, "accent_wall", Material::dielectric("blue paint", [0.2, 0.3, 0.55], 0.7), |b| {
        b.quad(DVec3::new(hx, 0.0, -hz), DVec3::new(0.0, 0.0, 2.0 * hz), DVec3::new(0.0, h, 0.0))
    });
    // A rug 1 cm thick, sunk 4 mm into the floor.
    add(&mut s, "rug", Material::dielectric("wool", [0.55, 0.12, 0.1], 0.95), |b| {
        b.cuboid(DVec3::new(-1.2, -0.004, -0.6), DVec3::new(0.6, 0.006, 0.9), false, Some(2))
    });
    // Table: a 4 cm top whose legs run 1 cm into it.
    add(&mut s, "table", Material::dielectric("oak", [0.5, 0.33, 0.18], 0.45), |b| {
        b.cuboid(DVec3::new(-0.9, 0.72, -0.3), DVec3::new(0.3, 0.76, 0.4), false, None);
        for (x, z) in [(-0.85, -0.25), (0.25, -0.25), (-0.85, 0.35), (0.25, 0.35)] {
            b.cuboid(DVec3::new(x - 0.025, 0.0, z - 0.025), DVec3::new(x + 0.025, 0.73, z + 0.025), false, Some(2));
        }
    });
    // Two chairs pushed under the table's edge (their backs touch the top).
    add(&mut s, "chairs", Material::dielectric("walnut", [0.32, 0.2, 0.12], 0.5), |b| {
        for (x, z, back) in [(-0.55, 0.55, 1.0), (-0.1, -0.5, -1.0)] {
            b.cuboid(DVec3::new(x - 0.2, 0.44, z - 0.2), DVec3::new(x + 0.2, 0.48, z + 0.2), false, None);
            for (dx, dz) in [(-0.17, -0.17), (0.17, -0.17), (-0.17, 0.17), (0.17, 0.17)] {
                b.cuboid(DVec3::new(x + dx - 0.015, 0.0, z + dz - 0.015), DVec3::new(x + dx + 0.015, 0.45, z + dz + 0.015), false, Some(2));
            }
            let zb = z + back * 0.19;
            b.cuboid(DVec3::new(x - 0.2, 0.48, zb - 0.015), DVec3::new(x + 0.2, 0.95, zb + 0.015), false, None);
        }
    });
    // Sofa against the left wall with three cushions sunk into its seat and back.
    add(&mut s, "sofa", Material::dielectric("fabric", [0.3, 0.36, 0.3], 0.9), |b| {
        b.cuboid(DVec3::new(-2.0, 0.0, -0.9), DVec3::new(-1.15, 0.42, 0.9), false, Some(2));
        b.cuboid(DVec3::new(-2.0, 0.42, -0.9), DVec3::new(-1.8, 0.85, 0.9), false, None);
        for z in [-0.55, 0.0, 0.55] {
            b.sphere(DVec3::new(-1.75, 0.62, z), 0.2, 12, 24);
        }
    });
    // Shelf on the back wall: three 2 cm boards pressed into the wall, books pressed together.
    add(&mut s, "shelf", Material::dielectric("pine", [0.6, 0.48, 0.32], 0.55), |b| {
        for y in [1.0, 1.35, 1.7] {
            b.cuboid(DVec3::new(0.4, y, -1.505), DVec3::new(1.6, y + 0.02, -1.25), false, None);
        }
    });
    add(&mut s, "books", Material::dielectric("book covers", [0.5, 0.25, 0.2], 0.6), |b| {
        let mut k = 0;
        for y in [1.02, 1.37, 1.72] {
            let mut x = 0.45;
            while x < 1.5 {
                let w = 0.025 + 0.02 * hash01(k);
                let hb = 0.18 + 0.1 * hash01(k + 1000);
                // Each book overlaps its neighbour by 1 mm: pressed together.
                b.cuboid(DVec3::new(x, y - 0.001, -1.48), DVec3::new(x + w + 0.001, y + hb, -1.3 + 0.03 * hash01(k + 2000)), false, None);
                x += w;
                k += 1;
            }
        }
    });
    // A brushed-metal vase and fruit on the table, a heap of toy blocks on the rug.
    let mut vase = Material::metal("brushed steel", [0.85, 0.85, 0.88], 1.0);
    vase.metallic_roughness_texture = Some(brushed);
    add(&mut s, "vase", vase, |b| b.cylinder(DVec3::new(-0.3, 0.755, 0.05), 0.06, 0.3, 40));
    add(&mut s, "fruit", Material::dielectric("apples", [0.7, 0.12, 0.08], 0.35), |b| {
        for (x, z) in [(-0.6, 0.1), (-0.52, 0.16), (-0.56, 0.02), (-0.65, 0.2)] {
            b.sphere(DVec3::new(x, 0.795, z), 0.04, 12, 24);
        }
    });
    add(&mut s, "blocks", Material::dielectric("painted wood", [0.85, 0.7, 0.2], 0.5), |b| {
        for k in 0..24u32 {
            let (x, z) = (-0.2 + 0.5 * hash01(k * 3), 0.3 + 0.45 * hash01(k * 3 + 1));
            // Sunk 2 mm into the rug or into each other, never exactly on a face.
            let y = 0.004 + 0.06 * (k % 3) as f64 * hash01(k * 3 + 2);
            b.cuboid(DVec3::new(x, y, z), DVec3::new(x + 0.07, y + 0.07, z + 0.07), false, None);
        }
    });
    // Floor lamp: a 12 mm chrome pole on a disc, a 3 mm fabric shade ring.
    add(&mut s, "lamp", Material::metal("chrome", [0.9, 0.9, 0.9], 0.12), |b| {
        b.cylinder(DVec3::new(1.55, -0.002, 1.05), 0.15, 0.02, 32);
        b.cylinder(DVec3::new(1.55, 0.01, 1.05), 0.006, 1.55, 12);
    });
    add(&mut s, "lampshade", Material::dielectric("linen", [0.9, 0.85, 0.7], 0.9), |b| {
        b.ring(DVec3::new(1.55, 1.45, 1.05), 0.18, 0.003, 0.25, 48)
    });
    s.add_light(spot(DVec3::new(1.7, 2.5, 1.2), DVec3::new(-0.4, 0.6, -0.1), 25.0, 30.0, 50.0));
    s.cameras.push(camera(DVec3::new(1.4, 1.5, 1.35), DVec3::new(-0.6, 0.7, -0.6), 60.0));
    s
}

/// A courtyard at the papers' scale (the 2015 and 2016 papers measured on scenes of 264k–331k
/// triangles): 300k triangles of finely tessellated columns round a court, arcades of arches
/// on them, hanging curtains (folded thin sheets), a floor of 1,600 tiles and planters of 1,200
/// leaves. The sun is a spot light high above one corner; the camera looks across the court.
pub fn atrium() -> Scene {
    let mut s = Scene { source: "builtin:atrium".into(), ..Default::default() };
    let (hx, hz) = (6.0, 4.0);
    // Floor: 40 × 40 tiles, each a quad, alternating two stones.
    add(&mut s, "floor_tiles_light", Material::dielectric("limestone", [0.7, 0.66, 0.58], 0.6), |b| {
        tiles(b, hx, hz, 40, 0)
    });
    add(&mut s, "floor_tiles_dark", Material::dielectric("slate", [0.3, 0.3, 0.32], 0.4), |b| tiles(b, hx, hz, 40, 1));
    // Walls round the court, 6 m high, facing in (four quads: a box would put a floor face
    // under the tiles, coplanar with them).
    add(&mut s, "walls", Material::dielectric("stucco", [0.75, 0.6, 0.45], 0.85), |b| {
        let (up, along_x, along_z) = (DVec3::new(0.0, 6.0, 0.0), DVec3::new(2.0 * hx, 0.0, 0.0), DVec3::new(0.0, 0.0, 2.0 * hz));
        b.quad(DVec3::new(-hx, 0.0, -hz), up, along_z);
        b.quad(DVec3::new(hx, 0.0, -hz), along_z, up);
        b.quad(DVec3::new(-hx, 0.0, -hz), along_x, up);
        b.quad(DVec3::new(-hx, 0.0, hz), up, along_x);
    });
    // Columns: 20 round the court, each 64 segments × 48 rings, with a base and a capital.
    add(&mut s, "columns", Material::dielectric("marble", [0.85, 0.83, 0.8], 0.3), |b| {
        for k in 0..20 {
            let (x, z) = column_place(k, hx, hz);
            b.grid(64, 48, [1.0, 4.0], |u, v| {
                let phi = 2.0 * PI * u;
                // A fluted shaft: 16 flutes 1 cm deep.
                let r = 0.2 - 0.01 * (0.5 + 0.5 * (16.0 * phi).cos());
                let dr = 0.01 * 8.0 * (16.0 * phi).sin(); // ∂r/∂φ
                let radial = DVec3::new(phi.cos(), 0.0, phi.sin());
                let tangent = DVec3::new(-phi.sin(), 0.0, phi.cos());
                let n = (r * radial - dr * tangent).normalize();
                (DVec3::new(x, 0.3 + 3.6 * v, z) + r * radial, n)
            });
            b.cylinder(DVec3::new(x, 0.0, z), 0.28, 0.3, 64);
            b.cylinder(DVec3::new(x, 3.9, z), 0.3, 0.2, 64);
        }
    });
    // Arches between neighbouring columns along the long sides: half rings 0.25 m deep.
    add(&mut s, "arches", Material::dielectric("sandstone", [0.72, 0.55, 0.4], 0.7), |b| {
        for side in [-1.0, 1.0] {
            for k in 0..7 {
                let (x0, _) = column_place(k, hx, hz);
                let centre = DVec3::new(x0 + 0.75, 4.1, side * (hz - 1.0));
                b.grid(96, 8, [1.0, 1.0], |u, v| {
                    let a = PI * u;
                    let r = 0.75;
                    let n = DVec3::new(-a.cos(), -a.sin(), 0.0);
                    (centre + DVec3::new(r * a.cos(), r * a.sin(), 0.25 * (v - 0.5)), n)
                });
            }
        }
    });
    // Curtains: folded thin sheets hanging in the arcades.
    add(&mut s, "curtains", Material::dielectric("silk", [0.6, 0.15, 0.2], 0.5), |b| {
        for k in 0..6 {
            let x0 = column_place(k, hx, hz).0 + 0.1;
            b.curtain(DVec3::new(x0, 4.6, -(hz - 0.4)), DVec3::new(1.3, 0.0, 0.0), DVec3::Z, 4.4, 6.0, 0.04, 160, 80);
        }
    });
    // Planters with leaves: 12 boxes, 100 leaves each (curved quads, 8 × 2 cells).
    add(&mut s, "planters", Material::dielectric("terracotta", [0.6, 0.3, 0.18], 0.8), |b| {
        for k in 0..12 {
            let (x, z) = planter_place(k, hx, hz);
            b.cuboid(DVec3::new(x - 0.3, 0.0, z - 0.3), DVec3::new(x + 0.3, 0.5, z + 0.3), false, Some(2));
        }
    });
    add(&mut s, "leaves", Material::dielectric("leaves", [0.15, 0.4, 0.1], 0.45), |b| {
        for k in 0..12u32 {
            let (x, z) = planter_place(k, hx, hz);
            for l in 0..100u32 {
                let id = k * 100 + l;
                let yaw = 2.0 * PI * hash01(id);
                let pitch = 0.3 + 0.9 * hash01(id + 5000);
                let root = DVec3::new(x + 0.25 * (hash01(id + 9000) - 0.5), 0.5 + 0.6 * hash01(id + 7000), z + 0.25 * (hash01(id + 8000) - 0.5));
                let dir = DVec3::new(yaw.cos() * pitch.cos(), pitch.sin(), yaw.sin() * pitch.cos());
                let side = DVec3::new(-yaw.sin(), 0.0, yaw.cos());
                b.grid(8, 2, [1.0, 1.0], |u, v| {
                    // A leaf 25 cm long, 6 cm wide, bent down along its length.
                    let w = 0.06 * (PI * u).sin().max(0.05) * (v - 0.5);
                    let p = root + dir * (0.25 * u) - DVec3::Y * (0.08 * u * u) + side * w;
                    let along = (dir * 0.25 - DVec3::Y * (0.16 * u)).normalize();
                    (p, along.cross(side).normalize())
                });
            }
        }
    });
    s.add_light(spot(DVec3::new(4.0, 14.0, 3.0), DVec3::new(-1.0, 0.0, -0.5), 900.0, 25.0, 40.0));
    s.cameras.push(camera(DVec3::new(3.8, 2.0, 1.9), DVec3::new(-3.0, 1.2, -1.5), 60.0));
    s
}

/// Floor tiles of the atrium of one parity (`parity` 0 or 1 of a checkerboard of n × n).
fn tiles(b: &mut MeshBuilder, hx: f64, hz: f64, n: u32, parity: u32) {
    let (w, d) = (2.0 * hx / n as f64, 2.0 * hz / n as f64);
    for i in 0..n {
        for j in 0..n {
            if (i + j) % 2 == parity {
                let origin = DVec3::new(-hx + w * i as f64, 0.0, -hz + d * (j + 1) as f64);
                b.quad(origin, DVec3::new(w, 0.0, 0.0), DVec3::new(0.0, 0.0, -d));
            }
        }
    }
}

fn column_place(k: u32, hx: f64, hz: f64) -> (f64, f64) {
    // 8 along each long side 1.5 m apart, and 2 more on each short side between its corners.
    let x0 = -(hx - 0.75);
    match k {
        0..=7 => (x0 + 1.5 * k as f64, -(hz - 1.0)),
        8..=15 => (x0 + 1.5 * (k - 8) as f64, hz - 1.0),
        16 | 17 => (x0, -1.0 + 2.0 * (k - 16) as f64),
        _ => (-x0, -1.0 + 2.0 * (k - 18) as f64),
    }
}

fn planter_place(k: u32, hx: f64, hz: f64) -> (f64, f64) {
    let (i, j) = (k % 6, k / 6);
    (-hx + 2.25 + 1.5 * i as f64, if j == 0 { -1.6 } else { 1.6 } * (hz - 2.0) / 2.0)
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
