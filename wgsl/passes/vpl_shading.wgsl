// VPL shading (compute): every pixel sums the VPLs of the current batch, without visibility
// (the papers' configuration for accuracy comparisons), or with `visibility="raytrace"`
// (VISIBILITY_TRACED) only those a shadow ray through the scene's BVH reaches, or with
// `visibility="ism"` (VISIBILITY_ISM) each weighted by its imperfect shadow map's lit fraction. With
// interleave k, a pixel sums only the VPLs of its class (j ≡ c mod k², common/interleave.wgsl) scaled by k², as VSGL shading
// does [Tok15 §5 compares both with 8×8 interleaving]; the denoise pass recombines them.
// A workgroup shades pixels of one class, so the VPLs it needs are the same for all its threads
// and are staged through workgroup memory in tiles: each is read from device memory once per
// workgroup. Results are added to the indirect buffers, so large VPL sets are shaded in several
// dispatches (the reference).
#include "common/constants.wgsl"
#include "common/frame.wgsl"
#include "common/gbuffer.wgsl"
#include "common/vpl.wgsl"
#include "common/interleave.wgsl"
#include "common/receiver.wgsl"
#include "common/light_visibility.wgsl"

struct ShadeParams {
    // This dispatch shades VPLs first … first + vpl_count − 1.
    vpl_count: u32,
    // Lower bound of the squared VPL distance (0 = unclamped).
    min_distance2: f32,
    first: u32,
    // Interleave factor k (1: every pixel sums every VPL).
    interleave: u32,
}

const WORKGROUP: u32 = 8u;
const TILE: u32 = 64u; // = WORKGROUP², one VPL loaded per thread

@group(0) @binding(0) var<uniform> frame: FrameUniforms;
@group(1) @binding(0) var<uniform> params: ShadeParams;
@group(1) @binding(1) var<storage, read> vpls: array<Vpl>;
@group(1) @binding(2) var<storage, read> gbuf_position: array<vec4f>;
@group(1) @binding(3) var<storage, read> gbuf_normal: array<vec4f>;
@group(1) @binding(4) var<storage, read> gbuf_geo_normal: array<vec4f>;
@group(1) @binding(5) var<storage, read> gbuf_base_color: array<vec4f>;
@group(1) @binding(6) var<storage, read_write> indirect_diffuse: array<vec4f>;
@group(1) @binding(7) var<storage, read_write> indirect_specular: array<vec4f>;

var<workgroup> tile: array<Vpl, TILE>;

@compute @workgroup_size(WORKGROUP, WORKGROUP, 1)
fn main(@builtin(workgroup_id) wg: vec3u, @builtin(local_invocation_id) lid: vec3u, @builtin(local_invocation_index) local: u32) {
    let k = params.interleave;
    let stride = k * k;
    let ip = interleaved_pixel(wg, lid, frame.size, k, WORKGROUP);
    let inside = ip.pixel.x < frame.size.x && ip.pixel.y < frame.size.y;
    let index = ip.pixel.y * frame.size.x + ip.pixel.x;
    var rcv = no_receiver();
    if (inside) {
        rcv = receiver_from_gbuffer(gbuf_position[index], gbuf_normal[index], gbuf_geo_normal[index], gbuf_base_color[index]);
    }
    let p = rcv.p;
    let n = rcv.n;
    let v = rcv.v;
    let rd = rcv.rd;
    let rs = rcv.rs;
    let alpha = rcv.alpha;
    let has_surface = rcv.has_surface;
    var geo_normal = vec3f(0.0, 0.0, 1.0);
    if (VISIBILITY_TRACED && has_surface) {
        geo_normal = gbuf_geo_normal[index].xyz;
    }
    let shadowing = shadow_receiver(has_surface, geo_normal, ip.pixel);
    var diffuse = vec3f(0.0);
    var specular = vec3f(0.0);
    // The class's VPLs are params.first + class_index + m·k², m = 0 … class_count − 1.
    let class_first = params.first + ip.class_index;
    let class_count = class_light_count(ip.class_index, params.vpl_count, k);
    // Every thread takes part in the tile loads and barriers, with a surface or not.
    for (var tile_start = 0u; tile_start < class_count; tile_start += TILE) {
        let m = tile_start + local;
        if (m < class_count) {
            tile[local] = vpls[class_first + m * stride];
        }
        workgroupBarrier();
        let n_tile = min(TILE, class_count - tile_start);
        if (has_surface) {
            for (var k = 0u; k < n_tile; k++) {
                var r = vpl_radiance(tile[k], p, n, v, rd, rs, alpha, params.min_distance2);
                // Visibility only where the VPL contributes (no ray or lookup for nothing).
                if ((VISIBILITY_TRACED || VISIBILITY_ISM) && any((r.diffuse + r.specular) > vec3f(0.0))) {
                    let lit = light_visibility(p, n, shadowing, class_first + (tile_start + k) * stride, tile[k].position);
                    if (lit <= 0.0) {
                        continue;
                    }
                    r.diffuse *= lit;
                    r.specular *= lit;
                }
                diffuse += r.diffuse;
                specular += r.specular;
            }
        }
        workgroupBarrier();
    }
    if (inside) {
        // × k² (exactly 1 without interleaving): each class stands for all k² of them.
        let scale = f32(stride);
        indirect_diffuse[index] += vec4f(min(diffuse * scale, vec3f(FLT_MAX)), 0.0);
        if (HAS_SPECULAR) {
            indirect_specular[index] += vec4f(min(specular * scale, vec3f(FLT_MAX)), 0.0);
        }
    }
}
