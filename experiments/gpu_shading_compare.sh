#!/usr/bin/env bash
# Two builds' shading passes back to back on one warm GPU, then VSGLs against the path tracer with the
# new one (one device call, ~3 min; results under $OUT):
#   - the previous build's wheel in .whl-old/, this build's in .whl/ (installed to /tmp/site by
#     the device preamble);
#   - per-pass timings at 1920x1080 on cornell_box (R_s 0.04), diffuse_cornell (diffuse only) and
#     glossy_cornell, vsgl
#     and vpl at interleave 1 (1024 lights per pixel: the 6 ms target) and 8x8: old, new, the
#     diagnostic variants, new again (its difference from the first is the drift of the machine);
#   - vsgl_vs_pathtracer.py at 256² (GPU clock for the equal-time tables), with and without
#     shadow rays;
#   - vsgl2's subgroup against shared-memory reduction by RSM side;
#   - the temporal (sequence) benchmark on cave_flashlight, cut to fit (K = 1, 4; 20 frames; 512-spp truth).
#   prepare .gl/ and .whl/ (experiments/README.md, "Running a device script"); mkdir -p .whl-old && cp <previous wheel> .whl-old/
#   optional diagnostic builds in .whl-var/NAME.whl (timed once each, vsgl at interleave 1)
#   SHADING_ONLY=1: stop after the builds' timings; FULL_METHODS=vsgl: leave vpl out of them
#   device (carry .gl .whl .whl-old .whl-var): <device preamble> bash experiments/gpu_shading_compare.sh
set -uo pipefail
source "$(dirname "$0")/gpu_common.sh"  # $FINAL_OUT, $RES, pack; cd to the repository root
SIZE=${SIZE:-1920x1080} ACC_SIZE=${ACC_SIZE:-256} ACC_LIGHTS=${ACC_LIGHTS:-256,1024,4096,16384,65536}  # smaller for a smoke test
{
# Wheels are zip files: extracting them is installing them, whatever their platform tag.
python3 -m zipfile -e .whl-old/*.whl /tmp/old || exit 1
for w in .whl-var/*.whl; do [ -f "$w" ] && python3 -m zipfile -e "$w" "/tmp/var_$(basename "$w" .whl)"; done
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm --format=csv 2>&1 | tee "$RES/gpu.txt"
common=(--size "$SIZE" --frames 20 --scenes cornell_box,diffuse_cornell,glossy_cornell --aovs image --warm-seconds 3)
strip() { grep -v adapter | sed -E 's/  (visibility|shadow_map|material|direct|rsm_[a-z]+|aov_pack|pdf_mips|vsgl_moments|moment_mips|vsgl_gen|vpl_sample)=[^ ]+//g' | cut -c1-230; }
time_build() {  # NAME PYTHONPATH FULL: k1 vsgl (and vpl, k8 vsgl when FULL=1)
  local name=$1 path=$2 full=$3 methods=vsgl
  [ "$full" = 1 ] && methods=${FULL_METHODS:-vsgl,vpl}
  echo "-- $name"
  PYTHONPATH=$path timeout 90 python3 experiments/gpu_timings.py "${common[@]}" --methods $methods --interleave 1 --vpl-interleave 1 --tag "_k1_$name" 2>&1 | strip
  [ "$full" = 1 ] && PYTHONPATH=$path timeout 60 python3 experiments/gpu_timings.py "${common[@]}" --methods vsgl --tag "_k8_$name" 2>&1 | strip
  pack
}
# Diagnostic variants (.whl-var/, when present): "nospec" replaces the receiver's SG-ASG specular
# by a trivial term, "floor" also the incoming-radiance and diffuse arithmetic: where the pass's
# time goes per (pixel, VSGL) pair. Their images are wrong by construction; only their time counts.
time_build old_1 /tmp/old 1
time_build new_1 /tmp/site 1
for v in /tmp/var_*; do [ -d "$v" ] && time_build "${v#/tmp/var_}" "$v" 0; done
time_build new_2 /tmp/site 0  # the same build again: the drift over the comparison
if [ "${SHADING_ONLY:-0}" = 1 ]; then pack; exit 0; fi  # the builds' timings only (a caller's step)
echo "== VSGLs against the path tracer, 256², no shadows"
timeout 100 python3 experiments/vsgl_vs_pathtracer.py --size "$ACC_SIZE" --lights "$ACC_LIGHTS" --brsm \
  --cache "$RES/truth" --out "$RES/vsgl_vs_pathtracer_none.json" > "$RES/vsgl_vs_pathtracer_none.log" 2>&1
grep -v '^<!--' "$RES/vsgl_vs_pathtracer_none.log" | grep -E '^\| `?(vpl|vsgl)|^###' | cut -c1-200; pack
echo "== VSGLs against the path tracer, 256², shadow rays"
timeout 120 python3 experiments/vsgl_vs_pathtracer.py --size "$ACC_SIZE" --lights "${ACC_LIGHTS%,65536}" --visibility raytrace \
  --cache "$RES/truth" --time-rounds 3 --out "$RES/vsgl_vs_pathtracer_raytrace.json" > "$RES/vsgl_vs_pathtracer_raytrace.log" 2>&1
grep -v '^<!--' "$RES/vsgl_vs_pathtracer_raytrace.log" | grep -E '^\| `?(vpl|vsgl)|^###|^\| [0-9]' | cut -c1-200
rm -rf "$RES/truth"; pack
echo "== vsgl2's reductions"
timeout 45 python3 experiments/gpu_vsgl2_reduction.py --size "$SIZE" --rsm 256,1024,4096 2>&1 | tail -4; pack
echo "== temporal benchmark on a GPU: error, flicker and time under the animated flashlight"
timeout 50 python3 -m vsgl bench --scene cave_flashlight --methods vpl,vsgl --K 1,4 --sequence 20 --sampling stratified,metropolis \
  --size 960x540 --lights 1024 --rsm-sizes 256 --seeds 1 --frames 3 --reference pathtrace --reference-spp 512 \
  --no-progress --out "$RES/bench_temporal" 2>&1 | tail -25 | cut -c1-230
} 2>&1 | tee "$FINAL_OUT/log.txt"
pack
