// Interleaved sampling [Keller & Heidrich 2001; Tok15 §5] with deinterleaved workgroups. With
// interleave k, pixel (x, y) belongs to class c = (y mod k)·k + (x mod k) and evaluates only
// the virtual lights j ≡ c (mod k²). A workgroup of the shading passes covers pixels of one
// class only (every k-th pixel in x and y), so its WORKGROUP² pixels need the same lights and
// one light load from device memory, staged in workgroup memory, serves all of them. k = 1 is
// the plain mapping (one class, every pixel evaluates every light).
//
// Dispatch size (crates/vsgl-core/src/gpu/dispatch.rs, `interleaved_groups`): per axis, k
// classes × ceil(ceil(size/k)/WORKGROUP) workgroups. A pass whose threads shade several pixels
// each (vsgl_shading's register blocking) covers a larger footprint of its class per workgroup
// (`interleaved_block_pixel`; `interleaved_block_groups` on the host).

struct InterleavedPixel {
    pixel: vec2u,
    // c = (y mod k)·k + (x mod k): the first light of the class (relative to the list's start).
    class_index: u32,
}

// The pixel of local thread `lid` of workgroup `wg` (workgroups of `workgroup`² threads).
fn interleaved_pixel(wg: vec3u, lid: vec3u, size: vec2u, k: u32, workgroup: u32) -> InterleavedPixel {
    return interleaved_block_pixel(wg, lid.xy, size, k, vec2u(workgroup));
}

// The pixel at `offset` (in pixels of the class, < footprint) within workgroup `wg`'s block,
// where each workgroup covers `footprint` pixels of its class along x and y. All pixels of a
// workgroup belong to one class, whatever the offset.
fn interleaved_block_pixel(wg: vec3u, offset: vec2u, size: vec2u, k: u32, footprint: vec2u) -> InterleavedPixel {
    // Workgroups per class along each axis.
    let per_class = (((size + vec2u(k - 1u)) / k) + footprint - vec2u(1u)) / footprint;
    let class_xy = wg.xy / per_class;
    let block = wg.xy % per_class;
    let pixel = class_xy + k * (block * footprint + offset);
    return InterleavedPixel(pixel, class_xy.y * k + class_xy.x);
}

// How many of the lights first … first + count − 1 a class evaluates (uniform over a
// workgroup, so the tile loop's barriers are in uniform control flow).
fn class_light_count(class_index: u32, count: u32, k: u32) -> u32 {
    let stride = k * k;
    if (class_index >= count) {
        return 0u;
    }
    return (count - class_index + stride - 1u) / stride;
}
