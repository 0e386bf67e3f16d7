"""The simulator's named numbers, for code outside it: its numeric limits and its parameter layout.

Both are the kernels' own values (:mod:`pool_env.sim.kernels.limits`,
:mod:`pool_env.sim.kernels.params`), named here so that nothing outside :mod:`pool_env`
imports :mod:`pool_env.sim.kernels` (the import contract "agents, bench and tools use
public names only" in ``pyproject.toml``).

* The limits every entry point enforces with a ``ValueError`` (why these values: the
  docstring of :mod:`pool_env.sim.kernels.limits`): lengths in
  ``[MIN_LENGTH, MAX_LENGTH]`` (m), speeds up to ``MAX_SPEED`` (m/s). The fuzz
  (``tools/fuzz.py``) draws scenes up to them.
* The entries of ``Table.params``, the flat array the roll level's kernels read, that a
  reference engine reading the same array (``bench/engines/fixed_step.py``) needs: the
  table's length and width, the ball radius, the rolling deceleration, the restitutions of
  a ball-ball impact and of a cushion.
"""

from __future__ import annotations

from pool_env.sim.kernels.limits import MAX_LENGTH, MAX_SPEED, MIN_LENGTH
from pool_env.sim.kernels.params import P_DECEL, P_E_BALL, P_E_CUSHION, P_LENGTH, P_RADIUS, P_WIDTH

__all__ = [
    "MAX_LENGTH",
    "MAX_SPEED",
    "MIN_LENGTH",
    "P_DECEL",
    "P_E_BALL",
    "P_E_CUSHION",
    "P_LENGTH",
    "P_RADIUS",
    "P_WIDTH",
]
