// Where a k-means texel sits in its clustering space [Tok16 Appendix D]: "kmeans2d" clusters
// in RSM texel coordinates (the texel's centre), "kmeans3d" in world positions (relative to the
// light, as the moment chains hold them: chain E's w·y over chain A's w). The including shader
// declares `moments` (the chains of passes/vsgl_moments.wgsl, level 0 first in each).
// vsgl:include-only (validated inside the shaders that include it)

fn kmeans_texel_point(space: u32, texel: u32, rsm_size: u32, chain_len: u32) -> vec3f {
    if (space == 0u) {
        return vec3f(f32(texel % rsm_size) + 0.5, f32(texel / rsm_size) + 0.5, 0.0);
    }
    let w = moments[texel].w;
    return moments[4u * chain_len + texel].xyz / max(w, FLT_MIN);
}
