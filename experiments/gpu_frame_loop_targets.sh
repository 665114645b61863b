#!/usr/bin/env bash
# The frame-loop targets on a GPU, in two device calls (each fits one 600 s call; results under $OUT):
#   bash experiments/gpu_frame_loop_targets.sh timings    # ~2 min: warm per-pass timings at 1920x1080 of every
#                                          # shading configuration the targets name, and the wall
#                                          # time of a render() loop vs render_sequence per AOV set
#   bash experiments/gpu_frame_loop_targets.sh stability  # ~6.5 min: one configuration timed at the start, after a
#                                          # 5-minute sweep and after a long GPU job (<= 10% apart?)
# Prepare .gl/ and .whl/ and begin the device command with the device preamble (experiments/README.md, "Running a device script").
set -uo pipefail
OUT=$(realpath -m "${OUT:-out}"); mkdir -p "$OUT"  # absolute: the script changes directory
export PYTHONUNBUFFERED=1
cd "$(dirname "$0")"
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm --format=csv > "$OUT/gpu.txt" 2>&1; cat "$OUT/gpu.txt"
case "${1:-timings}" in
  timings)
    common=(--size 1920x1080 --frames 30 --scenes cornell_box --aovs image --warm-seconds 6)
    # The shading targets: vpl/vsgl with 1024 lights per pixel (interleave 1) <= 6 ms; 8x8
    # interleaved vsgl_shading and denoise <= 0.15 ms each; VSGL generation <= 0.05 ms; the
    # whole vsgl frame <= 1.2 ms.
    timeout 100 python3 gpu_timings.py "${common[@]}" --methods direct,vsgl,vsgl2,vpl --tag _k8 --vpl-interleave 8 | cut -c1-600
    timeout 100 python3 gpu_timings.py "${common[@]}" --methods vsgl,vpl --interleave 1 --vpl-interleave 1 --tag _k1 | cut -c1-600
    # Wall time: render() loop and render_sequence (next frame on the GPU during the readback;
    # moving camera without re-upload) with aovs [], image, ldr: image <= 4 ms over the GPU
    # time, >= 150 frames/s with ldr.
    timeout 150 python3 gpu_frame_wall.py --size 1920x1080 --frames 60 --methods direct,vsgl
    ;;
  stability)
    timeout 560 python3 gpu_clock_stability.py --size 1920x1080 --sweep-seconds 300 --job-seconds 30 --idle-seconds 20
    ;;
  *) echo "usage: $0 timings|stability" >&2; exit 2 ;;
esac
