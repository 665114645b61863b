// Test harness: evaluates one pure function of wgsl/common/{math,sg,ggx,vsgl}.wgsl on every
// record of a storage buffer, so tests can compare the GPU's f32 results with the f64 oracle
// (crates/vsgl-core/src/verify/oracle) element by element. Driven by
// crates/vsgl-core/src/verify/harness.rs, which documents the record layout of every function
// (HarnessFunction); the ids in the switch below are that enum's discriminants.
// Records: INPUT_WIDTH f32 in, OUTPUT_WIDTH f32 out; unused output slots are written as 0.
// The function is chosen by a uniform (one pipeline for all functions, so the shader is
// compiled once per device).
#include "common/constants.wgsl"
#include "common/math.wgsl"
#include "common/sg.wgsl"
#include "common/ggx.wgsl"
#include "common/vsgl.wgsl"
#include "common/vsgl_tangent_plane.wgsl"

const WORKGROUP: u32 = 64u;
const INPUT_WIDTH: u32 = 16u;
const OUTPUT_WIDTH: u32 = 16u;

struct HarnessParams {
    function: u32,
    count: u32,
    pad0: u32,
    pad1: u32,
}

@group(0) @binding(0) var<uniform> params: HarnessParams;
@group(0) @binding(1) var<storage, read> harness_inputs: array<f32>;
@group(0) @binding(2) var<storage, read_write> harness_outputs: array<f32>;

var<private> record: u32;

fn in1(i: u32) -> f32 {
    return harness_inputs[record * INPUT_WIDTH + i];
}

fn in3(i: u32) -> vec3f {
    return vec3f(in1(i), in1(i + 1u), in1(i + 2u));
}

// Sg at slots i.. : axis (3), sharpness, amplitude.
fn in_sg(i: u32) -> Sg {
    return Sg(in3(i), in1(i + 3u), in1(i + 4u));
}

// Asg at slots i.. : x axis (3), x bandwidth, y axis (3), y bandwidth, z axis (3).
fn in_asg(i: u32) -> Asg {
    return Asg(in3(i), in1(i + 3u), in3(i + 4u), in1(i + 7u), in3(i + 8u));
}

fn out1(i: u32, v: f32) {
    harness_outputs[record * OUTPUT_WIDTH + i] = v;
}

fn out3(i: u32, v: vec3f) {
    out1(i, v.x);
    out1(i + 1u, v.y);
    out1(i + 2u, v.z);
}

fn out_sg(s: Sg) {
    out3(0u, s.axis);
    out1(3u, s.sharpness);
    out1(4u, s.amplitude);
}

@compute @workgroup_size(WORKGROUP)
fn main(@builtin(global_invocation_id) gid: vec3u) {
    if (gid.x >= params.count) {
        return;
    }
    record = gid.x;
    for (var i = 0u; i < OUTPUT_WIDTH; i++) {
        out1(i, 0.0);
    }
    switch (params.function) {
        // math.wgsl
        case 0u: { out1(0u, expm1_over_x(in1(0u))); }
        case 1u: { out1(0u, expm1(in1(0u))); }
        case 2u: { out1(0u, mulsign(in1(0u), in1(1u))); }
        case 3u: { out1(0u, erf(in1(0u))); }
        case 4u: { out3(0u, safe_normalize(in3(0u), in3(3u))); }
        case 5u: {
            let m = orthonormal_basis(in3(0u));
            out3(0u, m[0]);
            out3(3u, m[1]);
            out3(6u, m[2]);
        }
        // sg.wgsl
        case 6u: { out1(0u, sg_evaluate(in3(0u), in3(3u), in1(6u))); }
        case 7u: { out1(0u, sg_integral(in1(0u))); }
        case 8u: { out1(0u, sg_integral_approx(in1(0u))); }
        case 9u: {
            let p = sg_product(in3(0u), in1(3u), in3(4u), in1(7u));
            out3(0u, p.axis);
            out1(3u, p.sharpness);
            out1(4u, p.log_amplitude);
        }
        case 10u: { out1(0u, sg_product_integral(in3(0u), in1(3u), in3(4u), in1(7u))); }
        case 11u: { out1(0u, sg_mean_cosine(in1(0u))); }
        case 12u: { out1(0u, sg_tangent_second_moment(in1(0u))); }
        case 13u: { out1(0u, sg_cosine_variance(in1(0u))); }
        case 14u: { out1(0u, sg_clamped_cosine_integral(in3(0u), in1(3u), in3(4u))); }
        case 15u: { out3(0u, sg_toksvig_mean_direction(in3(0u), in1(3u))); }
        case 16u: { out_sg(sg_from_toksvig_mean_direction(in3(0u))); }
        case 17u: { out_sg(lambert_lobe_sg(in3(0u))); }
        case 18u: { out1(0u, ggx_ndf_sg_sharpness(in1(0u))); }
        case 19u: { out_sg(ggx_lobe_sg(in3(0u), in3(3u), in1(6u))); }
        case 20u: { out1(0u, asg_evaluate(in3(0u), in_asg(3u))); }
        case 21u: {
            let a = ggx_lobe_asg(in3(0u), in3(3u), in1(6u));
            out3(0u, a.x_axis);
            out1(3u, a.x_bandwidth);
            out3(4u, a.y_axis);
            out1(7u, a.y_bandwidth);
            out3(8u, a.z_axis);
        }
        case 22u: { out1(0u, sg_asg_product_integral(in3(0u), in1(3u), in_asg(4u))); }
        case 23u: { out1(0u, sg_asg_product_integral_over_asg_integral(in3(0u), in1(3u), in_asg(4u))); }
        // vsgl.wgsl
        case 24u: { out_sg(vsgl_lobe_from_moments(in1(0u), in3(1u))); }
        case 25u: {
            let p = vsgl_position_from_moments(in1(0u), in3(1u), in1(4u));
            out3(0u, p.mean);
            out1(3u, p.variance);
        }
        case 26u: { out_sg(vsgl_incoming_radiance(in_sg(0u), VsglPosition(in3(5u), in1(8u)), in3(9u))); }
        case 27u: { out1(0u, vsgl_diffuse(in_sg(0u), in3(5u))); }
        case 28u: { out1(0u, vsgl_diffuse_approx(in_sg(0u), in3(5u))); }
        case 29u: { out1(0u, vsgl_diffuse_accurate(in_sg(0u), in3(5u))); }
        case 30u: { out1(0u, vsgl_diffuse_sg_product(in_sg(0u), in3(5u))); }
        case 31u: { out1(0u, vsgl_specular(in_sg(0u), in3(5u), in3(8u), in1(11u))); }
        // ggx.wgsl
        case 32u: { out1(0u, ggx_alpha_from_roughness(in1(0u))); }
        case 33u: { out1(0u, ggx_d(in1(0u), in1(1u), in1(2u))); }
        case 34u: { out1(0u, ggx_smith_lambda(in1(0u), in1(1u))); }
        case 35u: { out1(0u, ggx_smith_g2(in1(0u), in1(1u), in1(2u))); }
        case 36u: { out1(0u, ggx_brdf_over_rs(in3(0u), in3(3u), in3(6u), in1(9u))); }
        case 37u: { out1(0u, lambert_brdf_over_rd(in3(0u), in3(3u))); }
        // vsgl.wgsl (added after the ggx block: ids are append-only)
        case 38u: { out1(0u, vsgl_specular_accurate(in_sg(0u), in3(5u), in3(8u), in1(11u))); }
        // vsgl.wgsl, the split forms of vsgl_incoming_radiance and vsgl_specular (append-only ids)
        case 39u: {
            let s = vsgl_position_seen_from(VsglPosition(in3(0u), in1(3u)), in3(4u));
            out1(0u, s.inv_variance);
            out1(1u, s.sharpness);
            out3(2u, s.axis);
            out1(5u, select(0.0, 1.0, s.has_axis));
        }
        case 40u: { out_sg(vsgl_incoming_radiance_seen(in3(0u), in1(3u), in1(4u), vsgl_position_seen_from(VsglPosition(in3(5u), in1(8u)), in3(9u)))); }
        case 41u: {
            let r = vsgl_specular_receiver_from(in3(0u), in3(3u), in1(6u));
            out1(0u, r.n_dot_v);
            out1(1u, r.lambda_v);
            out3(2u, r.asg.x_axis);
            out1(5u, r.asg.x_bandwidth);
            out3(6u, r.asg.y_axis);
            out1(9u, r.asg.y_bandwidth);
            out3(10u, r.asg.z_axis);
        }
        case 42u: { out1(0u, vsgl_specular_with_receiver(in_sg(0u), vsgl_specular_receiver_from(in3(5u), in3(8u), in1(11u)))); }
        // vsgl.wgsl, lighting="blend" (append-only ids)
        case 43u: { out1(0u, vsgl_specular_blend(in_sg(0u), in3(5u), in3(8u), in1(11u))); }
        case 44u: {
            let f = vsgl_specular_filtered(in_sg(0u), in3(5u), in3(8u), in1(11u));
            out1(0u, f.x);
            out1(1u, f.y);
        }
        case 45u: { out1(0u, vsgl_specular_blend_with_receiver(in_sg(0u), vsgl_specular_receiver_from(in3(5u), in3(8u), in1(11u)))); }
        // vsgl_tangent_plane.wgsl (append-only ids)
        case 46u: {
            let plane = vsgl_tangent_plane_from_moments(in1(0u), in3(1u), in1(4u), in3(5u));
            out3(0u, plane.normal);
            out1(3u, plane.offset);
        }
        case 47u: { out1(0u, vsgl_tangent_plane_fade(VsglTangentPlane(in3(0u), in1(3u)), VsglPosition(in3(4u), in1(7u)), in3(8u))); }
        // Ids come from HarnessFunction only; anything else leaves the zeros.
        default: {}
    }
}
