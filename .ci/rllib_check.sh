#!/usr/bin/env bash
# The rllib extra in a venv of its own: ray[rllib] 2.60 pins gymnasium==1.2.2, older than the
# newest Gymnasium this package supports (which `dev` installs), so its tests run apart, on
# the Gymnasium that extra resolves. Ray binds loopback only (RAY_ENABLE_...=0).
set -euo pipefail
repo="$(cd "$(dirname "$0")/.." && pwd)"
cd "$repo"
python3 -m venv .ci-venv-rllib
.ci-venv-rllib/bin/python -m pip install --quiet --upgrade pip
.ci-venv-rllib/bin/python -m pip install --quiet -e ".[rllib]" "pytest>=8" "hypothesis>=6.100" \
    "mpmath>=1.3" "sybil>=9"
.ci-venv-rllib/bin/python -c "import gymnasium, ray; print('rllib venv: gymnasium', \
gymnasium.__version__, 'ray', ray.__version__)"
RAY_ENABLE_WINDOWS_OR_OSX_CLUSTER=0 .ci-venv-rllib/bin/python -m pytest -q -p no:cacheprovider \
    tests/agents/test_rllib.py tests/agents/test_rllib_cluster.py
