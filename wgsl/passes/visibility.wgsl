// Visibility raster: depth and the id of the visible triangle, nothing else. Material
// evaluation happens in compute (passes/material.wgsl): on the H100 the same per-pixel work ran
// 32× slower in a fragment shader (measured on an H100 while the pass was built; experiments/README.md).
#include "common/frame.wgsl"

@group(0) @binding(0) var<uniform> frame: FrameUniforms;

struct VsOut {
    @builtin(position) clip: vec4f,
    @location(0) @interpolate(flat) triangle: u32,
}

@vertex
fn vs_main(@location(0) position: vec3f, @location(1) triangle: u32) -> VsOut {
    var out: VsOut;
    out.clip = frame.view_proj * vec4f(position, 1.0);
    out.triangle = triangle;
    return out;
}

// 0 means background; triangle ids are stored + 1.
@fragment
fn fs_main(in: VsOut) -> @location(0) u32 {
    return in.triangle + 1u;
}
