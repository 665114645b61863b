//! The f64 oracle: a straightforward double-precision twin of every function in
//! `wgsl/common/{math,sg,vsgl,ggx}.wgsl`, with the same names, arguments and named clamps, plus
//! numerical quadrature on the sphere that checks the closed forms.
//!
//! Principle: the oracle computes what each WGSL function *means*, not how the GPU gets there.
//! Where the WGSL replaces a transcendental by an approximation or a series branch (`erf` by
//! Abramowitz–Stegun 7.1.26, `expm1` by a Taylor branch), the oracle evaluates it accurately in
//! f64, so an f32-vs-f64 comparison on the GPU measures the WGSL's approximation error as well as
//! its rounding. Clamps are part of a function's definition, so the oracle applies the same
//! clamps with the same values (checked against the WGSL text by `tests::constants_match_wgsl`).
//! Approximations that are the *method* (SG lobes, the SG–ASG product integral, the
//! clamped-cosine formula) are reproduced as formulas, and the quadrature tests measure how
//! far they are from the true integrals.
//!
//! Modules: [`math`] (expm1, erf, …), [`sg`] (SG/ASG algebra and lobes), [`ggx`] (the GGX and
//! Lambert BRDFs of `ggx.wgsl`), [`vsgl`] (VSGL generation, incoming radiance, shading),
//! [`quadrature`] (Gauss–Legendre rules and lobe-centred sphere integration).
//! The measured errors are summarized in `docs/numerics.md`.

pub mod ggx;
pub mod math;
pub mod quadrature;
pub mod sg;
pub mod vsgl;

pub use ggx::*;
pub use math::*;
pub use sg::*;
pub use vsgl::*;

/// Reading constants and series coefficients out of the embedded WGSL text, so the tests can
/// prove that the oracle and the shaders use the same numbers.
#[cfg(test)]
pub(crate) mod wgsl_text {
    use crate::shader_lib;

    fn eval_const_expr(file: &str, expr: &str) -> f64 {
        expr.split('*')
            .map(|factor| {
                let f = factor.trim();
                f.parse::<f64>().unwrap_or_else(|_| const_value(file, f))
            })
            .product()
    }

    /// Value of `const NAME: f32 = <literal or product of literals/consts>;` in `file`
    /// (path relative to `wgsl/`), following includes of `common/constants.wgsl`.
    pub fn const_value(file: &str, name: &str) -> f64 {
        for f in [file, "common/constants.wgsl", "common/math.wgsl", "common/sg.wgsl"] {
            let src = shader_lib::source(f).unwrap_or_else(|| panic!("{f} is not embedded"));
            let prefix = format!("const {name}: f32 = ");
            if let Some(line) = src.lines().find(|l| l.starts_with(&prefix)) {
                let expr = line[prefix.len()..].split(';').next().unwrap_or("");
                return eval_const_expr(f, expr);
            }
        }
        panic!("const {name} not found in {file}");
    }

    /// The body of `fn name(` in `file`, up to the closing `}` at column 0.
    pub fn function_body(file: &str, name: &str) -> String {
        let src = shader_lib::source(file).unwrap_or_else(|| panic!("{file} is not embedded"));
        let start = src
            .find(&format!("fn {name}("))
            .unwrap_or_else(|| panic!("fn {name} not in {file}"));
        let rest = &src[start..];
        let end = rest.find("\n}").unwrap_or(rest.len());
        rest[..end].to_string()
    }

    /// Every literal fraction `a / b` (as in `-1382.0 / 638512875.0`: two numeric literals
    /// around a ` / `) in a text, in order, comments excluded.
    pub fn fractions(text: &str) -> Vec<f64> {
        let code: String = text
            .lines()
            .map(|l| l.split("//").next().unwrap_or(""))
            .collect::<Vec<_>>()
            .join(" ");
        let is_num_char = |c: char| c.is_ascii_digit() || c == '.';
        let mut out = Vec::new();
        let mut search = 0;
        while let Some(pos) = code[search..].find(" / ") {
            let at = search + pos;
            search = at + 3;
            let left: String = code[..at]
                .chars()
                .rev()
                .take_while(|&c| is_num_char(c))
                .collect::<Vec<_>>()
                .into_iter()
                .rev()
                .collect();
            let sign = if code[..at - left.len()].ends_with('-') { -1.0 } else { 1.0 };
            let right: String = code[at + 3..].chars().take_while(|&c| is_num_char(c)).collect();
            if let (Ok(a), Ok(b)) = (left.parse::<f64>(), right.parse::<f64>()) {
                out.push(sign * a / b);
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::wgsl_text::const_value;

    /// Every named clamp / threshold exists with the same value on both sides.
    #[test]
    fn constants_match_wgsl() {
        let pairs: &[(&str, &str, f64)] = &[
            ("common/math.wgsl", "EXP_ARG_MAX", super::math::EXP_ARG_MAX),
            ("common/math.wgsl", "EXPM1_SERIES_RADIUS", super::math::EXPM1_SERIES_RADIUS),
            ("common/math.wgsl", "ERF_SERIES_RADIUS", super::math::ERF_SERIES_RADIUS),
            ("common/sg.wgsl", "SG_SHARPNESS_MAX", super::sg::SG_SHARPNESS_MAX),
            (
                "common/sg.wgsl",
                "SG_INTEGRAL_APPROX_SHARPNESS_MIN",
                super::sg::SG_INTEGRAL_APPROX_SHARPNESS_MIN,
            ),
            ("common/sg.wgsl", "SG_MOMENT_SERIES_RADIUS", super::sg::SG_MOMENT_SERIES_RADIUS),
            ("common/sg.wgsl", "LAMBERT_LOBE_SG_SHARPNESS", super::sg::LAMBERT_LOBE_SG_SHARPNESS),
            ("common/sg.wgsl", "TOKSVIG_SHARPNESS_MAX", super::sg::TOKSVIG_SHARPNESS_MAX),
            ("common/sg.wgsl", "ASG_BANDWIDTH_MAX", super::sg::ASG_BANDWIDTH_MAX),
            ("common/sg.wgsl", "ASG_ISOTROPIC_SIN2_MAX", super::sg::ASG_ISOTROPIC_SIN2_MAX),
            (
                "common/vsgl.wgsl",
                "VSGL_VARIANCE_MIN_FRACTION",
                super::vsgl::VSGL_VARIANCE_MIN_FRACTION,
            ),
            ("common/ggx.wgsl", "GGX_ALPHA_MIN", super::ggx::GGX_ALPHA_MIN),
            ("common/vsgl.wgsl", "VSGL_FILTERED_ALPHA2_MIN", super::vsgl::VSGL_FILTERED_ALPHA2_MIN),
            ("common/vsgl.wgsl", "VSGL_FILTERED_ALPHA2_MAX", super::vsgl::VSGL_FILTERED_ALPHA2_MAX),
            (
                "common/vsgl.wgsl",
                "VSGL_FILTERED_INV_HALF_LENGTH_MAX",
                super::vsgl::VSGL_FILTERED_INV_HALF_LENGTH_MAX,
            ),
        ];
        for &(file, name, oracle) in pairs {
            let wgsl = const_value(file, name);
            // The WGSL literal is an f32: equal after rounding the oracle value to f32.
            assert_eq!(wgsl as f32, oracle as f32, "{file}: {name} = {wgsl}, oracle has {oracle}");
        }
    }
}
