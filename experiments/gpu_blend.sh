#!/usr/bin/env bash
# lighting="blend" on a GPU (docs/methods/vsgl.md, "lighting=\"blend\""), in ONE device call: steps
# in order of importance, each capped by what is left of $BUDGET seconds (default 480), results
# packed into $OUT/results.tgz after every step.
#
#   prepare .gl/ and .whl/ (experiments/README.md, "Running a device script")
#   device run (carry .gl .whl, timeout_s 540): <device preamble> bash experiments/gpu_blend.sh
#   locally, a smoke test of every step at toy sizes on lavapipe: SMOKE=1 bash experiments/gpu_blend.sh
#
# Steps (why):
#   1 the bench sweep at 960x540 where lavapipe's verdict on lighting="accurate" reversed
#     (glossy_cornell, caustics_ring, mirror_panel; asg, accurate, blend; both kernels): whether
#     blend is below asg at GPU size, which decides the default;
#   2 the same shadowed (visibility="raytrace"), where the specular shadow loss is open;
#   3 the cost of blend per pass: vsgl_shading at 1080p, 1024 VSGLs per pixel, asg against blend,
#     and of the tangent-plane fade (plane_fade, vsgl's default since 2026-11-29: a sixth moment
#     chain and one more test per pair) against the papers' form without it;
#   4 plane_fade's error at GPU size with and without shadows (on lavapipe at 64² it halved the
#     ring's unshadowed glow and cost the shadowed boxes 2-6%).
set -uo pipefail
source "$(dirname "$0")/gpu_common.sh"  # $FINAL_OUT, $RES, pack, step, require_gpu; cd to the repository root
BUDGET=${BUDGET:-480}
T0=$SECONDS
if [ "${SMOKE:-0}" = 1 ]; then
  MID=64x48; SPP=16; BIG=96x64
else
  MID=960x540; SPP=4096; BIG=1920x1080
fi
{
require_gpu

TAIL=40 step bench_blend 160 python3 -m vsgl bench --scene glossy_cornell,caustics_ring,mirror_panel --methods vsgl,vpl \
  --kernels integral,node --lighting asg,accurate,blend --lights 1024,4096 --size "$MID" \
  --rsm-sizes 256 --seeds 2 --frames 4 --reference pathtrace --reference-strategy bidirectional \
  --reference-spp "$SPP" --no-progress --out "$RES/bench_blend"
pack
TAIL=40 step bench_blend_shadowed 120 python3 -m vsgl bench --scene glossy_cornell,mirror_panel --methods vsgl,vpl \
  --lighting asg,blend --lights 1024,4096 --size "$MID" --visibility raytrace \
  --rsm-sizes 256 --seeds 2 --frames 4 --reference pathtrace --reference-strategy bidirectional \
  --reference-spp "$SPP" --no-progress --out "$RES/bench_blend_shadowed"
pack
TAIL=20 step shading_cost 60 python3 -m vsgl bench --scene glossy_cornell --methods vsgl --lighting asg,blend \
  --lights 1024 --size "$BIG" --interleave 1 --seeds 1 --frames 8 --reference-rsm 128 --no-progress --out "$RES/shading_cost"
pack
# plane_fade applies to the papers' diffuse form (lighting="asg"); blend always fades. The cost
# steps' errors do not matter: a small reference RSM keeps the reference's time out of the cap.
TAIL=20 step fade_cost 40 python3 -m vsgl bench --scene cornell_box,glossy_cornell --methods vsgl --lighting asg -O plane_fade=true,false \
  --lights 1024 --size "$BIG" --interleave 1 --seeds 1 --frames 8 --reference-rsm 128 --no-progress --out "$RES/fade_cost"
pack
for VIS in none raytrace; do
  TAIL=30 step "bench_plane_fade_$VIS" 40 python3 -m vsgl bench --scene cornell_box,caustics_ring --methods vsgl --lighting asg \
    -O plane_fade=true,false --lights 1024,4096 --size "$MID" --visibility "$VIS" --rsm-sizes 256 --seeds 2 --frames 4 \
    --reference pathtrace --reference-strategy bidirectional --reference-spp "$SPP" --no-progress --out "$RES/bench_plane_fade_$VIS"
  pack
done
echo "== done in $((SECONDS - T0)) s"
} 2>&1 | tee "$FINAL_OUT/log.txt"
pack
