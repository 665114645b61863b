# Sourced by the device scripts (gpu_session.sh, gpu_shading_compare.sh). A device call returns
# at most 8 files from $OUT, two folders deep: each step writes into its own temporary folder
# $RES (exported as OUT to the Python scripts), and `pack` archives all of it into
# $FINAL_OUT/results.tgz, so whatever has finished comes back even if a later step is killed.
FINAL_OUT=${OUT:-out}
mkdir -p "$FINAL_OUT"
RES=$(mktemp -d)
export OUT=$RES PYTHONUNBUFFERED=1
cd "$(dirname "${BASH_SOURCE[0]}")/.."
pack() { tar czf "$FINAL_OUT/results.tgz" -C "$RES" . 2>/dev/null; }
