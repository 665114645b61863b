#!/usr/bin/env bash
# What one emissive lamp next to one spot light costs each method on a GPU, in ONE device call:
# experiments/emitter_cost.py at 1920x1080 (CornellBoxOriginal, its spot against spot + its
# ceiling lamp made emissive, frames alternated, median GPU totals), with the default
# emitter_lights (1) and with 4, after a warm-up minute; then emitter_direct="sg" against the
# point sum (experiments/emitter_soft_shadows.py: error against the path tracer, frame wall time).
#
#   device run (carry .gl .whl .scenes, timeout_s 300): <device preamble> bash experiments/gpu_emitter_cost.sh
#   (.scenes: a copy of the shared scene folder, as for gpu_corpus.sh)
#   locally, at a toy size on lavapipe: SMOKE=1 bash experiments/gpu_emitter_cost.sh
set -uo pipefail
source "$(dirname "$0")/gpu_common.sh"  # $FINAL_OUT, $RES, pack, step, require_gpu; cd to the repository root
BUDGET=${BUDGET:-350}
T0=$SECONDS
if [ "${SMOKE:-0}" = 1 ]; then SIZE=64x36; FRAMES=2; WARM=64x36; else SIZE=1920x1080; FRAMES=21; WARM=1920x1080; fi
export VSGL_SCENES=${VSGL_SCENES:-$PWD/.scenes}
{
require_gpu
step warmup 60 python3 -m vsgl render glossy_cornell --method vsgl --size "$WARM" -o "$RES/warm.png"
step emitter_cost_default 90 python3 experiments/emitter_cost.py --size "$SIZE" --frames "$FRAMES" --methods direct,vpl,vsgl,vsgl2,lpv
step emitter_cost_4 90 python3 experiments/emitter_cost.py --size "$SIZE" --frames "$FRAMES" --methods direct,vpl,vsgl,vsgl2,lpv --emitter-lights 4
step emitter_soft_shadows 90 python3 experiments/emitter_soft_shadows.py --size 512 --spp 256 --frames 9
echo "== done in $((SECONDS - T0)) s"
} 2>&1 | tee "$FINAL_OUT/log.txt"
pack
