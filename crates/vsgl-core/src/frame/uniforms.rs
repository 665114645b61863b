//! CPU twins of the per-frame GPU structs in `wgsl/common/frame.wgsl`: the frame uniforms and
//! one `LightRaw` per light.

use crate::scene::{Camera, DirectionalLight, EmitterLight, Light, PointLight, SpotLight};
use glam::{DMat4, DVec3, Mat4};

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
pub struct FrameUniforms {
    pub view_proj: [[f32; 4]; 4],
    pub cam_right: [f32; 4],
    pub cam_up: [f32; 4],
    pub cam_forward: [f32; 4],
    pub view_origin: [f32; 4],
    pub size: [u32; 2],
    pub light_count: u32,
    pub texture_layer_size: u32,
    pub scene_extent: f32,
    pub shadow_size: f32,
    /// 1 for an orthographic view (a directional light's RSM): rays start on the image plane
    /// at view_origin + ndc.x·cam_right + ndc.y·cam_up and all run along cam_forward (whose
    /// cam_right / cam_up are then the plane's half-widths); 0 for a perspective view.
    pub orthographic: u32,
    pub _pad: f32,
}
const _: () = assert!(std::mem::size_of::<FrameUniforms>() == 160);

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
pub struct LightRaw {
    pub position: [f32; 3],
    pub intensity: f32,
    pub direction: [f32; 3],
    pub cos_outer: f32,
    pub color: [f32; 3],
    pub cos_inner: f32,
    /// Frame-relative view-projection of the light's shadow map (spot, directional); unused
    /// for a point light, whose six cube faces the direct pass projects itself.
    pub view_proj: [[f32; 4]; 4],
    /// Perspective maps (spot, point): 2·tan(half field of view)/shadow size, so a shadow texel
    /// is `texel_tan · distance` wide. Directional (orthographic) map: the texel's world width.
    pub texel_tan: f32,
    /// First layer of the light's shadow map in the shadow array (a point light has six).
    pub shadow_layer: u32,
    /// [`LIGHT_KIND_SPOT`], … (`LIGHT_KIND_*` in frame.wgsl).
    pub kind: u32,
    /// Near plane of the point light's cube faces (the direct pass's reverse-Z depth is
    /// near / distance along the face axis); 0 for other kinds.
    pub shadow_near: f32,
}
const _: () = assert!(std::mem::size_of::<LightRaw>() == 128);

impl LightRaw {
    /// What the RSM passes that infer the light's incoming direction at a texel need
    /// (`rsm_lobe_means` in wgsl/common/rsm_lobes.wgsl): (direction, 1) for a directional
    /// light, lit from −direction everywhere; 0 for a spot or point light, whose direction is
    /// the texel's offset from the light.
    pub fn rsm_light_dir(&self) -> [f32; 4] {
        if self.kind == LIGHT_KIND_DIRECTIONAL {
            let d = self.direction;
            [d[0], d[1], d[2], 1.0]
        } else {
            [0.0; 4]
        }
    }
}

/// `LightRaw::kind` of a spot light.
pub const LIGHT_KIND_SPOT: u32 = 0;
/// `LightRaw::kind` of a point light.
pub const LIGHT_KIND_POINT: u32 = 1;
/// `LightRaw::kind` of a directional light.
pub const LIGHT_KIND_DIRECTIONAL: u32 = 2;
/// `LightRaw::kind` of an emitter cluster ([`crate::scene::EmitterLight`]): a point light with
/// a cosine lobe about `LightRaw::direction`.
pub const LIGHT_KIND_EMITTER: u32 = 3;

/// Shadow map layers a light takes in the shadow array: a cube (six 90° faces) for a point
/// light, one layer otherwise.
pub fn shadow_layer_count(light: &Light) -> u32 {
    if light.has_cube_faces() { 6 } else { 1 }
}

/// The GPU twins of a scene's lights, with their shadow layers assigned in order (positions
/// relative to `origin`, the frame origin; `anchor` is the scene bounds' centre).
pub fn light_raws(lights: &[Light], origin: DVec3, anchor: DVec3, extent: f64, shadow_size: u32) -> Vec<LightRaw> {
    let mut layer = 0;
    lights
        .iter()
        .map(|light| {
            let raw = match light {
                Light::Spot(spot) => spot_light_raw(spot, origin, extent, layer, shadow_size),
                Light::Point(point) => point_light_raw(point, origin, extent, layer, shadow_size),
                Light::Directional(dir) => directional_light_raw(dir, anchor - origin, extent, layer, shadow_size),
                Light::Emitter(emitter) => emitter_light_raw(emitter, origin, extent, layer, shadow_size),
            };
            layer += shadow_layer_count(light);
            raw
        })
        .collect()
}

/// The view-projections that rasterise `light`'s shadow layers, of positions relative to
/// `anchor` (the scene upload's): one for a spot or directional light, the six cube faces
/// (in [`CUBE_FACES`] order) for a point light.
pub fn shadow_view_projs(light: &Light, anchor: DVec3, extent: f64) -> Vec<Mat4> {
    match light {
        Light::Spot(spot) => vec![light_view_proj(spot, anchor, extent)],
        Light::Point(PointLight { position, .. }) | Light::Emitter(EmitterLight { position, .. }) => {
            (0..6).map(|face| cube_face_view_proj(*position - anchor, face, extent)).collect()
        }
        // The anchor is the bounds' centre: relative to it, the centre is at zero.
        Light::Directional(dir) => vec![directional_view_proj(dir, DVec3::ZERO, extent)],
    }
}

/// A point light's shadow cube faces: (forward, up) of face `i`, the order the layers are
/// rendered in and the direct pass's `CUBE_FACE_*` tables in wgsl/common/frame.wgsl list
/// them (+X, −X, +Y, −Y, +Z, −Z; face 2k + 1 is the negative k axis).
pub const CUBE_FACES: [(DVec3, DVec3); 6] = [
    (DVec3::X, DVec3::Y),
    (DVec3::NEG_X, DVec3::Y),
    (DVec3::Y, DVec3::Z),
    (DVec3::NEG_Y, DVec3::Z),
    (DVec3::Z, DVec3::Y),
    (DVec3::NEG_Z, DVec3::Y),
];

/// Face `face` of a point light's shadow cube at `pos` (relative to the positions it will
/// project): a square 90° reverse-Z perspective, so the six faces tile the sphere of
/// directions exactly.
pub fn cube_face_view_proj(pos: DVec3, face: usize, extent: f64) -> Mat4 {
    let (forward, up) = CUBE_FACES[face];
    let view = DMat4::look_to_rh(pos, forward, up);
    let proj = DMat4::perspective_infinite_reverse_rh(std::f64::consts::FRAC_PI_2, 1.0, extent * NEAR_PLANE_FRACTION);
    (proj * view).as_mat4()
}

/// Which of a light's views (its shadow-map layers and RSMs, [`shadow_view_projs`] order) can
/// see any of the scene: the sphere around the scene's bounds (centre `anchor`, radius half the
/// bounds' diagonal `extent`) meets the view's cone of directions. Conservative — a view that
/// fails sees no geometry, so no shaded point ever looks up its shadow map and its RSM reflects
/// nothing; leaving it out changes no pixel:
/// - a spot light's view is its cone (half-angle `outer_cone`);
/// - a cube face's view lies inside the cone around its axis through the face's corners
///   (half-angle atan √2 ≈ 54.7°);
/// - a directional light's box is fitted to the sphere, and a light inside (or on) the sphere
///   may see geometry in every direction: both are always kept.
/// A sphere at distance d and radius R subtends the half-angle asin(R/d) from the light: the
/// view sees it when the angle between the view's axis and the sphere's centre is at most the
/// view's half-angle plus that (with a 1e-6 rad margin against rounding).
pub fn views_seeing_scene(light: &Light, anchor: DVec3, extent: f64) -> Vec<bool> {
    let radius = 0.5 * extent;
    let sees = |position: DVec3, axis: DVec3, half_angle: f64| -> bool {
        let to_centre = anchor - position;
        let distance = to_centre.length();
        if !(distance > radius) || !distance.is_finite() {
            return true;
        }
        let between = axis.normalize().dot(to_centre / distance).clamp(-1.0, 1.0).acos();
        between <= half_angle + (radius / distance).asin() + 1e-6
    };
    match light {
        Light::Spot(spot) => vec![sees(spot.position, spot.direction, spot.outer_cone as f64)],
        Light::Point(point) => CUBE_FACES.iter().map(|(forward, _)| sees(point.position, *forward, 2f64.sqrt().atan())).collect(),
        Light::Directional(_) => vec![true],
        // An emitter lights only the side its normal points to: a face none of whose
        // directions has a positive cosine with it (the face behind the emitter) sees no light.
        Light::Emitter(emitter) => CUBE_FACES
            .iter()
            .map(|&(forward, up)| sees(emitter.position, forward, 2f64.sqrt().atan()) && cube_face_reaches(forward, up, emitter.normal))
            .collect(),
    }
}

/// Whether some direction of the 90° cube face (forward, up) has a positive cosine with
/// `normal`: the face's directions, unnormalised, fill the square forward ± right ± up, on which
/// the cosine's sign is linear, so a corner has the largest.
fn cube_face_reaches(forward: DVec3, up: DVec3, normal: DVec3) -> bool {
    let right = forward.cross(up);
    [(1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)].iter().any(|&(a, b)| (forward + a * right + b * up).dot(normal) > 0.0)
}

/// Margin of the directional light's orthographic box over the scene's bounding sphere, so
/// geometry on the sphere is not clipped by rounding.
const DIRECTIONAL_BOX_MARGIN: f64 = 1.01;

/// Half-width of a directional light's orthographic shadow box: the radius of the sphere
/// around the scene's bounds (half its diagonal), which holds the scene for every direction.
fn directional_half_width(extent: f64) -> f64 {
    0.5 * extent.max(f64::MIN_POSITIVE) * DIRECTIONAL_BOX_MARGIN
}

/// The directional light's orthographic shadow view, fitted to the scene bounds (documented
/// in docs/scenes.md): a square box of half-width R (the bounding sphere's radius) around
/// `centre` (the bounds' centre relative to the projected positions' origin), looking along
/// the light from R before the centre to R past it; reverse-Z (depth 1 at the near end).
pub fn directional_view_proj(light: &DirectionalLight, centre: DVec3, extent: f64) -> Mat4 {
    let r = directional_half_width(extent);
    let dir = light.direction.normalize();
    let view = DMat4::look_to_rh(centre - dir * r, dir, orthogonal(dir));
    // glam maps view depth `near` → 0 and `far` → 1; swapping them gives reverse-Z.
    let proj = DMat4::orthographic_rh(-r, r, -r, r, 2.0 * r, 0.0);
    (proj * view).as_mat4()
}

/// Widest shadow frustum: a perspective projection degenerates at 180°, so cones wider than
/// this (outer half-angle > 85°) are unshadowed outside it (documented in docs/scenes.md).
pub const SHADOW_FOV_MAX: f64 = 170.0 * std::f64::consts::PI / 180.0;

/// Near plane as a fraction of the scene extent. With reverse-Z and an infinite far plane the
/// depth precision hardly depends on it; it only must not clip nearby geometry.
pub const NEAR_PLANE_FRACTION: f64 = 1e-5;

/// The camera's view-projection of positions relative to `anchor` (the scene upload's), made
/// in f64: the eye's offset from the anchor is the view's translation.
pub fn camera_view_proj(cam: &Camera, anchor: DVec3, aspect: f64, extent: f64) -> DMat4 {
    let view = DMat4::look_to_rh(cam.eye - anchor, cam.forward, cam.up);
    let proj = DMat4::perspective_infinite_reverse_rh(cam.fov_y as f64, aspect, extent * NEAR_PLANE_FRACTION);
    proj * view
}

/// The camera's frame uniforms. The frame origin (where rays start, and what frame-space
/// positions are relative to) is the eye; uploaded vertices are relative to `anchor`, so
/// `view_proj` takes anchor-relative positions and `view_origin` is the eye's offset from the
/// anchor (the material pass subtracts it).
pub fn frame_uniforms(cam: &Camera, anchor: DVec3, (width, height): (u32, u32), lights: u32, layer: u32, extent: f64, shadow_size: u32) -> FrameUniforms {
    let aspect = width as f64 / height as f64;
    let t = (cam.fov_y as f64 * 0.5).tan();
    let right = cam.forward.cross(cam.up).normalize();
    let v4 = |v: DVec3| [v.x as f32, v.y as f32, v.z as f32, 0.0];
    FrameUniforms {
        view_proj: camera_view_proj(cam, anchor, aspect, extent).as_mat4().to_cols_array_2d(),
        cam_right: v4(right * t * aspect),
        cam_up: v4(cam.up * t),
        cam_forward: v4(cam.forward),
        view_origin: v4(cam.eye - anchor),
        size: [width, height],
        light_count: lights,
        texture_layer_size: layer,
        scene_extent: extent as f32,
        shadow_size: shadow_size as f32,
        orthographic: 0,
        _pad: 0.0,
    }
}

/// Any unit vector orthogonal to `d`.
fn orthogonal(d: DVec3) -> DVec3 {
    if d.y.abs() < 0.9 { d.cross(DVec3::Y).normalize() } else { d.cross(DVec3::X).normalize() }
}

/// The spot light's view-projection of positions relative to `origin`: the frame origin for
/// the direct pass's shadow lookups, the upload anchor for rasterising its shadow map or RSM.
pub fn light_view_proj(light: &SpotLight, origin: DVec3, extent: f64) -> Mat4 {
    let pos = light.position - origin;
    let view = DMat4::look_to_rh(pos, light.direction, orthogonal(light.direction));
    let fov = (2.0 * light.outer_cone as f64).min(SHADOW_FOV_MAX);
    let proj = DMat4::perspective_infinite_reverse_rh(fov, 1.0, extent * NEAR_PLANE_FRACTION);
    (proj * view).as_mat4()
}

pub fn spot_light_raw(light: &SpotLight, origin: DVec3, extent: f64, layer: u32, shadow_size: u32) -> LightRaw {
    let pos = (light.position - origin).as_vec3();
    let fov = (2.0 * light.outer_cone as f64).min(SHADOW_FOV_MAX);
    LightRaw {
        position: pos.to_array(),
        intensity: light.intensity,
        direction: light.direction.normalize().as_vec3().to_array(),
        cos_outer: light.outer_cone.cos(),
        color: light.color.to_array(),
        cos_inner: light.inner_cone.cos(),
        view_proj: light_view_proj(light, origin, extent).to_cols_array_2d(),
        texel_tan: (2.0 * (fov * 0.5).tan() / shadow_size as f64) as f32,
        shadow_layer: layer,
        kind: LIGHT_KIND_SPOT,
        shadow_near: 0.0,
    }
}

pub fn point_light_raw(light: &PointLight, origin: DVec3, extent: f64, layer: u32, shadow_size: u32) -> LightRaw {
    LightRaw {
        position: (light.position - origin).as_vec3().to_array(),
        intensity: light.intensity,
        direction: [0.0; 3],
        cos_outer: -1.0,
        color: light.color.to_array(),
        cos_inner: -1.0,
        view_proj: Mat4::IDENTITY.to_cols_array_2d(),
        // tan(45°) = 1 for each 90° face.
        texel_tan: (2.0 / shadow_size as f64) as f32,
        shadow_layer: layer,
        kind: LIGHT_KIND_POINT,
        shadow_near: (extent * NEAR_PLANE_FRACTION) as f32,
    }
}

/// An emitter cluster: a point light's cube (shadow layers, near plane) with its cosine lobe's
/// axis in `direction` (`light_lobe` in wgsl/common/frame.wgsl).
pub fn emitter_light_raw(light: &EmitterLight, origin: DVec3, extent: f64, layer: u32, shadow_size: u32) -> LightRaw {
    let point = PointLight { position: light.position, intensity: light.intensity, color: light.color };
    LightRaw {
        direction: light.normal.normalize().as_vec3().to_array(),
        kind: LIGHT_KIND_EMITTER,
        ..point_light_raw(&point, origin, extent, layer, shadow_size)
    }
}

/// `centre`: the scene bounds' centre relative to the frame origin.
pub fn directional_light_raw(light: &DirectionalLight, centre: DVec3, extent: f64, layer: u32, shadow_size: u32) -> LightRaw {
    LightRaw {
        position: [0.0; 3],
        intensity: light.intensity,
        direction: light.direction.normalize().as_vec3().to_array(),
        cos_outer: -1.0,
        color: light.color.to_array(),
        cos_inner: -1.0,
        view_proj: directional_view_proj(light, centre, extent).to_cols_array_2d(),
        texel_tan: (2.0 * directional_half_width(extent) / shadow_size as f64) as f32,
        shadow_layer: layer,
        kind: LIGHT_KIND_DIRECTIONAL,
        shadow_near: 0.0,
    }
}

/// The views of a light's reflective shadow maps, one per RSM: a spot light's over its cone
/// ([`light_view_uniforms`]), a point light's six cube faces ([`cube_face_view_uniforms`],
/// in [`CUBE_FACES`] order), a directional light's orthographic view of the scene's bounding
/// sphere ([`directional_view_uniforms`]).
///
/// `fit`: a spot light's RSM is fitted to the scene's bounds (`half_size`, half the bounds'
/// sides, around `anchor`) where they are narrower than its cone ([`fitted_spot_view`]).
pub fn rsm_views(light: &Light, anchor: DVec3, half_size: DVec3, extent: f64, size: u32, texture_layer_size: u32, fit: RsmFit) -> Vec<FrameUniforms> {
    match light {
        Light::Spot(spot) => vec![match (fit, fitted_spot_view(spot, anchor, half_size)) {
            (RsmFit::Scene, Some((forward, t))) => spot_view_uniforms(spot, forward, t, anchor, extent, size, texture_layer_size),
            _ => light_view_uniforms(spot, anchor, extent, size, texture_layer_size),
        }],
        Light::Point(PointLight { position, .. }) | Light::Emitter(EmitterLight { position, .. }) => {
            (0..6).map(|face| cube_face_view_uniforms(*position, face, anchor, extent, size, texture_layer_size)).collect()
        }
        Light::Directional(dir) => vec![directional_view_uniforms(dir, extent, size, texture_layer_size)],
    }
}

/// Where the rays of a directional light's RSM start, relative to the scene bounds' centre:
/// the centre of the near face of its orthographic box ([`directional_view_proj`]), R before
/// the centre along the light. The RSM's positions are relative to it.
pub fn directional_rsm_origin(light: &DirectionalLight, extent: f64) -> DVec3 {
    -light.direction.normalize() * directional_half_width(extent)
}

/// The view of a directional light's reflective shadow map: the same orthographic box as its
/// shadow map ([`directional_view_proj`]: a square of half-width R, the radius of the scene's
/// bounding sphere, seen along the light), rays parallel to the light starting on the box's
/// near face ([`directional_rsm_origin`]). Vertices are relative to the upload anchor, the
/// bounds' centre. A texel covers (2R/N)² of the plane perpendicular to the light.
pub fn directional_view_uniforms(light: &DirectionalLight, extent: f64, size: u32, texture_layer_size: u32) -> FrameUniforms {
    let r = directional_half_width(extent);
    let dir = light.direction.normalize();
    // The basis look_to_rh(eye, dir, up) uses: right = dir × up, up' = right × dir.
    let up = orthogonal(dir);
    let right = dir.cross(up).normalize();
    let up = right.cross(dir);
    let view_proj = directional_view_proj(light, DVec3::ZERO, extent);
    let view = RsmView { view_proj, right: right * r, up: up * r, forward: dir, origin: directional_rsm_origin(light, extent), orthographic: true };
    view.uniforms(extent, size, texture_layer_size)
}

/// What differs between the lights' square RSM views: the projection, the image plane's
/// half-axes (scaled by tan(fov/2) for a perspective view, by the half-width for an orthographic
/// one), the view axis and where its rays start (anchor-relative).
struct RsmView {
    view_proj: Mat4,
    right: DVec3,
    up: DVec3,
    forward: DVec3,
    origin: DVec3,
    orthographic: bool,
}

impl RsmView {
    fn uniforms(&self, extent: f64, size: u32, texture_layer_size: u32) -> FrameUniforms {
        let v4 = |v: DVec3| [v.x as f32, v.y as f32, v.z as f32, 0.0];
        FrameUniforms {
            view_proj: self.view_proj.to_cols_array_2d(),
            cam_right: v4(self.right),
            cam_up: v4(self.up),
            cam_forward: v4(self.forward),
            view_origin: v4(self.origin),
            size: [size, size],
            light_count: 1,
            texture_layer_size,
            scene_extent: extent as f32,
            shadow_size: size as f32,
            orthographic: u32::from(self.orthographic),
            _pad: 0.0,
        }
    }
}

/// Face `face` of a point light's RSM cube: a square 90° perspective image from the light
/// (tan 45° = 1, so `rsm_flux`'s texel solid angle (2/N)²cos³θ needs no other factor and the
/// six faces' texels tile the sphere: Σ Δω → 4π). Rasterises anchor-relative vertices like
/// the shadow cube; positions it writes are relative to the light.
pub fn cube_face_view_uniforms(position: DVec3, face: usize, anchor: DVec3, extent: f64, size: u32, texture_layer_size: u32) -> FrameUniforms {
    let (forward, up) = CUBE_FACES[face];
    let right = forward.cross(up);
    let view_proj = cube_face_view_proj(position - anchor, face, extent);
    RsmView { view_proj, right, up, forward, origin: position - anchor, orthographic: false }.uniforms(extent, size, texture_layer_size)
}

/// How a spot light's RSM frames the scene (`rsm_fit=`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RsmFit {
    /// Over the light's outer cone, whatever the scene fills of it (before 2026-12-02).
    Cone,
    /// Over the part of the cone the scene's bounds can fill ([`fitted_spot_view`]).
    Scene,
}

/// Margin of a fitted RSM frustum over the bounds' corners (rasterisation at the very edge).
const RSM_FIT_MARGIN: f64 = 1.01;

/// A spot light's RSM fitted to the scene: the axis and tan(half field of view) of the
/// narrowest square frustum, along the light's axis or towards the bounds' centre, that holds
/// every corner of the bounds (`anchor` ± `half_size`) and, along the light's axis, no more
/// than the cone; `None` where that is no narrower than the cone's own frustum, or where a
/// corner is not in front of the light (the light within or beside the bounds). Every RSM
/// texel that sees nothing is wasted: a 40° spot over a helmet half a metre across a metre
/// away spends 91% of a 128² RSM on empty space, and the helmet's light then comes from 1,402
/// texels on a 12 mm grid (docs/methods/rsm.md, "Fitting a spot light's RSM to the scene").
/// The flux of each texel follows from the view (rsm_flux.wgsl: its solid angle and the
/// cone's profile in its own direction), so the fit changes the sampling, not the light.
pub fn fitted_spot_view(light: &SpotLight, anchor: DVec3, half_size: DVec3) -> Option<(DVec3, f64)> {
    let t_cone = ((2.0 * light.outer_cone as f64).min(SHADOW_FOV_MAX) * 0.5).tan();
    if !(half_size.min_element() >= 0.0) || !half_size.is_finite() {
        return None;
    }
    let centre = anchor - light.position;
    let corners = (0..8).map(|i| centre + half_size * DVec3::new([-1.0, 1.0][i & 1], [-1.0, 1.0][(i >> 1) & 1], [-1.0, 1.0][(i >> 2) & 1]));
    // tan of the half field of view a square frustum along `axis` needs to hold every corner.
    let needed = |axis: DVec3| -> Option<f64> {
        let up = orthogonal(axis);
        let right = axis.cross(up).normalize();
        let up = right.cross(axis);
        let mut t = 0.0f64;
        for q in corners.clone() {
            let z = q.dot(axis);
            if !(z > 1e-9 * q.length()) {
                return None;
            }
            t = t.max(q.dot(right).abs().max(q.dot(up).abs()) / z);
        }
        Some(t * RSM_FIT_MARGIN)
    };
    let along_light = light.direction.normalize();
    let towards_centre = centre.normalize();
    let candidates = [
        needed(along_light).map(|t| (along_light, t.min(t_cone))),
        if towards_centre.is_finite() { needed(towards_centre).map(|t| (towards_centre, t)) } else { None },
    ];
    let best = candidates.into_iter().flatten().filter(|(_, t)| t.is_finite() && *t > 0.0).min_by(|a, b| a.1.total_cmp(&b.1))?;
    (best.1 < t_cone).then_some(best)
}

/// The view of a spot light's reflective shadow map fitted to the scene ([`fitted_spot_view`]):
/// a square perspective image along `forward` with half-width `t` (tan of the half field of
/// view) at unit distance, rays starting at the light; otherwise as [`light_view_uniforms`].
fn spot_view_uniforms(light: &SpotLight, forward: DVec3, t: f64, anchor: DVec3, extent: f64, size: u32, texture_layer_size: u32) -> FrameUniforms {
    let up = orthogonal(forward);
    let right = forward.cross(up).normalize();
    let pos = light.position - anchor;
    let view = DMat4::look_to_rh(pos, forward, up);
    let proj = DMat4::perspective_infinite_reverse_rh(2.0 * t.atan(), 1.0, extent * NEAR_PLANE_FRACTION);
    let view_proj = (proj * view).as_mat4();
    RsmView { view_proj, right: right * t, up: up * t, forward, origin: pos, orthographic: false }.uniforms(extent, size, texture_layer_size)
}

/// The view of a spot light's reflective shadow map: a square perspective image over the outer
/// cone (at most [`SHADOW_FOV_MAX`]), rays starting at the light. `anchor` is the scene
/// upload's: the view rasterises anchor-relative vertices, and the positions it writes are
/// relative to the light.
pub fn light_view_uniforms(light: &SpotLight, anchor: DVec3, extent: f64, size: u32, texture_layer_size: u32) -> FrameUniforms {
    let fov = (2.0 * light.outer_cone as f64).min(SHADOW_FOV_MAX);
    let t = (fov * 0.5).tan();
    let dir = light.direction.normalize();
    let up = orthogonal(dir);
    let right = dir.cross(up).normalize();
    let view_proj = light_view_proj(light, anchor, extent);
    RsmView { view_proj, right: right * t, up: up * t, forward: dir, origin: light.position - anchor, orthographic: false }.uniforms(extent, size, texture_layer_size)
}

#[cfg(test)]
mod tests {
    use super::{fitted_spot_view, orthogonal, views_seeing_scene, CUBE_FACES, SHADOW_FOV_MAX};
    use crate::rng::SplitMix64;
    use crate::scene::{DirectionalLight, Light, PointLight, SpotLight};
    use glam::{DVec3, Vec3};

    fn point(at: DVec3) -> Light {
        Light::Point(PointLight { position: at, intensity: 1.0, color: Vec3::ONE })
    }

    fn spot(at: DVec3, direction: DVec3, outer_deg: f32) -> Light {
        let outer = outer_deg.to_radians();
        Light::Spot(SpotLight { position: at, direction, intensity: 1.0, color: Vec3::ONE, inner_cone: 0.5 * outer, outer_cone: outer })
    }

    #[test]
    fn cube_faces_facing_away_from_the_scene_are_left_out() {
        // Scene: the unit sphere around the origin (bounds diagonal 2).
        let above = views_seeing_scene(&point(DVec3::new(0.0, 3.0, 0.0)), DVec3::ZERO, 2.0);
        assert_eq!(above, vec![false, false, false, true, false, false], "only −Y sees a sphere 3 away below");
        // Closer (the sphere subtends 56°): the side faces see its top, +Y still nothing.
        let near = views_seeing_scene(&point(DVec3::new(0.0, 1.2, 0.0)), DVec3::ZERO, 2.0);
        assert_eq!(near, vec![true, true, false, true, true, true]);
        assert_eq!(views_seeing_scene(&point(DVec3::new(0.1, 0.2, 0.3)), DVec3::ZERO, 2.0), vec![true; 6], "inside: all");
        assert_eq!(views_seeing_scene(&point(DVec3::splat(f64::NAN)), DVec3::ZERO, 2.0), vec![true; 6], "no position: keep");
        let at = DVec3::new(0.0, 3.0, 0.0);
        assert_eq!(views_seeing_scene(&spot(at, DVec3::Y, 80.0), DVec3::ZERO, 2.0), vec![false], "pointing away");
        assert_eq!(views_seeing_scene(&spot(at, -DVec3::Y, 5.0), DVec3::ZERO, 2.0), vec![true]);
        assert_eq!(views_seeing_scene(&spot(at, DVec3::X, 30.0), DVec3::ZERO, 2.0), vec![false], "90° off, 30° + 19.5° cone");
        assert_eq!(views_seeing_scene(&spot(at, DVec3::X, 80.0), DVec3::ZERO, 2.0), vec![true], "90° off, 80° + 19.5° cone");
        let sun = Light::Directional(DirectionalLight { direction: DVec3::Y, intensity: 1.0, color: Vec3::ONE });
        assert_eq!(views_seeing_scene(&sun, DVec3::ZERO, 2.0), vec![true]);
    }

    /// Conservative: for random lights around a sphere, every cube face that holds a random point
    /// of the sphere (the face of its dominant axis from the light) is kept, and so is every
    /// spot light whose cone holds one.
    #[test]
    fn no_view_that_sees_part_of_the_scene_is_left_out() {
        let mut rng = SplitMix64(7);
        let unit = |rng: &mut SplitMix64| DVec3::new(rng.next_f64() * 2.0 - 1.0, rng.next_f64() * 2.0 - 1.0, rng.next_f64() * 2.0 - 1.0);
        let mut left_out = 0;
        for _ in 0..200 {
            let anchor = unit(&mut rng) * 5.0;
            let radius = 0.2 + rng.next_f64() * 2.0;
            let at = anchor + unit(&mut rng).normalize() * radius * (1.01 + rng.next_f64() * 3.0);
            let faces = views_seeing_scene(&point(at), anchor, 2.0 * radius);
            let direction = unit(&mut rng).normalize();
            let outer_deg = 1.0 + 88.0 * rng.next_f64() as f32;
            let cone = views_seeing_scene(&spot(at, direction, outer_deg), anchor, 2.0 * radius)[0];
            left_out += faces.iter().filter(|f| !**f).count();
            for _ in 0..400 {
                let mut p = unit(&mut rng);
                while p.length() > 1.0 {
                    p = unit(&mut rng);
                }
                let d = anchor + p * radius - at;
                let face = CUBE_FACES.iter().position(|(axis, _)| axis.dot(d) >= d.abs().max_element() * (1.0 - 1e-12)).unwrap();
                assert!(faces[face], "face {face} holds a point of the sphere but was left out (light {at}, sphere {anchor} r {radius})");
                let inside_cone = direction.dot(d.normalize()).clamp(-1.0, 1.0).acos() <= (outer_deg as f64).to_radians();
                assert!(!inside_cone || cone, "a spot light's cone holds a point of the sphere but was left out");
            }
        }
        assert!(left_out > 100, "the test should exercise faces that are left out: {left_out}");
    }

    fn spot_light(at: DVec3, direction: DVec3, outer_deg: f32) -> crate::scene::SpotLight {
        let outer = outer_deg.to_radians();
        SpotLight { position: at, direction, intensity: 1.0, color: Vec3::ONE, inner_cone: 0.5 * outer, outer_cone: outer }
    }

    /// Every point of the bounds that the spot's cone holds is inside the fitted frustum: the
    /// fit may leave out only what the light cannot reach.
    #[test]
    fn a_fitted_spot_frustum_holds_every_lit_point_of_the_bounds() {
        let mut rng = SplitMix64(11);
        let r = |rng: &mut SplitMix64| rng.next_f64() * 2.0 - 1.0;
        let (mut fitted, mut narrower_than_half) = (0, 0);
        for _ in 0..300 {
            let anchor = DVec3::new(r(&mut rng), r(&mut rng), r(&mut rng)) * 10.0;
            let half = DVec3::new(0.05 + rng.next_f64(), 0.05 + rng.next_f64(), 0.05 + rng.next_f64());
            let away = DVec3::new(r(&mut rng), r(&mut rng), r(&mut rng)).normalize() * (half.length() * (0.5 + 6.0 * rng.next_f64()));
            let at = anchor + away;
            let aim = (anchor - at).normalize() + DVec3::new(r(&mut rng), r(&mut rng), r(&mut rng)) * 0.3;
            let outer_deg = 5.0 + 80.0 * rng.next_f64() as f32;
            let light = spot_light(at, aim.normalize(), outer_deg);
            let Some((forward, t)) = fitted_spot_view(&light, anchor, half) else { continue };
            fitted += 1;
            let t_cone = ((2.0 * light.outer_cone as f64).min(SHADOW_FOV_MAX) * 0.5).tan();
            assert!(t > 0.0 && t < t_cone, "a fit is narrower than the cone: {t} against {t_cone}");
            if t < 0.5 * t_cone {
                narrower_than_half += 1;
            }
            let up = orthogonal(forward);
            let right = forward.cross(up).normalize();
            for _ in 0..300 {
                let q = anchor + half * DVec3::new(r(&mut rng), r(&mut rng), r(&mut rng)) - at;
                let in_cone = light.direction.normalize().dot(q.normalize()).clamp(-1.0, 1.0).acos() <= light.outer_cone as f64;
                if !in_cone {
                    continue;
                }
                let z = q.dot(forward);
                assert!(z > 0.0 && q.dot(right).abs() <= t * z * (1.0 + 1e-9) && q.dot(up).abs() <= t * z * (1.0 + 1e-9),
                    "a lit point of the bounds {q} lies outside the fitted frustum (axis {forward}, tan {t})");
            }
        }
        assert!(fitted > 50 && narrower_than_half > 20, "the test should exercise fits: {fitted} fitted, {narrower_than_half} at under half the cone");
    }

    #[test]
    fn a_spot_inside_or_beside_the_bounds_keeps_its_cone() {
        let half = DVec3::splat(1.0);
        assert_eq!(fitted_spot_view(&spot_light(DVec3::new(0.2, 0.9, 0.0), -DVec3::Y, 40.0), DVec3::ZERO, half), None, "inside");
        assert_eq!(fitted_spot_view(&spot_light(DVec3::new(0.0, 1.0, 0.0), -DVec3::Y, 40.0), DVec3::ZERO, half), None, "on a face");
        assert_eq!(fitted_spot_view(&spot_light(DVec3::new(0.0, 10.0, 0.0), -DVec3::Y, 2.0), DVec3::ZERO, half), None, "a cone narrower than the bounds");
        assert_eq!(fitted_spot_view(&spot_light(DVec3::new(0.0, 10.0, 0.0), -DVec3::Y, 40.0), DVec3::ZERO, DVec3::NAN), None, "no geometry");
        let (forward, t) = fitted_spot_view(&spot_light(DVec3::new(0.0, 10.0, 0.0), -DVec3::Y, 40.0), DVec3::ZERO, half).expect("a far box is fitted");
        assert!((forward + DVec3::Y).length() < 1e-12, "a spot aimed at the box's centre keeps its axis");
        assert!((t - 1.01 * 1.0 / 9.0).abs() < 1e-12, "the nearest face's corners fix the frustum: tan {t}");
    }
}
