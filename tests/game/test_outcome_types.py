"""One table's outcome hands the rules' kernels the same array types, hit or miss.

numba compiles a kernel once per argument signature, read-only arrays counting apart from
writable ones. A miss used to hand the rules a shared read-only ``(1, 2)`` first-contact
array and a hit a fresh writable one, so a process compiled the rules' kernels a second
time at its first miss: after ``python -m pool_env.precompile``, ``train.py`` on a game id
still compiled three kernels.
"""

from __future__ import annotations

import numba
import numpy as np
import pytest

from pool_env.game.state import new_state
from pool_env.game.step import _simulate
from pool_env.sim.table import Table


@pytest.mark.parametrize("model", ["roll", "spin"])
def test_a_miss_and_a_hit_give_the_same_first_contact_type(model: str) -> None:
    table = Table(model=model)
    state = new_state(1, 2)
    state.positions[0] = [[0.5, 0.635], [1.5, 0.635]]
    state.on_table[0] = True
    tables = np.zeros(1, dtype=np.intp)
    spins = None if model == "roll" else np.zeros((1, 2, 3))
    hit = np.array([[[1.0, 0.0], [0.0, 0.0]]])
    miss = np.array([[[0.0, 1.0], [0.0, 0.0]]])  # straight up the table, past the ball
    outcomes = [_simulate(table, state, tables, v, spins, False, None) for v in (hit, miss)]
    assert outcomes[0].first[0, 1] == 1 and outcomes[1].first[0, 1] == -1
    types = {numba.typeof(out.first) for out in outcomes}
    assert len(types) == 1, types
    assert all(out.first.flags.writeable for out in outcomes)
    assert outcomes[0].first is not outcomes[1].first
