//! GPU test harness: evaluates one pure WGSL function of `wgsl/common/{math,sg,ggx,vsgl,vsgl_tangent_plane}.wgsl`
//! on a buffer of fixed-width f32 records (`wgsl/harness/eval.wgsl`), and the f64 oracle twin of
//! the same function on the same records, so the two can be compared element by element.
//!
//! Every function reads its arguments from the slots of an [`Input`] record and writes its result
//! into the first [`HarnessFunction::output_len`] slots of an [`Output`] record (the rest are 0).
//! Vectors take three consecutive slots; an `Sg` takes five (axis, sharpness, amplitude); an
//! `Asg` eleven (x axis, x bandwidth, y axis, y bandwidth, z axis). The layouts are listed per
//! function in [`HarnessFunction::layout`]; [`HarnessFunction::oracle`] applies the f64 twin to
//! the same record, converting each f32 slot exactly to f64, so the oracle sees bit-identical
//! arguments.
//!
//! ```no_run
//! use vsgl_core::gpu::Gpu;
//! use vsgl_core::verify::harness::{evaluate, HarnessFunction};
//! let gpu = Gpu::new(None)?;
//! let mut x = [0.0f32; 16];
//! x[0] = 1e-3; // sg_integral(λ = 1e-3)
//! let gpu_out = evaluate(&gpu, HarnessFunction::SgIntegral, &[x])?;
//! let f64_out = HarnessFunction::SgIntegral.oracle(&x);
//! assert!(((gpu_out[0][0] as f64) - f64_out[0]).abs() < 1e-5 * f64_out[0]);
//! # Ok::<(), vsgl_core::Error>(())
//! ```

use crate::error::{Error, Result};
use crate::gpu::{groups, Gpu};
use crate::verify::oracle;
use glam::DVec3;
use wgpu::util::DeviceExt;

use crate::shader_lib::constants::eval as shader;

/// f32 slots per input record (`INPUT_WIDTH` in eval.wgsl).
pub const INPUT_WIDTH: usize = shader::INPUT_WIDTH as usize;
/// f32 slots per output record (`OUTPUT_WIDTH` in eval.wgsl).
pub const OUTPUT_WIDTH: usize = shader::OUTPUT_WIDTH as usize;
/// Threads per workgroup (`WORKGROUP` in eval.wgsl).
const WORKGROUP: u32 = shader::WORKGROUP;

/// One input record.
pub type Input = [f32; INPUT_WIDTH];
/// One output record of the GPU.
pub type Output = [f32; OUTPUT_WIDTH];
/// One output record of the oracle.
pub type Output64 = [f64; OUTPUT_WIDTH];

/// The WGSL functions the harness can evaluate. The discriminant is the id used by the switch in
/// `wgsl/harness/eval.wgsl`.
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum HarnessFunction {
    // math.wgsl
    Expm1OverX = 0,
    Expm1 = 1,
    Mulsign = 2,
    Erf = 3,
    SafeNormalize = 4,
    OrthonormalBasis = 5,
    // sg.wgsl
    SgEvaluate = 6,
    SgIntegral = 7,
    SgIntegralApprox = 8,
    SgProduct = 9,
    SgProductIntegral = 10,
    SgMeanCosine = 11,
    SgTangentSecondMoment = 12,
    SgCosineVariance = 13,
    SgClampedCosineIntegral = 14,
    SgToksvigMeanDirection = 15,
    SgFromToksvigMeanDirection = 16,
    LambertLobeSg = 17,
    GgxNdfSgSharpness = 18,
    GgxLobeSg = 19,
    AsgEvaluate = 20,
    GgxLobeAsg = 21,
    SgAsgProductIntegral = 22,
    SgAsgProductIntegralOverAsgIntegral = 23,
    // vsgl.wgsl
    VsglLobeFromMoments = 24,
    VsglPositionFromMoments = 25,
    VsglIncomingRadiance = 26,
    VsglDiffuse = 27,
    VsglDiffuseApprox = 28,
    VsglDiffuseAccurate = 29,
    VsglDiffuseSgProduct = 30,
    VsglSpecular = 31,
    // ggx.wgsl
    GgxAlphaFromRoughness = 32,
    GgxD = 33,
    GgxSmithLambda = 34,
    GgxSmithG2 = 35,
    GgxBrdfOverRs = 36,
    LambertBrdfOverRd = 37,
    // vsgl.wgsl, lighting="accurate"
    VsglSpecularAccurate = 38,
    // vsgl.wgsl, the split forms the shading loop calls (vsgl_incoming_radiance and vsgl_specular
    // are wrappers over them)
    VsglPositionSeenFrom = 39,
    VsglIncomingRadianceSeen = 40,
    VsglSpecularReceiverFrom = 41,
    VsglSpecularWithReceiver = 42,
    // vsgl.wgsl, lighting="blend"
    VsglSpecularBlend = 43,
    VsglSpecularFiltered = 44,
    VsglSpecularBlendWithReceiver = 45,
    // vsgl_tangent_plane.wgsl (on vsgl's default path since plane_fade)
    VsglTangentPlaneFromMoments = 46,
    VsglTangentPlaneFade = 47,
}

use HarnessFunction as F;

impl HarnessFunction {
    /// Every function, in id order.
    pub const ALL: [HarnessFunction; 48] = [
        F::Expm1OverX,
        F::Expm1,
        F::Mulsign,
        F::Erf,
        F::SafeNormalize,
        F::OrthonormalBasis,
        F::SgEvaluate,
        F::SgIntegral,
        F::SgIntegralApprox,
        F::SgProduct,
        F::SgProductIntegral,
        F::SgMeanCosine,
        F::SgTangentSecondMoment,
        F::SgCosineVariance,
        F::SgClampedCosineIntegral,
        F::SgToksvigMeanDirection,
        F::SgFromToksvigMeanDirection,
        F::LambertLobeSg,
        F::GgxNdfSgSharpness,
        F::GgxLobeSg,
        F::AsgEvaluate,
        F::GgxLobeAsg,
        F::SgAsgProductIntegral,
        F::SgAsgProductIntegralOverAsgIntegral,
        F::VsglLobeFromMoments,
        F::VsglPositionFromMoments,
        F::VsglIncomingRadiance,
        F::VsglDiffuse,
        F::VsglDiffuseApprox,
        F::VsglDiffuseAccurate,
        F::VsglDiffuseSgProduct,
        F::VsglSpecular,
        F::GgxAlphaFromRoughness,
        F::GgxD,
        F::GgxSmithLambda,
        F::GgxSmithG2,
        F::GgxBrdfOverRs,
        F::LambertBrdfOverRd,
        F::VsglSpecularAccurate,
        F::VsglPositionSeenFrom,
        F::VsglIncomingRadianceSeen,
        F::VsglSpecularReceiverFrom,
        F::VsglSpecularWithReceiver,
        F::VsglSpecularBlend,
        F::VsglSpecularFiltered,
        F::VsglSpecularBlendWithReceiver,
        F::VsglTangentPlaneFromMoments,
        F::VsglTangentPlaneFade,
    ];

    /// The id of the function in the shader's switch.
    pub fn id(self) -> u32 {
        self as u32
    }

    /// The WGSL (and oracle) function name.
    pub fn name(self) -> &'static str {
        self.spec().0
    }

    /// The WGSL file that defines it (relative to `wgsl/`).
    pub fn file(self) -> &'static str {
        self.spec().1
    }

    /// (input slots, output slots) in words, e.g. `("dir 0-2, axis 3-5, sharpness 6", "value 0")`.
    pub fn layout(self) -> (&'static str, &'static str) {
        let s = self.spec();
        (s.2, s.3)
    }

    /// How many output slots carry the result.
    pub fn output_len(self) -> usize {
        self.spec().4
    }

    /// How many input slots the function reads (slots 0..input_len).
    pub fn input_len(self) -> usize {
        match self {
            F::Expm1OverX | F::Expm1 | F::Erf | F::SgIntegral | F::SgIntegralApprox => 1,
            F::SgMeanCosine | F::SgTangentSecondMoment | F::SgCosineVariance => 1,
            F::GgxNdfSgSharpness | F::GgxAlphaFromRoughness => 1,
            F::Mulsign | F::GgxSmithLambda => 2,
            F::OrthonormalBasis | F::SgFromToksvigMeanDirection | F::LambertLobeSg | F::GgxD | F::GgxSmithG2 => 3,
            F::VsglPositionSeenFrom | F::VsglSpecularReceiverFrom => 7,
            F::SgToksvigMeanDirection | F::VsglLobeFromMoments => 4,
            F::VsglPositionFromMoments => 5,
            F::VsglTangentPlaneFromMoments => 8,
            F::VsglTangentPlaneFade => 11,
            F::SafeNormalize | F::LambertBrdfOverRd => 6,
            F::SgEvaluate | F::SgClampedCosineIntegral | F::GgxLobeSg | F::GgxLobeAsg => 7,
            F::SgProduct | F::SgProductIntegral => 8,
            F::VsglDiffuse | F::VsglDiffuseApprox | F::VsglDiffuseAccurate | F::VsglDiffuseSgProduct => 8,
            F::GgxBrdfOverRs => 10,
            F::VsglIncomingRadiance | F::VsglSpecular | F::VsglSpecularAccurate | F::VsglSpecularBlend => 12,
            F::VsglSpecularFiltered | F::VsglSpecularBlendWithReceiver => 12,
            F::VsglIncomingRadianceSeen | F::VsglSpecularWithReceiver => 12,
            F::AsgEvaluate => 14,
            F::SgAsgProductIntegral | F::SgAsgProductIntegralOverAsgIntegral => 15,
        }
    }

    /// Looks a function up by its WGSL name.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|f| f.name() == name)
    }

    fn spec(self) -> (&'static str, &'static str, &'static str, &'static str, usize) {
        const M: &str = "common/math.wgsl";
        const S: &str = "common/sg.wgsl";
        const V: &str = "common/vsgl.wgsl";
        const G: &str = "common/ggx.wgsl";
        const T: &str = "common/vsgl_tangent_plane.wgsl";
        const SG_OUT: &str = "axis 0-2, sharpness 3, amplitude 4";
        const RAD_N: &str = "radiance Sg 0-4, normal 5-7";
        const SG_ASG: &str = "sg axis 0-2, sg sharpness 3, asg 4-14 (x 4-6, ηx 7, y 8-10, ηy 11, z 12-14)";
        match self {
            F::Expm1OverX => ("expm1_over_x", M, "x 0", "value 0", 1),
            F::Expm1 => ("expm1", M, "x 0", "value 0", 1),
            F::Mulsign => ("mulsign", M, "x 0, s 1", "value 0", 1),
            F::Erf => ("erf", M, "x 0", "value 0", 1),
            F::SafeNormalize => ("safe_normalize", M, "v 0-2, fallback 3-5", "vector 0-2", 3),
            F::OrthonormalBasis => ("orthonormal_basis", M, "z 0-2", "columns x 0-2, y 3-5, z 6-8", 9),
            F::SgEvaluate => ("sg_evaluate", S, "dir 0-2, axis 3-5, sharpness 6", "value 0", 1),
            F::SgIntegral => ("sg_integral", S, "sharpness 0", "value 0", 1),
            F::SgIntegralApprox => ("sg_integral_approx", S, "sharpness 0", "value 0", 1),
            F::SgProduct => (
                "sg_product",
                S,
                "axis1 0-2, sharpness1 3, axis2 4-6, sharpness2 7",
                "axis 0-2, sharpness 3, log_amplitude 4",
                5,
            ),
            F::SgProductIntegral => {
                ("sg_product_integral", S, "axis1 0-2, sharpness1 3, axis2 4-6, sharpness2 7", "value 0", 1)
            }
            F::SgMeanCosine => ("sg_mean_cosine", S, "sharpness 0", "value 0", 1),
            F::SgTangentSecondMoment => ("sg_tangent_second_moment", S, "sharpness 0", "value 0", 1),
            F::SgCosineVariance => ("sg_cosine_variance", S, "sharpness 0", "value 0", 1),
            F::SgClampedCosineIntegral => {
                ("sg_clamped_cosine_integral", S, "axis 0-2, sharpness 3, normal 4-6", "value 0", 1)
            }
            F::SgToksvigMeanDirection => ("sg_toksvig_mean_direction", S, "axis 0-2, sharpness 3", "vector 0-2", 3),
            F::SgFromToksvigMeanDirection => ("sg_from_toksvig_mean_direction", S, "mean direction 0-2", SG_OUT, 5),
            F::LambertLobeSg => ("lambert_lobe_sg", S, "normal 0-2", SG_OUT, 5),
            F::GgxNdfSgSharpness => ("ggx_ndf_sg_sharpness", S, "alpha 0", "value 0", 1),
            F::GgxLobeSg => ("ggx_lobe_sg", S, "normal 0-2, w_in 3-5, alpha 6", SG_OUT, 5),
            F::AsgEvaluate => (
                "asg_evaluate",
                S,
                "dir 0-2, asg 3-13 (x 3-5, ηx 6, y 7-9, ηy 10, z 11-13)",
                "value 0",
                1,
            ),
            F::GgxLobeAsg => (
                "ggx_lobe_asg",
                S,
                "normal 0-2, w_o 3-5, alpha 6",
                "x axis 0-2, ηx 3, y axis 4-6, ηy 7, z axis 8-10",
                11,
            ),
            F::SgAsgProductIntegral => ("sg_asg_product_integral", S, SG_ASG, "value 0", 1),
            F::SgAsgProductIntegralOverAsgIntegral => {
                ("sg_asg_product_integral_over_asg_integral", S, SG_ASG, "value 0", 1)
            }
            F::VsglLobeFromMoments => {
                ("vsgl_lobe_from_moments", V, "ΣΦR 0, ΣΦRξ̄ 1-3", SG_OUT, 5)
            }
            F::VsglPositionFromMoments => (
                "vsgl_position_from_moments",
                V,
                "Σw 0, Σwy 1-3, Σw‖y‖² 4",
                "mean 0-2, variance 3",
                4,
            ),
            F::VsglIncomingRadiance => (
                "vsgl_incoming_radiance",
                V,
                "lobe Sg 0-4, position mean 5-7, variance 8, shading position 9-11",
                SG_OUT,
                5,
            ),
            F::VsglDiffuse => ("vsgl_diffuse", V, RAD_N, "value 0", 1),
            F::VsglDiffuseApprox => ("vsgl_diffuse_approx", V, RAD_N, "value 0", 1),
            F::VsglDiffuseAccurate => ("vsgl_diffuse_accurate", V, RAD_N, "value 0", 1),
            F::VsglDiffuseSgProduct => ("vsgl_diffuse_sg_product", V, RAD_N, "value 0", 1),
            F::VsglSpecular => {
                ("vsgl_specular", V, "radiance Sg 0-4, normal 5-7, w_o 8-10, alpha 11", "value 0", 1)
            }
            F::VsglSpecularAccurate => {
                ("vsgl_specular_accurate", V, "radiance Sg 0-4, normal 5-7, w_o 8-10, alpha 11", "value 0", 1)
            }
            F::VsglSpecularBlend => ("vsgl_specular_blend", V, "radiance Sg 0-4, normal 5-7, w_o 8-10, alpha 11", "value 0", 1),
            F::VsglSpecularFiltered => {
                ("vsgl_specular_filtered", V, "radiance Sg 0-4, normal 5-7, w_o 8-10, alpha 11", "value 0, receiver share α/α' 1", 2)
            }
            F::VsglSpecularBlendWithReceiver => (
                "vsgl_specular_blend_with_receiver",
                V,
                "radiance Sg 0-4, receiver from normal 5-7, w_o 8-10, alpha 11",
                "value 0",
                1,
            ),
            F::VsglTangentPlaneFromMoments => (
                "vsgl_tangent_plane_from_moments",
                T,
                "sum weight 0, sum weighted normal 1-3, sum weighted height y·n 4, mean 5-7",
                "normal N̄ 0-2, offset 3",
                4,
            ),
            F::VsglTangentPlaneFade => (
                "vsgl_tangent_plane_fade",
                T,
                "plane normal 0-2, offset 3, position mean 4-6, variance 7, shading position 8-10",
                "value 0",
                1,
            ),
            F::VsglPositionSeenFrom => (
                "vsgl_position_seen_from",
                V,
                "position mean 0-2, variance 3, shading position 4-6",
                "1/σ² 0, λσ 1, axis ξμ 2-4, has_axis (0 or 1) 5",
                6,
            ),
            F::VsglIncomingRadianceSeen => (
                "vsgl_incoming_radiance_seen",
                V,
                "lobe axis 0-2, sharpness 3, amplitude/(2π) 4, seen from position mean 5-7, variance 8, shading position 9-11",
                SG_OUT,
                5,
            ),
            F::VsglSpecularReceiverFrom => (
                "vsgl_specular_receiver_from",
                V,
                "normal 0-2, w_o 3-5, alpha 6",
                "n·ω_o 0, Λ(ω_o) 1, asg 2-12 (x 2-4, ηx 5, y 6-8, ηy 9, z 10-12)",
                13,
            ),
            F::VsglSpecularWithReceiver => (
                "vsgl_specular_with_receiver",
                V,
                "radiance Sg 0-4, receiver from normal 5-7, w_o 8-10, alpha 11",
                "value 0",
                1,
            ),
            F::GgxAlphaFromRoughness => ("ggx_alpha_from_roughness", G, "roughness 0", "value 0", 1),
            F::GgxD => ("ggx_d", G, "n·h 0, ‖n×h‖² 1, alpha 2", "value 0", 1),
            F::GgxSmithLambda => ("ggx_smith_lambda", G, "cos θ 0, alpha 1", "value 0", 1),
            F::GgxSmithG2 => ("ggx_smith_g2", G, "n·l 0, n·v 1, alpha 2", "value 0", 1),
            F::GgxBrdfOverRs => ("ggx_brdf_over_rs", G, "n 0-2, l 3-5, v 6-8, alpha 9", "value 0", 1),
            F::LambertBrdfOverRd => ("lambert_brdf_over_rd", G, "n 0-2, l 3-5", "value 0", 1),
        }
    }

    /// The f64 oracle twin of the function on the same record (each f32 slot converted exactly).
    pub fn oracle(self, input: &Input) -> Output64 {
        self.oracle64(&input.map(|x| x as f64))
    }

    /// The f64 oracle on an f64 record (used to probe how sensitive a function is to its inputs).
    pub fn oracle64(self, input: &[f64; INPUT_WIDTH]) -> Output64 {
        let a = |i: usize| input[i];
        let v = |i: usize| DVec3::new(a(i), a(i + 1), a(i + 2));
        let sg = |i: usize| oracle::Sg { axis: v(i), sharpness: a(i + 3), amplitude: a(i + 4) };
        let asg = |i: usize| oracle::Asg {
            x_axis: v(i),
            x_bandwidth: a(i + 3),
            y_axis: v(i + 4),
            y_bandwidth: a(i + 7),
            z_axis: v(i + 8),
        };
        let mut o = [0.0f64; OUTPUT_WIDTH];
        let put3 = |o: &mut Output64, i: usize, x: DVec3| o[i..i + 3].copy_from_slice(&x.to_array());
        let put_sg = |o: &mut Output64, s: oracle::Sg| {
            o[0..3].copy_from_slice(&s.axis.to_array());
            o[3] = s.sharpness;
            o[4] = s.amplitude;
        };
        match self {
            F::Expm1OverX => o[0] = oracle::expm1_over_x(a(0)),
            F::Expm1 => o[0] = oracle::expm1(a(0)),
            F::Mulsign => o[0] = oracle::mulsign(a(0), a(1)),
            F::Erf => o[0] = oracle::erf(a(0)),
            F::SafeNormalize => put3(&mut o, 0, oracle::safe_normalize(v(0), v(3))),
            F::OrthonormalBasis => {
                let m = oracle::orthonormal_basis(v(0));
                put3(&mut o, 0, m.x_axis);
                put3(&mut o, 3, m.y_axis);
                put3(&mut o, 6, m.z_axis);
            }
            F::SgEvaluate => o[0] = oracle::sg_evaluate(v(0), v(3), a(6)),
            F::SgIntegral => o[0] = oracle::sg_integral(a(0)),
            F::SgIntegralApprox => o[0] = oracle::sg_integral_approx(a(0)),
            F::SgProduct => {
                let p = oracle::sg_product(v(0), a(3), v(4), a(7));
                put3(&mut o, 0, p.axis);
                o[3] = p.sharpness;
                o[4] = p.log_amplitude;
            }
            F::SgProductIntegral => o[0] = oracle::sg_product_integral(v(0), a(3), v(4), a(7)),
            F::SgMeanCosine => o[0] = oracle::sg_mean_cosine(a(0)),
            F::SgTangentSecondMoment => o[0] = oracle::sg_tangent_second_moment(a(0)),
            F::SgCosineVariance => o[0] = oracle::sg_cosine_variance(a(0)),
            F::SgClampedCosineIntegral => o[0] = oracle::sg_clamped_cosine_integral(v(0), a(3), v(4)),
            F::SgToksvigMeanDirection => put3(&mut o, 0, oracle::sg_toksvig_mean_direction(v(0), a(3))),
            F::SgFromToksvigMeanDirection => put_sg(&mut o, oracle::sg_from_toksvig_mean_direction(v(0))),
            F::LambertLobeSg => put_sg(&mut o, oracle::lambert_lobe_sg(v(0))),
            F::GgxNdfSgSharpness => o[0] = oracle::ggx_ndf_sg_sharpness(a(0)),
            F::GgxLobeSg => put_sg(&mut o, oracle::ggx_lobe_sg(v(0), v(3), a(6))),
            F::AsgEvaluate => o[0] = oracle::asg_evaluate(v(0), asg(3)),
            F::GgxLobeAsg => {
                let g = oracle::ggx_lobe_asg(v(0), v(3), a(6));
                put3(&mut o, 0, g.x_axis);
                o[3] = g.x_bandwidth;
                put3(&mut o, 4, g.y_axis);
                o[7] = g.y_bandwidth;
                put3(&mut o, 8, g.z_axis);
            }
            F::SgAsgProductIntegral => o[0] = oracle::sg_asg_product_integral(v(0), a(3), asg(4)),
            F::SgAsgProductIntegralOverAsgIntegral => {
                o[0] = oracle::sg_asg_product_integral_over_asg_integral(v(0), a(3), asg(4))
            }
            F::VsglLobeFromMoments => put_sg(&mut o, oracle::vsgl_lobe_from_moments(a(0), v(1))),
            F::VsglPositionFromMoments => {
                let p = oracle::vsgl_position_from_moments(a(0), v(1), a(4));
                put3(&mut o, 0, p.mean);
                o[3] = p.variance;
            }
            F::VsglIncomingRadiance => {
                let pos = oracle::VsglPosition { mean: v(5), variance: a(8) };
                put_sg(&mut o, oracle::vsgl_incoming_radiance(sg(0), pos, v(9)))
            }
            F::VsglDiffuse => o[0] = oracle::vsgl_diffuse(sg(0), v(5)),
            F::VsglDiffuseApprox => o[0] = oracle::vsgl_diffuse_approx(sg(0), v(5)),
            F::VsglDiffuseAccurate => o[0] = oracle::vsgl_diffuse_accurate(sg(0), v(5)),
            F::VsglDiffuseSgProduct => o[0] = oracle::vsgl_diffuse_sg_product(sg(0), v(5)),
            F::VsglSpecular => o[0] = oracle::vsgl_specular(sg(0), v(5), v(8), a(11)),
            F::VsglSpecularAccurate => o[0] = oracle::vsgl_specular_accurate(sg(0), v(5), v(8), a(11)),
            F::VsglSpecularBlend => o[0] = oracle::vsgl_specular_blend(sg(0), v(5), v(8), a(11)),
            F::VsglSpecularFiltered => {
                let (value, share) = oracle::vsgl_specular_filtered(sg(0), v(5), v(8), a(11));
                o[0] = value;
                o[1] = share;
            }
            F::VsglSpecularBlendWithReceiver => {
                o[0] = oracle::vsgl_specular_blend_with_receiver(sg(0), &oracle::vsgl_specular_receiver_from(v(5), v(8), a(11)))
            }
            F::VsglTangentPlaneFromMoments => {
                let plane = oracle::vsgl_tangent_plane_from_moments(a(0), v(1), a(4), v(5));
                put3(&mut o, 0, plane.normal);
                o[3] = plane.offset;
            }
            F::VsglTangentPlaneFade => {
                let plane = oracle::VsglTangentPlane { normal: v(0), offset: a(3) };
                o[0] = oracle::vsgl_tangent_plane_fade(plane, oracle::VsglPosition { mean: v(4), variance: a(7) }, v(8));
            }
            F::VsglPositionSeenFrom => {
                let s = oracle::vsgl_position_seen_from(oracle::VsglPosition { mean: v(0), variance: a(3) }, v(4));
                o[0] = s.inv_variance;
                o[1] = s.sharpness;
                put3(&mut o, 2, s.axis);
                o[5] = if s.has_axis { 1.0 } else { 0.0 };
            }
            F::VsglIncomingRadianceSeen => {
                let pos = oracle::VsglPosition { mean: v(5), variance: a(8) };
                let seen = oracle::vsgl_position_seen_from(pos, v(9));
                put_sg(&mut o, oracle::vsgl_incoming_radiance_seen(v(0), a(3), a(4), seen))
            }
            F::VsglSpecularReceiverFrom => {
                let r = oracle::vsgl_specular_receiver_from(v(0), v(3), a(6));
                o[0] = r.n_dot_v;
                o[1] = r.lambda_v;
                put3(&mut o, 2, r.asg.x_axis);
                o[5] = r.asg.x_bandwidth;
                put3(&mut o, 6, r.asg.y_axis);
                o[9] = r.asg.y_bandwidth;
                put3(&mut o, 10, r.asg.z_axis);
            }
            F::VsglSpecularWithReceiver => {
                o[0] = oracle::vsgl_specular_with_receiver(sg(0), &oracle::vsgl_specular_receiver_from(v(5), v(8), a(11)))
            }
            F::GgxAlphaFromRoughness => o[0] = oracle::ggx_alpha_from_roughness(a(0)),
            F::GgxD => o[0] = oracle::ggx_d(a(0), a(1), a(2)),
            F::GgxSmithLambda => o[0] = oracle::ggx_smith_lambda(a(0), a(1)),
            F::GgxSmithG2 => o[0] = oracle::ggx_smith_g2(a(0), a(1), a(2)),
            F::GgxBrdfOverRs => o[0] = oracle::ggx_brdf_over_rs(v(0), v(3), v(6), a(9)),
            F::LambertBrdfOverRd => o[0] = oracle::lambert_brdf_over_rd(v(0), v(3)),
        }
        o
    }
}

/// `HarnessParams` in eval.wgsl.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct ParamsRaw {
    function: u32,
    count: u32,
    pad: [u32; 2],
}
const _: () = assert!(std::mem::size_of::<ParamsRaw>() == 16);

/// The compiled harness pipeline (compile once, evaluate many times).
pub struct Harness {
    pipeline: wgpu::ComputePipeline,
}

impl Harness {
    pub fn new(gpu: &Gpu) -> Result<Self> {
        gpu.scoped("harness pipeline", || {
            let module = gpu.shader("harness/eval.wgsl")?;
            Ok(Self { pipeline: gpu.compute_pipeline("harness_eval_pipeline", &module, "main") })
        })
    }

    /// Evaluates `function` on every record on the GPU (f32) and returns the output records.
    pub fn evaluate(&self, gpu: &Gpu, function: HarnessFunction, inputs: &[Input]) -> Result<Vec<Output>> {
        let record_bytes = (INPUT_WIDTH.max(OUTPUT_WIDTH) * 4) as u64;
        // Records per dispatch: within the storage binding size and the 1-D dispatch limit.
        let by_binding = gpu.limits.max_storage_buffer_binding_size / record_bytes;
        let by_dispatch = gpu.limits.max_compute_workgroups_per_dimension as u64 * WORKGROUP as u64;
        let chunk = by_binding.min(by_dispatch).max(1) as usize;
        let mut out = Vec::with_capacity(inputs.len());
        for part in inputs.chunks(chunk) {
            out.extend(self.evaluate_chunk(gpu, function, part)?);
        }
        Ok(out)
    }

    fn evaluate_chunk(&self, gpu: &Gpu, function: HarnessFunction, inputs: &[Input]) -> Result<Vec<Output>> {
        if inputs.is_empty() {
            return Ok(Vec::new());
        }
        let count = u32::try_from(inputs.len()).map_err(|_| Error::invalid("inputs", "too many records"))?;
        let bytes = gpu.scoped("harness evaluate", || {
            let params = ParamsRaw { function: function.id(), count, pad: [0; 2] };
            let params_buf = gpu.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("harness_params_buffer"),
                contents: bytemuck::bytes_of(&params),
                usage: wgpu::BufferUsages::UNIFORM,
            });
            let input_buf = gpu.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("harness_input_buffer"),
                contents: bytemuck::cast_slice(inputs),
                usage: wgpu::BufferUsages::STORAGE,
            });
            let output_buf = gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("harness_output_buffer"),
                size: (inputs.len() * OUTPUT_WIDTH * 4) as u64,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            });
            let bind = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("harness_bind_group"),
                layout: &self.pipeline.get_bind_group_layout(0),
                entries: &crate::gpu::entries(&[
                    params_buf.as_entire_binding(),
                    input_buf.as_entire_binding(),
                    output_buf.as_entire_binding(),
                ]),
            });
            let mut enc = gpu
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("harness_encoder") });
            {
                let mut pass = enc.begin_compute_pass(&wgpu::ComputePassDescriptor {
                    label: Some("harness_eval_pass"),
                    timestamp_writes: None,
                });
                pass.set_pipeline(&self.pipeline);
                pass.set_bind_group(0, &bind, &[]);
                pass.dispatch_workgroups(groups(count, WORKGROUP), 1, 1);
            }
            gpu.queue.submit([enc.finish()]);
            Ok(gpu.read_buffers(&[&output_buf])?.remove(0))
        })?;
        let words: &[f32] = bytemuck::cast_slice(&bytes);
        Ok(words
            .chunks_exact(OUTPUT_WIDTH)
            .map(|c| {
                let mut r = [0.0f32; OUTPUT_WIDTH];
                r.copy_from_slice(c);
                r
            })
            .collect())
    }
}

/// Compiles the harness and evaluates `function` on `inputs` (see [`Harness`] to reuse the
/// pipeline across calls).
pub fn evaluate(gpu: &Gpu, function: HarnessFunction, inputs: &[Input]) -> Result<Vec<Output>> {
    Harness::new(gpu)?.evaluate(gpu, function, inputs)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every enum entry names a function of the file it claims, ids are dense and in order, and
    /// every id has a `case` in the harness shader that calls that very function.
    #[test]
    fn functions_match_the_shaders() {
        let harness = crate::shader_lib::source("harness/eval.wgsl").expect("harness shader embedded");
        for (i, f) in HarnessFunction::ALL.iter().enumerate() {
            assert_eq!(f.id() as usize, i, "{f:?}");
            let src = crate::shader_lib::source(f.file()).expect("embedded");
            assert!(src.contains(&format!("fn {}(", f.name())), "{} not in {}", f.name(), f.file());
            let case = harness
                .lines()
                .skip_while(|l| !l.trim_start().starts_with(&format!("case {}u:", f.id())))
                .take(4)
                .collect::<String>();
            assert!(case.contains(&format!("{}(", f.name())), "case {} does not call {}", f.id(), f.name());
            assert_eq!(HarnessFunction::from_name(f.name()), Some(*f));
        }
    }

    /// `input_len` and `output_len` agree with the slot numbers written in `layout`.
    #[test]
    fn lengths_match_layouts() {
        let max_slot = |text: &str| {
            text.split(|c: char| !c.is_ascii_digit()).filter_map(|t| t.parse::<usize>().ok()).max().unwrap_or(0)
        };
        for f in HarnessFunction::ALL {
            let (inputs, outputs) = f.layout();
            assert_eq!(f.input_len(), max_slot(inputs) + 1, "{}: {inputs}", f.name());
            assert_eq!(f.output_len(), max_slot(outputs) + 1, "{}: {outputs}", f.name());
            assert!(f.input_len() <= INPUT_WIDTH && f.output_len() <= OUTPUT_WIDTH);
        }
    }

    /// Every public function of the four shared modules is covered by the harness.
    #[test]
    fn every_common_function_is_covered() {
        for file in ["common/math.wgsl", "common/sg.wgsl", "common/vsgl.wgsl", "common/ggx.wgsl"] {
            let src = crate::shader_lib::source(file).expect("embedded");
            for line in src.lines().filter(|l| l.starts_with("fn ")) {
                let name = line[3..].split('(').next().unwrap_or("").trim();
                assert!(HarnessFunction::from_name(name).is_some(), "{file}: fn {name} has no harness entry");
            }
        }
    }
}
