//! Families of `wgsl/common/vsgl.wgsl`: VSGL generation (lobe and position from moments, with
//! clusters 1e5 m from the world origin), vsgl_incoming_radiance, and diffuse and specular
//! shading from a radiance SG.

use super::error_model::{dot_scale, fl, floor_tiny, floor_unit, perturbation, rel_sg_integral};
use super::grids::{
    a, alphas, axes, out3, rec, tilt, v3, COSINES, GRAZING_COSINES, INTENSITIES, NEAR_ANGLES,
    SHARPNESS,
};
use super::lobes::{toksvig_amplitude_bound, toksvig_sharpness_bound};
use super::asg::{bound_ggx_lobe_asg, frame_residuals};
use super::ggx::rel_smith_lambda;
use super::sg::{bound_sg_product_integral, clamped_cosine_abs_bound};
use super::{check, Check, Family, FloorFn, FLT_MAX, FLT_MIN, ULP};
use crate::rng::SplitMix64;
use crate::verify::harness::{HarnessFunction as F, Input, Output64};
use crate::verify::oracle;
use glam::DVec3;
use std::f64::consts::PI;
use std::ops::Range;

/// vsgl_lobe_from_moments: ξ̄ = Σ/W (2.5 ULP per component) then the Toksvig inverse, so r = ‖ξ̄‖
/// errs by 2.5 + 5.25 ULP and λ, the amplitude W/A(λ) (+½ ULP) follow as in
/// sg_from_toksvig_mean_direction; the axis errs by 2.5 + 6 ULP. No power (W ≤ 0): exact zeros.
fn bound_lobe_from_moments(i: &Input, r: &Output64, part: usize) -> f64 {
    let w = a(i, 0);
    if w.is_nan() || w <= 0.0 {
        return 0.0;
    }
    let rr = (v3(i, 1) / w).length();
    match part {
        0 => 8.5 * ULP,
        1 => toksvig_sharpness_bound(rr, 7.75 * ULP, r[3]),
        _ => {
            let amp = if r[4] >= FLT_MAX { r[4] } else { r[4] / w };
            w * toksvig_amplitude_bound(rr, 7.75 * ULP, r[3], amp) + 0.5 * ULP * r[4]
        }
    }
}

/// vsgl_position_from_moments: 1/W (2.5) then products (½): the mean and M₂ = Σw‖y‖²/W err by 3 ULP
/// (relative); σ² = M₂ − ‖μ‖² errs by ≤ 3.5·M₂ + 7.5·‖μ‖² ≤ 11 ULP × M₂ (absolute), i.e. its
/// condition number is M₂/σ², bounded by 1e6 through the VSGL_VARIANCE_MIN_FRACTION clamp (whose
/// own value errs by 3.5 ULP). This is why positions must be relative to a local origin: M₂/σ² is
/// (distance to the local origin / cluster radius)², 1e14 for a 1 cm cluster 1e5 m from the world
/// origin.
fn bound_position_variance(i: &Input, r: &Output64) -> f64 {
    let w = a(i, 0);
    if w.is_nan() || w <= 0.0 {
        return 0.0;
    }
    let m2 = (a(i, 4) / w).max(0.0);
    11.0 * ULP * m2 + 3.5 * ULP * r[3] + FLT_MIN
}

/// vsgl_incoming_radiance: t = μ − y_p (½ ULP), d² (1.5), the σ² clamp d²/1e9 (3), λσ = d²/σ² (2.5),
/// ξμ = normalize(t) (6), sg_product of (−ξv, λv) and (ξμ, λσ): the log-amplitude's 10.25 ULP, exp's
/// 2|ℓ| ULP; c = 20 ULP per input (the longest chain, on ℓ). c₀: the coefficient c_v/(2πσ²) (3.5) and
/// exp's 3 ULP for the amplitude, 6 ULP absolute for the axis, 5.5 ULP for λ_in. Condition numbers:
/// the product's (λv + λσ)/λ_in (a lobe pointing away from the shading point), |ℓ|, and
/// ‖μ‖/‖μ − y_p‖ (the perturbation moves μ and y_p by ULPs of their own size; the GPU's t is in fact
/// rounded relative to itself, so this part is conservative).
/// Since vsgl_incoming_radiance is vsgl_incoming_radiance_seen(vsgl_position_seen_from(…)), the
/// same chain holds for both: the split form replaces the divisions by 2π, σ² and the clamp's 1e9
/// with one reciprocal 1/σ² (2.5) and products (½ each), and ξμ = t·inverseSqrt(d²) (2.5), ξ_in =
/// v·inverseSqrt(‖v‖²) (2.5 + the dot's 1.5), each no longer than the division chains they replace,
/// so c, c₀ are unchanged. `two_pi` is 2π where slot 4 holds c_v (vsgl_incoming_radiance) and 1
/// where it holds c_v/(2π) already (vsgl_incoming_radiance_seen).
fn bound_incoming(f: F, two_pi: f64, i: &Input, r: &Output64, slots: Range<usize>, c0_abs: f64, c0_rel: f64) -> f64 {
    let norm = slots.clone().map(|j| r[j] * r[j]).sum::<f64>().sqrt();
    // exp(ℓ) may flush to 0 before it is multiplied by the coefficient c_v/(2πσ²)
    let flush = if slots.start == 4 { FLT_MIN * (a(i, 4) / (two_pi * a(i, 8).max(FLT_MIN))).min(FLT_MAX) } else { 0.0 };
    perturbation(f, i, slots, 20.0, &[0, 5, 9]) + c0_abs * ULP + c0_rel * ULP * norm + flush + FLT_MIN
}
fn incoming_variance(i: &Input) -> f64 {
    let to_mean = v3(i, 5) - v3(i, 9);
    a(i, 8).max(to_mean.length_squared() / oracle::SG_SHARPNESS_MAX).max(FLT_MIN)
}
fn floor_incoming_amplitude(i: &Input, _: &Output64) -> f64 {
    fl(1e-30 * a(i, 4) / (2.0 * PI * incoming_variance(i)))
}
fn floor_incoming_seen_amplitude(i: &Input, _: &Output64) -> f64 {
    fl(1e-30 * a(i, 4) / incoming_variance(i))
}

/// vsgl_position_seen_from: t = μ − y_p (½ ULP), d² (1.5), the clamp d²·(1/1e9) (the constant's
/// reciprocal rounded to f32, ½, and the product, ½): c = 3 ULP per input (the perturbation
/// moves μ and y_p by ULPs of their own size, which also covers the cancellation in t). Then
/// 1/σ² (c₀ = 2.5, the division), λσ = d²·(1/σ²) (c₀ = 2.5 + ½; under the clamp λσ ≈ 1e9
/// whatever d is, and the GPU's f32 1e-9 differs from the oracle's 1/1e9 by ½ ULP: c₀ = 4.5),
/// ξμ = t·inverseSqrt(d²) (c₀ = 2 + ½ absolute, 3). Where d² < FLT_MIN (y_p at μ) the axis is
/// unused and both sides return t itself.
fn bound_seen(i: &Input, r: &Output64, slots: Range<usize>, c0_abs: f64, c0_rel: f64) -> f64 {
    let norm = slots.clone().map(|j| r[j] * r[j]).sum::<f64>().sqrt();
    perturbation(F::VsglPositionSeenFrom, i, slots, 3.0, &[0, 4]) + c0_abs * ULP + c0_rel * ULP * norm + FLT_MIN
}

/// vsgl_specular_receiver_from: n·ω_o is one dot (1.5 ULP × Σ|nᵢωᵢ|, absolute: a grazing view's
/// cosine is known only that well); Λ(ω_o) = ggx_smith_lambda of that cosine: the dot's error
/// reaches it through the perturbation (c = 1.5 per input, vectors moved by their length), plus
/// Λ's own roundings (rel_smith_lambda, the bound of the ggx_smith_lambda rows); the ASG is
/// ggx_lobe_asg on the same record (its bound and its frame-orthonormality check, slots + 2).
fn bound_receiver_lambda(i: &Input, r: &Output64) -> f64 {
    perturbation(F::VsglSpecularReceiverFrom, i, 1..2, 1.5, &[0, 3]) + rel_smith_lambda(r[0], a(i, 6)) * r[1] + FLT_MIN
}
fn bound_receiver_asg(i: &Input, slots: Range<usize>, c0_abs: f64, c0_rel: f64) -> f64 {
    let inner = F::GgxLobeAsg.oracle(i);
    bound_ggx_lobe_asg(i, &inner, slots.start - 2..slots.end - 2, c0_abs, c0_rel)
}
fn receiver_frame_residuals(o: &[f64]) -> Vec<f64> {
    frame_residuals(&o[2..])
}

/// vsgl_specular_with_receiver(L, vsgl_specular_receiver_from(n, ω_o, α)) performs the same
/// roundings as vsgl_specular (which is now that composition): the same c = 10, c₀ = 16.
fn bound_vsgl_specular_with_receiver(i: &Input, r: &Output64) -> f64 {
    perturbation(F::VsglSpecularWithReceiver, i, 0..1, 10.0, &[0, 5, 8]) + 16.0 * ULP * r[0] + FLT_MIN * a(i, 4)
}

/// Radiance SG inputs: slots 0–4 (axis, sharpness, amplitude c_in), normal 5–7.
fn radiance_parts(i: &Input) -> (DVec3, f64, f64, DVec3) {
    (v3(i, 0), a(i, 3), a(i, 4), v3(i, 5))
}
/// vsgl_diffuse = c·(1/π)·A(λ)·max(ξ·n, 0): A's bound, 1/π (½) and three products (1.5); the cosine
/// errs by 1.5 ULP·Σ|ξᵢnᵢ| absolute (grazing lobes: condition Σ|ξᵢnᵢ|/(ξ·n)), which also covers a
/// flipped max(·, 0) decision.
fn bound_vsgl_diffuse(i: &Input, r: &Output64) -> f64 {
    let (xi, lambda, c, n) = radiance_parts(i);
    r[0] * (rel_sg_integral(lambda) + 2.0 * ULP) + c / PI * oracle::sg_integral(lambda) * 1.5 * ULP * dot_scale(xi, n) + FLT_MIN
}
/// vsgl_diffuse_approx: the same with 2π/max(λ, ½) (3 ULP).
fn bound_vsgl_diffuse_approx(i: &Input, r: &Output64) -> f64 {
    let (xi, lambda, c, n) = radiance_parts(i);
    r[0] * 5.0 * ULP + c / PI * oracle::sg_integral_approx(lambda) * 1.5 * ULP * dot_scale(xi, n) + FLT_MIN
}
/// vsgl_diffuse_accurate = c/π·sg_clamped_cosine_integral: that bound × c/π, + 1.5 ULP.
fn bound_vsgl_diffuse_accurate(i: &Input, r: &Output64) -> f64 {
    let (xi, lambda, c, n) = radiance_parts(i);
    let value = r[0] * PI / c.max(FLT_MIN);
    c / PI * clamped_cosine_abs_bound(xi, lambda, n, value) + 1.5 * ULP * r[0]
}
/// vsgl_diffuse_sg_product = c·(1/A(λd))·sg_product_integral(ξ, λ, n, λd): that bound × c/A(λd), plus
/// 1/A(λd) (A's bound + 2.5 + ½ for the constant) and the products (1).
fn bound_vsgl_diffuse_sg_product(i: &Input, r: &Output64) -> f64 {
    let (xi, lambda, c, n) = radiance_parts(i);
    let ld = oracle::LAMBERT_LOBE_SG_SHARPNESS;
    let amp = 1.0 / oracle::sg_integral(ld);
    let inner = rec(&[xi.x, xi.y, xi.z, lambda, n.x, n.y, n.z, ld]);
    let pi_value = F::SgProductIntegral.oracle(&inner);
    c * amp * bound_sg_product_integral(&inner, &pi_value) + r[0] * (rel_sg_integral(ld) + 4.0 * ULP)
}
/// vsgl_specular: ggx_lobe_asg (4 ULP), G2 (Smith Λ's 8 ULP through α), the convolved bandwidths
/// (3.5) and exp (2): c = 10 ULP per input; c₀ = 3 (exp) + 10 (two inverseSqrt(1 + ν/η)) + 3.5 (G2's
/// sums and division) ≈ 16. Condition numbers: grazing n·l and n·v (G2 and the frame), the
/// sharpness of the convolved ASG times the frame's absolute error, |exponent|.
fn bound_vsgl_specular(i: &Input, r: &Output64) -> f64 {
    perturbation(F::VsglSpecular, i, 0..1, 10.0, &[0, 5, 8]) + 16.0 * ULP * r[0] + FLT_MIN * a(i, 4)
}

/// vsgl_specular_accurate: the half vector and m = n × (ξ − ω_o)/‖u‖ (normalize 6, cross and
/// inverseSqrt 4), B's entries and det (3), the eigenvalue b₊ (sqrt 4.5, sums 2) and b₋ = det/b₊
/// (2.5), the eigenvector (inverseSqrt 2), the widened σ (division 2.5), the quadratic form (2.5
/// per division, 3 sums) and G2 (Smith Λ's 8 ULP through α): c = 12 ULP per input; c₀ = sg_integral
/// (~4) + the final 1/(π√(σ₊σ₋)q²) (2.5 + 4.5 + 2) + /(4 n·ω_o) (2.5) + products (2) ≈ 18.
/// Condition numbers (from the perturbation): grazing n·l and n·v, the eigenvector of a nearly
/// isotropic B (harmless: σ₊ ≈ σ₋ there) and the sharp NDF's exponent-like q².
fn bound_vsgl_specular_accurate(i: &Input, r: &Output64) -> f64 {
    perturbation(F::VsglSpecularAccurate, i, 0..1, 12.0, &[0, 5, 8]) + 18.0 * ULP * r[0] + FLT_MIN * a(i, 4)
}

/// vsgl_specular_blend = w·filtered + (1 − w)·asg: both forms' bounds (each at most the larger
/// form's value: the bounds are taken at each form's own value) and the share w = √(α²·σ₊^-½·σ₋^-½)
/// (2 inverseSqrt, sqrt, products: 6 ULP), which enters as |filtered − asg|·δw; the perturbation
/// covers the inputs' rounding through all three (c = 12 ULP per input as the filtered form).
fn bound_vsgl_specular_blend(i: &Input, r: &Output64) -> f64 {
    let filtered = F::VsglSpecularAccurate.oracle(i)[0];
    let asg = F::VsglSpecular.oracle(i)[0];
    perturbation(F::VsglSpecularBlend, i, 0..1, 12.0, &[0, 5, 8])
        + 18.0 * ULP * filtered.max(asg)
        + 6.0 * ULP * (filtered - asg).abs()
        + 3.0 * ULP * r[0]
        + FLT_MIN * a(i, 4)
}

pub(super) fn vsgl_families(f: &mut Vec<Family>) {
    // vsgl_lobe_from_moments: single lobes and mixtures × powers 1e-8…1e8; zero power.
    let (mut broad, mut sharp, mut zero) = (Vec::new(), Vec::new(), Vec::new());
    for ax in axes() {
        for &w in &INTENSITIES[1..] {
            for &l in &SHARPNESS {
                let m = w * oracle::sg_toksvig_mean_direction(ax, l);
                (if l <= 1e3 { &mut broad } else { &mut sharp }).push(rec(&[w, m.x, m.y, m.z]));
            }
            let m = w * 0.5 * (oracle::sg_toksvig_mean_direction(ax, 100.0) + oracle::sg_toksvig_mean_direction(tilt(ax, 0.3, 2.0), 10.0));
            broad.push(rec(&[w, m.x, m.y, m.z]));
        }
        zero.push(rec(&[0.0, 0.0, 0.0, 0.0]));
        zero.push(rec(&[0.0, ax.x, ax.y, ax.z]));
        zero.push(rec(&[-1.0, ax.x, ax.y, ax.z]));
    }
    let lobe_checks = || {
        vec![
            check("axis", 0..3, floor_unit, |i, r| bound_lobe_from_moments(i, r, 0)),
            check("sharpness", 3..4, floor_tiny, |i, r| bound_lobe_from_moments(i, r, 1)),
            check("amplitude", 4..5, floor_tiny, |i, r| bound_lobe_from_moments(i, r, 2)),
        ]
    };
    for (name, ins) in [("λ <= 1e3, power 1e-8…1e8", broad), ("λ > 1e3 (Toksvig clamp), power 1e-8…1e8", sharp), ("zero power", zero)] {
        f.push(Family { function: F::VsglLobeFromMoments, name, inputs: ins, checks: lobe_checks() });
    }
    // vsgl_position_from_moments: VPL clusters summed in f32 as a GPU would, relative to a local
    // origin (the light) — near it, and 1e5 m from the world origin — and degenerate clusters.
    let mut rng = SplitMix64(0x5eed);
    let (mut near, mut far, mut degenerate) = (Vec::new(), Vec::new(), Vec::new());
    let world = DVec3::new(1e5, -1e5, 1e5);
    for &dist in &[0.0, 0.1, 1.0, 10.0, 100.0] {
        for &radius_fraction in &[1e-6, 1e-4, 1e-2, 0.3, 1.0] {
            for &power in &INTENSITIES[1..] {
                let light = world + dist * rng.unit_vector();
                let radius = radius_fraction * dist.max(1.0);
                let (mut w, mut sy, mut sy2) = (0f32, glam::Vec3::ZERO, 0f32);
                for _ in 0..64 {
                    let p = world + radius * rng.unit_vector() * rng.next_f64().sqrt();
                    let y = (p - light).as_vec3(); // position relative to the local origin, in f32
                    let pw = (power * (0.5 + rng.next_f64())) as f32;
                    w += pw;
                    sy += pw * y;
                    sy2 += pw * y.length_squared();
                }
                let r = rec(&[w as f64, sy.x as f64, sy.y as f64, sy.z as f64, sy2 as f64]);
                (if dist <= 10.0 * radius { &mut near } else { &mut far }).push(r);
            }
        }
    }
    for &power in &INTENSITIES[1..] {
        for y in [DVec3::ZERO, DVec3::new(2.0, 0.0, 0.0), DVec3::new(1e-3, -3.0, 7.0)] {
            // every VPL at one point: σ² = 0 exactly (up to the f32 moments)
            let (w, s1, s2) = (64.0 * power, 64.0 * power * y, 64.0 * power * y.length_squared());
            degenerate.push(rec(&[w, s1.x, s1.y, s1.z, s2]));
        }
    }
    degenerate.push(rec(&[0.0, 0.0, 0.0, 0.0, 0.0]));
    degenerate.push(rec(&[0.0, 1.0, 2.0, 3.0, 4.0]));
    let pos_checks = || {
        vec![
            check("mean", 0..3, floor_tiny, |i, r| if a(i, 0) > 0.0 { 3.0 * ULP * out3(r, 0).length() } else { 0.0 }),
            check("variance", 3..4, floor_tiny, bound_position_variance),
        ]
    };
    for (name, ins) in [
        ("clusters within 10 radii of the local origin", near),
        ("clusters 1e5 m from the world origin, local origin 0.1…100 m away", far),
        ("all VPLs at one point (σ² = 0), zero power", degenerate),
    ] {
        f.push(Family { function: F::VsglPositionFromMoments, name, inputs: ins, checks: pos_checks() });
    }
    // vsgl_incoming_radiance: σ²/d² 0, 1e-12…1e3 × λv × lobe directions × intensities; the shading
    // point at the mean; positions from world coordinates 1e5 m away, relative to the light.
    let (mut toward, mut away, mut at_mean, mut offset) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let ratios = [0.0, 1e-12, 1e-9, 1e-6, 1e-3, 1.0, 1e3];
    let lambdas_v = [0.0, 1e-6, 0.5, 10.0, 1e3, 1e5];
    for (k, &mean) in [DVec3::new(0.5, -0.3, 2.0), DVec3::new(-3.0, 1.0, 0.2)].iter().enumerate() {
        let y_p = DVec3::new(0.1, 0.2, 0.0);
        let to_p = (y_p - mean).normalize(); // the VSGL lobe emits toward the shading point along +to_p
        for &ratio in &ratios {
            let var = ratio * (mean - y_p).length_squared();
            for &lv in &lambdas_v {
                for (j, t) in [0.0, 1e-7, 1e-3, 0.5, 2.0, PI].iter().enumerate() {
                    let axis = tilt(to_p, *t, 0.7 * (j + k) as f64);
                    for &c in &INTENSITIES {
                        let r = rec(&[axis.x, axis.y, axis.z, lv, c, mean.x, mean.y, mean.z, var, y_p.x, y_p.y, y_p.z]);
                        (if *t <= 0.5 { &mut toward } else { &mut away }).push(r);
                    }
                }
            }
        }
    }
    for &var in &[0.0, 1e-6, 1.0] {
        for &lv in &lambdas_v {
            for &c in &[0.0, 1.0, 1e8] {
                let m = DVec3::new(0.4, 1.5, -0.7);
                at_mean.push(rec(&[0.0, 0.0, 1.0, lv, c, m.x, m.y, m.z, var, m.x, m.y, m.z]));
            }
        }
    }
    let light = world + DVec3::new(0.3, 2.5, -0.4);
    for &(mean_w, p_w) in &[
        (world + DVec3::new(1.0, 0.0, 0.5), world + DVec3::new(-0.5, 0.1, 0.2)),
        (world + DVec3::new(0.01, 0.0, 0.0), world + DVec3::new(0.0, 0.01, 0.0)),
        (world + DVec3::new(30.0, -5.0, 2.0), world + DVec3::new(-2.0, 0.0, 0.0)),
    ] {
        let (mean, y_p) = (mean_w - light, p_w - light); // relative to the local origin, in f64
        for &ratio in &ratios {
            let var = ratio * (mean - y_p).length_squared();
            for &lv in &lambdas_v {
                let axis = tilt((y_p - mean).normalize(), 0.3, 1.0);
                for &c in &INTENSITIES {
                    offset.push(rec(&[axis.x, axis.y, axis.z, lv, c, mean.x, mean.y, mean.z, var, y_p.x, y_p.y, y_p.z]));
                }
            }
        }
    }
    const TWO_PI: f64 = 2.0 * PI;
    let incoming_checks = || {
        vec![
            check("axis", 0..3, floor_unit, |i, r| bound_incoming(F::VsglIncomingRadiance, TWO_PI, i, r, 0..3, 6.0, 0.0)),
            check("sharpness", 3..4, floor_tiny, |i, r| bound_incoming(F::VsglIncomingRadiance, TWO_PI, i, r, 3..4, 0.0, 5.5)),
            check("amplitude", 4..5, floor_incoming_amplitude, |i, r| bound_incoming(F::VsglIncomingRadiance, TWO_PI, i, r, 4..5, 0.0, 6.5)),
        ]
    };
    let seen_incoming_checks = || {
        vec![
            check("axis", 0..3, floor_unit, |i, r| bound_incoming(F::VsglIncomingRadianceSeen, 1.0, i, r, 0..3, 6.0, 0.0)),
            check("sharpness", 3..4, floor_tiny, |i, r| bound_incoming(F::VsglIncomingRadianceSeen, 1.0, i, r, 3..4, 0.0, 5.5)),
            check("amplitude", 4..5, floor_incoming_seen_amplitude, |i, r| {
                bound_incoming(F::VsglIncomingRadianceSeen, 1.0, i, r, 4..5, 0.0, 6.5)
            }),
        ]
    };
    // vsgl_position_seen_from on the positions of the same records (mean 0-2, σ² 3, y_p 4-6).
    // has_axis is a decision on d² ≥ FLT_MIN: no case lies within rounding of that threshold
    // (d = 0 exactly, or d² ≥ 1e-4), so it must agree exactly (bound 0).
    let seen_checks = || {
        vec![
            check("inv_variance", 0..1, floor_tiny, |i, r| bound_seen(i, r, 0..1, 0.0, 2.5)),
            check("sharpness", 1..2, floor_tiny, |i, r| bound_seen(i, r, 1..2, 0.0, 4.5)),
            check("axis", 2..5, floor_unit, |i, r| bound_seen(i, r, 2..5, 3.0, 0.0)),
            check("has_axis", 5..6, floor_unit, |_, _| 0.0),
        ]
    };
    let positions = |ins: &[Input]| {
        let mut out: Vec<Input> = Vec::new();
        for i in ins {
            let p = rec(&[a(i, 5), a(i, 6), a(i, 7), a(i, 8), a(i, 9), a(i, 10), a(i, 11)]);
            if !out.contains(&p) {
                out.push(p);
            }
        }
        out
    };
    // The same records with c_v/(2π) in slot 4 (the seen form's amplitude argument).
    let over_two_pi = |ins: &[Input]| {
        ins.iter()
            .map(|i| {
                let mut r = *i;
                r[4] = (a(i, 4) / TWO_PI) as f32;
                r
            })
            .collect::<Vec<Input>>()
    };
    let mut near_positions = positions(&toward);
    for p in positions(&away) {
        if !near_positions.contains(&p) {
            near_positions.push(p);
        }
    }
    f.push(Family {
        function: F::VsglPositionSeenFrom,
        name: "σ²/d² 0, 1e-12…1e3 near the local origin",
        inputs: near_positions,
        checks: seen_checks(),
    });
    f.push(Family { function: F::VsglPositionSeenFrom, name: "shading point at the mean (d = 0)", inputs: positions(&at_mean), checks: seen_checks() });
    f.push(Family {
        function: F::VsglPositionSeenFrom,
        name: "scene 1e5 m from the origin, light as local origin",
        inputs: positions(&offset),
        checks: seen_checks(),
    });
    for (name, ins) in [
        ("lobe toward y_p; σ²/d² 0, 1e-12…1e3; λv 0…1e5; I 0, 1e-8…1e8", toward),
        ("lobe away from y_p (the SG product cancels), same grids", away),
        ("shading point at the mean (d = 0)", at_mean),
        ("scene 1e5 m from the origin, light as local origin", offset),
    ] {
        f.push(Family { function: F::VsglIncomingRadianceSeen, name, inputs: over_two_pi(&ins), checks: seen_incoming_checks() });
        f.push(Family { function: F::VsglIncomingRadiance, name, inputs: ins, checks: incoming_checks() });
    }
    // Diffuse and specular shading from a radiance SG: λ_in × lobe/normal angle × c_in.
    let shade = |cosines: &[f64]| {
        let mut ins = Vec::new();
        for n in axes() {
            for &l in SHARPNESS.iter().step_by(2).chain(&[1e9]) {
                for (j, &c) in cosines.iter().enumerate() {
                    let xi = tilt(n, c.clamp(-1.0, 1.0).acos(), 0.4 + j as f64);
                    for &amp in &[0.0, 1e-8, 1.0, 1e8, 1e20] {
                        ins.push(rec(&[xi.x, xi.y, xi.z, l, amp, n.x, n.y, n.z]));
                    }
                }
            }
        }
        ins
    };
    let above = COSINES.to_vec();
    let grazing: Vec<f64> = GRAZING_COSINES.iter().flat_map(|&c| [c, -c]).collect();
    let below: Vec<f64> = [-0.01, -0.3, -1.0].to_vec();
    // Floors: relative (1e-30 of the scale c·A(λ)/π) above the horizon; the scale itself at grazing
    // and below, where the cosine is known only to ±1.5 ULP absolute.
    let relative: FloorFn = |i, _| fl(1e-30 * a(i, 4) * oracle::sg_integral(a(i, 3)) / PI);
    let absolute: FloorFn = |i, _| fl(a(i, 4) * oracle::sg_integral(a(i, 3)) / PI);
    for (name, cos, scale) in [("ξ·n 0.01…1", above, relative), ("grazing |ξ·n| <= 3e-3 (incl. 0)", grazing, absolute), ("ξ·n < 0", below, absolute)] {
        let ins = shade(&cos);
        f.push(Family { function: F::VsglDiffuse, name, inputs: ins.clone(), checks: vec![check("value", 0..1, scale, bound_vsgl_diffuse)] });
        f.push(Family {
            function: F::VsglDiffuseApprox,
            name,
            inputs: ins.clone(),
            checks: vec![check("value", 0..1, scale, bound_vsgl_diffuse_approx)],
        });
        f.push(Family {
            function: F::VsglDiffuseAccurate,
            name,
            inputs: ins.clone(),
            checks: vec![check("value", 0..1, absolute, bound_vsgl_diffuse_accurate)],
        });
        f.push(Family {
            function: F::VsglDiffuseSgProduct,
            name,
            inputs: ins,
            checks: vec![check("value", 0..1, scale, bound_vsgl_diffuse_sg_product)],
        });
    }
    // vsgl_specular: views normal…grazing × light lobes at the mirror direction and off it.
    let (mut normal_view, mut oblique, mut grazing) = (Vec::new(), Vec::new(), Vec::new());
    for n in axes() {
        for (j, &t) in NEAR_ANGLES.iter().chain(&[0.3, 1.0, 1.4]).chain(&GRAZING_COSINES.map(f64::acos)).enumerate() {
            let w_o = tilt(n, t, 0.6 * j as f64 + 0.2);
            let mirror = 2.0 * w_o.dot(n) * n - w_o;
            for al in alphas().into_iter().step_by(2) {
                for &l in &[1e-6, 1.0, 1e2, 1e4, 1e6, 1e9] {
                    for off in [0.0, 1e-7, 0.5 * al, 2.0 * al] {
                        let xi = tilt(mirror, off, 1.0 + j as f64);
                        let r = rec(&[xi.x, xi.y, xi.z, l, 1.0, n.x, n.y, n.z, w_o.x, w_o.y, w_o.z, al]);
                        if t <= 1e-3 {
                            normal_view.push(r);
                        } else if t < 1.5 {
                            oblique.push(r);
                        } else {
                            grazing.push(r);
                        }
                    }
                }
            }
        }
    }
    for (name, ins) in [
        ("normal view (θo 0…1e-3 rad)", normal_view),
        ("oblique view, light at and off the mirror direction", oblique),
        ("grazing view n·ω_o <= 3e-3 (incl. 0)", grazing),
    ] {
        f.push(Family {
            function: F::VsglSpecular,
            name,
            inputs: ins.clone(),
            checks: vec![check("value", 0..1, |i, _| fl(1e-30 * a(i, 4)), bound_vsgl_specular)],
        });
        f.push(Family {
            function: F::VsglSpecularWithReceiver,
            name,
            inputs: ins.clone(),
            checks: vec![check("value", 0..1, |i, _| fl(1e-30 * a(i, 4)), bound_vsgl_specular_with_receiver)],
        });
        // The receiver alone, on the (n, ω_o, α) of the same records (slots 5-11 → 0-6).
        let mut receivers: Vec<Input> = Vec::new();
        for i in &ins {
            let r = rec(&[a(i, 5), a(i, 6), a(i, 7), a(i, 8), a(i, 9), a(i, 10), a(i, 11)]);
            if !receivers.contains(&r) {
                receivers.push(r);
            }
        }
        f.push(Family {
            function: F::VsglSpecularReceiverFrom,
            name,
            inputs: receivers,
            checks: vec![
                check("n_dot_v", 0..1, floor_unit, |i, _| 1.5 * ULP * dot_scale(v3(i, 0), v3(i, 3))),
                check("lambda_v", 1..2, floor_tiny, bound_receiver_lambda),
                check("x_axis", 2..5, floor_unit, |i, _| bound_receiver_asg(i, 2..5, 8.0, 0.0)),
                check("x_bandwidth", 5..6, floor_tiny, |i, _| bound_receiver_asg(i, 5..6, 0.0, 4.5)),
                check("y_axis", 6..9, floor_unit, |i, _| bound_receiver_asg(i, 6..9, 8.0, 0.0)),
                check("y_bandwidth", 9..10, floor_tiny, |i, _| bound_receiver_asg(i, 9..10, 0.0, 4.5)),
                check("z_axis", 10..13, floor_unit, |i, _| bound_receiver_asg(i, 10..13, 8.0, 0.0)),
                Check { output: "frame orthonormality", slots: 2..13, derive: Some(receiver_frame_residuals), floor: floor_unit, bound: |_, _| 16.0 * ULP },
            ],
        });
        f.push(Family {
            function: F::VsglSpecularAccurate,
            name,
            inputs: ins.clone(),
            checks: vec![check("value", 0..1, |i, _| fl(1e-30 * a(i, 4)), bound_vsgl_specular_accurate)],
        });
        f.push(Family {
            function: F::VsglSpecularFiltered,
            name,
            inputs: ins.clone(),
            checks: vec![
                check("value", 0..1, |i, _| fl(1e-30 * a(i, 4)), bound_vsgl_specular_accurate),
                check("receiver share", 1..2, floor_unit, |i, r| perturbation(F::VsglSpecularFiltered, i, 1..2, 12.0, &[0, 5, 8]) + 8.0 * ULP * r[1]),
            ],
        });
        f.push(Family {
            function: F::VsglSpecularBlend,
            name,
            inputs: ins.clone(),
            checks: vec![check("value", 0..1, |i, _| fl(1e-30 * a(i, 4)), bound_vsgl_specular_blend)],
        });
        f.push(Family {
            function: F::VsglSpecularBlendWithReceiver,
            name,
            inputs: ins,
            checks: vec![check("value", 0..1, |i, _| fl(1e-30 * a(i, 4)), bound_vsgl_specular_blend)],
        });
    }
}

/// vsgl_tangent_plane_from_moments: N̄ = Σw n/Σw (one division per component) and the offset
/// μ·N̄ − Σw(y·n)/Σw (a dot, a division, a subtraction of terms of size ‖μ‖·|N̄| and |Σw(y·n)/Σw|,
/// which cancel for a plane through the local origin's neighbourhood): the perturbation of the
/// sums and of μ (c = 2; vectors by their length), and 2 ULP of the terms' sizes.
fn bound_plane_normal(i: &Input, r: &Output64) -> f64 {
    perturbation(F::VsglTangentPlaneFromMoments, i, 0..3, 2.0, &[1, 5]) + ULP * out3(r, 0).length() + FLT_MIN
}
fn bound_plane_offset(i: &Input, r: &Output64) -> f64 {
    let w = a(i, 0);
    let terms = if w > 0.0 { dot_scale(v3(i, 5), out3(r, 0)) + (a(i, 4) / w).abs() } else { 0.0 };
    perturbation(F::VsglTangentPlaneFromMoments, i, 3..4, 2.0, &[1, 5]) + 2.0 * ULP * (terms + r[3].abs()) + FLT_MIN
}
fn floor_plane_offset(i: &Input, _: &Output64) -> f64 {
    fl(v3(i, 5).length())
}

/// vsgl_tangent_plane_fade: a ramp of slope 1/τ in the height H = (p − μ)·N̄ + offset, so the
/// error is H's rounding over τ: p − μ, the dot and the sum (c = 3 per input, positions and the
/// normal moved by their length), and τ's own (length, sqrt, products: relative, inside c); the
/// perturbation is taken on the f64 twin at finite size, so the clamp's corners count. A receiver
/// whose H is not known in f32 to within τ (1 mm from a cluster 1 km from the local origin) gets
/// a bound ≥ 1: the fade is then honestly either. 4 ULP for the ramp's own division.
fn bound_plane_fade(i: &Input, _: &Output64) -> f64 {
    perturbation(F::VsglTangentPlaneFade, i, 0..1, 3.0, &[0, 4, 8]) + 4.0 * ULP + FLT_MIN
}

/// The cluster's mean tangent plane (vsgl_tangent_plane.wgsl): from the cluster sums,
/// and the fade it gives a receiver.
pub(super) fn tangent_plane_families(f: &mut Vec<Family>) {
    // From the moments: planar clusters and corners (half the weight on a second plane at 90°),
    // summed in f32 relative to a local origin, as vsgl_moments.wgsl does; no weight.
    let mut rng = SplitMix64(0x9a1e);
    let (mut planar, mut corner, mut empty) = (Vec::new(), Vec::new(), Vec::new());
    for n in axes() {
        for &dist in &[0.0, 0.1, 1.0, 100.0, 1e4] {
            for &radius in &[1e-4, 1e-2, 1.0] {
                for two_planes in [false, true] {
                    let centre = dist * rng.unit_vector();
                    let m = oracle::orthonormal_basis(n);
                    let second = tilt(n, std::f64::consts::FRAC_PI_2, 1.0 + rng.next_f64());
                    let (mut w, mut sn, mut sh, mut sy) = (0f32, glam::Vec3::ZERO, 0f32, glam::Vec3::ZERO);
                    for k in 0..64 {
                        let texel_normal = if two_planes && k % 2 == 1 { second } else { n };
                        let along = m.x_axis * (rng.next_f64() - 0.5) + m.y_axis * (rng.next_f64() - 0.5);
                        let y = (centre + radius * along).as_vec3();
                        let nn = texel_normal.as_vec3();
                        let pw = (0.5 + rng.next_f64()) as f32;
                        w += pw;
                        sn += pw * nn;
                        sh += pw * y.dot(nn);
                        sy += pw * y;
                    }
                    let mean = sy / w;
                    let r = rec(&[w as f64, sn.x as f64, sn.y as f64, sn.z as f64, sh as f64, mean.x as f64, mean.y as f64, mean.z as f64]);
                    (if two_planes { &mut corner } else { &mut planar }).push(r);
                }
            }
        }
        empty.push(rec(&[0.0, n.x, n.y, n.z, 1.0, 1.0, 2.0, 3.0]));
        empty.push(rec(&[-1.0, n.x, n.y, n.z, 1.0, 1.0, 2.0, 3.0]));
    }
    let plane_checks = || vec![check("normal", 0..3, floor_unit, bound_plane_normal), check("offset", 3..4, floor_plane_offset, bound_plane_offset)];
    for (name, ins) in [
        ("planar clusters 0…1e4 m from the local origin, radius 1e-4…1 m, f32 sums", planar),
        ("corners (two planes at 90°), same grids", corner),
        ("no weight", empty),
    ] {
        f.push(Family { function: F::VsglTangentPlaneFromMoments, name, inputs: ins, checks: plane_checks() });
    }
    // The fade: receivers at heights H = (−1e3 … 1e3)·τ, at distances 1e-3…1e4 m from μ, σ²/d²
    // 0, 1e-6, 1, |N̄| 1 (a plane), 0.6 and 0.2 (corners, curved patches); μ near the local
    // origin and 1e3 m from it; no plane (N̄ = 0: 1 exactly); d = σ = 0 (τ = 0: the step).
    let (mut near, mut far, mut degenerate) = (Vec::new(), Vec::new(), Vec::new());
    for n in axes() {
        let m = oracle::orthonormal_basis(n);
        for &shrink in &[1.0, 0.6, 0.2] {
            let normal = shrink * n;
            for &d in &[1e-3, 1.0, 1e2, 1e4] {
                for &var_frac in &[0.0, 1e-6, 1.0] {
                    for &h_over_tau in &[-1e3, -1.0, 0.0, 0.5, 1.0, 1.25, 1.5, 2.0, 3.0, 1e3] {
                        for (mean_dist, list) in [(1.0, &mut near), (1e3, &mut far)] {
                            let mean = mean_dist * rng.unit_vector();
                            let variance: f64 = var_frac * d * d;
                            let tau = oracle::VSGL_PLANE_TOLERANCE * (d + variance.sqrt());
                            let offset = 0.3 * d * shrink * (rng.next_f64() - 0.5);
                            let cos_phi = (h_over_tau * tau - offset) / (d * shrink);
                            if cos_phi.abs() > 1.0 {
                                continue;
                            }
                            let sin_phi = (1.0 - cos_phi * cos_phi).sqrt();
                            let p = mean + d * (n * cos_phi + m.x_axis * sin_phi);
                            list.push(rec(&[normal.x, normal.y, normal.z, offset, mean.x, mean.y, mean.z, variance, p.x, p.y, p.z]));
                        }
                    }
                }
            }
        }
        degenerate.push(rec(&[0.0, 0.0, 0.0, 0.5, 1.0, 2.0, 3.0, 0.1, 1.5, 2.0, 3.0]));
        degenerate.push(rec(&[n.x, n.y, n.z, 0.0, 1.0, 2.0, 3.0, 0.0, 1.0, 2.0, 3.0]));
        degenerate.push(rec(&[n.x, n.y, n.z, 1e-3, 1.0, 2.0, 3.0, 0.0, 1.0, 2.0, 3.0]));
    }
    for (name, ins) in [
        ("H/τ −1e3…1e3, d 1e-3…1e4 m, σ²/d² 0…1, |N̄| 1, 0.6, 0.2; μ near the local origin", near),
        ("same, μ 1e3 m from the local origin", far),
        ("no plane (N̄ = 0); receiver at μ with σ = 0 (τ = 0)", degenerate),
    ] {
        f.push(Family { function: F::VsglTangentPlaneFade, name, inputs: ins, checks: vec![check("value", 0..1, floor_unit, bound_plane_fade)] });
    }
}
