// The vertex stage of the window's passes: one triangle covering the target (vertices 0, 1, 2
// at clip-space (-1, -1), (3, -1), (-1, 3)); each pass's fragment stage reads its own pixel.
// Prepended to each pass's WGSL by `crate::pass_shader`.

@vertex
fn vs_main(@builtin(vertex_index) v: u32) -> @builtin(position) vec4<f32> {
    // One triangle that covers the target.
    let uv = vec2<f32>(f32((v << 1u) & 2u), f32(v & 2u));
    return vec4<f32>(uv * 2.0 - 1.0, 0.0, 1.0);
}
