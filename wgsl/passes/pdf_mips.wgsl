// One level of the sampling-weight pyramid (compute): each texel of level l is the sum of its
// 2×2 children in level l − 1, so the top level holds the total weight. All levels live in one
// buffer, level l starting at `offsets[l]`; level l is (N >> l)² texels.

struct Level {
    // Offset of the source level (l − 1) and of the destination level (l), in texels.
    src_offset: u32,
    dst_offset: u32,
    // Side of the destination level.
    dst_size: u32,
    _pad: u32,
}

const WORKGROUP: u32 = 8u;

@group(0) @binding(0) var<uniform> level: Level;
@group(0) @binding(1) var<storage, read_write> pyramid: array<f32>;

@compute @workgroup_size(WORKGROUP, WORKGROUP, 1)
fn main(@builtin(global_invocation_id) gid: vec3u) {
    let m = level.dst_size;
    if (gid.x >= m || gid.y >= m) {
        return;
    }
    let src_size = 2u * m;
    let s = level.src_offset + (2u * gid.y) * src_size + 2u * gid.x;
    let sum = (pyramid[s] + pyramid[s + 1u]) + (pyramid[s + src_size] + pyramid[s + src_size + 1u]);
    pyramid[level.dst_offset + gid.y * m + gid.x] = sum;
}
