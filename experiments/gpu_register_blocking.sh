#!/usr/bin/env bash
# One device call after register blocking in vsgl_shading and line tiles in denoise (this
# session's second call; results under $OUT, each step capped by what is left of $BUDGET s):
#   1 the shading builds back to back (experiments/gpu_shading_compare.sh, SHADING_ONLY): the
#     previous build (.whl-old), this one (.whl, PIXELS_PER_THREAD = 2, tiled denoise) and the
#     P = 1 / P = 4 builds (.whl-var/), vsgl at interleave 1 (the 6 ms target) and 8x8 (the
#     0.15 ms targets of vsgl_shading and denoise);
#   2 the scene-level stability suite with the surface-flip rule (143 of 162 rows passed on the
#     first call, before it);
#   3 the temporal (sequence) benchmark, now that bench warms until the SM clock is up;
#   4 the kernels x lighting x importance sweep on caustics_ring re-timed warm (the first call had rows at 360-900 MHz).
#   prepare .gl/ and .whl/ (experiments/README.md, "Running a device script"); .whl-old/ and .whl-var/P1.whl, P4.whl as gpu_shading_compare.sh says
#   device (carry .gl .whl .whl-old .whl-var): <device preamble> bash experiments/gpu_register_blocking.sh
#   locally: SMOKE=1 bash experiments/gpu_register_blocking.sh
set -uo pipefail
source "$(dirname "$0")/gpu_common.sh"  # $FINAL_OUT, $RES, pack, step, require_gpu; cd to the repository root
BUDGET=${BUDGET:-380}
T0=$SECONDS
if [ "${SMOKE:-0}" = 1 ]; then
  SIZE=96x64; MID=48x32; SEQ=3; RSM_SEQ=128; SPP=16
else
  SIZE=1920x1080; MID=960x540; SEQ=16; RSM_SEQ=512; SPP=4096
fi
{
require_gpu
step shading 190 env OUT="$RES/shading" SIZE="$SIZE" SHADING_ONLY=1 FULL_METHODS=vsgl bash experiments/gpu_shading_compare.sh
TAIL=25 step stability 40 sh -c 'python3 -m vsgl stability --scenes --verbose | grep -v " pass$"'
TAIL=16 step bench_temporal 60 python3 -m vsgl bench --scene cave_flashlight --methods vpl,vsgl --K 1,4 --sequence "$SEQ" \
  --sampling stratified,metropolis --size "$MID" --lights 1024 --rsm-sizes 256 --seeds 1 --frames 3 \
  --reference-rsm "$RSM_SEQ" --no-progress --out "$RES/bench_temporal"
TAIL=30 step bench_kernels_lighting_importance_ring 150 python3 -m vsgl bench --scene caustics_ring --methods vsgl,vpl \
  --kernels integral,node --lighting asg,accurate --importance rsm,brsm --lights 1024,4096 --size "$MID" \
  --rsm-sizes 256 --seeds 2 --frames 4 --reference pathtrace --reference-strategy bidirectional \
  --reference-spp "$SPP" --no-progress --out "$RES/bench_kernels_lighting_importance_ring"
echo "== done in $((SECONDS - T0)) s"
} 2>&1 | tee "$FINAL_OUT/log.txt"
# Only the text and JSON come back (plots and caches made the archive too large on the first call).
find "$RES" \( -name '*.png' -o -name '*.npy' -o -name '*.npz' -o -path '*cache*' \) -delete 2>/dev/null
pack
