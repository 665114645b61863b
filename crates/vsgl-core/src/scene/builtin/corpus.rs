//! The generated corpus scenes: what real scenes have and the small built-ins lack (a curved thin
//! shell with creases, a furnished room of many small touching objects with textures and a normal
//! map, an atrium at the papers' scale of 250k+ triangles).

use super::*;

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
            let sheet = Curtain { top_left: DVec3::new(x0, 4.6, -(hz - 0.4)), across: DVec3::new(1.3, 0.0, 0.0), n0: DVec3::Z, height: 4.4, folds: 6.0, depth: 0.04 };
            b.curtain(&sheet, 160, 80);
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
