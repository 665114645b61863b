#!/usr/bin/env bash
# Sets up a fresh Debian/Ubuntu machine with a Rust toolchain and Python ≥ 3.9: a Vulkan driver
# when none is installed (lavapipe is enough), a virtual environment in .venv, and vsgl built
# into it in release mode. Idempotent: rerunning only rebuilds what changed.
set -euo pipefail
cd "$(dirname "$0")/.."

SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
# (grep without -q: with pipefail, -q's early exit would make ldconfig's SIGPIPE fail the test)
if ! ls /usr/share/vulkan/icd.d/*.json /etc/vulkan/icd.d/*.json >/dev/null 2>&1 || ! ldconfig -p | grep libvulkan.so.1 >/dev/null; then
  echo "setup: no Vulkan driver or loader found; installing mesa-vulkan-drivers libvulkan1" >&2
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq mesa-vulkan-drivers libvulkan1 >/dev/null
fi

# The desktop window's tests open a real window under Xvfb and drive it with xdotool; the
# notebook widget's browser test drives headless Chromium. Without these those tests skip (and
# fail under CI=true, which must run them).
if ! command -v Xvfb >/dev/null || ! command -v xdotool >/dev/null || ! command -v chromium >/dev/null || ! command -v chromedriver >/dev/null; then
  echo "setup: installing xvfb xdotool chromium chromium-driver (for the window and browser tests)" >&2
  { $SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq xvfb xdotool chromium chromium-driver >/dev/null; } \
    || echo "setup: could not install xvfb, xdotool and chromium; the window and browser tests will skip" >&2
fi

PYTHON=${PYTHON:-python3}
[ -x .venv/bin/python ] || "$PYTHON" -m venv .venv
.venv/bin/python -m pip install -q --upgrade pip >/dev/null
# The build and test tools, and every extra of pyproject.toml, so that no test skips for a missing
# package (tests/test_packaging.py checks this list against the extras).
.venv/bin/python -m pip install -q "maturin>=1.7,<2" "numpy>=1.21" "pytest>=7" "mypy>=1.8" \
  "pillow>=9" "matplotlib>=3.5" "tqdm>=4.60" "nvidia-ml-py>=12" "imageio>=2.28" "imageio-ffmpeg>=0.4.8" "flip-evaluator>=1.7" \
  "jupyter_rfb>=0.5" "ipywidgets>=8" "nbclient>=0.7" "nbformat>=5" "ipykernel>=6" "ray>=2.9" "selenium>=4.20" "jupyterlab>=4"
# `maturin develop` installs the extension into .venv (release: lavapipe runs the shaders, but
# the CPU side — scene upload, readback, glTF parsing — is Rust and benefits from it).
VIRTUAL_ENV="$PWD/.venv" PATH="$PWD/.venv/bin:$PATH" maturin develop --release -q
