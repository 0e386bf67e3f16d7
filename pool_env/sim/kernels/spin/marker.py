"""The spin level's marker: the value compiled callers pass to pick this level.

A module of its own so that every module of the level can register its implementations
of the interface (:mod:`pool_env.sim.kernels.level`) for the marker's type.
"""

from __future__ import annotations

from collections import namedtuple

#: The spin level's marker type (a named tuple: numba tells levels apart by type).
SpinLevel = namedtuple("SpinLevel", ["code"])
#: The marker the compiled callers pass for the spin level.
SPIN = SpinLevel(1)
