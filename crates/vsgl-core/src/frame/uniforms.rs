//! CPU twins of the per-frame GPU structs in `wgsl/common/frame.wgsl`: the frame uniforms and
//! one `LightRaw` per light.

use crate::error::{Error, Result};
use crate::scene::{Camera, Light, SpotLight};
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
    pub _pad: [f32; 2],
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
    pub view_proj: [[f32; 4]; 4],
    pub texel_tan: f32,
    pub shadow_layer: u32,
    /// [`LIGHT_KIND_SPOT`], … (`LIGHT_KIND_*` in frame.wgsl).
    pub kind: u32,
    pub _pad: f32,
}
const _: () = assert!(std::mem::size_of::<LightRaw>() == 128);

/// `LightRaw::kind` of a spot light (the only kind the passes render so far).
pub const LIGHT_KIND_SPOT: u32 = 0;

/// The GPU twin of light `index` of a scene, or an error naming it when its type does not
/// render yet.
pub fn light_raw(light: &Light, index: usize, origin: DVec3, extent: f64, shadow_size: u32) -> Result<LightRaw> {
    match light {
        Light::Spot(spot) => Ok(spot_light_raw(spot, origin, extent, index as u32, shadow_size)),
        other => Err(Error::invalid(
            format!("scene.lights[{index}]"),
            format!("{} lights do not render in this build yet (spot lights only)", other.kind()),
        )),
    }
}

/// Widest shadow frustum: a perspective projection degenerates at 180°, so cones wider than
/// this (outer half-angle > 85°) are unshadowed outside it (documented in docs/rendering.md).
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
#[allow(clippy::too_many_arguments)]
pub fn frame_uniforms(cam: &Camera, anchor: DVec3, width: u32, height: u32, lights: u32, layer: u32, extent: f64, shadow_size: u32) -> FrameUniforms {
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
        _pad: [0.0; 2],
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
        _pad: 0.0,
    }
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
    let v4 = |v: DVec3| [v.x as f32, v.y as f32, v.z as f32, 0.0];
    FrameUniforms {
        view_proj: light_view_proj(light, anchor, extent).to_cols_array_2d(),
        cam_right: v4(right * t),
        cam_up: v4(up * t),
        cam_forward: v4(dir),
        view_origin: v4(light.position - anchor),
        size: [size, size],
        light_count: 1,
        texture_layer_size,
        scene_extent: extent as f32,
        shadow_size: size as f32,
        _pad: [0.0; 2],
    }
}
