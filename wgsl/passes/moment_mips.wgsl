// One mip level of the VSGL moment chains (compute): 2×2 averages [Tok15 §4.1], the
// GenerateMips of the paper's implementation, which wgpu lacks.

struct Level {
    src_offset: u32,
    dst_offset: u32,
    dst_size: u32,
    chain_len: u32,
    // 5, or 6 with the tangent-plane chain F (frame/rsm.rs MomentChains).
    chains: u32,
}

const WORKGROUP: u32 = 8u;

@group(0) @binding(0) var<uniform> level: Level;
@group(0) @binding(1) var<storage, read_write> moments: array<vec4f>;

@compute @workgroup_size(WORKGROUP, WORKGROUP, 1)
fn main(@builtin(global_invocation_id) gid: vec3u) {
    let m = level.dst_size;
    if (gid.x >= m || gid.y >= m) {
        return;
    }
    let src_size = 2u * m;
    let s = level.src_offset + (2u * gid.y) * src_size + 2u * gid.x;
    let d = level.dst_offset + gid.y * m + gid.x;
    for (var c = 0u; c < level.chains; c++) {
        let base = c * level.chain_len;
        let sum = (moments[base + s] + moments[base + s + 1u]) + (moments[base + s + src_size] + moments[base + s + src_size + 1u]);
        moments[base + d] = 0.25 * sum;
    }
}
