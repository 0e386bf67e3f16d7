"""Batched rollout (compiled): many cue shots from one layout, for search and planning.

Shot ``s`` strikes ball ``cue`` of the same layout with row ``s`` of ``shots``
(:data:`SHOT_COLUMNS`), the level's strike (:func:`~pool_env.sim.kernels.level.strike`),
then runs the one event loop (:func:`~pool_env.sim.kernels.loop.shoot`) without
recording, exactly as ``shoot()`` would on that table (the same strike arithmetic, the same
validation, the same loop), so shot ``s`` gives bit for bit the result of one ``shoot()``.
Results go to the batch's :data:`~pool_env.sim.kernels.packing.BatchOutput` fields, row
``s`` for shot ``s``, from :func:`~pool_env.sim.kernels.packing.store_table`.

Written once for every model level (the marker ``level`` picks one). The kernel runs the
shots ``lo <= s < hi`` and releases the GIL, so the Python front
(:mod:`pool_env.sim.rollout`) splits a rollout over threads that write disjoint rows of
one output.
"""

from __future__ import annotations

import numpy as np

from pool_env.sim.jit import kernel
from pool_env.sim.kernels.level import check_scene, strike
from pool_env.sim.kernels.loop import shoot
from pool_env.sim.kernels.packing import BatchOutput, store_error, store_table
from pool_env.sim.kernels.validation import BEHIND_LINE, IN_JAW, IN_POCKET, OK

#: Columns of a shot row: the aim (rad from +x), the cue ball's speed (m/s), the tip's
#: side and vertical offsets ``a, b`` (fractions of R) and the cue's elevation (rad).
SHOT_ANGLE, SHOT_SPEED, SHOT_TIP_A, SHOT_TIP_B, SHOT_ELEVATION = range(5)
SHOT_COLUMNS = 5


@kernel
def run_shots(level, pos, mass, index, cue, shots, prm, pockets, max_events, lo, hi, fields):
    """Shots ``lo <= s < hi``: ball ``cue`` struck with ``shots[s]``, then the shot.

    Args:
        level: The model level's marker (``ROLL`` or ``SPIN``).
        pos: ``(n, 2)`` the balls in play (rows of the layout given by ``index``).
        mass: ``(n,)`` their masses (empty: the table's).
        index: ``(n,)`` each ball's row in the full layout of ``N`` balls.
        cue: The struck ball, a row of ``pos``.
        shots: ``(S, SHOT_COLUMNS)`` shot rows (the tip columns are zero on the roll level).
        prm: The level's flat parameter array. pockets: ``Table.pocket_geometry``.
        max_events: The event cap of each shot.
        lo, hi: The shots to run.
        fields: The fields of a :data:`BatchOutput` of ``S`` rows and ``N`` balls.
    """
    out = BatchOutput(*fields)
    n = pos.shape[0]
    vel = np.zeros((n, 2))
    ang = np.zeros((n, 3))
    struck = np.empty(5)
    for s in range(lo, hi):
        strike(
            level, shots[s, SHOT_SPEED], shots[s, SHOT_ANGLE], shots[s, SHOT_TIP_A],
            shots[s, SHOT_TIP_B], shots[s, SHOT_ELEVATION], prm, struck,
        )  # fmt: skip
        vel[cue, 0], vel[cue, 1] = struck[0], struck[1]
        ang[cue, 0], ang[cue, 1], ang[cue, 2] = struck[2], struck[3], struck[4]
        code, i, j = check_scene(level, pos, vel, ang, mass, prm, pockets)
        if code != OK:
            pocket = (code == IN_POCKET) | (code == IN_JAW) | (code == BEHIND_LINE)
            store_error(out, s, index, code, i, j, pocket)
            continue
        # The loop reads its inputs and never writes them: vel and ang serve every shot.
        st, _, balls, first_i, first_j, n_ev, _, capped, _, _, _ = shoot(
            level, pos, vel, ang, mass, prm, pockets, max_events, False
        )
        store_table(out, s, index, st, balls, first_i, first_j, n_ev, capped)
