// The VSGL as stored between generation and shading (96 bytes; twin `VsglRaw` in
// crates/vsgl-core/src/passes/vsgl_gen.rs, read by `Frame.vsgls()`).
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
    _pad: f32,
}
