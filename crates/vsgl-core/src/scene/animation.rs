//! Node animation: keyframed translation, rotation and scale, as glTF 2.0 animations define
//! them (spec §3.11 "Animations" and Appendix C "Interpolation"), sampled on the CPU in f64.
//!
//! A [`Scene`](super::Scene) holds its animations and the rest pose (TRS) of every node a
//! channel targets. `Scene::set_time(t)` starts every animated node from its rest pose, applies
//! every channel of every animation sampled at `t` clamped to that animation's own
//! [0, duration], and writes the node's local matrix. Lights that sit on nodes follow
//! (`Scene::attach_light`).

use glam::{DMat4, DQuat, DVec3, DVec4};

/// How values between two keyframes are formed (glTF `sampler.interpolation`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Interpolation {
    /// The value of the last keyframe at or before t.
    Step,
    /// Linear for translation and scale, spherical linear (shortest arc) for rotation.
    Linear,
    /// Cubic Hermite spline with the file's in- and out-tangents.
    CubicSpline,
}

impl Interpolation {
    pub fn name(&self) -> &'static str {
        match self {
            Interpolation::Step => "STEP",
            Interpolation::Linear => "LINEAR",
            Interpolation::CubicSpline => "CUBICSPLINE",
        }
    }
}

/// Which part of a node's TRS a channel drives.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AnimatedProperty {
    Translation,
    /// A unit quaternion (x, y, z, w).
    Rotation,
    Scale,
}

impl AnimatedProperty {
    /// Numbers per value: 3 for translation and scale, 4 for a quaternion.
    pub fn components(&self) -> usize {
        match self {
            AnimatedProperty::Rotation => 4,
            _ => 3,
        }
    }
    pub fn name(&self) -> &'static str {
        match self {
            AnimatedProperty::Translation => "translation",
            AnimatedProperty::Rotation => "rotation",
            AnimatedProperty::Scale => "scale",
        }
    }
}

/// The keyframes of one property. Invariants (checked where they are made, see
/// [`Keyframes::new`]): at least one key, times finite, ≥ 0 and strictly increasing, values
/// finite; `values` holds `components` numbers per key, or for [`Interpolation::CubicSpline`]
/// three groups per key (in-tangent, value, out-tangent), as glTF stores them.
#[derive(Clone, Debug)]
pub struct Keyframes {
    times: Vec<f64>,
    values: Vec<f64>,
    components: usize,
    interpolation: Interpolation,
}

impl Keyframes {
    /// Checks the invariants; the error says which one fails and in which part (`"input"`
    /// for the times, `"output"` for the values, `""` for both), so the caller can name the
    /// element.
    pub fn new(times: Vec<f64>, values: Vec<f64>, components: usize, interpolation: Interpolation) -> Result<Self, (&'static str, String)> {
        if times.is_empty() {
            return Err(("input", "no keyframe times".into()));
        }
        if let Some(k) = times.iter().position(|t| !t.is_finite()) {
            return Err(("input", format!("keyframe time {k} is not finite")));
        }
        if times[0] < 0.0 {
            return Err(("input", format!("keyframe time 0 is {} (times must be ≥ 0)", times[0])));
        }
        if let Some(k) = times.windows(2).position(|w| !(w[1] > w[0])) {
            return Err(("input", format!(
                "keyframe times are not strictly increasing: time {} = {} follows time {} = {}",
                k + 1,
                times[k + 1],
                k,
                times[k]
            )));
        }
        let per_key = if interpolation == Interpolation::CubicSpline { 3 * components } else { components };
        if values.len() != times.len() * per_key {
            let groups = if interpolation == Interpolation::CubicSpline { " (in-tangent, value, out-tangent)" } else { "" };
            return Err(("", format!(
                "{} keyframe times but {} output values: {} interpolation needs {}{groups} per time",
                times.len(),
                values.len() / components.max(1),
                interpolation.name(),
                per_key / components.max(1)
            )));
        }
        if let Some(k) = values.iter().position(|v| !v.is_finite()) {
            return Err(("output", format!("non-finite output value {}", k / components.max(1))));
        }
        Ok(Self { times, values, components, interpolation })
    }

    pub fn interpolation(&self) -> Interpolation {
        self.interpolation
    }

    /// Time of the last key, in seconds.
    pub fn end(&self) -> f64 {
        self.times.last().copied().unwrap_or(0.0)
    }

    /// The value at key `k` (for a spline: its value, not a tangent), padded to 4 numbers.
    fn key(&self, k: usize, group: usize) -> DVec4 {
        let groups = if self.interpolation == Interpolation::CubicSpline { 3 } else { 1 };
        let start = (k * groups + group) * self.components;
        let mut v = [0.0; 4];
        for (c, out) in v.iter_mut().enumerate().take(self.components) {
            *out = self.values.get(start + c).copied().unwrap_or(0.0);
        }
        DVec4::from_array(v)
    }

    fn value(&self, k: usize) -> DVec4 {
        self.key(k, if self.interpolation == Interpolation::CubicSpline { 1 } else { 0 })
    }

    /// The value at time `t` (held at the first key before it and at the last key after it).
    /// `rotation` makes LINEAR a slerp and normalises the result.
    pub fn sample(&self, t: f64, rotation: bool) -> DVec4 {
        let n = self.times.len();
        if n == 1 || t <= self.times[0] {
            return self.value(0);
        }
        if t >= self.times[n - 1] {
            return self.value(n - 1);
        }
        // The interval [t_k, t_{k+1}) holding t: times are strictly increasing, so this is
        // well defined and 0 ≤ k < n − 1.
        let k = self.times.partition_point(|&x| x <= t) - 1;
        let (t0, t1) = (self.times[k], self.times[k + 1]);
        let dt = t1 - t0;
        let s = (t - t0) / dt;
        let v = match self.interpolation {
            Interpolation::Step => self.value(k),
            Interpolation::Linear if rotation => {
                return slerp(self.value(k), self.value(k + 1), s);
            }
            Interpolation::Linear => self.value(k).lerp(self.value(k + 1), s),
            Interpolation::CubicSpline => {
                // glTF 2.0 Appendix C, cubic Hermite spline: with s ∈ [0, 1] and Δt = t1 − t0,
                // p(s) = (2s³ − 3s² + 1)·v_k + Δt(s³ − 2s² + s)·b_k + (−2s³ + 3s²)·v_{k+1}
                //        + Δt(s³ − s²)·a_{k+1},
                // b_k the out-tangent of key k and a_{k+1} the in-tangent of key k + 1.
                let (s2, s3) = (s * s, s * s * s);
                let out_tangent = self.key(k, 2);
                let in_tangent = self.key(k + 1, 0);
                (2.0 * s3 - 3.0 * s2 + 1.0) * self.value(k)
                    + dt * (s3 - 2.0 * s2 + s) * out_tangent
                    + (-2.0 * s3 + 3.0 * s2) * self.value(k + 1)
                    + dt * (s3 - s2) * in_tangent
            }
        };
        if rotation { normalize_quat(v) } else { v }
    }
}

/// A quaternion (x, y, z, w) scaled to unit length; the identity when it has no length (a
/// spline can pass through 0 between opposite keys).
fn normalize_quat(q: DVec4) -> DVec4 {
    let len = q.length();
    if len > 1e-300 && len.is_finite() { q / len } else { DVec4::new(0.0, 0.0, 0.0, 1.0) }
}

/// Spherical linear interpolation of unit quaternions along the shorter arc (glTF 2.0
/// Appendix C: negate one end when their dot product is negative; Shoemake 1985, "Animating
/// rotation with quaternion curves", for the sin-weighted form). Near-parallel ends fall back
/// to normalised lerp, where sin θ in the denominator would lose every digit.
fn slerp(a: DVec4, b: DVec4, s: f64) -> DVec4 {
    let (a, mut b) = (normalize_quat(a), normalize_quat(b));
    let mut d = a.dot(b);
    if d < 0.0 {
        b = -b;
        d = -d;
    }
    if d > 1.0 - 1e-12 {
        return normalize_quat(a.lerp(b, s));
    }
    let theta = d.min(1.0).acos();
    let sin_theta = theta.sin();
    let wa = ((1.0 - s) * theta).sin() / sin_theta;
    let wb = (s * theta).sin() / sin_theta;
    normalize_quat(wa * a + wb * b)
}

/// A node's local transform as translation, rotation and scale (M = T·R·S, glTF's order).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Trs {
    pub translation: DVec3,
    pub rotation: DQuat,
    pub scale: DVec3,
}

impl Default for Trs {
    fn default() -> Self {
        Self { translation: DVec3::ZERO, rotation: DQuat::IDENTITY, scale: DVec3::ONE }
    }
}

impl Trs {
    pub fn matrix(&self) -> DMat4 {
        DMat4::from_scale_rotation_translation(self.scale, self.rotation, self.translation)
    }

    /// Sets the property `property` from a sampled value.
    pub fn set(&mut self, property: AnimatedProperty, v: DVec4) {
        match property {
            AnimatedProperty::Translation => self.translation = v.truncate(),
            AnimatedProperty::Scale => self.scale = v.truncate(),
            AnimatedProperty::Rotation => self.rotation = DQuat::from_vec4(normalize_quat(v)),
        }
    }
}

/// One channel: a property of a node driven by keyframes.
#[derive(Clone, Debug)]
pub struct Channel {
    /// Index into `Scene::nodes`.
    pub node: usize,
    pub property: AnimatedProperty,
    pub keys: Keyframes,
}

impl Channel {
    pub fn sample(&self, t: f64) -> DVec4 {
        self.keys.sample(t, self.property == AnimatedProperty::Rotation)
    }
}

/// One animation (a glTF `animations[i]`): channels played together on one clock.
#[derive(Clone, Debug)]
pub struct Animation {
    pub name: String,
    pub channels: Vec<Channel>,
}

impl Animation {
    /// The time of its last keyframe, in seconds (0 without channels).
    pub fn duration(&self) -> f64 {
        self.channels.iter().map(|c| c.keys.end()).fold(0.0, f64::max)
    }
}

/// A light that sits on a node: its position is the node's world origin and it points along
/// the node's world −Z (KHR_lights_punctual), so it follows the node when it moves.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LightAttachment {
    /// Index into `Scene::lights`.
    pub light: usize,
    /// Index into `Scene::nodes`.
    pub node: usize,
}

#[cfg(test)]
mod tests {
    use super::*;

    fn keys(times: &[f64], values: &[f64], c: usize, i: Interpolation) -> Keyframes {
        Keyframes::new(times.to_vec(), values.to_vec(), c, i).unwrap()
    }

    #[test]
    fn linear_step_and_clamping() {
        let k = keys(&[1.0, 3.0], &[0.0, 0.0, 0.0, 4.0, 2.0, -2.0], 3, Interpolation::Linear);
        assert_eq!(k.sample(2.0, false), DVec4::new(2.0, 1.0, -1.0, 0.0));
        assert_eq!(k.sample(0.0, false), DVec4::ZERO, "before the first key: the first value");
        assert_eq!(k.sample(9.0, false), DVec4::new(4.0, 2.0, -2.0, 0.0));
        let s = keys(&[1.0, 3.0], &[0.0, 0.0, 0.0, 4.0, 2.0, -2.0], 3, Interpolation::Step);
        assert_eq!(s.sample(2.9, false), DVec4::ZERO);
        assert_eq!(s.sample(3.0, false), DVec4::new(4.0, 2.0, -2.0, 0.0));
    }

    #[test]
    fn slerp_halves_the_angle_on_the_shorter_arc() {
        let h = std::f64::consts::FRAC_PI_4;
        // 0° and 90° about +Y: the midpoint is 45°.
        let k = keys(&[0.0, 1.0], &[0.0, 0.0, 0.0, 1.0, 0.0, h.sin(), 0.0, h.cos()], 4, Interpolation::Linear);
        let q = k.sample(0.5, true);
        let e = (std::f64::consts::PI / 8.0).sin_cos();
        assert!((q - DVec4::new(0.0, e.0, 0.0, e.1)).length() < 1e-12, "{q}");
        // The same end given as −q (the same rotation) must take the same short way.
        let k = keys(&[0.0, 1.0], &[0.0, 0.0, 0.0, 1.0, 0.0, -h.sin(), 0.0, -h.cos()], 4, Interpolation::Linear);
        let q2 = k.sample(0.5, true);
        assert!((q2 - q).length() < 1e-12 || (q2 + q).length() < 1e-12, "{q2}");
    }

    #[test]
    fn cubic_spline_hits_its_keys_and_follows_the_hermite_form() {
        // Scalar-like: x from 0 to 1 over [0, 2] with tangents 1 and 0 (y, z zero).
        let v = [
            0.0, 0.0, 0.0, /*value*/ 0.0, 0.0, 0.0, /*out*/ 1.0, 0.0, 0.0, //
            /*in*/ 0.0, 0.0, 0.0, /*value*/ 1.0, 0.0, 0.0, 0.0, 0.0, 0.0,
        ];
        let k = keys(&[0.0, 2.0], &v, 3, Interpolation::CubicSpline);
        assert_eq!(k.sample(0.0, false).x, 0.0);
        assert_eq!(k.sample(2.0, false).x, 1.0);
        // s = 0.5: h00 = 0.5, h10 = 0.125, h01 = 0.5, h11 = −0.125; Δt = 2.
        let expected = 0.5 * 0.0 + 2.0 * 0.125 * 1.0 + 0.5 * 1.0 + 2.0 * -0.125 * 0.0;
        assert!((k.sample(1.0, false).x - expected).abs() < 1e-15);
    }

    #[test]
    fn bad_keyframes_are_refused_with_the_reason() {
        let e = |t: Vec<f64>, v: Vec<f64>, i| Keyframes::new(t, v, 3, i).unwrap_err().1;
        let e = e(vec![0.0, 1.0], vec![0.0; 9], Interpolation::Linear);
        assert!(e.contains("2 keyframe times but 3 output values"), "{e}");
        let f = |t: Vec<f64>, v: Vec<f64>, i| Keyframes::new(t, v, 3, i).unwrap_err();
        let (part, e) = f(vec![0.0, 1.0, 1.0], vec![0.0; 9], Interpolation::Linear);
        assert!(part == "input" && e.contains("not strictly increasing"), "{e}");
        let (part, e) = f(vec![0.0, f64::NAN], vec![0.0; 6], Interpolation::Linear);
        assert!(part == "input" && e.contains("not finite"), "{e}");
        let (part, e) = f(vec![-1.0, 0.0], vec![0.0; 6], Interpolation::Linear);
        assert!(part == "input" && e.contains("≥ 0"), "{e}");
        let (part, e) = f(vec![0.0], vec![f64::NAN, 0.0, 0.0], Interpolation::Step);
        assert!(part == "output" && e.contains("non-finite output value 0"), "{e}");
        let (_, e) = f(vec![0.0, 1.0], vec![0.0; 6], Interpolation::CubicSpline);
        assert!(e.contains("needs 3"), "{e}");
    }
}
