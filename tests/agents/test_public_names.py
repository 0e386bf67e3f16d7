"""The public names that stand for kernels above pool_env: the kernels' own, and the hook counts.

``pool_env.sim.formulas``, ``pool_env.sim.constants`` and ``pool_env.game.formulas`` name
what agents, benchmarks and tools need of the compiled kernels (the import contract "public
names only"); they must be the kernels' own objects, never a second copy of a formula.
``pool_env.testing.solver_counts`` is the documented hook a benchmark counts root solves with.
"""

from __future__ import annotations

import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from pool_env.game import formulas as game_formulas
from pool_env.game.kernels import encode, geometry, observe, tips
from pool_env.sim import constants
from pool_env.sim import formulas as sim_formulas
from pool_env.sim.kernels import limits, params
from pool_env.sim.kernels.spin import collide, cushion, mathavan, strike
from pool_env.sim.kernels.spin import params as spin_params

ROOT = Path(__file__).resolve().parents[2]

OWNERS = {
    sim_formulas: (collide, cushion, mathavan, strike, spin_params),
    constants: (limits, params),
    game_formulas: (encode, geometry, observe, tips),
}


@pytest.mark.parametrize("module", list(OWNERS), ids=lambda m: m.__name__)
def test_every_public_name_is_the_kernels_own(module: object) -> None:
    names = [n for n in module.__all__ if n != "decode_on_layout"]  # type: ignore[attr-defined]
    for name in names:
        owners = [k for k in OWNERS[module] if getattr(k, name, None) is getattr(module, name)]
        assert owners, f"{module.__name__}.{name} is not a kernel module's own object"  # type: ignore[attr-defined]


def test_the_solver_hook_counts_the_solves_of_a_shot() -> None:
    """Interpreted kernels, one two-ball shot: the predictors' solves reach the counter."""
    code = textwrap.dedent(
        """
        import os
        os.environ["NUMBA_DISABLE_JIT"] = "1"
        from collections import Counter
        from pool_env import Table, shoot
        from pool_env.testing import solver_counts
        counts = Counter()
        solver_counts.install(counts)
        result = shoot(Table(), [[0.5, 0.635], [1.5, 0.635]], 0.0, 1.0)
        kinds = [e.kind for e in result.events]
        assert "ball" in kinds, kinds
        solves = counts["quartic"] + counts["quadratic"]
        found = counts["quartic found"] + counts["quadratic found"]
        assert solves >= 1 and 0 <= found <= solves, counts
        """
    )
    subprocess.run([sys.executable, "-c", code], check=True, cwd=ROOT, timeout=300)
