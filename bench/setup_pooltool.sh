#!/usr/bin/env bash
# Install pooltool 0.6.0 into its own virtualenv, apart from the project's (its pins would
# downgrade numba/llvmlite there). Idempotent: a second run only checks the install.
#
# Why not a plain `pip install pooltool-billiards`: on Linux 0.4+ pins
# panda3d==1.11.0.dev3702, which is not on the package index, so pip silently falls back to
# 0.3.3. We install 0.6.0 with --no-deps, then its runtime dependencies (from its wheel
# metadata) with panda3d 1.10.x, under which it runs headless.
#
# Usage: bash bench/setup_pooltool.sh [VENV_DIR]   (default: .bench-venvs/pooltool)
set -euo pipefail
cd "$(dirname "$0")/.."
VENV="${1:-.bench-venvs/pooltool}"
PYTHON="${PYTHON:-python3.11}"
command -v "$PYTHON" >/dev/null 2>&1 || PYTHON=python3

if [ -x "$VENV/bin/python" ] && "$VENV/bin/python" -c "import pooltool" >/dev/null 2>&1; then
    echo "pooltool already installed in $VENV"
    exit 0
fi

"$PYTHON" -m venv "$VENV"
PIP=("$VENV/bin/python" -m pip --disable-pip-version-check --quiet)
"${PIP[@]}" install --upgrade pip
# Runtime dependencies of pooltool-billiards 0.6.0 (Requires-Dist of its wheel), with
# panda3d 1.10.x in place of the unpublished 1.11 dev build. llvmlite<0.46 caps numba at 0.62.
"${PIP[@]}" install \
    "panda3d>=1.10.13,<1.11" "panda3d-gltf>=1.2.0" "panda3d-simplepbr>=0.12.0" \
    "numpy>=1.26.0" "numba>=0.59.0" "llvmlite>=0.44.0,<0.46" "scipy>=1.12.0" \
    "attrs>=21.3.0" "cattrs>=22.1.0" "msgpack>=1.0.0" "msgpack-numpy>=0.4.8" \
    "pyyaml>=5.2" "click>=8.0.0" "pillow>=6.2.0" "h5py>=3.10" "h11>=0.16.0" \
    "rich>=14.0.0,<15.0.0" "numpy-quaternion>=2024.0.12"
"${PIP[@]}" install --no-deps "pooltool-billiards==0.6.0"

# pooltool writes its config under $HOME/.config on import: keep it out of the real home.
SCRATCH="$(mktemp -d)"
HOME="$SCRATCH" "$VENV/bin/python" -c "import pooltool; print('pooltool', pooltool.__version__)"
rm -rf "$SCRATCH"
