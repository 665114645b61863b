// AOV packing (compute): the AOVs a frame reads back, written one after another into one buffer
// in the layout NumPy gets — (H, W, C) float32 each, row 0 at the top, and `ldr` as (H, W, 4)
// uint8 — so the readback copies exactly the bytes it returns and the CPU does no per-pixel
// work. Sums are formed in the order the CPU formed them before (indirect = diffuse +
// specular, image = direct + indirect), so every value is bit-identical to that path.
// Emitted radiance (the camera's G-buffer emission channel, where a material emits) is part of
// what reaches the camera without a bounce: it is added to `direct`, so image = direct +
// indirect still holds, and never to `indirect`.
#include "common/gbuffer.wgsl"

const WORKGROUP: u32 = 8u;
// AOV kinds, in the order of `renderer::AOV_NAMES`.
const AOV_IMAGE: u32 = 0u;
const AOV_INDIRECT: u32 = 1u;
const AOV_INDIRECT_DIFFUSE: u32 = 2u;
const AOV_INDIRECT_SPECULAR: u32 = 3u;
const AOV_DIRECT: u32 = 4u;
const AOV_ALBEDO: u32 = 5u;
const AOV_NORMAL: u32 = 6u;
const AOV_DEPTH: u32 = 7u;
const AOV_STDERR: u32 = 8u;
const AOV_LDR: u32 = 9u;
const MAX_ENTRIES: u32 = 10u;

struct PackParams {
    width: u32,
    height: u32,
    count: u32,
    // bit 0: the method makes indirect light; bit 1: the specular target exists (else it is a
    // placeholder and reads as zero); bit 2: the emission channel exists (else a placeholder,
    // and nothing is added: frames of scenes without emission keep every bit); bit 3: the
    // emitter VSGLs' direct light (emitter_direct="sg") is added to the direct light (else its
    // bindings are stand-ins, not read).
    flags: u32,
    // (kind, first word in `packed`, 0, 0) per packed AOV.
    entries: array<vec4u, MAX_ENTRIES>,
}

@group(0) @binding(0) var<uniform> params: PackParams;
@group(0) @binding(1) var<storage, read> direct: array<vec4f>;
@group(0) @binding(2) var<storage, read> indirect_diffuse: array<vec4f>;
@group(0) @binding(3) var<storage, read> indirect_specular: array<vec4f>;
@group(0) @binding(4) var<storage, read> gbuf_position: array<vec4f>;
@group(0) @binding(5) var<storage, read> gbuf_normal: array<vec4f>;
@group(0) @binding(6) var<storage, read> gbuf_base_color: array<vec4f>;
@group(0) @binding(7) var<storage, read> stderr_in: array<vec4f>;
@group(0) @binding(10) var<storage, read> gbuf_emission: array<vec4f>;
@group(0) @binding(11) var<storage, read> emitter_direct_diffuse: array<vec4f>;
@group(0) @binding(12) var<storage, read> emitter_direct_specular: array<vec4f>;
// Words: float AOVs as their bit patterns, `ldr` as one RGBA8 word a pixel.
@group(0) @binding(8) var<storage, read_write> packed: array<u32>;
// Words 0 … MAX_ENTRIES − 1: per packed AOV, how many of its values are NaN or ±Inf (the
// image's, for `ldr`), so no frame hands out a non-finite value unnoticed. Word COVERED: pixels
// that see a surface; word LIT: pixels whose image is not black (the frame's warnings about
// black images). Zero before the pass; read back with the AOVs.
const COVERED: u32 = MAX_ENTRIES;
const LIT: u32 = MAX_ENTRIES + 1u;
@group(0) @binding(9) var<storage, read_write> counts: array<atomic<u32>, 12>;

// The workgroup's COVERED and LIT counts, added to `counts` once per workgroup.
var<workgroup> group_covered: atomic<u32>;
var<workgroup> group_lit: atomic<u32>;

// The specular target, or zero where it is a placeholder (no specular materials).
fn specular_or_zero(i: u32) -> vec3f {
    var s = vec3f(0.0);
    if ((params.flags & 2u) != 0u) {
        s = indirect_specular[i].rgb;
    }
    return s;
}

// Direct light: the direct pass's, plus the emitter VSGLs' where they shade emitters.
fn direct_light(i: u32) -> vec3f {
    if ((params.flags & 8u) == 0u) {
        return direct[i].rgb;
    }
    var d = direct[i].rgb + emitter_direct_diffuse[i].rgb;
    if ((params.flags & 2u) != 0u) {
        d += emitter_direct_specular[i].rgb;
    }
    return d;
}

// What reaches the camera without a bounce: direct light plus emitted radiance.
fn direct_radiance(i: u32) -> vec3f {
    if ((params.flags & 4u) == 0u) {
        return direct_light(i);
    }
    return direct_light(i) + gbuf_emission[i].rgb;
}

fn indirect_sum(i: u32) -> vec3f {
    return indirect_diffuse[i].rgb + specular_or_zero(i);
}

fn image(i: u32) -> vec3f {
    if ((params.flags & 1u) == 0u) {
        return direct_radiance(i);
    }
    return direct_radiance(i) + indirect_sum(i);
}

fn is_finite(x: f32) -> bool {
    return (bitcast<u32>(x) & 0x7f800000u) != 0x7f800000u;
}

// The sRGB transfer function [IEC 61966-2-1], as image_io::srgb_encode.
fn srgb_encode(x: f32) -> f32 {
    if (x <= 0.0031308) {
        return 12.92 * x;
    }
    return 1.055 * pow(x, 1.0 / 2.4) - 0.055;
}

// One channel as `Frame.save(".png")` writes it (exposure 1): clamp to [0, 1], encode, round.
fn ldr_channel(v: f32) -> u32 {
    var x = 0.0;
    if (is_finite(v)) {
        x = clamp(v, 0.0, 1.0);
    }
    return min(u32(srgb_encode(x) * 255.0 + 0.5), 255u);
}

fn count_nonfinite(e: u32, v: vec3f) {
    let bad = u32(!is_finite(v.x)) + u32(!is_finite(v.y)) + u32(!is_finite(v.z));
    // Rare by design: the atomic runs only for a non-finite value.
    if (bad > 0u) {
        atomicAdd(&counts[e], bad);
    }
}

// Writes entry e's three words of pixel i and counts their non-finite values.
fn put3(e: u32, base: u32, i: u32, v: vec3f) {
    count_nonfinite(e, v);
    packed[base + 3u * i] = bitcast<u32>(v.x);
    packed[base + 3u * i + 1u] = bitcast<u32>(v.y);
    packed[base + 3u * i + 2u] = bitcast<u32>(v.z);
}

@compute @workgroup_size(WORKGROUP, WORKGROUP)
fn main(@builtin(global_invocation_id) id: vec3u, @builtin(local_invocation_index) local: u32) {
    let inside = id.x < params.width && id.y < params.height;
    if (inside) {
        pack_pixel(id.y * params.width + id.x);
    }
    workgroupBarrier();
    if (local == 0u) {
        let covered = atomicLoad(&group_covered);
        let lit = atomicLoad(&group_lit);
        if (covered > 0u) {
            atomicAdd(&counts[COVERED], covered);
        }
        if (lit > 0u) {
            atomicAdd(&counts[LIT], lit);
        }
    }
}

fn pack_pixel(i: u32) {
    // Read once: every AOV below that needs the image (image, ldr, the lit count) shares it.
    let img = image(i);
    if (gbuf_position[i].w != GBUFFER_BACKGROUND) {
        atomicAdd(&group_covered, 1u);
    }
    if (any(img != vec3f(0.0))) {
        atomicAdd(&group_lit, 1u);
    }
    for (var e = 0u; e < min(params.count, MAX_ENTRIES); e++) {
        let kind = params.entries[e].x;
        let base = params.entries[e].y;
        switch kind {
            case AOV_IMAGE: { put3(e, base, i, img); }
            case AOV_INDIRECT: { put3(e, base, i, indirect_sum(i)); }
            case AOV_INDIRECT_DIFFUSE: { put3(e, base, i, indirect_diffuse[i].rgb); }
            case AOV_INDIRECT_SPECULAR: { put3(e, base, i, specular_or_zero(i)); }
            case AOV_DIRECT: { put3(e, base, i, direct_radiance(i)); }
            case AOV_ALBEDO: { put3(e, base, i, gbuf_base_color[i].rgb); }
            case AOV_NORMAL: { put3(e, base, i, gbuf_normal[i].xyz); }
            case AOV_DEPTH: {
                // View depth; 0 where no surface was hit (never Inf).
                let w = gbuf_position[i].w;
                packed[base + i] = bitcast<u32>(select(0.0, w, w > 0.0));
            }
            case AOV_STDERR: { put3(e, base, i, stderr_in[i].rgb); }
            case AOV_LDR: {
                count_nonfinite(e, img);
                packed[base + i] = ldr_channel(img.x) | (ldr_channel(img.y) << 8u) | (ldr_channel(img.z) << 16u) | (255u << 24u);
            }
            default: {}
        }
    }
}
