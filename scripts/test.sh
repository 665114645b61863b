#!/usr/bin/env bash
# The test command: set-up (scripts/setup.sh), then the Rust tests and the pytest suite on the
# best adapter wgpu finds (lavapipe on machines without a GPU). Fails when any test fails or
# when no test ran.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
# Mesa's WSI warns on stderr when no runtime dir exists; headless rendering does not need it.
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-$(mktemp -d)}"

echo "== cargo test"
# A log of its own: two runs on one machine must not read each other's (a fixed /tmp path did).
cargo_log=$(mktemp -t vsgl-cargo-test.XXXXXX)
cargo test --workspace --exclude vsgl-py --release 2>&1 | tee "$cargo_log"
grep -qE "^test result: ok\. [1-9]" "$cargo_log" || { echo "cargo ran no test" >&2; exit 1; }
rm -f "$cargo_log"

echo "== stub check"
.venv/bin/python -m mypy.stubtest vsgl._vsgl --allowlist python/vsgl/stubtest-allowlist.txt

echo "== pytest"
.venv/bin/python -m pytest tests "$@"
