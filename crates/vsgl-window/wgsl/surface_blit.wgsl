// Copies the window's target (RGBA8 unorm, sRGB-encoded bytes) texel for texel onto the surface,
// viewed in its non-sRGB format so the bytes reach the display unchanged whatever the surface's
// channel order (BGRA on most X11 and Windows surfaces).

@group(0) @binding(0) var target_image: texture_2d<f32>;

@fragment
fn fs_main(@builtin(position) p: vec4<f32>) -> @location(0) vec4<f32> {
    let size = textureDimensions(target_image);
    let texel = min(vec2<u32>(p.xy), size - 1u);
    return textureLoad(target_image, texel, 0);
}
