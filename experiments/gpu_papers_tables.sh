#!/usr/bin/env bash
# The papers' tables on a GPU, in ONE device call: `python -m vsgl reproduce` at the papers'
# settings (1920x1088; RSM 256² for the 2015 paper's Table 1, 512² for the 2016 paper's k-means
# Table 1, 128² for the poster's LPV table), each table a step capped by what is left of $BUDGET
# seconds (default 480), results packed into $OUT/results.tgz after every step. Owed by the
# papers' comparisons (docs/error.md, "The papers' tables"): lavapipe gives only ratios.
#
#   prepare .gl/ and .whl/ (experiments/README.md, "Running a device script")
#   device run (carry .gl .whl, timeout_s 540): <device preamble> bash experiments/gpu_papers_tables.sh
#   locally, a smoke test of every step at toy sizes on lavapipe: SMOKE=1 bash experiments/gpu_papers_tables.sh
set -uo pipefail
source "$(dirname "$0")/gpu_common.sh"  # $FINAL_OUT, $RES, pack, step, require_gpu; cd to the repository root
BUDGET=${BUDGET:-480}
T0=$SECONDS
if [ "${SMOKE:-0}" = 1 ]; then
  SIZE=(--size 48x27 --rsm 32 --frames 1); WARM=64x36
else
  SIZE=(--frames 20); WARM=1920x1080
fi
{
require_gpu
# Warm the clocks first (a minute of back-to-back frames), so no table is timed on a cold GPU.
step warmup 90 python3 -m vsgl render glossy_cornell --method vsgl --size "$WARM" -o "$RES/warm.png"
for TABLE in tok16 poster tok15; do
  TAIL=40 step "reproduce_$TABLE" 150 python3 -m vsgl reproduce --tables "$TABLE" "${SIZE[@]}"
done
echo "== done in $((SECONDS - T0)) s"
} 2>&1 | tee "$FINAL_OUT/log.txt"
pack
