//! Input records and grids: building f32 input records from f64 values, reading them back, and
//! the axes, sharpness, angle, cosine, roughness and intensity grids the families are built from.

use crate::verify::harness::{Input, Output64, INPUT_WIDTH};
use crate::verify::oracle;
use glam::DVec3;
use std::f64::consts::PI;

pub(super) fn rec(values: &[f64]) -> Input {
    let mut r = [0.0f32; INPUT_WIDTH];
    for (slot, x) in r.iter_mut().zip(values) {
        *slot = *x as f32;
    }
    r
}

pub(super) fn a(i: &Input, k: usize) -> f64 {
    i[k] as f64
}

pub(super) fn v3(i: &Input, k: usize) -> DVec3 {
    DVec3::new(a(i, k), a(i, k + 1), a(i, k + 2))
}

pub(super) fn out3(o: &Output64, k: usize) -> DVec3 {
    DVec3::new(o[k], o[k + 1], o[k + 2])
}

/// `axis` turned by `angle` toward azimuth `phi` of its own frame (f64).
pub(super) fn tilt(axis: DVec3, angle: f64, phi: f64) -> DVec3 {
    let m = oracle::orthonormal_basis(axis);
    (axis * angle.cos() + (m.x_axis * phi.cos() + m.y_axis * phi.sin()) * angle.sin()).normalize()
}

/// Axes: two coordinate axes (exact f32 arithmetic) and three general directions (every dot
/// product rounds).
pub(super) fn axes() -> Vec<DVec3> {
    vec![
        DVec3::Z,
        -DVec3::Y,
        DVec3::new(0.3, -0.5, 0.81).normalize(),
        DVec3::new(-0.62, 0.21, -0.75).normalize(),
        DVec3::new(1.0, 1.0, 1.0).normalize(),
    ]
}

/// SG sharpness: 0, the 1e-6…1e8, and SG_SHARPNESS_MAX = 1e9.
pub(super) const SHARPNESS: [f64; 20] =
    [0.0, 1e-6, 1e-4, 1e-2, 0.1, 0.25, 0.5, 1.0, 2.0, 5.0, 10.0, 30.0, 100.0, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9];
/// A coarser sharpness grid for pairs.
pub(super) const SHARPNESS_PAIRS: [f64; 12] = [0.0, 1e-6, 1e-3, 0.5, 1.0, 3.0, 10.0, 100.0, 1e4, 1e6, 1e8, 1e9];
/// Angles between two axes: equal, 1e-7 rad apart, …, nearly opposite, opposite.
pub(super) const NEAR_ANGLES: [f64; 6] = [0.0, 1e-7, 1e-6, 1e-5, 1e-4, 1e-3];
pub(super) const MID_ANGLES: [f64; 8] = [1e-2, 0.1, 0.3, 0.7, 1.2, 1.8, 2.5, 3.0];
pub(super) const FAR_ANGLES: [f64; 4] = [PI - 1e-4, PI - 1e-6, PI - 1e-7, PI];
/// Cosines: exactly 0, grazing 1e-6 …, normal 1.
pub(super) const GRAZING_COSINES: [f64; 6] = [0.0, 1e-6, 1e-5, 1e-4, 1e-3, 3e-3];
pub(super) const COSINES: [f64; 10] = [0.01, 0.05, 0.1, 0.3, 0.5, 0.7, 0.9, 0.99, 0.9999, 1.0];
/// glTF roughness 1e-4…1 (α = max(roughness², GGX_ALPHA_MIN) as the renderer does).
pub(super) const ROUGHNESS: [f64; 13] = [1e-4, 3e-4, 1e-3, 3e-3, 0.01, 0.02, 0.05, 0.1, 0.2, 0.35, 0.5, 0.75, 1.0];
/// Radiant intensities / powers, and 0.
pub(super) const INTENSITIES: [f64; 6] = [0.0, 1e-8, 1e-4, 1.0, 1e4, 1e8];

pub(super) fn alphas() -> Vec<f64> {
    ROUGHNESS.iter().map(|&r| oracle::ggx_alpha_from_roughness(r)).collect()
}

pub(super) fn lin(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    (0..=n).map(|k| lo + (hi - lo) * k as f64 / n as f64).collect()
}

pub(super) fn logspace(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    (0..=n).map(|k| (lo.ln() + (hi.ln() - lo.ln()) * k as f64 / n as f64).exp()).collect()
}
