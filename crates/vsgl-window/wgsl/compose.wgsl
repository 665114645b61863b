// The frame composition pass of the desktop window: the methods' `ldr` images (one RGBA8 word a
// pixel, as `aov_pack.wgsl` packs them: red in the low byte) are drawn into the window's target,
// the second right of a divider column when two methods are compared. The words are written as
// they are (the target is RGBA8 unorm holding sRGB-encoded bytes), so the target's pixels are the
// frame's bytes exactly.

struct Compose {
    // Width and height of the images and of the target.
    size: vec2<u32>,
    // First column shown from the right image; the divider is drawn on it.
    split: u32,
    // 1: the left image alone; 2: left and right with a divider.
    images: u32,
}

@group(0) @binding(0) var<uniform> compose: Compose;
@group(0) @binding(1) var<storage, read> left_image: array<u32>;
@group(0) @binding(2) var<storage, read> right_image: array<u32>;

@fragment
fn fs_main(@builtin(position) p: vec4<f32>) -> @location(0) vec4<f32> {
    let x = min(u32(p.x), compose.size.x - 1u);
    let y = min(u32(p.y), compose.size.y - 1u);
    let i = y * compose.size.x + x;
    if compose.images == 2u {
        if x == min(compose.split, compose.size.x - 1u) {
            return vec4<f32>(1.0);
        }
        if x >= compose.split {
            return unpack4x8unorm(right_image[i]);
        }
    }
    return unpack4x8unorm(left_image[i]);
}
