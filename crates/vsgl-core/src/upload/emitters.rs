//! Emissive triangles as area lights: the table the path tracer samples emitters from.
//!
//! Each triangle whose material emits (glTF `emissiveFactor` × `KHR_materials_emissive_strength`
//! > 0) is a one-sided Lambertian emitter of radiance L_e on the side its vertex normals point
//! to (the side a glTF file shades as its front; docs/scenes.md, "Emission"). Its power is
//! Φ = π · A · (L_r + L_g + L_b): a Lambertian surface's exitance is π L_e. Emitters are drawn
//! in proportion to that power, then uniformly over the triangle's area, so the density of a
//! point z on triangle i is p_i / A_i with p_i = Φ_i / ΣΦ (`EmitterRaw::probability`).
//!
//! The emissive texture multiplies L_e at the sampled point and is not in Φ: texels are at most
//! 1, so the factor's power bounds the textured one and every point that emits keeps a density
//! above zero (the estimator stays unbiased, only less well matched to dark texels).

use super::VertexRaw;
use crate::scene::{EmitterLight, Material, Texture, UvTransform};
use glam::{DVec3, Vec3};

/// One emissive triangle (16 bytes; `EmitterRaw` in `wgsl/passes/pathtrace.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct EmitterRaw {
    /// Index of the triangle in the upload's index buffer (three indices per triangle).
    pub triangle: u32,
    /// World-space area.
    pub area: f32,
    /// Σ of `probability` up to and including this row (the last row holds exactly 1): a
    /// uniform u picks the first row whose `cdf` exceeds it.
    pub cdf: f32,
    /// Φ_i / ΣΦ: how often this triangle is drawn.
    pub probability: f32,
}
const _: () = assert!(std::mem::size_of::<EmitterRaw>() == 16);

/// The scene's emitters and their total power (rgb summed, in the scene's units).
#[derive(Clone, Debug, Default)]
pub struct EmitterTable {
    pub rows: Vec<EmitterRaw>,
    pub total_power: f64,
    /// Per row, what the clusters of the real-time methods are made from.
    pub triangles: Vec<EmitterTriangle>,
}

/// One emissive triangle as the emitter clusters see it (upload-anchor-relative, f64).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EmitterTriangle {
    pub corners: [DVec3; 3],
    /// Unit normal of the emitting side (the side the vertex normals point to).
    pub normal: DVec3,
    /// L_e · A per channel with the emissive factor (the texture, if any, multiplies it at each
    /// patch: [`EmitterTriangle::texture`]): the radiant intensity it sends along its normal.
    pub intensity: DVec3,
    pub area: f64,
    /// The corners' texture coordinates, and the material's emissive texture (an index into the
    /// scene's textures) with its transform.
    pub uvs: [[f32; 2]; 3],
    pub texture: Option<(usize, UvTransform)>,
}

/// The emissive texture's linear colour at `uv` (nearest texel, wrapping; sRGB decoded as the
/// GPU's colour textures are), or 1 without a texture.
fn emissive_texel(textures: &[Texture], texture: Option<(usize, UvTransform)>, uv: [f32; 2]) -> DVec3 {
    let Some((index, transform)) = texture else { return DVec3::ONE };
    let Some(t) = textures.get(index) else { return DVec3::ONE };
    let uv = transform.apply(uv);
    let (w, h) = (t.width.max(1), t.height.max(1));
    let wrap = |x: f32, n: u32| (((x - x.floor()) * n as f32) as u32).min(n - 1);
    let i = 4 * (wrap(uv[1], h) as usize * w as usize + wrap(uv[0], w) as usize);
    let decode = |c: u8| {
        let c = c as f64 / 255.0;
        if c <= 0.04045 { c / 12.92 } else { ((c + 0.055) / 1.055).powf(2.4) }
    };
    match t.rgba8.get(i..i + 3) {
        Some(rgb) => DVec3::new(decode(rgb[0]), decode(rgb[1]), decode(rgb[2])),
        None => DVec3::ONE,
    }
}

/// The emitter table of an upload's triangles (`indices`: three per triangle into `vertices`,
/// `triangle_materials`: one material index per triangle). Triangles of zero area or of a
/// material that does not emit are left out.
pub fn emitter_table(vertices: &[VertexRaw], indices: &[u32], triangle_materials: &[u32], materials: &[Material]) -> EmitterTable {
    let mut rows = Vec::new();
    let mut powers = Vec::new();
    let mut triangles = Vec::new();
    for (t, &m) in triangle_materials.iter().enumerate() {
        let Some(material) = materials.get(m as usize).filter(|m| m.has_emission()) else { continue };
        let corner = |k: usize| {
            let v = indices.get(3 * t + k).and_then(|&i| vertices.get(i as usize)).map_or([0.0; 3], |v| v.position);
            glam::DVec3::new(v[0] as f64, v[1] as f64, v[2] as f64)
        };
        let (a, b, c) = (corner(0), corner(1), corner(2));
        let area = 0.5 * (b - a).cross(c - a).length();
        let radiance: f64 = material.emissive.iter().map(|&e| e.max(0.0) as f64).sum();
        let power = std::f64::consts::PI * area * radiance;
        if !(power > 0.0 && power.is_finite()) {
            continue;
        }
        rows.push(EmitterRaw { triangle: t as u32, area: area as f32, cdf: 0.0, probability: 0.0 });
        powers.push(power);
        let vertex_normals: DVec3 = (0..3)
            .filter_map(|k| indices.get(3 * t + k).and_then(|&i| vertices.get(i as usize)))
            .map(|v| DVec3::new(v.normal[0] as f64, v.normal[1] as f64, v.normal[2] as f64))
            .sum();
        let geometric = (b - a).cross(c - a).normalize_or_zero();
        let normal = if geometric.dot(vertex_normals) >= 0.0 { geometric } else { -geometric };
        let radiance = DVec3::new(material.emissive[0] as f64, material.emissive[1] as f64, material.emissive[2] as f64).max(DVec3::ZERO);
        let uvs = [0, 1, 2].map(|k| indices.get(3 * t + k).and_then(|&i| vertices.get(i as usize)).map_or([0.0; 2], |v| v.uv));
        let texture = material.emissive_texture.map(|i| (i, material.emissive_uv));
        triangles.push(EmitterTriangle { corners: [a, b, c], normal, intensity: radiance * area, area, uvs, texture });
    }
    let total_power: f64 = powers.iter().sum();
    let mut running = 0.0;
    for (row, power) in rows.iter_mut().zip(&powers) {
        running += power;
        row.probability = (power / total_power) as f32;
        row.cdf = (running / total_power) as f32;
    }
    if let Some(last) = rows.last_mut() {
        // Rounding must not leave a gap above the last row that a u near 1 could fall into.
        last.cdf = 1.0;
    }
    EmitterTable { rows, total_power, triangles }
}

/// Whether no emissive triangle faces any part of the box `±half_size` (the scene's bounds
/// around the upload anchor, in the triangles' coordinates): every corner of the box lies on or
/// behind each triangle's emitting plane (within `tolerance`), so the emitters light nothing.
/// Conservative: a corner in front does not prove that geometry is.
pub fn face_nothing(triangles: &[EmitterTriangle], half_size: DVec3, tolerance: f64) -> bool {
    if triangles.is_empty() || !half_size.is_finite() {
        return false;
    }
    let corners = (0..8).map(|k| DVec3::new(
        if k & 1 == 0 { -half_size.x } else { half_size.x },
        if k & 2 == 0 { -half_size.y } else { half_size.y },
        if k & 4 == 0 { -half_size.z } else { half_size.z },
    ));
    let corners: Vec<DVec3> = corners.collect();
    triangles.iter().all(|t| corners.iter().all(|&c| (c - t.corners[0]).dot(t.normal) <= tolerance))
}

/// The six normal directions emitter clusters are first split by (a cluster's triangles face
/// within 90° of one another, so its summed cosine lobes stay close to one lobe).
fn normal_bin(n: DVec3) -> usize {
    let a = n.abs();
    let axis = if a.x >= a.y && a.x >= a.z { 0 } else if a.y >= a.z { 1 } else { 2 };
    2 * axis + usize::from(n[axis] < 0.0)
}

/// Patches per light the emissive area is cut into before clustering, so a large emitter of
/// few triangles (a quad lamp) can still become `budget` lights of a fraction of its size, each
/// with [`POINTS_PER_LIGHT`] points of several patches.
const PATCHES_PER_LIGHT: f64 = 256.0;
/// Most patches in all: past it, triangles are clustered as they are.
const MAX_PATCHES: usize = 1 << 16;
/// Most midpoint subdivisions of one triangle (4⁵ = 1024 patches).
const MAX_SUBDIVISION: u32 = 5;

/// A piece of an emissive triangle: its centroid, and its share of the triangle's area and
/// intensity (the normal is the triangle's).
#[derive(Clone, Copy)]
struct Patch {
    centroid: DVec3,
    normal: DVec3,
    intensity: DVec3,
    area: f64,
}

/// The emissive triangles cut into patches: each triangle into 4^k similar pieces by midpoint
/// subdivision, k the least that makes its pieces at most total area / (PATCHES_PER_LIGHT ·
/// budget), unless that passes MAX_PATCHES in all (then every triangle is one patch). A
/// patch's intensity is its share of the triangle's times the emissive texture at its
/// centroid (a midpoint rule over the texture too).
fn patches(triangles: &[EmitterTriangle], textures: &[Texture], budget: usize) -> Vec<Patch> {
    let total: f64 = triangles.iter().map(|t| t.area).sum();
    let target = total / (PATCHES_PER_LIGHT * budget.max(1) as f64);
    let level = |t: &EmitterTriangle| {
        let mut k = 0;
        while k < MAX_SUBDIVISION && t.area / 4f64.powi(k as i32) > target {
            k += 1;
        }
        k
    };
    let count: usize = triangles.iter().map(|t| 1usize << (2 * level(t))).sum();
    let mut out = Vec::with_capacity(count.min(MAX_PATCHES));
    for t in triangles {
        let k = if count > MAX_PATCHES { 0 } else { level(t) };
        // Barycentric corners of each piece: positions and texture coordinates follow them.
        let mut pieces = vec![[DVec3::X, DVec3::Y, DVec3::Z]];
        for _ in 0..k {
            pieces = pieces
                .iter()
                .flat_map(|&[a, b, c]| {
                    let (ab, bc, ca) = ((a + b) * 0.5, (b + c) * 0.5, (c + a) * 0.5);
                    [[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]
                })
                .collect();
        }
        let share = 1.0 / pieces.len() as f64;
        out.extend(pieces.iter().map(|&[a, b, c]| {
            let w = (a + b + c) / 3.0;
            let centroid = t.corners[0] * w.x + t.corners[1] * w.y + t.corners[2] * w.z;
            let uv = [0, 1].map(|j| (t.uvs[0][j] as f64 * w.x + t.uvs[1][j] as f64 * w.y + t.uvs[2][j] as f64 * w.z) as f32);
            let texel = if t.texture.is_some() { emissive_texel(textures, t.texture, uv) } else { DVec3::ONE };
            Patch { centroid, normal: t.normal, intensity: t.intensity * texel * share, area: t.area * share }
        }));
    }
    out
}

/// Splits `clusters` of patches (indices into `patches`) until there are `count` or none can be
/// split: each time the cluster whose point approximation errs most — the largest intensity ×
/// squared extent, the first-order error of a point light standing for an area — is cut at the
/// median of its longest side. A cluster of one patch is not split. Deterministic.
fn split_clusters(patches: &[Patch], mut clusters: Vec<Vec<usize>>, count: usize) -> Vec<Vec<usize>> {
    let bounds = |c: &[usize]| {
        c.iter().fold((DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)), |(lo, hi), &i| {
            (lo.min(patches[i].centroid), hi.max(patches[i].centroid))
        })
    };
    let error = |c: &[usize]| {
        let (lo, hi) = bounds(c);
        let weight: f64 = c.iter().map(|&i| patches[i].intensity.element_sum()).sum();
        if c.len() < 2 { -1.0 } else { weight * (hi - lo).length_squared() }
    };
    let mut errors: Vec<f64> = clusters.iter().map(|c| error(c)).collect();
    while clusters.len() < count {
        let (worst, e) = errors.iter().copied().enumerate().fold((0, -1.0), |a, b| if b.1 > a.1 { b } else { a });
        if e <= 0.0 {
            break;
        }
        let mut c = std::mem::take(&mut clusters[worst]);
        let (lo, hi) = bounds(&c);
        let axis = (hi - lo).max_position();
        c.sort_by(|&a, &b| patches[a].centroid[axis].total_cmp(&patches[b].centroid[axis]).then(a.cmp(&b)));
        let right = c.split_off(c.len() / 2);
        errors[worst] = error(&c);
        errors.push(error(&right));
        clusters[worst] = c;
        clusters.push(right);
    }
    clusters
}

/// Points each emitter light's direct light is summed over ([`EmitterClusters::points`]): its
/// patches split into this many sub-clusters, each a point light of its share of the
/// intensity. Under a unit square at height 1 a midpoint rule of 4, 16 and 64 points is 1.05,
/// 1.012 and 1.003 of the form factor.
pub const POINTS_PER_LIGHT: usize = 64;

/// The emitter lights of a frame and the points their direct light is summed over.
#[derive(Clone, Debug, Default)]
pub struct EmitterClusters {
    pub lights: Vec<EmitterLight>,
    /// [`POINTS_PER_LIGHT`] per light, in light order: world position and the point's share of
    /// the light's intensity (the shares of a light add up to 1; unused points have 0).
    pub points: Vec<(DVec3, f32)>,
    /// Per point, the spread of the area it stands for: the trace of its positions' covariance
    /// (E‖y − μ‖², its patches' centroids weighted by intensity, plus each patch's own spread,
    /// area/6 as for a square), what an emitter VSGL's positional Gaussian takes.
    pub point_variances: Vec<f64>,
}

/// The emissive triangles as at most `budget` lights for the real-time methods
/// ([`EmitterLight`]; positions world-space, `anchor` added back). The triangles are cut into
/// patches ([`patches`]) and binned by normal direction (six bins by the dominant axis), and
/// the bins are split up to the budget ([`split_clusters`]). Each light's own patches are then
/// split into [`POINTS_PER_LIGHT`] points for its direct light. `offset`: how far each light
/// sits off its patches along its normal.
pub fn emitter_lights(triangles: &[EmitterTriangle], textures: &[Texture], budget: usize, anchor: DVec3, offset: f64) -> EmitterClusters {
    let patches = patches(triangles, textures, budget);
    let mut bins: Vec<Vec<usize>> = vec![Vec::new(); 6];
    for (i, t) in patches.iter().enumerate() {
        bins[normal_bin(t.normal)].push(i);
    }
    bins.retain(|c| !c.is_empty());
    // Every normal direction that emits keeps a light of its own, so a budget below the
    // number of such directions (at most six) gives that many lights.
    let clusters = split_clusters(&patches, bins, budget.max(1));
    let mut out = EmitterClusters::default();
    for c in &clusters {
        let intensity: DVec3 = c.iter().map(|&i| patches[i].intensity).sum();
        let weight = intensity.element_sum();
        if !(weight > 0.0) {
            continue;
        }
        let weighted = |f: &dyn Fn(&Patch) -> DVec3, members: &[usize]| members.iter().map(|&i| f(&patches[i]) * patches[i].intensity.element_sum()).sum::<DVec3>();
        let centroid = weighted(&|p| p.centroid, c) / weight;
        let normal = weighted(&|p| p.normal, c).normalize_or_zero();
        let normal = if normal == DVec3::ZERO { patches[c[0]].normal } else { normal };
        let peak = intensity.max_element();
        out.lights.push(EmitterLight {
            position: anchor + centroid + normal * offset,
            normal,
            intensity: peak as f32,
            color: (intensity / peak).as_vec3().min(Vec3::ONE),
            area: c.iter().map(|&i| patches[i].area).sum(),
            patches: c.len() as u32,
        });
        let parts = split_clusters(&patches, vec![c.clone()], POINTS_PER_LIGHT);
        let mut points: Vec<(DVec3, f32)> = Vec::with_capacity(POINTS_PER_LIGHT);
        let mut variances: Vec<f64> = Vec::with_capacity(POINTS_PER_LIGHT);
        for part in &parts {
            let w: f64 = part.iter().map(|&i| patches[i].intensity.element_sum()).sum();
            let w_safe = w.max(f64::MIN_POSITIVE);
            let mean = weighted(&|p| p.centroid, part) / w_safe;
            let spread: f64 = part.iter().map(|&i| patches[i].intensity.element_sum() * ((patches[i].centroid - mean).length_squared() + patches[i].area / 6.0)).sum::<f64>() / w_safe;
            points.push((anchor + mean + normal * offset, (w / weight) as f32));
            variances.push(spread);
        }
        points.resize(POINTS_PER_LIGHT, (anchor + centroid + normal * offset, 0.0));
        variances.resize(POINTS_PER_LIGHT, 0.0);
        out.points.extend(points);
        out.point_variances.extend(variances);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn vertex(p: [f32; 3]) -> VertexRaw {
        VertexRaw { position: p, _pad0: 0.0, normal: [0.0, 1.0, 0.0], _pad1: 0.0, tangent: [1.0, 0.0, 0.0, 1.0], uv: [0.0; 2], _pad2: [0.0; 2] }
    }

    fn glowing(l: [f32; 3]) -> Material {
        Material { emissive: l, ..Material::lambertian("glow", [0.5; 3]) }
    }

    #[test]
    fn emitters_are_drawn_by_power_and_dark_or_flat_triangles_are_left_out() {
        // Triangle 0: area 0.5, L = 1+1+1; triangle 1: dark; triangle 2: area 2, L = 2 (red only);
        // triangle 3: zero area.
        let vertices = [
            vertex([0.0, 0.0, 0.0]), vertex([1.0, 0.0, 0.0]), vertex([0.0, 0.0, 1.0]),
            vertex([0.0, 0.0, 2.0]), vertex([2.0, 0.0, 0.0]), vertex([4.0, 0.0, 0.0]),
        ];
        let indices = [0, 1, 2, 0, 1, 2, 0, 3, 4, 0, 4, 5];
        let materials = [glowing([1.0; 3]), Material::lambertian("dark", [0.5; 3]), glowing([2.0, 0.0, 0.0])];
        let table = emitter_table(&vertices, &indices, &[0, 1, 2, 2], &materials);
        let pi = std::f64::consts::PI;
        assert!((table.total_power - pi * (0.5 * 3.0 + 2.0 * 2.0)).abs() < 1e-12, "{}", table.total_power);
        assert_eq!(table.rows.iter().map(|r| r.triangle).collect::<Vec<_>>(), vec![0, 2]);
        assert_eq!(table.rows[0].area, 0.5);
        assert_eq!(table.rows[1].area, 2.0);
        assert!((table.rows[0].probability as f64 - 1.5 / 5.5).abs() < 1e-7);
        assert!((table.rows[0].cdf as f64 - 1.5 / 5.5).abs() < 1e-7);
        assert_eq!(table.rows[1].cdf, 1.0);
    }

    /// A unit square at y = 1 facing down (two triangles), radiance (2, 1, 0).
    fn unit_square() -> Vec<EmitterTriangle> {
        let c = [DVec3::new(-0.5, 1.0, -0.5), DVec3::new(0.5, 1.0, -0.5), DVec3::new(0.5, 1.0, 0.5), DVec3::new(-0.5, 1.0, 0.5)];
        let l = DVec3::new(2.0, 1.0, 0.0);
        [[c[0], c[1], c[2]], [c[0], c[2], c[3]]]
            .iter()
            .map(|&corners| EmitterTriangle { corners, normal: DVec3::NEG_Y, intensity: l * 0.5, area: 0.5, uvs: [[0.0; 2]; 3], texture: None })
            .collect()
    }

    #[test]
    fn emitter_lights_keep_the_intensity_and_split_a_large_emitter_into_quarters() {
        let anchor = DVec3::new(10.0, 0.0, 0.0);
        let one = emitter_lights(&unit_square(), &[], 1, anchor, 0.0).lights;
        assert_eq!(one.len(), 1);
        assert!((one[0].position - (anchor + DVec3::new(0.0, 1.0, 0.0))).length() < 1e-12, "{:?}", one[0].position);
        assert_eq!(one[0].normal, DVec3::NEG_Y);
        // Peak intensity Σ L·A = (2, 1, 0): its largest channel, and the colour relative to it.
        assert!((one[0].intensity - 2.0).abs() < 1e-6 && (one[0].color - Vec3::new(1.0, 0.5, 0.0)).length() < 1e-6);
        assert!((one[0].area - 1.0).abs() < 1e-12);
        // Four lights: the square's quarters (two triangles, cut into patches first), each a
        // quarter of the intensity at its quarter's centre.
        let four = emitter_lights(&unit_square(), &[], 4, DVec3::ZERO, 0.0).lights;
        assert_eq!(four.len(), 4);
        let mut centres: Vec<(i64, i64)> = four.iter().map(|l| ((l.position.x * 4.0).round() as i64, (l.position.z * 4.0).round() as i64)).collect();
        centres.sort();
        assert_eq!(centres, vec![(-1, -1), (-1, 1), (1, -1), (1, 1)]);
        for l in &four {
            assert!((l.intensity - 0.5).abs() < 1e-6 && (l.area - 0.25).abs() < 1e-12, "{l:?}");
            assert!((l.position.x.abs() - 0.25).abs() < 1e-9 && (l.position.z.abs() - 0.25).abs() < 1e-9, "{l:?}");
        }
        // Off the surface along the normal by the offset.
        assert!((emitter_lights(&unit_square(), &[], 1, DVec3::ZERO, 0.01).lights[0].position.y - 0.99).abs() < 1e-12);
    }

    #[test]
    fn each_light_has_its_points_spread_over_its_area_with_shares_adding_up() {
        let clusters = emitter_lights(&unit_square(), &[], 1, DVec3::ZERO, 0.0);
        assert_eq!(clusters.points.len(), POINTS_PER_LIGHT);
        let total: f64 = clusters.points.iter().map(|&(_, w)| w as f64).sum();
        assert!((total - 1.0).abs() < 1e-6, "{total}");
        // The shares' centroid is the light's; the points fill the square (an 8 × 8 grid of
        // sub-squares' centres: |x|, |z| up to 7/16).
        let centroid: DVec3 = clusters.points.iter().map(|&(p, w)| p * w as f64).sum();
        assert!((centroid - clusters.lights[0].position).length() < 1e-6, "{centroid:?}");
        let reach = clusters.points.iter().map(|&(p, _)| p.x.abs().max(p.z.abs())).fold(0.0, f64::max);
        assert!((reach - 7.0 / 16.0).abs() < 1e-9, "{reach}");
        assert!(clusters.points.iter().all(|&(p, w)| w > 0.0 && p.y == 1.0));
        // Each point stands for an eighth × eighth of the square: spread 2 · (1/8)²/12.
        assert_eq!(clusters.point_variances.len(), POINTS_PER_LIGHT);
        for v in &clusters.point_variances {
            assert!((v - 2.0 / (64.0 * 12.0)).abs() < 0.25 * 2.0 / (64.0 * 12.0), "{v}");
        }
    }

    #[test]
    fn an_emissive_texture_weighs_the_patches() {
        // Left half of the texture white, right half black (u = x + 1/2): the light keeps half
        // the factor's intensity, centred on the lit half.
        let texture = Texture { name: "half".into(), width: 2, height: 1, rgba8: vec![255, 255, 255, 255, 0, 0, 0, 255], usage: crate::scene::TextureUsage::Color };
        let uv = |p: DVec3| [(p.x + 0.5) as f32, (p.z + 0.5) as f32];
        let textured: Vec<EmitterTriangle> = unit_square()
            .iter()
            .map(|t| EmitterTriangle { uvs: t.corners.map(uv), texture: Some((0, UvTransform::IDENTITY)), ..*t })
            .collect();
        let c = emitter_lights(&textured, &[texture], 1, DVec3::ZERO, 0.0);
        let light = c.lights[0];
        assert!((light.intensity - 1.0).abs() < 1e-3, "{light:?}");
        assert!((light.position.x + 0.25).abs() < 1e-3 && light.position.z.abs() < 1e-3, "{light:?}");
        assert!(c.points.iter().all(|&(p, w)| w == 0.0 || p.x < 0.0));
    }

    #[test]
    fn emitters_facing_apart_get_a_light_each_whatever_the_budget() {
        let mut both = unit_square();
        both.extend(unit_square().iter().map(|t| EmitterTriangle { normal: DVec3::Y, corners: t.corners.map(|p| p - DVec3::Y), ..*t }));
        let lights = emitter_lights(&both, &[], 1, DVec3::ZERO, 0.0).lights;
        assert_eq!(lights.len(), 2);
        let mut normals: Vec<f64> = lights.iter().map(|l| l.normal.y).collect();
        normals.sort_by(f64::total_cmp);
        assert_eq!(normals, vec![-1.0, 1.0]);
    }

    #[test]
    fn emitters_that_face_out_of_the_bounds_face_nothing() {
        // The unit square at y = 1 facing down in a box reaching y = 0 faces the box's floor;
        // turned up, at the top of a box reaching only y = 1, it faces nothing.
        let half = DVec3::new(3.0, 0.5, 3.0);
        let centred: Vec<EmitterTriangle> = unit_square().iter().map(|t| EmitterTriangle { corners: t.corners.map(|p| p - DVec3::new(0.0, 0.5, 0.0)), ..*t }).collect();
        assert!(!face_nothing(&centred, half, 1e-9));
        let up: Vec<EmitterTriangle> = centred.iter().map(|t| EmitterTriangle { normal: DVec3::Y, ..*t }).collect();
        assert!(face_nothing(&up, half, 1e-9));
        assert!(!face_nothing(&[], half, 1e-9));
    }

    #[test]
    fn a_scene_without_emission_has_an_empty_table() {
        let vertices = [vertex([0.0; 3]), vertex([1.0, 0.0, 0.0]), vertex([0.0, 0.0, 1.0])];
        let table = emitter_table(&vertices, &[0, 1, 2], &[0], &[Material::lambertian("dark", [0.5; 3])]);
        assert!(table.rows.is_empty());
        assert_eq!(table.total_power, 0.0);
    }
}
