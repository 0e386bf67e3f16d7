"""The roll level as a strategy of the one event loop (compiled): the seed's model.

Every moving ball rolls on a straight line with constant deceleration ``a = mu_roll g``
(:mod:`~pool_env.sim.kernels.roll.motion`); impacts are the seed's, its misprints fixed
(:mod:`~pool_env.sim.kernels.roll.resolve`, :mod:`~pool_env.sim.kernels.roll.jaw_impacts`). This
module implements every function of :mod:`pool_env.sim.kernels.level` for the marker
:data:`~pool_env.sim.kernels.roll.marker.ROLL`.

A stop changes no pair prediction (each pair's prediction already includes both balls'
rest phase), so a stop re-predicts only the ball's own event and logs no segment: the
segment a ball started with already ends at its rest point.
"""

from __future__ import annotations

import numpy as np

from pool_env.sim.jit import level_method
from pool_env.sim.kernels import level
from pool_env.sim.kernels.contact import CONTACT_TOL, V_REST, V_ZENO
from pool_env.sim.kernels.entries import entries
from pool_env.sim.kernels.jaw_geometry import JAW_COLS
from pool_env.sim.kernels.kinds import CUSHION
from pool_env.sim.kernels.params import P_DECEL
from pool_env.sim.kernels.record import log_anchor, new_segment_log
from pool_env.sim.kernels.roll import predict  # noqa: F401 (registers its predictors)
from pool_env.sim.kernels.roll.jaw_impacts import jaw_impact, unpress_lump
from pool_env.sim.kernels.roll.marker import ROLL, RollLevel  # noqa: F401 (ROLL: importing it from here registers the level)
from pool_env.sim.kernels.roll.motion import (
    MOVING,
    NCOL,
    POTTED,
    PX,
    PY,
    VX,
    VY,
    rest_point,
    set_anchor,
    state_at,
    struck_velocity,
)
from pool_env.sim.kernels.roll.resolve import ball_ball, cushion, stick_cluster
from pool_env.sim.kernels.validation import validate

#: The anchor columns a roll segment row holds: ``x, y, vx, vy`` at the row's time.
SEGMENT_COLUMNS = (PX, PY, VX, VY)
#: Columns of a roll segment row.
SEG_COLS = len(SEGMENT_COLUMNS)


@level_method(level.start, RollLevel)
def _start(level, positions, velocities, angular, prm):
    n = positions.shape[0]
    st = np.zeros((n, NCOL), dtype=np.float64)
    status = np.zeros(n, dtype=np.int8)
    a = prm[P_DECEL]
    for i in range(n):
        # No rest threshold on the cue: any positive speed moves the ball.
        set_anchor(
            st, status, i, 0.0, positions[i, 0], positions[i, 1], velocities[i, 0],
            velocities[i, 1], a, 0.0,
        )  # fmt: skip
    return st, status


@level_method(level.impact, RollLevel)
def _impact(level, st, ms, masses, i, j, now, repeats, prm, pockets, changed, out):
    if ball_ball(st, ms, masses, i, j, now, prm, repeats):
        n_changed = stick_cluster(st, ms, masses, i, now, prm, changed)
        if pockets.shape[1] == JAW_COLS:
            unpress_lump(st, ms, changed, n_changed, now, prm, pockets, V_ZENO, CONTACT_TOL, V_REST)
        return n_changed
    changed[0] = i
    changed[1] = j
    return 2


@level_method(level.cushion, RollLevel)
def _cushion(level, st, ms, kind, i, j, now, repeats, prm, pockets, out):
    if kind == CUSHION:
        cushion(st, ms, i, j, now, prm)
    else:  # a jaw facing or point
        jaw_impact(st, ms, i, kind, j, now, prm, pockets, V_REST)


@level_method(level.capture, RollLevel)
def _capture(level, st, ms, i, now, prm):
    a = prm[P_DECEL]
    x, y, _, _ = state_at(st, ms, i, now, a)
    set_anchor(st, ms, i, now, x, y, 0.0, 0.0, a, V_REST)
    ms[i] = POTTED


@level_method(level.settle, RollLevel)
def _settle(level, st, ms, kind, i, now, prm):
    # The roll level's one transition: a stop. Each pair's prediction already includes
    # the ball's rest phase, so they all hold.
    a = prm[P_DECEL]
    x, y = rest_point(st, i, a)
    set_anchor(st, ms, i, now, x, y, 0.0, 0.0, a, V_REST)
    return True


@level_method(level.moving, RollLevel)
def _moving(level, ms, i):
    return ms[i] == MOVING


@level_method(level.halt, RollLevel)
def _halt(level, st, ms, i, now, prm):
    a = prm[P_DECEL]
    x, y, _, _ = state_at(st, ms, i, now, a)
    set_anchor(st, ms, i, now, x, y, 0.0, 0.0, a, V_REST)


@level_method(level.new_segments, RollLevel, inline=False)
def _new_segments(level, capacity):
    return new_segment_log(capacity, SEG_COLS)


@level_method(level.log_segment, RollLevel, inline=False)
def _log_segment(level, log, row, k, now, st, ms):
    log_anchor(log, row, k, now, st, SEGMENT_COLUMNS, ms[k] == POTTED)


@level_method(level.check_scene, RollLevel)
def _check_scene(level, positions, velocities, angular, masses, prm, pockets):
    return validate(positions, velocities, masses, prm, pockets)


@level_method(level.strike, RollLevel)
def _strike(level, speed, angle, a, b, elevation, prm, out):
    struck_velocity(speed, angle, out)  # as pool_env.shoot on this level: no squirt, no spin
    out[2] = out[3] = out[4] = 0.0


@level_method(level.tail_sizes, RollLevel)
def _tail_sizes(level):
    return 0, 0


@level_method(level.write_tails, RollLevel)
def _write_tails(level, floats, ints, f, k, st, ms, now, prm):
    pass


#: The level's entry points for Python (:mod:`~pool_env.sim.kernels.entries`).
ENTRIES = entries(RollLevel)
