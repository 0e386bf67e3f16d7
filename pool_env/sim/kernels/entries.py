"""A model level's entry points for Python: the shared kernels, the level's marker made inside.

numba types every argument of a call from Python; a named tuple (a level's marker) costs its
dispatcher about 0.45 us a call, a twentieth of a two-ball shot. So Python never passes the
marker: each level gets, from :func:`entries`, one entry point per shared kernel that takes
arrays and numbers and builds the marker in compiled code. The entries are closures over
the marker's type, which numba caches on disk by that type (a class pickles by name).

Each level's closures get a qualified name of their own (the spin level's ``packed_shot`` is
``entries.<locals>.SpinLevel.packed_shot``): numba names a compiled function's environment,
the constants its machine code reads, after the qualified name, the argument types and a
counter of the process that compiled it. With one name for every level, the roll level's
``packed_shot`` compiled by one process and the spin level's compiled by another could be
named alike, and a process loading both from the cache gave the second the first one's
constants (``SystemError ... 'descr' is NULL``; ``tests/sim/test_compile_cache.py``).
"""

from __future__ import annotations

from collections import namedtuple
from typing import Any

from pool_env.sim.jit import kernel
from pool_env.sim.kernels import batch, loop, rollout_kernel

#: One level's entry points: :func:`~pool_env.sim.kernels.loop.packed_shot`,
#: :func:`~pool_env.sim.kernels.loop.packed_strike`,
#: :func:`~pool_env.sim.kernels.batch.run_batch`, ``run_batch_parallel`` and
#: :func:`~pool_env.sim.kernels.rollout_kernel.run_shots`, each without the ``level`` argument.
Entries = namedtuple(
    "Entries", ["packed_shot", "packed_strike", "run_batch", "run_batch_parallel", "run_shots"]
)


def entries(level_class: type) -> Any:
    """The :data:`Entries` of the level whose marker type is ``level_class``."""

    def entry(fn: Any) -> Any:
        """Compile ``fn`` as this level's entry, under a qualified name of the level's own."""
        fn.__qualname__ = f"entries.<locals>.{level_class.__name__}.{fn.__name__}"
        return kernel(fn)

    @entry
    def packed_shot(positions, velocities, angular, masses, prm, pockets, max_events, record):
        return loop.packed_shot(
            level_class(0), positions, velocities, angular, masses, prm, pockets, max_events,
            record,
        )  # fmt: skip

    @entry
    def packed_strike(
        positions, cue, speed, angle, a, b, elevation, masses, prm, pockets, max_events, record
    ):
        return loop.packed_strike(
            level_class(0), positions, cue, speed, angle, a, b, elevation, masses, prm,
            pockets, max_events, record,
        )  # fmt: skip

    @entry
    def run_batch(positions, velocities, angular, masses, active, prm, pockets, max_events):
        return batch.run_batch(
            level_class(0), positions, velocities, angular, masses, active, prm, pockets,
            max_events,
        )  # fmt: skip

    @entry
    def run_batch_parallel(
        positions, velocities, angular, masses, active, prm, pockets, max_events
    ):
        return batch.run_batch_parallel(
            level_class(0), positions, velocities, angular, masses, active, prm, pockets,
            max_events,
        )  # fmt: skip

    @entry
    def run_shots(pos, mass, index, cue, shots, prm, pockets, max_events, lo, hi, fields):
        rollout_kernel.run_shots(
            level_class(0), pos, mass, index, cue, shots, prm, pockets, max_events, lo, hi,
            fields,
        )  # fmt: skip

    return Entries(packed_shot, packed_strike, run_batch, run_batch_parallel, run_shots)
