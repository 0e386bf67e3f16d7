#!/usr/bin/env bash
# The wheel as a user gets it: built from this clone, installed in a fresh virtualenv in a
# temporary folder outside the repository, then the README's install (the precompile), its
# quickstart and the training entry point (console script, hyperparameters from the package
# data) on a tiny budget.
set -euo pipefail
repo="$(cd "$(dirname "$0")/.." && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
python -m build --wheel --outdir "$work/dist" "$repo" > "$work/build.log" 2>&1 \
    || { cat "$work/build.log"; exit 1; }
wheel="$(ls "$work"/dist/pool_env-*.whl)"
python -m venv "$work/venv"
"$work/venv/bin/python" -m pip install --quiet --upgrade pip
"$work/venv/bin/python" -m pip install --quiet "${wheel}[train]"
# The README's first python block is the quickstart.
awk '/^```python/{on=1; next} on && /^```/{exit} on' "$repo/README.md" > "$work/quickstart.py"
cd "$work"  # nothing of the clone on sys.path
"$work/venv/bin/python" - <<'PY'
import pool_env, agents, pathlib
for mod in (pool_env, agents):
    assert "site-packages" in mod.__file__, mod.__file__
print("wheel:", pool_env.__version__, pathlib.Path(pool_env.__file__).parent)
PY
"$work/venv/bin/python" -m pool_env.precompile --quiet  # the README's install, its second part
"$work/venv/bin/python" quickstart.py
"$work/venv/bin/pool-env-train" --timesteps 256 --n-envs 2 --eval-freq 0 --final-episodes 10 \
    --no-baselines --no-progress --runs "$work/runs" --set n_steps=128 batch_size=64
test -f "$(ls -d "$work"/runs/OneBall-v1/*/)model.zip"
echo "wheel check: precompile, quickstart and pool-env-train ran from the installed wheel"
