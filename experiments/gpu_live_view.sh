#!/usr/bin/env bash
# The live view's frame source on a GPU, in ONE device call: ViewSession.frame() (render, `ldr`
# readback, compositing) at 960x540 and 1920x1080 on cornell_box and FlightHelmet, one method
# and two compared, after a warm-up minute. The target (the live-view issue): >= 30 frames per
# second at 960x540 for the widget's source. The same script then times the desktop window's frame
# path offscreen (render with ldr kept on the GPU, compose, egui panel, blit to a BGRA8 stand-in
# for the surface; target >= 120 fps at 1920x1080). The device has no package registry, so the widget's
# JPEG/PNG encode is timed only if jupyter_rfb and simplejpeg wheels were carried in .whl.
#
#   device run (carry .gl .whl .scenes, timeout_s 400): <device preamble> bash experiments/gpu_live_view.sh
#   locally, at toy sizes on lavapipe: SMOKE=1 bash experiments/gpu_live_view.sh
set -uo pipefail
source "$(dirname "$0")/gpu_common.sh"  # $FINAL_OUT, $RES, pack, step, require_gpu; cd to the repository root
BUDGET=${BUDGET:-360}
T0=$SECONDS
if [ "${SMOKE:-0}" = 1 ]; then SIZES=(64x36); FRAMES=3; WARM=64x36; else SIZES=(960x540 1920x1080); FRAMES=60; WARM=1920x1080; fi
export VSGL_SCENES=${VSGL_SCENES:-$PWD/.scenes}
{
require_gpu
step warmup 90 python3 -m vsgl render glossy_cornell --method vsgl --size "$WARM" -o "$RES/warm.png"
for SIZE in "${SIZES[@]}"; do
  TAIL=20 step "live_view_$SIZE" 120 python3 experiments/live_view_frame_rate.py --size "$SIZE" --frames "$FRAMES"
done
echo "== done in $((SECONDS - T0)) s"
} 2>&1 | tee "$FINAL_OUT/log.txt"
pack
