"""A model level's entry points for Python: the shared kernels, the level's marker made inside.

numba types every argument of a call from Python; a named tuple (a level's marker) costs its
dispatcher about 0.45 us a call, a twentieth of a two-ball shot. So Python never passes the
marker: each level gets, from :func:`entries`, one entry point per shared kernel that takes
arrays and numbers and builds the marker in compiled code. The entries are closures over
the marker's type, which numba caches on disk by that type (a class pickles by name).
"""

from __future__ import annotations

from collections import namedtuple
from typing import Any

from pool_env.sim.jit import kernel
from pool_env.sim.kernels import batch, loop, rollout

#: One level's entry points: :func:`~pool_env.sim.kernels.loop.packed_shot`,
#: :func:`~pool_env.sim.kernels.loop.packed_strike`,
#: :func:`~pool_env.sim.kernels.batch.run_batch`, ``run_batch_parallel`` and
#: :func:`~pool_env.sim.kernels.rollout.run_shots`, each without the ``level`` argument.
Entries = namedtuple(
    "Entries", ["packed_shot", "packed_strike", "run_batch", "run_batch_parallel", "run_shots"]
)


def entries(level_class: type) -> Any:
    """The :data:`Entries` of the level whose marker type is ``level_class``."""

    @kernel
    def packed_shot(positions, velocities, angular, masses, prm, pockets, max_events, record):
        return loop.packed_shot(
            level_class(0), positions, velocities, angular, masses, prm, pockets, max_events,
            record,
        )  # fmt: skip

    @kernel
    def packed_strike(
        positions, cue, speed, angle, a, b, elevation, masses, prm, pockets, max_events, record
    ):
        return loop.packed_strike(
            level_class(0), positions, cue, speed, angle, a, b, elevation, masses, prm,
            pockets, max_events, record,
        )  # fmt: skip

    @kernel
    def run_batch(positions, velocities, angular, masses, active, prm, pockets, max_events):
        return batch.run_batch(
            level_class(0), positions, velocities, angular, masses, active, prm, pockets,
            max_events,
        )  # fmt: skip

    @kernel
    def run_batch_parallel(
        positions, velocities, angular, masses, active, prm, pockets, max_events
    ):
        return batch.run_batch_parallel(
            level_class(0), positions, velocities, angular, masses, active, prm, pockets,
            max_events,
        )  # fmt: skip

    @kernel
    def run_shots(pos, mass, index, cue, shots, prm, pockets, max_events, lo, hi, fields):
        rollout.run_shots(
            level_class(0), pos, mass, index, cue, shots, prm, pockets, max_events, lo, hi,
            fields,
        )  # fmt: skip

    return Entries(packed_shot, packed_strike, run_batch, run_batch_parallel, run_shots)
