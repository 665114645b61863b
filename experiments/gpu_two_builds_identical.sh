#!/usr/bin/env bash
# The house refactor on a GPU machine: the previous build (wheel in .whl-old/) and this one
# (.whl/, installed to /tmp/site by the device preamble) render every method on every built-in
# at 480x270 — bit-identical AOVs expected — and are timed back to back on warm clocks at
# 1920x1080 (old, new, old, new), so a slower frame script would show. Results under $OUT.
#   prepare .gl/ and .whl/ (experiments/README.md, "Running a device script"); mkdir -p .whl-old && cp <previous wheel> .whl-old/
#   device: <device preamble> bash experiments/gpu_two_builds_identical.sh
set -uo pipefail
OUT=${OUT:-out}; mkdir -p "$OUT"
export PYTHONUNBUFFERED=1
python3 -m pip install -q --no-index --no-deps --no-compile --target /tmp/old .whl-old/*.whl || exit 1
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm --format=csv > "$OUT/gpu.txt" 2>&1
cat "$OUT/gpu.txt"
PYTHONPATH=/tmp/old timeout 120 python3 scripts/image_fingerprints.py --size 480x270 --out "$OUT/fp_old.json"
PYTHONPATH=/tmp/site timeout 120 python3 scripts/image_fingerprints.py --size 480x270 --out "$OUT/fp_new.json" --compare "$OUT/fp_old.json" > "$OUT/fp_compare.txt"
grep -v "^  " "$OUT/fp_compare.txt" | grep -v "settings differ" | tail -5
common=(--size 1920x1080 --frames 30 --scenes cornell_box --methods direct,vsgl,vsgl2,vpl --aovs image --warm-seconds 6)
for round in 1 2; do
  PYTHONPATH=/tmp/old timeout 150 python3 experiments/gpu_timings.py "${common[@]}" --tag "_old_$round" | cut -c1-400
  PYTHONPATH=/tmp/site timeout 150 python3 experiments/gpu_timings.py "${common[@]}" --tag "_new_$round" | cut -c1-400
done
