// Imperfect shadow maps, built entirely in compute [Ritschel et al. 2008, "Imperfect Shadow Maps
// for Efficient Computation of Indirect Illumination", §3; Tok15 §5 and Tok16 §6 use them for
// every VSGL]: each virtual light's map receives a subset of the scene's point set (`splat`,
// one point per thread, an atomic depth test per texel instead of a rasterizer), then the holes
// that sparse points leave are filled by pull-push [Grossman & Dally 1998, "Point Sample
// Rendering", §6; Ritschel et al. 2008 §3.3]: `pull` averages the occupied texels of each 2×2
// block into the next coarser level (where at least two are occupied), `push` copies a coarse texel into the empty fine texels
// below it, coarsest first. Addressing and depth keys: common/ism.wgsl.
#include "common/constants.wgsl"
#include "common/frame.wgsl"
#include "common/ism.wgsl"

struct IsmBuildParams {
    map_size: u32,
    words_per_map: u32,
    // Maps this dispatch covers: first_map … first_map + map_count − 1 (a dispatch has at most
    // 65535 workgroups along y, so long light lists are built in chunks).
    first_map: u32,
    map_count: u32,
    // The scene's point set has point_count points; map m splats points_per_map of them, every
    // point_stride-th from (m mod point_stride), so neighbouring maps use disjoint subsets that
    // are each spread over the whole scene (the point set is stratified by area in this order).
    point_count: u32,
    points_per_map: u32,
    point_stride: u32,
    // A light record is light_record_words u32 words with its position (frame-relative vec3f)
    // first: Vpl and VsglRaw both start so.
    light_record_words: u32,
    // pull / push: the fine level (side 2·coarse_size) and the coarse level, as word offsets
    // within a map.
    fine_offset: u32,
    coarse_offset: u32,
    coarse_size: u32,
    _pad: u32,
}

// Points closer to the light than this fraction of the scene's extent have no direction from it
// (a VPL's own surface point); they are left out.
const ISM_MIN_DISTANCE_FRACTION: f32 = 1.0e-6;

@group(0) @binding(0) var<storage, read_write> ism_atlas: array<atomic<u32>>;
@group(0) @binding(1) var<uniform> params: IsmBuildParams;
@group(0) @binding(2) var<uniform> frame: FrameUniforms;
@group(0) @binding(3) var<storage, read> scene_points: array<vec4f>;
@group(0) @binding(4) var<storage, read> light_records: array<u32>;

const WORKGROUP: u32 = 64u;

// A coarse texel takes a depth only where at least half of its 2×2 children have one. Holes
// inside a sparsely splatted surface are filled (their neighbours are occupied), but the border
// of a surface against directions where nothing lies (the open side of a scene) is not grown
// outwards: push would otherwise copy nearby depths into empty sky and shadow what lies beyond.
const ISM_PULL_MIN_OCCUPIED: u32 = 2u;

@compute @workgroup_size(WORKGROUP, 1, 1)
fn splat(@builtin(global_invocation_id) gid: vec3u) {
    let m = params.first_map + gid.y;
    if (gid.x >= params.points_per_map || m >= params.first_map + params.map_count) {
        return;
    }
    let point_index = m % params.point_stride + gid.x * params.point_stride;
    if (point_index >= params.point_count) {
        return;
    }
    let record = m * params.light_record_words;
    let light = vec3f(bitcast<f32>(light_records[record]), bitcast<f32>(light_records[record + 1u]), bitcast<f32>(light_records[record + 2u]));
    // Points are relative to the upload anchor, lights to the eye (frame.view_origin from it).
    let d = (scene_points[point_index].xyz - frame.view_origin.xyz) - light;
    let distance = length(d);
    if (!(distance > ISM_MIN_DISTANCE_FRACTION * frame.scene_extent) || !(distance < FLT_MAX)) {
        return;
    }
    let texel = ism_texel(d / distance, params.map_size);
    atomicMax(&ism_atlas[m * params.words_per_map + texel.y * params.map_size + texel.x], ism_depth_key(distance));
}

@compute @workgroup_size(WORKGROUP, 1, 1)
fn pull(@builtin(global_invocation_id) gid: vec3u) {
    let m = params.first_map + gid.y;
    let coarse = params.coarse_size;
    if (gid.x >= coarse * coarse || m >= params.first_map + params.map_count) {
        return;
    }
    let x = gid.x % coarse;
    let y = gid.x / coarse;
    let fine = 2u * coarse;
    let base = m * params.words_per_map;
    var sum = 0.0;
    var occupied = 0u;
    for (var j = 0u; j < 2u; j++) {
        for (var i = 0u; i < 2u; i++) {
            let key = atomicLoad(&ism_atlas[base + params.fine_offset + (2u * y + j) * fine + 2u * x + i]);
            if (key != ISM_EMPTY) {
                sum += ism_key_depth(key);
                occupied += 1u;
            }
        }
    }
    var key = ISM_EMPTY;
    if (occupied >= ISM_PULL_MIN_OCCUPIED) {
        key = ism_depth_key(sum / f32(occupied));
    }
    atomicStore(&ism_atlas[base + params.coarse_offset + gid.x], key);
}

@compute @workgroup_size(WORKGROUP, 1, 1)
fn push(@builtin(global_invocation_id) gid: vec3u) {
    let m = params.first_map + gid.y;
    let fine = 2u * params.coarse_size;
    if (gid.x >= fine * fine || m >= params.first_map + params.map_count) {
        return;
    }
    let base = m * params.words_per_map;
    let at = base + params.fine_offset + gid.x;
    if (atomicLoad(&ism_atlas[at]) != ISM_EMPTY) {
        return;
    }
    let x = gid.x % fine;
    let y = gid.x / fine;
    let parent = atomicLoad(&ism_atlas[base + params.coarse_offset + (y / 2u) * params.coarse_size + x / 2u]);
    atomicStore(&ism_atlas[at], parent);
}
