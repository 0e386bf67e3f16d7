"""Batched rollout (compiled): many cue shots from one layout, for search and planning.

Shot ``s`` strikes ball ``cue`` of the same layout with row ``s`` of ``shots``
(:data:`SHOT_COLUMNS`), then runs the level's event loop without recording: the roll level's
:func:`~pool_env.sim.kernels.loop._shoot` or the spin level's
:func:`~pool_env.sim.kernels.spin_loop.shoot_spin`, exactly as ``shoot()`` would on that
table (the same strike arithmetic, the same validation, the same loop), so shot ``s`` gives
bit for bit the result of one ``shoot()``. Results go to the batch's
:data:`~pool_env.sim.kernels.packing.BatchOutput` fields, row ``s`` for shot ``s``, from
:func:`~pool_env.sim.kernels.packing.store_table`.

Each kernel runs the shots ``lo <= s < hi`` and releases the GIL, so the Python front
(:mod:`pool_env.sim.rollout`) splits a rollout over threads that write disjoint rows of
one output.
"""

from __future__ import annotations

import math

import numpy as np

from pool_env.sim.jit import kernel
from pool_env.sim.kernels.loop import _shoot
from pool_env.sim.kernels.packing import BatchOutput, store_error, store_table
from pool_env.sim.kernels.params import P_MASS, P_RADIUS
from pool_env.sim.kernels.spin_loop import shoot_spin, validate_spin_scene
from pool_env.sim.kernels.spin_params import S_END_MASS, S_TIP_RADIUS
from pool_env.sim.kernels.spin_strike import cue_strike
from pool_env.sim.kernels.validation import BEHIND_LINE, IN_JAW, IN_POCKET, OK, validate

#: Columns of a shot row: the aim (rad from +x), the cue ball's speed (m/s), the tip's
#: side and vertical offsets ``a, b`` (fractions of R) and the cue's elevation (rad).
SHOT_ANGLE, SHOT_SPEED, SHOT_TIP_A, SHOT_TIP_B, SHOT_ELEVATION = range(5)
SHOT_COLUMNS = 5


@kernel
def _store_error(fields, s, index, code, i, j):
    """Record shot ``s``'s validation failure (nothing of it simulated)."""
    pocket = (code == IN_POCKET) | (code == IN_JAW) | (code == BEHIND_LINE)
    store_error(BatchOutput(*fields), s, index, code, i, j, pocket)


@kernel
def run_roll(pos, mass, index, cue, shots, params, pockets, max_events, lo, hi, fields):
    """Roll-level shots ``lo <= s < hi``: ball ``cue`` struck along ``shots[s]``.

    Args:
        pos: ``(n, 2)`` the balls in play (rows of the layout given by ``index``).
        mass: ``(n,)`` their masses (empty: the table's).
        index: ``(n,)`` each ball's row in the full layout of ``N`` balls.
        cue: The struck ball, a row of ``pos``.
        shots: ``(S, SHOT_COLUMNS)`` shot rows (the tip columns are zero on this level).
        params: ``Table.params``. pockets: ``Table.pocket_geometry``.
        max_events: The event cap of each shot.
        lo, hi: The shots to run.
        fields: The fields of a :data:`BatchOutput` of ``S`` rows and ``N`` balls.
    """
    out = BatchOutput(*fields)
    vel = np.zeros_like(pos)
    for s in range(lo, hi):
        angle, speed = shots[s, SHOT_ANGLE], shots[s, SHOT_SPEED]
        # The same arithmetic as pool_env.shoot: speed times the aim's cosine and sine.
        vel[cue, 0] = speed * math.cos(angle)
        vel[cue, 1] = speed * math.sin(angle)
        code, i, j = validate(pos, vel, mass, params, pockets)
        if code != OK:
            _store_error(fields, s, index, code, i, j)
            continue
        st, balls, first_i, first_j, n_ev, _, capped, _, _, _ = _shoot(
            pos, vel, mass, params, pockets, max_events, False
        )
        store_table(out, s, index, st, balls, first_i, first_j, n_ev, capped)


@kernel
def run_spin(pos, mass, index, cue, shots, prm, pockets, max_events, lo, hi, fields):
    """Spin-level shots ``lo <= s < hi``: the cue strike of ``shots[s]``, then the shot.

    As :func:`run_roll`, with ``prm = Table.spin_params`` and the strike of
    :func:`~pool_env.sim.kernels.spin_strike.cue_strike` (tip and elevation) as
    ``packed_spin_strike`` makes it.
    """
    out = BatchOutput(*fields)
    n = pos.shape[0]
    vel = np.zeros((n, 2))
    ang = np.zeros((n, 3))
    strike = np.empty(5)
    for s in range(lo, hi):
        cue_strike(
            shots[s, SHOT_SPEED], shots[s, SHOT_ANGLE], shots[s, SHOT_TIP_A],
            shots[s, SHOT_TIP_B], shots[s, SHOT_ELEVATION], prm[P_RADIUS], prm[P_MASS],
            prm[S_END_MASS], prm[S_TIP_RADIUS], strike,
        )  # fmt: skip
        vel[cue, 0], vel[cue, 1] = strike[0], strike[1]
        ang[cue, 0], ang[cue, 1], ang[cue, 2] = strike[2], strike[3], strike[4]
        code, i, j = validate_spin_scene(pos, vel, ang, mass, prm, pockets)
        if code != OK:
            _store_error(fields, s, index, code, i, j)
            continue
        # The loop reads its inputs and never writes them: vel and ang serve every shot.
        st, _, balls, first_i, first_j, n_ev, _, capped, _, _, _ = shoot_spin(
            pos, vel, ang, mass, prm, pockets, max_events, False
        )
        store_table(out, s, index, st, balls, first_i, first_j, n_ev, capped)
