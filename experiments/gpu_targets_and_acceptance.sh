#!/usr/bin/env bash
# Every GPU figure still owed, in ONE device call that fits a 15-minute lease: the steps run in
# order of importance, each under a timeout cut to what is left of the budget ($BUDGET seconds,
# default 520), and everything each step writes is packed into $OUT/results.tgz after every step,
# so a step that runs out of time loses only itself. The full output is in $OUT/log.txt.
#
#   prepare .gl/ and .whl/ (experiments/README.md, "Running a device script")
#   device run (carry .gl .whl, timeout_s 590): <device preamble> bash experiments/gpu_targets_and_acceptance.sh
#   locally, as a smoke test of every step at toy sizes on lavapipe: SMOKE=1 bash experiments/gpu_targets_and_acceptance.sh
#
# Order (why): 1 the adapter must be a GPU, else stop at once (a rerun is cheaper than a useless
# lease); 2 the per-pass timings against the performance targets (the wave's first
# complaint: numbers that depend on the clock state); 3–4 VSGLs against the path tracer at a GPU size,
# with and without shadow rays, and its equal-time table on GPU wall time; 5–6 the cost of
# `lambert_lobe` and of bidirectional importance by pass; 7 the frame loop's wall time; 8 the
# visibility timings; 9 the benchmark at 960x540 on the glossy and caustic
# built-ins; 10 the clock stability, shortened to what is left.
set -uo pipefail
source "$(dirname "$0")/gpu_common.sh"  # $FINAL_OUT, $RES, pack, step, require_gpu; cd to the repository root
BUDGET=${BUDGET:-520}
T0=$SECONDS
if [ "${SMOKE:-0}" = 1 ]; then
  BIG=96x64; MID=64x48; SQ=32; N_HI=1024; N_ACC=256,1024; FR=3; WARM=0.5; ROUNDS=2; SPP=16
else
  BIG=1920x1080; MID=960x540; SQ=256; N_HI=65536; N_ACC=256,1024,4096,16384,65536; FR=30; WARM=6; ROUNDS=9; SPP=4096
fi

{
require_gpu

common=(--size "$BIG" --frames "$FR" --scenes cornell_box --aovs image --warm-seconds "$WARM")
# Targets (the frame-loop targets, experiments/gpu_targets_and_acceptance.md): vpl/vsgl with 1024 lights per pixel at interleave 1 <= 6 ms; 8x8 vsgl_shading
# and denoise <= 0.15 ms each; VSGL generation <= 0.05 ms; the whole vsgl frame <= 1.2 ms.
step timings_k8 80 python3 experiments/gpu_timings.py "${common[@]}" --methods direct,vsgl,vsgl2,vpl --tag _k8 --vpl-interleave 8
step timings_k1 60 python3 experiments/gpu_timings.py "${common[@]}" --methods vsgl,vpl --interleave 1 --vpl-interleave 1 --tag _k1
TAIL=40 step vsgl_vs_pathtracer_none 110 python3 experiments/vsgl_vs_pathtracer.py --size "$SQ" --lights "$N_ACC" --brsm \
  --cache "$RES/truth" --out "$RES/vsgl_vs_pathtracer_none.json"
TAIL=40 step vsgl_vs_pathtracer_raytrace 110 python3 experiments/vsgl_vs_pathtracer.py --size "$SQ" --lights "${N_ACC%,65536}" \
  --visibility raytrace --cache "$RES/truth" --time-rounds 5 --out "$RES/vsgl_vs_pathtracer_raytrace.json"
rm -rf "$RES/truth"; pack  # the truths are re-made in seconds; keep the archive small
step lambert_lobe 50 python3 experiments/lambert_lobe_timing.py --size "$SQ" --lights 1024,4096 --rounds "$ROUNDS"
step brsm_cost 50 python3 experiments/brsm_importance_timing.py --size "$SQ" --rsm 256 --rounds "$ROUNDS" --interleaves 1,2,4
step frame_wall 60 python3 experiments/gpu_frame_wall.py --size "$BIG" --frames 40 --methods direct,vsgl
step visibility 90 python3 experiments/gpu_visibility_and_flicker.py --size "$MID" --frames 7 --warm-seconds 2 --methods vsgl,vpl
TAIL=30 step bench_vs_pathtracer 120 python3 -m vsgl bench --scene glossy_cornell,caustics_ring --methods vsgl,vpl,vsgl2 \
  --lights 256,1024,4096 --size "$MID" --rsm-sizes 256 --seeds 2 --frames 5 --warmup-seconds 1 \
  --reference pathtrace --reference-strategy bidirectional --reference-spp "$SPP" --no-progress --out "$RES/bench_vs_pathtracer"
left=$((BUDGET - (SECONDS - T0) - 25))
[ "$left" -gt 60 ] && sweep=$(( (left - 40) * 2 / 3 )) || sweep=0
[ "$sweep" -gt 300 ] && sweep=300
if [ "$sweep" -ge 20 ]; then
  step stability "$left" python3 experiments/gpu_clock_stability.py --size "$BIG" --sweep-seconds "$sweep" --job-seconds 10 --idle-seconds 10
else
  echo "== stability: SKIPPED (${left} s left)"
fi
echo "== done in $((SECONDS - T0)) s"
} 2>&1 | tee "$FINAL_OUT/log.txt"
pack
