// Stable least-significant-digit radix sort of (key, value) pairs (compute), 8 bits a digit:
// the sort of the k-means clustering [Tok16 Appendix D: "texels sorted by cluster id (radix
// sort)"]. One digit is three dispatches over blocks of BLOCK pairs:
//   histogram: each block counts its digits            -> table[digit · blocks + block]
//   scan:      one workgroup turns the table, read digit-major, into exclusive offsets
//   scatter:   each pair goes to table[digit · blocks + block] + its rank among the pairs of
//              its block with the same digit that come before it
// Ranks keep the input order of equal digits (stable), so after the digits of a key the pairs
// are ordered by key and, among equal keys, by their order in the input: the same sort every run
// (no atomics decide an order), and the sums over a sorted run are the same floats every frame.
// The scatter's rank is a loop over the block's earlier pairs (≤ BLOCK − 1 iterations), which
// stays well inside lavapipe's cap on a shader invocation's loop iterations (65535 in all); the
// scan's one workgroup walks 2·⌈count/BLOCK⌉ entries per thread, inside the cap up to 8.4M pairs
// (a 2048² RSM: lavapipe's 128 MiB storage binding limit refuses a 4096² RSM before that).

struct SortParams {
    // Pairs to sort.
    count: u32,
    // Bit offset of this pass's digit.
    shift: u32,
    // ceil(count / BLOCK).
    blocks: u32,
    _pad: u32,
}

const BLOCK: u32 = 256u;
const RADIX: u32 = 256u;

@group(0) @binding(0) var<uniform> params: SortParams;
@group(0) @binding(1) var<storage, read> keys_in: array<u32>;
@group(0) @binding(2) var<storage, read> values_in: array<u32>;
@group(0) @binding(3) var<storage, read_write> keys_out: array<u32>;
@group(0) @binding(4) var<storage, read_write> values_out: array<u32>;
@group(0) @binding(5) var<storage, read_write> table: array<u32>;

var<workgroup> counts: array<atomic<u32>, RADIX>;
var<workgroup> digits: array<u32, BLOCK>;
var<workgroup> partial: array<u32, BLOCK>;

fn digit_of(key: u32) -> u32 {
    return (key >> params.shift) & (RADIX - 1u);
}

@compute @workgroup_size(BLOCK, 1, 1)
fn histogram(@builtin(workgroup_id) block: vec3u, @builtin(local_invocation_index) t: u32) {
    atomicStore(&counts[t], 0u);
    workgroupBarrier();
    let i = block.x * BLOCK + t;
    if (i < params.count) {
        atomicAdd(&counts[digit_of(keys_in[i])], 1u);
    }
    workgroupBarrier();
    table[t * params.blocks + block.x] = atomicLoad(&counts[t]);
}

// One workgroup: thread t sums its contiguous run of the table, the 256 run totals are scanned
// in workgroup memory (Hillis–Steele), and each run is rewritten as exclusive prefixes.
@compute @workgroup_size(BLOCK, 1, 1)
fn scan(@builtin(local_invocation_index) t: u32) {
    let len = RADIX * params.blocks;
    let run = (len + BLOCK - 1u) / BLOCK;
    let begin = min(t * run, len);
    let end = min(begin + run, len);
    var sum = 0u;
    for (var j = begin; j < end; j++) {
        sum += table[j];
    }
    partial[t] = sum;
    workgroupBarrier();
    for (var step = 1u; step < BLOCK; step *= 2u) {
        var add = 0u;
        if (t >= step) {
            add = partial[t - step];
        }
        workgroupBarrier();
        partial[t] += add;
        workgroupBarrier();
    }
    var running = partial[t] - sum;
    for (var j = begin; j < end; j++) {
        let c = table[j];
        table[j] = running;
        running += c;
    }
}

@compute @workgroup_size(BLOCK, 1, 1)
fn scatter(@builtin(workgroup_id) block: vec3u, @builtin(local_invocation_index) t: u32) {
    let i = block.x * BLOCK + t;
    var d = RADIX;
    if (i < params.count) {
        d = digit_of(keys_in[i]);
    }
    digits[t] = d;
    workgroupBarrier();
    if (i >= params.count) {
        return;
    }
    var rank = 0u;
    for (var j = 0u; j < t; j++) {
        rank += u32(digits[j] == d);
    }
    let at = table[d * params.blocks + block.x] + rank;
    keys_out[at] = keys_in[i];
    values_out[at] = values_in[i];
}
