//! Light sources: the three punctual types of glTF's KHR_lights_punctual as one enum, so every
//! layer (scene, loader, GPU twins, methods, bindings) handles a light type in one `match`.
//! Spot, point and directional lights give direct light (`direct`, `pathtrace`) and one-bounce
//! light through their reflective shadow maps (`vpl`, `vsgl`, `vsgl2`, `reference`).

use glam::{DVec3, Vec3};

/// A spot light (KHR_lights_punctual conventions: intensity in candela, smooth cone falloff).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpotLight {
    /// World position (f64 so scenes far from the origin keep their precision).
    pub position: DVec3,
    /// Unit direction the light points at.
    pub direction: DVec3,
    pub intensity: f32,
    pub color: Vec3,
    /// Half-angles in radians, 0 ≤ inner < outer ≤ π/2.
    pub inner_cone: f32,
    pub outer_cone: f32,
}

/// A point light (KHR_lights_punctual: intensity in candela, inverse-square falloff).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointLight {
    pub position: DVec3,
    pub intensity: f32,
    pub color: Vec3,
}

/// A directional light (KHR_lights_punctual: illuminance in lux, no falloff).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DirectionalLight {
    /// Unit direction the light travels in.
    pub direction: DVec3,
    pub intensity: f32,
    pub color: Vec3,
}

/// A cluster of emissive triangles as one light (never in `Scene::lights`: a frame of a method
/// that lights with emitter clusters adds these to the scene's lights, `emitter_lights`). It
/// shines like a small Lambertian area light seen from afar: radiant intensity
/// I(ω) = intensity · color · max(normal · ω, 0), the sum of its triangles' L_e·A·cosθ (exact for
/// a flat cluster, a point approximation in distance). Shadows and reflective shadow maps are a
/// point light's six cube faces, those behind the emitting side left out; its direct light is
/// summed over points of its patches (`upload::emitters::EmitterClusters::points`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EmitterLight {
    /// World position: the power-weighted centroid of the triangles, moved a little off them
    /// along `normal` so its own surface does not shadow or reflect it.
    pub position: DVec3,
    /// Unit normal of the emitting side (power-weighted mean of the triangles').
    pub normal: DVec3,
    /// Peak radiant intensity (along `normal`) per unit colour: Σ L_e·A, its largest channel.
    pub intensity: f32,
    pub color: Vec3,
    /// Emissive area it stands for, and how many patches of it (triangles, or pieces of them).
    pub area: f64,
    pub patches: u32,
}

/// Any light source of a scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Light {
    Spot(SpotLight),
    Point(PointLight),
    Directional(DirectionalLight),
    /// Only in a frame's light list, never in a scene's (see [`EmitterLight`]).
    Emitter(EmitterLight),
}

impl Light {
    /// "spot", "point" or "directional" (glTF's names).
    pub fn kind(&self) -> &'static str {
        match self {
            Light::Spot(_) => "spot",
            Light::Point(_) => "point",
            Light::Directional(_) => "directional",
            Light::Emitter(_) => "emitter",
        }
    }

    /// Whether its shadows and reflective shadow maps are six cube faces (point and emitter
    /// lights), not one view.
    pub fn has_cube_faces(&self) -> bool {
        matches!(self, Light::Point(_) | Light::Emitter(_))
    }

    pub fn as_spot(&self) -> Option<&SpotLight> {
        match self {
            Light::Spot(s) => Some(s),
            _ => None,
        }
    }
}

impl From<SpotLight> for Light {
    fn from(l: SpotLight) -> Self {
        Light::Spot(l)
    }
}
impl From<PointLight> for Light {
    fn from(l: PointLight) -> Self {
        Light::Point(l)
    }
}
impl From<DirectionalLight> for Light {
    fn from(l: DirectionalLight) -> Self {
        Light::Directional(l)
    }
}
