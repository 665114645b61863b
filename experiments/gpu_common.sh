# Sourced by the device scripts (gpu_targets_and_acceptance.sh, gpu_shading_compare.sh). A device call returns
# at most 8 files from $OUT, two folders deep: each step writes into its own temporary folder
# $RES (exported as OUT to the Python scripts), and `pack` archives all of it into
# $FINAL_OUT/results.tgz, so whatever has finished comes back even if a later step is killed.
FINAL_OUT=${OUT:-out}
mkdir -p "$FINAL_OUT"
RES=$(mktemp -d)
export OUT=$RES PYTHONUNBUFFERED=1
cd "$(dirname "${BASH_SOURCE[0]}")/.."
pack() { tar czf "$FINAL_OUT/results.tgz" -C "$RES" . 2>/dev/null; }

# step NAME WANT_SECONDS COMMAND...: run under min(WANT, what is left of $BUDGET since $T0), keep its
# log in $RES/NAME.log, print its tail ($TAIL lines, default 14), and pack.
step() {
  local name=$1 want=$2; shift 2
  local left=$((BUDGET - (SECONDS - T0)))
  if [ "$left" -lt 15 ]; then echo "== $name: SKIPPED (budget spent)"; return; fi
  local t=$((want < left ? want : left)) s=$SECONDS
  echo "== $name (cap ${t} s, ${left} s left)"
  timeout "$t" "$@" > "$RES/$name.log" 2>&1
  local rc=$?
  echo "-- $name: rc $rc in $((SECONDS - s)) s$([ $rc = 124 ] && echo ' (TIMED OUT)')"
  grep -v '^\s*$' "$RES/$name.log" | tail -n "${TAIL:-14}" | cut -c1-220
  pack
}

# Stop at once unless vsgl's adapter is a GPU (SMOKE=1 allows lavapipe): a rerun is cheaper than a
# useless lease.
require_gpu() {
  nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm,temperature.gpu,power.draw --format=csv 2>&1 | tee "$RES/gpu.txt"
  python3 - <<'PY' || { echo "vsgl found no usable adapter: stopping"; pack; exit 3; }
import os, sys, vsgl
r = vsgl.Renderer(width=64, height=64)
print("adapter:", r.adapter, "vsgl", vsgl.__version__)
sys.exit(0 if ("llvmpipe" not in str(r.adapter).lower() or os.environ.get("SMOKE") == "1") else 3)
PY
}
