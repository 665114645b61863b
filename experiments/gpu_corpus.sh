#!/usr/bin/env bash
# The real-scene corpus on a GPU (docs/scenes.md, "The real-scene corpus"), in ONE device call:
# steps in order of importance, each capped by what is left of $BUDGET seconds (default 480),
# results packed into $OUT/results.tgz after every step.
#
#   prepare .gl/ and .whl/ (experiments/README.md, "Running a device script")
#   cp -r ../shared/scenes .scenes      # the corpus files travel as an ignored path
#   device run (carry .gl .whl .scenes, timeout_s 540): <device preamble> VSGL_SCENES=.scenes bash experiments/gpu_corpus.sh
#   locally, a smoke test of every step at toy sizes on lavapipe: SMOKE=1 bash experiments/gpu_corpus.sh
#
# Steps (why):
#   1 the equal-time table at 960x540 on the three shared scenes (vsgl with its defaults of
#     2026-12-01 and as it was before: lighting, coherence and lambert_lobe swept; vpl) against
#     the bidirectional path tracer: the real-scene issue's figure owed to a GPU;
#   2 flicker of default vsgl and vpl at equal N on cave_flashlight at 512² against the reference
#     at RSM 1024² (its own error printed): the 5× of the real-scene issue, which lavapipe can only
#     measure at 64²-128², where 8x8 interleaving spans the scene's features
#     (experiments/flicker_against_a_converged_truth.md);
#   3 the cost of today's defaults (lighting="blend", coherence=0.9, lambert_lobe="exact_compact",
#     near_field="texels", rsm_fit="scene", kernel_filter="nodes") against the frame before them,
#     warm, at 512² and 1024²;
#   4 the cost of near_field="texels" alone, and of shadow_target="resampled" with shadow rays,
#     each against the frame without it;
#   5 the cost of kernel_filter="nodes" against the papers' trilinear read;
#   6 the cost of denoise_form="exchange" against the default gather.
set -uo pipefail
source "$(dirname "$0")/gpu_common.sh"  # $FINAL_OUT, $RES, pack, step, require_gpu; cd to the repository root
BUDGET=${BUDGET:-480}
T0=$SECONDS
: "${VSGL_SCENES:?set VSGL_SCENES to the shared glTF scene folder (see the header)}"
export VSGL_SCENES
if [ "${SMOKE:-0}" = 1 ]; then
  MID=48x32; SPP=16; LIGHTS=64,256; SIZES=64; REPEATS=2
  FLICKER="--size 32 --reference-rsm 64 --frames 3 --seed-sets 1"
else
  MID=960x540; SPP=4096; LIGHTS=256,1024,4096; SIZES=512,1024; REPEATS=11
  FLICKER="--size 512 --reference-rsm 1024 --frames 16 --seed-sets 4"
fi
{
require_gpu

TAIL=60 step bench_corpus 300 python3 -m vsgl bench --scene flight_helmet,cornell_box_original,boom_box --methods vsgl,vpl \
  --lighting blend,asg -O coherence=0.9,0 -O lambert_lobe=exact_compact,hemisphere --lights "$LIGHTS" --size "$MID" --rsm-sizes 256 --seeds 2 --frames 4 \
  --reference pathtrace --reference-strategy bidirectional --reference-spp "$SPP" --no-progress --out "$RES/bench_corpus"
pack
# shellcheck disable=SC2086  # $FLICKER is a list of options
TAIL=20 step flicker_cave 150 python3 experiments/lighting_default_flicker.py $FLICKER --scene cave_flashlight \
  --variant "vpl=method=vpl" --variant "vsgl (default)=" --variant "vsgl interleave 1=interleave=1,denoise=False"
pack
TAIL=20 step cost_defaults 120 python3 experiments/lighting_default_cost.py --sizes "$SIZES" --repeats "$REPEATS" \
  --variant before=lighting=asg,coherence=0,lambert_lobe=hemisphere,near_field=sg,rsm_fit=cone,kernel_filter=trilinear --variant today=
pack
TAIL=20 step cost_near_field 90 python3 experiments/lighting_default_cost.py --sizes "$SIZES" --repeats "$REPEATS" \
  --variant sg=near_field=sg --variant texels= \
  --variant centre_traced=visibility=raytrace,shadow_target=centre --variant resampled_traced=visibility=raytrace
pack
TAIL=20 step cost_kernel_filter 60 python3 experiments/lighting_default_cost.py --sizes "$SIZES" --repeats "$REPEATS" \
  --variant trilinear=kernel_filter=trilinear --variant nodes=
pack
TAIL=20 step cost_denoise_form 60 python3 experiments/lighting_default_cost.py --sizes "$SIZES" --repeats "$REPEATS" \
  --variant gather= --variant exchange=denoise_form=exchange
pack
echo "== done in $((SECONDS - T0)) s"
} 2>&1 | tee "$FINAL_OUT/log.txt"
pack
