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

mod corpus;
mod small;
pub use corpus::{atrium, furnished_room, helmet_shell};
pub use small::{cave_flashlight, caustics_ring, cornell_box, diffuse_cornell, glossy_cornell, mirror_panel};

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


/// A hanging curtain: a single sheet from `top_left` along `across` (horizontal, its length the
/// width) and down by `height`, folded along its normal `n0` by `depth`·sin(2π·folds·u).
#[derive(Clone, Copy)]
pub(crate) struct Curtain {
    pub top_left: DVec3,
    pub across: DVec3,
    pub n0: DVec3,
    pub height: f64,
    pub folds: f64,
    pub depth: f64,
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

    /// A hanging curtain (see [`Curtain`]) as an `nu` × `nv` grid, with the normals of the
    /// folded sheet.
    fn curtain(&mut self, curtain: &Curtain, nu: u32, nv: u32) {
        let Curtain { top_left, across, n0, height, folds, depth } = *curtain;
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
