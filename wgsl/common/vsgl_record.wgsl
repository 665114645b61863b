// The VSGL as stored between generation and shading (128 bytes; twin `VsglRaw` in
// crates/vsgl-core/src/passes/vsgl_gen.rs, read by `Frame.vsgls()`).
#include "common/sg.wgsl"
struct VsglRaw {
    // Positional Gaussian: mean relative to the frame origin (the camera), variance σ².
    mean: vec3f,
    variance: f32,
    // Diffuse radiant-intensity lobe: unit axis and sharpness; its power is diffuse_power (rgb):
    // I_d(ω) = diffuse_power · G(ω; axis, λ)/A(λ).
    diffuse_axis: vec3f,
    diffuse_sharpness: f32,
    diffuse_power: vec3f,
    // Mip level of the kernel (diagnostics and plots).
    level: f32,
    specular_axis: vec3f,
    specular_sharpness: f32,
    specular_power: vec3f,
    // Sampling density p(s) of the kernel centre on the unit RSM square (diagnostics).
    pdf: f32,
    // Kernel centre s in level-0 RSM texel units, and the kernel's probability mass
    // (4^l/M)·p̄(s, l) at the chosen level (what the integral kernel's bisection solves for).
    center: vec2f,
    mass: f32,
    // Texels in the cluster where the clustering knows them (k-means: its exact count), else 0.
    texels: f32,
    // The cluster's mean tangent plane: plane_normal = Σw·n/Σw (not unit:
    // its length says how coherent the normals are), plane_offset = E_w[(μ − y)·n], so that
    // (p − μ)·plane_normal + plane_offset is the weighted mean height of p above the texels'
    // tangent planes. Zero when the shading mode does not use it (vsgl_tangent_plane_fade).
    plane_normal: vec3f,
    plane_offset: f32,
    // Where `visibility="raytrace"` aims its shadow ray: the sampled centre texel's
    // own surface point (relative to the frame origin, like `mean`), not μ. μ of a cluster that
    // wraps around an object lies inside it, and one ray to μ shadows the whole cluster at once;
    // the centre is a lit surface point drawn from the sampling density, so over the VSGLs
    // V(p, centre) estimates the cluster's texel-averaged visibility (noise, not bias).
    shadow_target: vec3f,
    _pad2: f32,
}

// The record's radiant-intensity lobes as normalized SGs (amplitude 1/A(λ): per unit power), as
// every pass that shades VSGLs needs them (the includer brings common/sg.wgsl). The diffuse
// lobe takes `lambert_gain`: LAMBERT_LOBE_HEMISPHERE_GAIN normalizes it over each texel's
// hemisphere (lambert_lobe="hemisphere", the default), 1 keeps the papers' sphere
// normalization [Tok16s Eq. 1]. A cluster's lobe is the Toksvig merge of its texels' lobes, so
// the texels' normalization is one factor on the merged lobe.
fn vsgl_record_diffuse_lobe(v: VsglRaw, lambert_gain: f32) -> Sg {
    return Sg(v.diffuse_axis, v.diffuse_sharpness, lambert_gain / sg_integral(v.diffuse_sharpness));
}

fn vsgl_record_specular_lobe(v: VsglRaw) -> Sg {
    return Sg(v.specular_axis, v.specular_sharpness, 1.0 / sg_integral(v.specular_sharpness));
}
