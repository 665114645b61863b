//! Meshes and primitives: vertex attributes and indices read through the accessors, strips
//! and fans turned into triangle lists, normals generated when the file has none, and
//! tangents read or generated where a normal map needs them.

use glam::DVec3;
use gltf::json;
use json::accessor::{ComponentType, Type as AccType};
use json::mesh::{Mode, Semantic};
use json::validation::Checked;

use super::material::material_index;
use super::{finite_all, Builder, Ctx};
use crate::error::Result;
use crate::scene::{Mesh, Primitive};

pub(super) fn load_mesh(ctx: &Ctx, b: &mut Builder, m: usize, node: usize) -> Result<usize> {
    if let Some(&s) = b.mesh_map.get(&m) {
        return Ok(s);
    }
    let mesh = ctx.root.meshes.get(m).ok_or_else(|| {
        ctx.err(
            format!("nodes[{node}].mesh"),
            format!("meshes[{m}] does not exist"),
        )
    })?;
    let mut primitives = Vec::with_capacity(mesh.primitives.len());
    for (p, prim) in mesh.primitives.iter().enumerate() {
        if let Some(prim) = load_primitive(ctx, b, m, p, prim)? {
            primitives.push(prim);
        }
    }
    b.scene.meshes.push(Mesh {
        name: mesh.name.clone().unwrap_or_else(|| format!("meshes[{m}]")),
        primitives,
    });
    let s = b.scene.meshes.len() - 1;
    b.mesh_map.insert(m, s);
    Ok(s)
}

fn to_vec3s(v: &[f32]) -> Vec<[f32; 3]> {
    v.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect()
}

fn dv(p: [f32; 3]) -> DVec3 {
    DVec3::new(f64::from(p[0]), f64::from(p[1]), f64::from(p[2]))
}

fn load_primitive(
    ctx: &Ctx,
    b: &mut Builder,
    m: usize,
    p: usize,
    prim: &json::mesh::Primitive,
) -> Result<Option<Primitive>> {
    let el = format!("meshes[{m}].primitives[{p}]");
    let mode = match prim.mode {
        Checked::Valid(mode) => mode,
        Checked::Invalid => return Err(ctx.err(format!("{el}.mode"), "invalid primitive mode")),
    };
    let mode_name = match mode {
        Mode::Points => Some("POINTS"),
        Mode::Lines => Some("LINES"),
        Mode::LineLoop => Some("LINE_LOOP"),
        Mode::LineStrip => Some("LINE_STRIP"),
        Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan => None,
    };
    if let Some(name) = mode_name {
        b.warn(format!(
            "{el}: mode {name} is not supported (triangles only); primitive skipped"
        ));
        return Ok(None);
    }
    if prim.targets.as_ref().is_some_and(|t| !t.is_empty()) {
        b.warn(format!(
            "{el}: morph targets are not supported; base shape used"
        ));
    }
    let attr = |s: Semantic| prim.attributes.get(&Checked::Valid(s)).map(|i| i.value());

    let pos_idx = attr(Semantic::Positions)
        .ok_or_else(|| ctx.err(el.clone(), "primitive has no POSITION attribute"))?;
    let positions =
        to_vec3s(&ctx.read_floats(pos_idx, AccType::Vec3, &format!("{el}.attributes.POSITION"))?);
    let n = positions.len();
    if n > u32::MAX as usize {
        return Err(ctx.err(el, format!("{n} vertices exceed the u32 index range")));
    }
    let same_count = |len: usize, name: &str, idx: usize| -> Result<()> {
        if len != n {
            return Err(ctx.err(
                format!("accessors[{idx}]"),
                format!("{name} of {el} has {len} elements but POSITION has {n}"),
            ));
        }
        Ok(())
    };

    let file_normals = match attr(Semantic::Normals) {
        Some(i) => {
            let v =
                to_vec3s(&ctx.read_floats(i, AccType::Vec3, &format!("{el}.attributes.NORMAL"))?);
            same_count(v.len(), "NORMAL", i)?;
            Some(v)
        }
        None => None,
    };
    let uvs: Vec<[f32; 2]> = match attr(Semantic::TexCoords(0)) {
        Some(i) => {
            use ComponentType::*;
            let v: Vec<f32> = ctx.read_accessor(
                i,
                AccType::Vec2,
                &format!("{el}.attributes.TEXCOORD_0"),
                &[F32, U8, U16, I8, I16],
            )?;
            if !finite_all(&v) {
                return Err(ctx.err(
                    format!("accessors[{i}]"),
                    format!("non-finite TEXCOORD_0 value in {el}"),
                ));
            }
            let v: Vec<[f32; 2]> = v.chunks_exact(2).map(|c| [c[0], c[1]]).collect();
            same_count(v.len(), "TEXCOORD_0", i)?;
            v
        }
        None => Vec::new(),
    };

    // Indices, all checked against the vertex count.
    let raw_indices: Vec<u32> = match prim.indices {
        Some(ii) => {
            let ii = ii.value();
            use ComponentType::*;
            let idx: Vec<u32> = ctx.read_accessor(
                ii,
                AccType::Scalar,
                &format!("{el}.indices"),
                &[U8, U16, U32],
            )?;
            if let Some((k, &v)) = idx.iter().enumerate().find(|(_, &v)| v as usize >= n) {
                return Err(ctx.err(
                    el,
                    format!("index {v} (element {k} of accessors[{ii}]) is out of range: the vertex count is {n}"),
                ));
            }
            idx
        }
        None => {
            ctx.charge_geometry(n as u64 * 4, &el)?;
            (0..n as u32).collect()
        }
    };
    let mut indices: Vec<u32> = match mode {
        Mode::TriangleStrip => {
            let mut out = Vec::with_capacity(raw_indices.len().saturating_sub(2) * 3);
            for (i, w) in raw_indices.windows(3).enumerate() {
                let (a, b1, c) = (w[0], w[1], w[2]);
                if a == b1 || b1 == c || a == c {
                    continue;
                }
                if i % 2 == 0 {
                    out.extend([a, b1, c]);
                } else {
                    out.extend([a, c, b1]);
                }
            }
            out
        }
        Mode::TriangleFan => {
            let mut out = Vec::with_capacity(raw_indices.len().saturating_sub(2) * 3);
            if let Some((&first, rest)) = raw_indices.split_first() {
                for w in rest.windows(2) {
                    out.extend([w[0], w[1], first]);
                }
            }
            out
        }
        _ => raw_indices,
    };
    if !indices.len().is_multiple_of(3) {
        b.warn(format!(
            "{el}: {} indices are not a multiple of 3; the last partial triangle is dropped",
            indices.len()
        ));
        indices.truncate(indices.len() / 3 * 3);
    }
    if indices.is_empty() {
        b.warn(format!("{el}: no triangles; primitive skipped"));
        return Ok(None);
    }

    let normals = match file_normals {
        Some(v) => v
            .into_iter()
            .map(|nrm| {
                let d = dv(nrm);
                let l = d.length();
                if l > 1e-20 {
                    (d / l).as_vec3().to_array()
                } else {
                    [0.0, 1.0, 0.0]
                }
            })
            .collect(),
        None => generate_normals(&positions, &indices),
    };

    // Material, and whether its normal map can be used.
    let gm = prim.material.map(|i| i.value());
    let gltf_material = match gm {
        Some(g) => Some(ctx.root.materials.get(g).ok_or_else(|| {
            ctx.err(
                format!("{el}.material"),
                format!("materials[{g}] does not exist"),
            )
        })?),
        None => None,
    };
    let wants_normal_map = gltf_material
        .and_then(|mat| mat.normal_texture.as_ref())
        .is_some_and(|nt| nt.tex_coord == 0);
    let mut keep_normal_map = wants_normal_map;
    let mut tangents = Vec::new();
    if wants_normal_map {
        let file_tangents = match (attr(Semantic::Tangents), attr(Semantic::Normals)) {
            // Tangents are only meaningful with the file's own normals (glTF 2.0 §3.7.2.1).
            (Some(ti), Some(_)) => {
                let v = ctx.read_floats(ti, AccType::Vec4, &format!("{el}.attributes.TANGENT"))?;
                let v: Vec<[f32; 4]> = v
                    .chunks_exact(4)
                    .map(|c| [c[0], c[1], c[2], if c[3] < 0.0 { -1.0 } else { 1.0 }])
                    .collect();
                same_count(v.len(), "TANGENT", ti)?;
                Some(v)
            }
            _ => None,
        };
        if let Some(t) = file_tangents {
            tangents = t;
        } else if !uvs.is_empty() {
            tangents = generate_tangents(&positions, &normals, &uvs, &indices);
        } else {
            keep_normal_map = false;
            b.warn(format!(
                "{el}: materials[{}] has a normal map but the primitive has neither TANGENT nor TEXCOORD_0; \
                 normal map dropped",
                gm.unwrap_or_default()
            ));
        }
    }
    let material = material_index(ctx, b, gm, keep_normal_map)?;
    let vertex_bytes = (n as u64) * (12 + 12 + 8 + 16) + indices.len() as u64 * 4;
    ctx.charge_geometry(vertex_bytes, &el)?;
    Ok(Some(Primitive {
        positions,
        normals,
        uvs,
        tangents,
        indices,
        material,
    }))
}

/// Area-weighted vertex normals (the cross product's length is twice the triangle area).
fn generate_normals(positions: &[[f32; 3]], indices: &[u32]) -> Vec<[f32; 3]> {
    let mut acc = vec![DVec3::ZERO; positions.len()];
    for t in indices.chunks_exact(3) {
        let (i0, i1, i2) = (t[0] as usize, t[1] as usize, t[2] as usize);
        let (Some(&p0), Some(&p1), Some(&p2)) =
            (positions.get(i0), positions.get(i1), positions.get(i2))
        else {
            continue;
        };
        let n = (dv(p1) - dv(p0)).cross(dv(p2) - dv(p0));
        for i in [i0, i1, i2] {
            if let Some(a) = acc.get_mut(i) {
                *a += n;
            }
        }
    }
    acc.into_iter()
        .map(|n| {
            let l = n.length();
            if l > 0.0 && l.is_finite() {
                (n / l).as_vec3().to_array()
            } else {
                [0.0, 1.0, 0.0]
            }
        })
        .collect()
}

/// Any unit vector orthogonal to the unit vector `n`.
fn orthogonal(n: DVec3) -> DVec3 {
    let a = if n.x.abs() < 0.9 { DVec3::X } else { DVec3::Y };
    (a - n * n.dot(a)).normalize_or(DVec3::X)
}

/// Per-vertex tangents from per-triangle UV gradients, accumulated, then Gram–Schmidt
/// orthogonalised against the normal; w is the bitangent sign. (The built-in scenes' normal
/// maps use it too.)
pub(crate) fn generate_tangents(
    positions: &[[f32; 3]],
    normals: &[[f32; 3]],
    uvs: &[[f32; 2]],
    indices: &[u32],
) -> Vec<[f32; 4]> {
    let n = positions.len();
    let mut tan = vec![DVec3::ZERO; n];
    let mut bit = vec![DVec3::ZERO; n];
    for t in indices.chunks_exact(3) {
        let ids = [t[0] as usize, t[1] as usize, t[2] as usize];
        let (Some(&p0), Some(&p1), Some(&p2)) = (
            positions.get(ids[0]),
            positions.get(ids[1]),
            positions.get(ids[2]),
        ) else {
            continue;
        };
        let (Some(&u0), Some(&u1), Some(&u2)) = (uvs.get(ids[0]), uvs.get(ids[1]), uvs.get(ids[2]))
        else {
            continue;
        };
        let e1 = dv(p1) - dv(p0);
        let e2 = dv(p2) - dv(p0);
        let (du1, dv1) = (f64::from(u1[0] - u0[0]), f64::from(u1[1] - u0[1]));
        let (du2, dv2) = (f64::from(u2[0] - u0[0]), f64::from(u2[1] - u0[1]));
        let det = du1 * dv2 - du2 * dv1;
        if det.is_nan() || det.abs() <= 1e-20 {
            continue;
        }
        let r = 1.0 / det;
        let sdir = (e1 * dv2 - e2 * dv1) * r;
        let tdir = (e2 * du1 - e1 * du2) * r;
        if !(sdir.is_finite() && tdir.is_finite()) {
            continue;
        }
        for i in ids {
            if let (Some(a), Some(b)) = (tan.get_mut(i), bit.get_mut(i)) {
                *a += sdir;
                *b += tdir;
            }
        }
    }
    (0..n)
        .map(|i| {
            let nrm = normals.get(i).map_or(DVec3::Y, |&v| dv(v));
            let t = tan.get(i).copied().unwrap_or_default();
            let b = bit.get(i).copied().unwrap_or_default();
            let t_orth = t - nrm * nrm.dot(t);
            let l = t_orth.length();
            let t_unit = if l > 1e-12 * (1.0 + t.length()) && l.is_finite() {
                t_orth / l
            } else {
                orthogonal(nrm)
            };
            let w = if nrm.cross(t_unit).dot(b) < 0.0 {
                -1.0
            } else {
                1.0
            };
            let t32 = t_unit.as_vec3();
            [t32.x, t32.y, t32.z, w]
        })
        .collect()
}
