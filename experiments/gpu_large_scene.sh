#!/usr/bin/env bash
# What a scene past one storage binding costs each method on a GPU, in ONE device call:
# experiments/large_scene_cost.py at 960x540 on the hidden-sheet scene of 6.69M triangles
# (vertices, BVH nodes and triangle corners in several 128 MiB pages), each method's first frame
# (upload, and the BVH build on the machine's cores: bvh_build_ms) and its warm GPU total against
# the same surfaces without the bulk, after a warm-up minute.
#
#   device run (carry .gl .whl, timeout_s 300): <device preamble> bash experiments/gpu_large_scene.sh
#   locally, at a toy size on lavapipe: SMOKE=1 bash experiments/gpu_large_scene.sh
set -uo pipefail
source "$(dirname "$0")/gpu_common.sh"  # $FINAL_OUT, $RES, pack, step, require_gpu; cd to the repository root
BUDGET=${BUDGET:-260}
T0=$SECONDS
if [ "${SMOKE:-0}" = 1 ]; then SIDE=200; SIZE=32x32; FRAMES=1; WARM=64x36; QUICK=--quick; else SIDE=1830; SIZE=960x540; FRAMES=7; WARM=1920x1080; QUICK=; fi
{
require_gpu
step warmup 60 python3 -m vsgl render glossy_cornell --method vsgl --size "$WARM" -o "$RES/warm.png"
step large_scene_cost 180 python3 experiments/large_scene_cost.py --side "$SIDE" --size "$SIZE" --frames "$FRAMES" $QUICK
echo "== done in $((SECONDS - T0)) s"
} 2>&1 | tee "$FINAL_OUT/log.txt"
pack
