"""The house's import rules: layers, no cycle, public names, a simulator without Gymnasium.

The contracts live in ``pyproject.toml`` (``[tool.importlinter]``) and are checked by
import-linter's ``lint-imports``, here so that the README's test command checks them.
"""

from __future__ import annotations

import re
import shutil
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
CONTRACTS = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["importlinter"]


def _lint_imports(cwd: Path) -> subprocess.CompletedProcess[str]:
    """``lint-imports`` (the dev extra's script, beside this Python) run in ``cwd``."""
    script = Path(sys.executable).with_name("lint-imports")
    found = str(script) if script.exists() else shutil.which("lint-imports")
    assert found, "lint-imports not installed: pip install -e '.[dev]'"
    return subprocess.run(
        [found, "--no-cache", "--no-logo"], cwd=cwd, capture_output=True, text=True, timeout=300
    )


def test_every_contract_is_kept() -> None:
    out = _lint_imports(ROOT)
    assert out.returncode == 0, out.stdout + out.stderr
    n = len(CONTRACTS["contracts"])
    assert re.search(rf"Contracts: {n} kept, 0 broken", out.stdout), out.stdout


# One planted import per contract: (file, the line added, the contract that must catch it).
PLANTED = {
    "sim imports the game": (
        "pool_env/sim/table.py",
        "import pool_env.game.config",
        "pool_env in layers",
    ),
    "game imports a front": (
        "pool_env/game/scenes.py",
        "import pool_env.envs.env",
        "pool_env in layers",
    ),
    "pool_env imports agents": (
        "pool_env/render/canvas.py",
        "import agents.baselines.geometry",
        "the repository in layers",
    ),
    "a benchmark imports the tests": (
        "bench/scenes.py",
        "import tests.helpers_sim",
        "the repository in layers",
    ),
    "a tool imports a benchmark": (
        "tools/mutants.py",
        "import bench.scenes",
        "the repository in layers",
    ),
    "sim imports gymnasium": (
        "pool_env/sim/layouts.py",
        "import gymnasium.spaces",
        "the simulator stands alone",
    ),
    "game imports a private module of sim": (
        "pool_env/game/checks.py",
        "import pool_env.sim.kernels._planted",
        "a private module",
    ),
    "a baseline imports the training stack": (
        "agents/baselines/ghost_ball.py",
        "import agents.training.train_lib",
        "agents in wings",
    ),
    "the features import the SB3 vector adapter": (
        "agents/learned/features.py",
        "import agents.vec.native_vec",
        "agents in wings",
    ),
    "an agent imports a game kernel": (
        "agents/baselines/geometry.py",
        "import pool_env.game.kernels.geometry",
        "agents, bench and tools use public names only",
    ),
    "a tool imports a simulator kernel": (
        "tools/mutants.py",
        "from pool_env.sim.kernels.spin import strike",
        "agents, bench and tools use public names only",
    ),
    "a cycle inside agents": (
        "agents/evaluation/episodes.py",
        "import agents.evaluation.evaluate",
        "no import cycle",
    ),
    "a cycle inside sim": (
        "pool_env/sim/scalars.py",
        "import pool_env.sim.table",
        "no import cycle",
    ),
}


@pytest.mark.parametrize("case", list(PLANTED))
def test_a_planted_violation_breaks_its_contract(case: str, tmp_path: Path) -> None:
    """A copy of the tree with one bad import fails lint-imports, naming that contract."""
    path, line, contract = PLANTED[case]
    ignore = shutil.ignore_patterns("__pycache__")
    for package in CONTRACTS["root_packages"]:
        shutil.copytree(ROOT / package, tmp_path / package, ignore=ignore)
    shutil.copy(ROOT / "pyproject.toml", tmp_path)
    (tmp_path / "pool_env/sim/kernels/_planted.py").write_text('"""A private module."""\n')
    target = tmp_path / path
    target.write_text(target.read_text() + f"\n{line}  # noqa\n")
    out = _lint_imports(tmp_path)
    assert out.returncode != 0, out.stdout
    broken = re.findall(r"^(.*?) BROKEN", out.stdout, flags=re.MULTILINE)
    assert [name for name in broken if name.startswith(contract)], out.stdout


def test_the_simulator_loads_no_gymnasium() -> None:
    """``import pool_env.sim`` (which runs ``pool_env/__init__``) loads no Gymnasium nor game."""
    code = (
        "import pool_env.sim, sys;"
        "assert 'gymnasium' not in sys.modules;"
        "assert not [m for m in sys.modules if m.startswith('pool_env.game')];"
        "from pool_env import Table, shoot;"
        "assert shoot(Table(), [[0.5, 0.635], [1.5, 0.635]], 0.0, 1.0).n_events > 0;"
        "assert 'gymnasium' not in sys.modules"
    )
    subprocess.run([sys.executable, "-c", code], check=True, cwd=ROOT)
