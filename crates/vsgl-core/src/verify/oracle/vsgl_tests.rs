//! Tests of the VSGL oracle against quadrature and closed forms (`vsgl.rs`).

use super::*;
use crate::verify::oracle::ggx::ggx_brdf_over_rs;
use crate::verify::oracle::quadrature::{clamped_cosine_reference, integrate_sphere};
use crate::rng::SplitMix64;
use crate::verify::oracle::sg::{ggx_lobe_sg, sg_evaluate, sg_toksvig_mean_direction, TOKSVIG_SHARPNESS_MAX};

fn dir(theta: f64, phi: f64) -> DVec3 {
    DVec3::new(theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos())
}

#[test]
fn vsgl_lobe_from_moments_conserves_power() {
    // ∫ I_v dω = c_v A(λ_v) = Σ Φ R exactly (the definition of c_v); a single lobe comes back
    // unchanged (Toksvig round trip); no power gives amplitude 0. Tolerance 1e-12 relative.
    let mut rng = SplitMix64(7);
    let n0 = dir(0.3, 0.2);
    let (mut w, mut wd) = (0.0, DVec3::ZERO);
    for _ in 0..64 {
        let n = (n0 + 0.3 * rng.unit_vector()).normalize();
        let lobe = if rng.next_f64() < 0.5 {
            lambert_lobe_sg(n)
        } else {
            ggx_lobe_sg(n, (n + rng.unit_vector()).normalize(), 0.2)
        };
        let power = 1e-8 + 1e8 * rng.next_f64().powi(8);
        w += power;
        wd += power * sg_toksvig_mean_direction(lobe.axis, lobe.sharpness);
    }
    let v = vsgl_lobe_from_moments(w, wd);
    assert!((v.amplitude * sg_integral(v.sharpness) - w).abs() <= 1e-12 * w);
    let single = ggx_lobe_sg(DVec3::Z, dir(0.4, 1.0), 0.05);
    let v = vsgl_lobe_from_moments(3.0, 3.0 * sg_toksvig_mean_direction(single.axis, single.sharpness));
    assert!((v.sharpness - single.sharpness.min(TOKSVIG_SHARPNESS_MAX)).abs() <= 1e-9 * single.sharpness);
    assert!((v.axis - single.axis).length() < 1e-12);
    assert_eq!(vsgl_lobe_from_moments(0.0, DVec3::ZERO).amplitude, 0.0);
}

#[test]
fn vsgl_position_needs_a_local_origin_in_f32() {
    // VPLs spread by σ = 1 cm around a point 1e5 m from the world origin (the oracle's grid, docs/numerics.md).
    // Summed in f32 as a GPU would, the raw moments give a variance that is pure rounding noise
    // (here: ≥ 100% wrong); relative to a local origin (the first VPL, standing in for the
    // light position) the same f32 sums give σ² to 1e-3. The oracle then agrees with the
    // exact value to 1e-9 (f64 on relative positions).
    let mut rng = SplitMix64(11);
    let centre = DVec3::splat(1e5);
    let origin = centre + DVec3::new(0.3, -0.2, 0.1);
    let points: Vec<DVec3> = (0..256).map(|_| centre + 0.01 * (rng.unit_vector() * rng.next_f64().sqrt())).collect();
    let exact = {
        let mean = points.iter().sum::<DVec3>() / points.len() as f64;
        points.iter().map(|p| (*p - mean).length_squared()).sum::<f64>() / points.len() as f64
    };
    let f32_variance = |o: DVec3| {
        let (mut w, mut sy, mut sy2) = (0f32, [0f32; 3], 0f32);
        for p in &points {
            let y = (*p - o).as_vec3();
            w += 1.0;
            sy[0] += y.x;
            sy[1] += y.y;
            sy[2] += y.z;
            sy2 += y.length_squared();
        }
        let m = glam::Vec3::from(sy) / w;
        (sy2 / w - m.length_squared()) as f64
    };
    let raw_err = (f32_variance(DVec3::ZERO) - exact).abs() / exact;
    let local_err = (f32_variance(origin) - exact).abs() / exact;
    println!("σ² at 1e5 m in f32: world-origin moments relative error {raw_err:.2e}, local-origin {local_err:.2e}");
    assert!(raw_err > 1.0 && local_err < 1e-3);
    let (mut w, mut sy, mut sy2) = (0.0, DVec3::ZERO, 0.0);
    for p in &points {
        let y = *p - origin;
        w += 1.0;
        sy += y;
        sy2 += y.length_squared();
    }
    let pos = vsgl_position_from_moments(w, sy, sy2);
    assert!((pos.variance - exact).abs() <= 1e-9 * exact);
    // All VPLs at one point: σ² = 0 exactly is floored relative to the local scale.
    let y = DVec3::new(2.0, 0.0, 0.0);
    let pos = vsgl_position_from_moments(5.0, 5.0 * y, 5.0 * y.length_squared());
    assert_eq!(pos.variance, VSGL_VARIANCE_MIN_FRACTION * 4.0);
}

fn test_vsgl(sharpness: f64, intensity: f64, variance: f64) -> (Sg, VsglPosition) {
    (
        Sg {
            axis: dir(2.2, 0.4),
            sharpness,
            amplitude: intensity,
        },
        VsglPosition {
            mean: DVec3::new(0.5, -0.3, 2.0),
            variance,
        },
    )
}

#[test]
fn split_forms_equal_the_one_call_forms() {
    // The shading loop's split forms (the seen Gaussian shared by both lobes, the receiver
    // formed once per pixel) compose to vsgl_incoming_radiance and vsgl_specular, which are
    // written as one call each from the same equations (tolerance: f64 rounding).
    for (k, y_p) in [DVec3::new(0.1, 0.2, 0.0), DVec3::new(0.5, -0.3, 2.0), DVec3::new(-4.0, 1.0, 9.0)].into_iter().enumerate() {
        for sharpness in [0.0, 1e-6, 0.3, 10.0, 1e4, 1e9] {
            for variance in [0.0, 1e-8, 1e-3, 0.5, 30.0] {
                let (lobe, pos) = test_vsgl(sharpness, 7.0, variance);
                let one = vsgl_incoming_radiance(lobe, pos, y_p);
                let seen = vsgl_position_seen_from(pos, y_p);
                let split = vsgl_incoming_radiance_seen(lobe.axis, lobe.sharpness, lobe.amplitude / (2.0 * PI), seen);
                assert!((split.axis - one.axis).length() <= 1e-12, "{k} {sharpness} {variance}: {split:?} {one:?}");
                assert!((split.sharpness - one.sharpness).abs() <= 1e-12 * one.sharpness.max(1.0), "{split:?} {one:?}");
                assert!((split.amplitude - one.amplitude).abs() <= 1e-12 * one.amplitude, "{split:?} {one:?}");
                for alpha in [1e-4, 0.1, 0.7] {
                    for (j, w_o) in [DVec3::Z, dir(0.3, 1.0), dir(1.5, -2.0), dir(1.8, 0.5)].into_iter().enumerate() {
                        let n = DVec3::Z;
                        let a = vsgl_specular(one, n, w_o, alpha);
                        let b = vsgl_specular_with_receiver(one, &vsgl_specular_receiver_from(n, w_o, alpha));
                        assert!((a - b).abs() <= 1e-12 * a, "{j} {alpha}: {a} {b}");
                    }
                }
            }
        }
    }
}

#[test]
fn vsgl_incoming_radiance_is_eq5() {
    // c_in G(ω; ξ_in, λ_in) equals the defining product c_v/(2πσ²)·G(ω; −ξ_v, λ_v)·G(ω; ξ_μ, λσ)
    // of [Tok15 Eq. 5] pointwise (an identity; tolerance 1e-9 relative on values ≥ 1e-300).
    let y_p = DVec3::new(0.1, 0.2, 0.0);
    for sharpness in [1e-6, 0.3, 10.0, 1e4] {
        for variance in [1e-8, 1e-3, 0.5, 30.0] {
            let (lobe, pos) = test_vsgl(sharpness, 7.0, variance);
            let l_in = vsgl_incoming_radiance(lobe, pos, y_p);
            let d = pos.mean - y_p;
            let (xi_mu, lambda_sigma) = (d.normalize(), d.length_squared() / variance);
            for w in [xi_mu, -lobe.axis, l_in.axis, dir(1.0, 1.0), dir(0.5, 3.0)] {
                let defining = lobe.amplitude / (2.0 * PI * variance)
                    * sg_evaluate(w, -lobe.axis, lobe.sharpness)
                    * sg_evaluate(w, xi_mu, lambda_sigma);
                let got = l_in.amplitude * sg_evaluate(w, l_in.axis, l_in.sharpness);
                if defining > 1e-300 {
                    assert!(
                        (got - defining).abs() <= 1e-9 * defining,
                        "λv {sharpness} σ² {variance}: {got} vs {defining}"
                    );
                }
            }
        }
    }
}

#[test]
fn vsgl_incoming_radiance_point_light_limit_and_clamp() {
    // As σ → 0 the VSGL becomes a point source of intensity I_v: ∫ L_in dω = c_in A(λ_in) →
    // I_v(−ξ_μ)/d² = c_v G(−ξ_μ; ξ_v, λ_v)/d². The relative deviation is O(λ_v σ²/d²); below
    // σ²/d² = 1e-9 the clamp λσ ≤ SG_SHARPNESS_MAX is active and must keep the limit exactly.
    // Positions are relative to a local origin (a VSGL 1e5 m away is the same numbers).
    let y_p = DVec3::new(0.1, 0.2, 0.0);
    for lambda_v in [0.5, 10.0] {
        for ratio in [1e-4, 1e-8, 1e-12, 1e-30] {
            for intensity in [1e-8, 1.0, 1e8] {
                let (lobe, mut pos) = test_vsgl(lambda_v, intensity, 0.0);
                let d2 = (pos.mean - y_p).length_squared();
                pos.variance = ratio * d2;
                let l_in = vsgl_incoming_radiance(lobe, pos, y_p);
                let total = l_in.amplitude * sg_integral(l_in.sharpness);
                let xi_mu = (pos.mean - y_p).normalize();
                let point = lobe.amplitude * sg_evaluate(-xi_mu, lobe.axis, lobe.sharpness) / d2;
                let rel = (total - point).abs() / point;
                assert!(
                    rel <= 4.0 * lambda_v * ratio.max(1.0 / SG_SHARPNESS_MAX) + 1e-12,
                    "λv {lambda_v} σ²/d² {ratio}: {rel}"
                );
                assert!(l_in.sharpness <= SG_SHARPNESS_MAX * 1.000001 + lambda_v && l_in.amplitude.is_finite());
            }
        }
    }
    // Shading point at the VSGL mean with zero variance: finite (σ² floored at FLT_MIN).
    let (lobe, pos) = test_vsgl(3.0, 1.0, 0.0);
    let l_in = vsgl_incoming_radiance(lobe, pos, pos.mean);
    assert!(l_in.amplitude.is_finite() && l_in.sharpness.is_finite());
}

#[test]
fn vsgl_diffuse_forms_vs_quadrature() {
    // Reference: c_in/π ∫ G_in max(ω·n, 0) dω (analytic φ + Gauss–Legendre θ). The accurate
    // form is bounded like sg_clamped_cosine_integral (0.9% of c_in A(λ_in)/π); the papers'
    // pulled-out forms are printed (they ignore the horizon and, for 2π/λ, the small-λ limit).
    let n = DVec3::Z;
    let y_p = DVec3::ZERO;
    for (sharpness, variance) in [(1.0, 0.5), (10.0, 1e-2), (100.0, 1e-4), (3.0, 30.0)] {
        let (mut lobe, pos) = test_vsgl(sharpness, 1.0, variance);
        for theta in [0.2, 1.2, 1.5, 1.7] {
            lobe.axis = -dir(theta, 0.0); // incoming radiance points along −ξ_v, so ξ_in ~ dir(θ)
            let pos = VsglPosition {
                mean: 2.0 * dir(theta, 0.0),
                ..pos
            };
            let l_in = vsgl_incoming_radiance(lobe, pos, y_p);
            let scale = l_in.amplitude * sg_integral(l_in.sharpness) / PI;
            let reference = l_in.amplitude / PI * clamped_cosine_reference(l_in.sharpness, l_in.axis.dot(n));
            let errs = [
                vsgl_diffuse_accurate(l_in, n),
                vsgl_diffuse(l_in, n),
                vsgl_diffuse_approx(l_in, n),
                vsgl_diffuse_sg_product(l_in, n),
            ]
            .map(|v| (v - reference) / scale);
            println!(
                "diffuse λ_in = {:8.3} θ = {theta}: (value − reference)/(c_in A/π): accurate {:+.2e}, pulled out {:+.2e}, 2π/λ {:+.2e}, SG product {:+.2e}",
                l_in.sharpness, errs[0], errs[1], errs[2], errs[3]
            );
            assert!(errs[0].abs() <= 0.009, "{errs:?}");
        }
    }
}

#[test]
fn vsgl_specular_vs_quadrature() {
    // Reference: ∫ c_in G(ω; ξ_in, λ_in) f_GGX(ω, ω_o) max(ω·n, 0) dω with the exact GGX BRDF
    // (ggx.wgsl), by quadrature centred between the light lobe and the mirror direction.
    // (1) Point-light limit (λ_in = 1e8 at the mirror direction): the form must reproduce the
    //     exact BRDF value c_in A(λ_in) f(ξ_in) (n·ξ_in), i.e. the normalisation C(ω) of [Tok16s
    //     §4.2]; tolerance 1e-3 (O(ηmax/ν) of the convolution).
    // (2) Extended lights: the SG NDF G(h; n, 2/α²) has GGX's peak and projected area but not its
    //     shape (GGX has a core twice as curved and long tails), so for lights narrower than the
    //     whole lobe the form overestimates: measured +0…+21% here (printed); bound 25%.
    let n = DVec3::Z;
    for alpha in [0.05, 0.2] {
        for theta_o in [0.3, 1.0] {
            let w_o = dir(theta_o, PI);
            let mirror = dir(theta_o, 0.0);
            let c_in = 2.5;
            let point = Sg {
                axis: mirror,
                sharpness: 1e8,
                amplitude: c_in,
            };
            let exact = c_in * sg_integral(1e8) * ggx_brdf_over_rs(n, mirror, w_o, alpha) * mirror.dot(n);
            let got = vsgl_specular(point, n, w_o, alpha);
            assert!((got / exact - 1.0).abs() < 1e-3, "α {alpha} θo {theta_o}: {got} vs {exact}");
            for sharpness in [30.0, 1e3, 1e5] {
                for offset in [0.0, 0.5 * alpha] {
                    let axis = dir(theta_o - offset, 0.2 * offset);
                    let l_in = Sg {
                        axis,
                        sharpness,
                        amplitude: c_in,
                    };
                    let scale = (alpha * alpha).min(1.0 / sharpness).sqrt();
                    let centre = (axis * sharpness.sqrt() + mirror / alpha).normalize();
                    let q = integrate_sphere(centre, scale, 2048, &[], |w| {
                        l_in.amplitude * sg_evaluate(w, axis, sharpness) * ggx_brdf_over_rs(n, w, w_o, alpha) * w.dot(n).max(0.0)
                    });
                    let v = vsgl_specular(l_in, n, w_o, alpha);
                    let rel = v / q - 1.0;
                    println!("specular α {alpha} θo {theta_o} λ_in {sharpness:e} offset {offset}: relative error {rel:+.3}");
                    assert!(rel.abs() < 0.25, "α {alpha} θo {theta_o} λ {sharpness} offset {offset}: {v} vs {q}");
                }
            }
        }
    }
}

/// The exact GGX reflected radiance ∫ c G(ω; ξ, λ) f_GGX(ω, ω_o) max(ω·n, 0) dω by quadrature
/// (lobe-centred sphere rule, `n_phi` φ nodes).
fn specular_reference(l_in: Sg, n: DVec3, w_o: DVec3, alpha: f64, n_phi: usize, centre_weight: f64) -> f64 {
    let mirror = 2.0 * w_o.dot(n) * n - w_o;
    let scale = (alpha * alpha).min(1.0 / l_in.sharpness).sqrt();
    let centre = (l_in.axis * l_in.sharpness.sqrt() + centre_weight * mirror / alpha).normalize();
    integrate_sphere(centre, scale, n_phi, &[], |w| {
        l_in.amplitude * sg_evaluate(w, l_in.axis, l_in.sharpness) * ggx_brdf_over_rs(n, w, w_o, alpha) * w.dot(n).max(0.0)
    })
}

#[test]
fn filtered_slope_covariance_is_the_reflection_jacobian() {
    // Σ' − α²I = (2/λ)JJᵀ with J = ∂s/∂ω_i, s = h_t/h_n the slope of h = (ω_i + ω_o)/‖ω_i + ω_o‖:
    // checked against J by central differences of the slope map (two tangent directions at
    // ω_i), in the tangent frame of orthonormal_basis(n). λ is large enough that no cap bites.
    let n = dir(0.3, 0.7);
    let frame = crate::verify::oracle::math::orthonormal_basis(n);
    let (t, b) = (frame.x_axis, frame.y_axis);
    let slope = |w_i: DVec3, w_o: DVec3| {
        let h = (w_i + w_o).normalize();
        [h.dot(t) / h.dot(n), h.dot(b) / h.dot(n)]
    };
    let local = |theta: f64, phi: f64| frame * dir(theta, phi);
    for (tl, pl, to, po) in [(0.2, 0.0, 0.2, PI), (0.5, 0.3, 1.0, 2.5), (1.4, 1.0, 1.45, 4.0), (0.0, 0.0, 0.0, 0.0), (1.5, 0.2, 0.3, 0.1)] {
        let (w_i, w_o) = (local(tl, pl), local(to, po));
        let (lambda, alpha) = (1e7, 0.1);
        let (sp, sm, e, _) = vsgl_filtered_slope_covariance(lambda, n, w_i, w_o, alpha);
        let em = [-e[1], e[0]];
        let sigma = |i: usize, j: usize| sp * e[i] * e[j] + sm * em[i] * em[j];
        let tb = crate::verify::oracle::math::orthonormal_basis(w_i);
        let step = 1e-6;
        let cols: Vec<[f64; 2]> = [tb.x_axis, tb.y_axis]
            .iter()
            .map(|&g| {
                let (p, q) = (slope((w_i + step * g).normalize(), w_o), slope((w_i - step * g).normalize(), w_o));
                [(p[0] - q[0]) / (2.0 * step), (p[1] - q[1]) / (2.0 * step)]
            })
            .collect();
        for i in 0..2 {
            for j in 0..2 {
                let jj = cols[0][i] * cols[0][j] + cols[1][i] * cols[1][j];
                let want = if i == j { alpha * alpha } else { 0.0 } + 2.0 / lambda * jj;
                let got = sigma(i, j);
                assert!((got - want).abs() <= 1e-6 * (alpha * alpha), "θl {tl} θo {to} Σ[{i}{j}]: {got} vs {want}");
            }
        }
    }
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(|a, b| a.partial_cmp(b).unwrap());
    v[v.len() / 2]
}

#[test]
fn lighting_diffuse_forms_vs_quadrature_grid() {
    // lighting="accurate" shades diffuse by the clamped-cosine integral (vsgl_diffuse_accurate);
    // lighting="asg" with the default diffuse="papers" by the cosine pulled out with
    // A ≈ 2π/λ (vsgl_diffuse_approx). Reference: clamped_cosine_reference (analytic in φ,
    // Gauss–Legendre in θ; independent of both). Grid: λ_in 1e5 (point-like) … 0.3 (broad) ×
    // ξ·n 1 … 0.05 (relative error) and 0 … −0.3 (light below the horizon; error over the
    // scale c A(λ)/π, the relative error being undefined where the exact value is ~0).
    // Asserted: the point-light limit (λ_in = 1e5, ξ·n ≥ 0.05) within 1e-3 relative, and the
    // clamped cosine's stated bound (0.9% of the scale) everywhere; the table is printed.
    let n = DVec3::Z;
    let above: [f64; 6] = [1.0, 0.7, 0.4, 0.2, 0.1, 0.05];
    let at_or_below: [f64; 3] = [0.0, -0.1, -0.3];
    for lambda in [1e5, 1e3, 100.0, 30.0, 10.0, 3.0, 1.0, 0.3] {
        let (mut acc, mut papers, mut acc_below, mut papers_below) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        for &c in above.iter().chain(&at_or_below) {
            let l_in = Sg { axis: dir(c.acos(), 0.3), sharpness: lambda, amplitude: 0.8 };
            let reference = l_in.amplitude / PI * clamped_cosine_reference(lambda, c);
            let scale = l_in.amplitude * sg_integral(lambda) / PI;
            let (a, p) = (vsgl_diffuse_accurate(l_in, n), vsgl_diffuse_approx(l_in, n));
            assert!((a - reference).abs() <= 0.009 * scale, "λ {lambda} ξ·n {c}: {a} vs {reference}");
            if c > 0.0 {
                acc.push((a / reference - 1.0).abs());
                papers.push((p / reference - 1.0).abs());
                if lambda >= 1e5 {
                    assert!((a / reference - 1.0).abs() < 1e-3, "point limit ξ·n {c}: {a} vs {reference}");
                }
            } else {
                acc_below.push((a - reference).abs() / scale);
                papers_below.push((p - reference).abs() / scale);
            }
        }
        let mx = |v: &Vec<f64>| v.iter().cloned().fold(0.0, f64::max);
        println!(
            "diffuse λ_in {lambda:>7.0e}: ξ·n > 0 relative error: clamped cosine max {:.4} median {:.4} | papers (2π/λ) max {:.4} median {:.4}; ξ·n <= 0, error/scale: clamped cosine max {:.4} | papers {:.4}",
            mx(&acc), median(acc.clone()), mx(&papers), median(papers.clone()), mx(&acc_below), mx(&papers_below)
        );
    }
}

#[test]
fn vsgl_specular_accurate_vs_quadrature() {
    // Reference: the exact GGX integral by quadrature (specular_reference); its own error is
    // estimated by a second rule (half the φ nodes, centred on the light) and printed.
    // Grid: α 0.05…0.5 × light sharpness λ_in 1e6 (point-like) … 1 (broad) × view angle
    // θo 0 … 1.52 rad (n·ω_o = 0.05, grazing) × light axis at the mirror direction and
    // tilted off it (in and out of the plane of incidence), above the horizon.
    // (1) point-light limit: |value/exact − 1| < 1e-3 at λ_in = 1e8 with the light on the
    //     mirror direction (the exact value is c A(λ) f(ξ)(n·ξ), no quadrature needed).
    // (2) printed: max / median |relative error| of the filtered-NDF form and of the ASG form
    //     per λ_in over the grid; the filtered form's bound per λ (asserted) is stated below.
    let n = DVec3::Z;
    let c_in = 1.7;
    // VSGL_ALPHAS=0.7,1.0 prints the same grid at other roughnesses (docs/methods/vsgl.md, "SG
    // lighting": rough receivers); the assertions below hold for the default grid only and
    // are skipped then.
    let custom_alphas: Option<Vec<f64>> = std::env::var("VSGL_ALPHAS").ok().map(|s| s.split(',').map(|x| x.trim().parse().expect("VSGL_ALPHAS: comma-separated numbers")).collect());
    let alphas = custom_alphas.clone().unwrap_or_else(|| vec![0.05, 0.1, 0.2, 0.35, 0.5]);
    let lambdas = [1e6, 1e4, 1e3, 100.0, 30.0, 10.0, 3.0, 1.0];
    let views = [0.0, 0.5, 1.0, 1.3, 1.52];
    let mut rows = Vec::new();
    let mut ref_err: f64 = 0.0;
    for &lambda in &lambdas {
        let (mut acc, mut asg) = (Vec::new(), Vec::new());
        for &alpha in &alphas {
            for &theta_o in &views {
                let w_o = dir(theta_o, PI);
                let mirror = dir(theta_o, 0.0);
                if lambda >= 1e6 {
                    // The widening is b/(2λh_n⁴) against α²: O(1/(λα²(n·ω_o)²)) relative, so
                    // the limit is checked at λ = 1e8 (as vsgl_specular_vs_quadrature does).
                    let point = Sg { axis: mirror, sharpness: 1e8, amplitude: c_in };
                    let exact = c_in * sg_integral(1e8) * ggx_brdf_over_rs(n, mirror, w_o, alpha) * mirror.dot(n);
                    let got = vsgl_specular_accurate(point, n, w_o, alpha);
                    assert!((got / exact - 1.0).abs() < 1e-3, "point limit α {alpha} θo {theta_o}: {got} vs {exact}");
                }
                let width = (alpha * alpha + 1.0 / lambda).sqrt().min(0.6);
                for (dt, dp) in [(0.0, 0.0), (0.5 * width, 0.0), (-0.5 * width, 0.0), (0.0, 0.7 * width)] {
                    let theta_l = theta_o + dt;
                    if !(0.0..1.52).contains(&theta_l.abs()) {
                        continue;
                    }
                    let phi = if theta_l.abs() > 1e-9 { dp / theta_l.abs().sin() } else { 0.0 };
                    let axis = if dp == 0.0 { dir(theta_l, 0.0) } else { dir(theta_l.max(0.05), phi) };
                    let l_in = Sg { axis, sharpness: lambda, amplitude: c_in };
                    let q = specular_reference(l_in, n, w_o, alpha, 1024, 1.0);
                    if lambda <= 1e4 && theta_o == 1.0 {
                        let q2 = specular_reference(l_in, n, w_o, alpha, 512, 0.0);
                        ref_err = ref_err.max((q2 / q - 1.0).abs());
                    }
                    let e_acc = vsgl_specular_accurate(l_in, n, w_o, alpha) / q - 1.0;
                    // VSGL_DEBUG_GRID=1 prints every case (signed errors of both forms).
                    if std::env::var("VSGL_DEBUG_GRID").is_ok() {
                        println!("  λ {lambda:e} α {alpha} θo {theta_o} θl {theta_l:.3} φ {phi:.3}: filtered {e_acc:+.3} asg {:+.3}", vsgl_specular(l_in, n, w_o, alpha) / q - 1.0);
                    }
                    acc.push(e_acc.abs());
                    asg.push((vsgl_specular(l_in, n, w_o, alpha) / q - 1.0).abs());
                }
            }
        }
        let row = (lambda, acc.iter().cloned().fold(0.0, f64::max), median(acc.clone()), asg.iter().cloned().fold(0.0, f64::max), median(asg.clone()), acc.len());
        println!(
            "specular λ_in {:>8.0e}: filtered NDF max {:.3} median {:.3} | ASG max {:.3} median {:.3} ({} cases)",
            row.0, row.1, row.2, row.3, row.4, row.5
        );
        rows.push(row);
    }
    println!("quadrature reference: largest disagreement of two rules {ref_err:.1e}");
    assert!(ref_err < 1e-3);
    if custom_alphas.is_some() {
        return;
    }
    // What the option claims (docs/methods/vsgl.md, "SG lighting"): for lights from point-like to
    // λ_in = 30 the filtered form's median error is below the ASG form's, and no case of the
    // grid is off by more than 80% (the ASG form's worst is 78%).
    for &(lambda, max_acc, median_acc, _, median_asg, _) in &rows {
        if lambda >= 30.0 {
            assert!(median_acc < median_asg, "λ {lambda}: median {median_acc} vs ASG {median_asg}");
        }
        assert!(max_acc < 0.8, "λ {lambda}: max {max_acc}");
    }
}

#[test]
fn specular_forms_over_the_hemisphere() {
    // The near-mirror grid of vsgl_specular_accurate_vs_quadrature misses where a rough
    // receiver's light comes from: anywhere. Here the light axis sweeps the hemisphere (5 θ ×
    // 5 φ, both sides of the plane of incidence) for each α × λ_in × view θo, and each form is
    // scored by its L1 error summed over those lights and views over the exact sum
    // (specular_reference): how much of the reflected light it misplaces or loses, as an image
    // lit from all sides would show. Printed per (α, λ_in) with each form's energy (sum over
    // the exact sum); docs/methods/vsgl.md, "SG lighting", has the table.
    // Asserted (lighting="blend"): (1) over the whole grid its L1 is below 0.75× the better
    // single form's; (2) in no cell is it worse than the worse form (+0.01); (3) at α ≥ 0.5,
    // where the ASG warp loses a rough lobe's light, it is within 0.01 of the filtered form or
    // better; (4) the point-light limit of the filtered form (share → 1).
    let n = DVec3::Z;
    let alphas = [0.05, 0.15, 0.3, 0.5, 0.7, 1.0];
    let lambdas = [1e4, 300.0, 30.0, 10.0, 3.0, 1.0];
    let views = [0.0, 0.6, 1.1, 1.4];
    let (mut total_asg, mut total_filtered, mut total_blend) = (0.0, 0.0, 0.0);
    for &alpha in &alphas {
        for &lambda in &lambdas {
            let (mut exact, mut e_asg, mut e_filtered, mut e_blend, mut s_asg, mut s_filtered, mut s_blend) = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
            for &theta_o in &views {
                let w_o = dir(theta_o, PI);
                for &theta_l in &[0.15, 0.5, 0.85, 1.2, 1.45] {
                    for &phi_l in &[0.0, 0.8, 1.6, 2.4, PI] {
                        let l_in = Sg { axis: dir(theta_l, phi_l), sharpness: lambda, amplitude: 1.0 };
                        let q = specular_reference(l_in, n, w_o, alpha, 512, 1.0);
                        let (asg, filtered, blend) = (vsgl_specular(l_in, n, w_o, alpha), vsgl_specular_accurate(l_in, n, w_o, alpha), vsgl_specular_blend(l_in, n, w_o, alpha));
                        exact += q;
                        (e_asg, e_filtered, e_blend) = (e_asg + (asg - q).abs(), e_filtered + (filtered - q).abs(), e_blend + (blend - q).abs());
                        (s_asg, s_filtered, s_blend) = (s_asg + asg, s_filtered + filtered, s_blend + blend);
                    }
                }
            }
            let (l1_asg, l1_filtered, l1_blend) = (e_asg / exact, e_filtered / exact, e_blend / exact);
            println!(
                "α {alpha:4} λ_in {lambda:>6}: L1 ASG {l1_asg:.3} filtered {l1_filtered:.3} blend {l1_blend:.3} | energy ASG {:.3} filtered {:.3} blend {:.3}",
                s_asg / exact,
                s_filtered / exact,
                s_blend / exact
            );
            assert!(l1_blend <= l1_asg.max(l1_filtered) + 0.01, "α {alpha} λ {lambda}: blend {l1_blend} worse than both forms");
            if alpha >= 0.5 {
                assert!(l1_blend <= l1_filtered + 0.01, "α {alpha} λ {lambda}: blend {l1_blend} vs filtered {l1_filtered}");
            }
            total_asg += l1_asg;
            total_filtered += l1_filtered;
            total_blend += l1_blend;
        }
    }
    println!("summed over the grid: ASG {total_asg:.2}, filtered {total_filtered:.2}, blend {total_blend:.2}");
    assert!(total_blend < 0.75 * total_asg.min(total_filtered), "blend {total_blend} vs ASG {total_asg}, filtered {total_filtered}");
    for &alpha in &alphas {
        for &theta_o in &views {
            let w_o = dir(theta_o, PI);
            let mirror = dir(theta_o, 0.0);
            let point = Sg { axis: mirror, sharpness: 1e8, amplitude: 1.0 };
            let exact = sg_integral(1e8) * ggx_brdf_over_rs(n, mirror, w_o, alpha) * mirror.dot(n);
            let got = vsgl_specular_blend(point, n, w_o, alpha);
            assert!((got / exact - 1.0).abs() < 1e-3, "point limit α {alpha} θo {theta_o}: {got} vs {exact}");
        }
    }
}

#[test]
fn extreme_inputs_stay_finite() {
    // The oracle's grid (docs/numerics.md): sharpness 1e-6…1e8, roughness 1e-4…1, grazing cosines down to 1e-6,
    // σ² down to 1e-12 of d², intensities 1e-8…1e8. Every output finite and ≥ 0.
    let n = DVec3::Z;
    for sharpness in [1e-6, 1.0, 1e8] {
        for intensity in [1e-8, 1e8] {
            for ratio in [1e-12, 1.0] {
                for cos_v in [1e-6f64, 0.5, 1.0] {
                    for alpha in [1e-8, 1e-4, 1.0] {
                        let (lobe, mut pos) = test_vsgl(sharpness, intensity, 0.0);
                        pos.variance = ratio * pos.mean.length_squared();
                        let l_in = vsgl_incoming_radiance(lobe, pos, DVec3::ZERO);
                        let w_o = DVec3::new((1.0 - cos_v * cos_v).sqrt(), 0.0, cos_v);
                        for v in [
                            vsgl_diffuse(l_in, n),
                            vsgl_diffuse_approx(l_in, n),
                            vsgl_diffuse_accurate(l_in, n),
                            vsgl_diffuse_sg_product(l_in, n),
                            vsgl_specular(l_in, n, w_o, alpha),
                            vsgl_specular_accurate(l_in, n, w_o, alpha),
                            vsgl_specular_accurate(
                                Sg {
                                    axis: dir(1.5, 0.0),
                                    ..l_in
                                },
                                n,
                                w_o,
                                alpha,
                            ),
                            vsgl_specular(
                                Sg {
                                    axis: dir(1.5, 0.0),
                                    ..l_in
                                },
                                n,
                                w_o,
                                alpha,
                            ),
                        ] {
                            assert!(
                                v.is_finite() && v >= 0.0,
                                "λ {sharpness} I {intensity} σ²/d² {ratio} cos {cos_v} α {alpha}: {v}"
                            );
                        }
                    }
                }
            }
        }
    }
}
