#!/usr/bin/env bash
# The GPU figures still owed after experiments/gpu_targets_and_acceptance.sh's call (docs/status.md, "Not yet on a
# GPU"), in ONE device call: steps in order of importance, each capped by what is left of $BUDGET
# seconds (default 430), results packed into $OUT/results.tgz after every step.
#
#   prepare .gl/ and .whl/ (experiments/README.md, "Running a device script")
#   device run (carry .gl .whl, timeout_s 480): <device preamble> bash experiments/gpu_exact_lambert_box_and_sweeps.sh
#   locally, a smoke test of every step at toy sizes on lavapipe: SMOKE=1 bash experiments/gpu_exact_lambert_box_and_sweeps.sh
#
# Steps (why):
#   1 the diffuse cornell_box, the one scene where the default VSGLs are not below VPLs: the exact
#     Lambertian point emitter for compact clusters (lambert_lobe="exact_compact") with either
#     kernel, N up to 65536, with and without shadow rays, against the converged path tracer;
#   2 the bench sweep at 960x540: kernels x lighting x importance on the glossy and caustic
#     built-ins, with per-pass GPU times (brsm's passes next to the papers' Table 1);
#   3 the temporal benchmark's error / flicker / time under the animated flashlight (the reference of each
#     sequence frame at RSM 512: at the bench's default 1024 the previous call ran out of time);
#   4 the scene-level stability suite on a GPU.
set -uo pipefail
source "$(dirname "$0")/gpu_common.sh"  # $FINAL_OUT, $RES, pack, step, require_gpu; cd to the repository root
BUDGET=${BUDGET:-430}
T0=$SECONDS
if [ "${SMOKE:-0}" = 1 ]; then
  SQ=32; N_ACC=256,1024; MID=64x48; SEQ_SIZE=48x32; SPP=16; SEQ=4; RSM_SEQ=128
else
  SQ=256; N_ACC=256,1024,4096,16384,65536; MID=960x540; SEQ_SIZE=960x540; SPP=4096; SEQ=16; RSM_SEQ=512
fi
{
require_gpu

xc="vpl,vsgl exact_compact,vsgl node exact_compact"
TAIL=30 step box_none 60 python3 experiments/vsgl_vs_pathtracer.py --scenes cornell_box --size "$SQ" --lights "$N_ACC" \
  --variants "$xc" --cache "$RES/truth" --out "$RES/box_none.json"
TAIL=30 step box_raytrace 60 python3 experiments/vsgl_vs_pathtracer.py --scenes cornell_box --size "$SQ" --lights "${N_ACC%,65536}" \
  --variants "$xc" --visibility raytrace --cache "$RES/truth" --out "$RES/box_raytrace.json"
rm -rf "$RES/truth"; pack
TAIL=40 step bench_kernels_lighting_importance 160 python3 -m vsgl bench --scene glossy_cornell,caustics_ring --methods vsgl,vpl \
  --kernels integral,node --lighting asg,accurate --importance rsm,brsm --lights 1024,4096 --size "$MID" \
  --rsm-sizes 256 --seeds 2 --frames 4 --warmup-seconds 0.3 --reference pathtrace --reference-strategy bidirectional \
  --reference-spp "$SPP" --no-progress --out "$RES/bench_kernels_lighting_importance"
TAIL=30 step bench_temporal 90 python3 -m vsgl bench --scene cave_flashlight --methods vpl,vsgl --K 1,4 --sequence "$SEQ" \
  --sampling stratified,metropolis --size "$SEQ_SIZE" --lights 1024 --rsm-sizes 256 --seeds 1 --frames 3 \
  --warmup-seconds 0.3 --reference-rsm "$RSM_SEQ" --no-progress --out "$RES/bench_temporal"
TAIL=20 step stability 60 python3 -m vsgl stability --scenes --verbose
echo "== done in $((SECONDS - T0)) s"
} 2>&1 | tee "$FINAL_OUT/log.txt"
pack
