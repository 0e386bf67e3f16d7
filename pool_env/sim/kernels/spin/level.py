"""The spin level as a strategy of the one event loop (compiled): pooltool's model.

It implements every function of :mod:`pool_env.sim.kernels.level` for the marker
:data:`~pool_env.sim.kernels.spin.marker.SPIN`, with:

* ball state with angular velocity and a motion state
  (:mod:`~pool_env.sim.kernels.spin.state`), motion on curved (parabolic) paths;
* the transitions as events at closed-form times: ``SLIDE_ROLL``, ``STOP`` (a rolling ball
  comes to rest), ``ROLL_SPIN`` (it comes to rest spinning in place), ``SPIN_STOP``
  (:mod:`~pool_env.sim.kernels.spin.predict`), ordered after the roll level's kinds;
* the resolution kernels of the spin level, chosen by the table's parameters: ball-ball
  with throw (:mod:`~pool_env.sim.kernels.spin.collide`, closed form) or Mathavan's model
  (:mod:`~pool_env.sim.kernels.spin.mathavan`, its impulse integration), Han 2005 or
  Stronge's compliant cushions (:mod:`~pool_env.sim.kernels.spin.cushion`,
  :mod:`~pool_env.sim.kernels.spin.stronge`) for rails, jaw facings and jaw points (a
  point's normal runs from its tip's centre to the ball's), with ``e_jaw`` at the jaws.

The Zeno rules and the pressed-cushion rule: :mod:`~pool_env.sim.kernels.spin.zeno`. Every
event re-anchors the ball it concerns and logs a segment (a transition changes the path).
"""

from __future__ import annotations

import math

import numpy as np

from pool_env.sim.jit import kernel, level_method
from pool_env.sim.kernels import level
from pool_env.sim.kernels.contact import V_ZENO, ZENO_REPEATS
from pool_env.sim.kernels.entries import entries
from pool_env.sim.kernels.jaw_geometry import jaw_normal
from pool_env.sim.kernels.kinds import CUSHION, SLIDE_ROLL
from pool_env.sim.kernels.limits import MAX_SPEED, reachable_speed2_spin, speed_allowed
from pool_env.sim.kernels.packing import SPIN_TAIL_FLOATS, SPIN_TAIL_INTS
from pool_env.sim.kernels.params import P_DECEL, P_E_BALL, P_E_CUSHION, P_E_JAW, P_MASS, P_RADIUS
from pool_env.sim.kernels.record import log_anchor, new_segment_log
from pool_env.sim.kernels.spin import predict  # noqa: F401 (registers its predictors)
from pool_env.sim.kernels.spin.collide import ball_ball_spin
from pool_env.sim.kernels.spin.cushion import cushion_spin
from pool_env.sim.kernels.spin.marker import SPIN, SpinLevel  # noqa: F401 (SPIN: importing it from here registers the level)
from pool_env.sim.kernels.spin.mathavan import ball_ball_mathavan
from pool_env.sim.kernels.spin.params import (
    MATHAVAN_BALLS,
    S_BALL_MODEL,
    S_CUSHION_FRICTION,
    S_CUSHION_HEIGHT,
    S_CUSHION_MODEL,
    S_END_MASS,
    S_FRICTION_MODE,
    S_MATHAVAN_STEPS,
    S_MU_BALL,
    S_MU_SLIDE,
    S_OMEGA_RATIO,
    S_SLIDE_DECEL,
    S_TIP_RADIUS,
)
from pool_env.sim.kernels.spin.state import (
    AX,
    AY,
    CLASSIFY,
    FORCE_ROLL,
    POTTED,
    PX,
    PY,
    ROLLING,
    SCOL,
    VX,
    VY,
    WX,
    WY,
    WZ,
    moving,
    rest_point,
    set_anchor,
    set_potted,
    state_at,
)
from pool_env.sim.kernels.spin.strike import cue_strike
from pool_env.sim.kernels.spin.zeno import (
    RAIL_NX,
    RAIL_NY,
    pressed_pair,
    pressed_roll,
    stick,
    wedged_ball,
)
from pool_env.sim.kernels.validation import BAD_SPIN, OK, SPIN_TOO_FAST, TOO_ENERGETIC, validate

#: The anchor columns a spin segment row holds: ``x, y, vx, vy, wx, wy, wz, ax, ay`` at the
#: row's time.
SEGMENT_COLUMNS = (PX, PY, VX, VY, WX, WY, WZ, AX, AY)
#: Columns of a spin segment row.
SEG_COLS = len(SEGMENT_COLUMNS)


@kernel
def _impact(st, ms, masses, i, j, now, prm, repeats, out):
    """Resolve the impact of balls ``i`` and ``j``; return whether the pair must stick.

    It sticks after ``ZENO_REPEATS`` repeats in a row, or when the impact leaves it pressed
    together (:func:`~pool_env.sim.kernels.spin.zeno.pressed_pair`).
    """
    xi, yi, vxi, vyi, wxi, wyi, wzi = state_at(st, ms, i, now, prm)
    xj, yj, vxj, vyj, wxj, wyj, wzj = state_at(st, ms, j, now, prm)
    dx, dy = xj - xi, yj - yi
    dist = math.sqrt(dx * dx + dy * dy)
    nx, ny = dx / dist, dy / dist
    approach = (vxi - vxj) * nx + (vyi - vyj) * ny
    e = prm[P_E_BALL]
    e_eff = e if approach >= V_ZENO or (approach > 0.0 and repeats < 2) else 0.0
    if int(prm[S_BALL_MODEL]) == MATHAVAN_BALLS:
        ball_ball_mathavan(
            vxi, vyi, wxi, wyi, wzi, vxj, vyj, wxj, wyj, wzj, nx, ny, masses[i], masses[j],
            prm[P_RADIUS], e_eff, int(prm[S_FRICTION_MODE]), prm[S_MU_BALL], prm[S_MU_SLIDE],
            prm[S_MATHAVAN_STEPS], out,
        )  # fmt: skip
    else:
        ball_ball_spin(
            vxi, vyi, wxi, wyi, wzi, vxj, vyj, wxj, wyj, wzj, nx, ny, masses[i], masses[j],
            prm[P_RADIUS], e_eff, int(prm[S_FRICTION_MODE]), prm[S_MU_BALL], out,
        )  # fmt: skip
    set_anchor(st, ms, i, now, xi, yi, out[0], out[1], out[2], out[3], out[4], prm, CLASSIFY)
    set_anchor(st, ms, j, now, xj, yj, out[5], out[6], out[7], out[8], out[9], prm, CLASSIFY)
    return repeats >= ZENO_REPEATS or pressed_pair(st, i, j, nx, ny, now)


@kernel
def validate_spins(angular, radius):
    """Check ``(N, 3)`` angular velocities; return ``(code, i, -1)`` (``OK`` if none)."""
    for i in range(angular.shape[0]):
        w2 = 0.0
        for c in range(3):
            if not np.isfinite(angular[i, c]):
                return BAD_SPIN, i, -1
            w2 += angular[i, c] * angular[i, c]
        if not radius * math.sqrt(w2) <= MAX_SPEED:
            return SPIN_TOO_FAST, i, -1
    return OK, -1, -1


@kernel
def validate_spin_scene(positions, velocities, angular, masses, prm, pockets):
    """Check a spin scene; return ``(code, i, j)`` naming the first problem (``OK`` if none).

    :func:`~pool_env.sim.kernels.validation.validate`, then :func:`validate_spins`, then the
    energy limit with the spin's energy counted
    (:func:`~pool_env.sim.kernels.limits.reachable_speed2_spin`: ``TOO_ENERGETIC``).
    """
    code, i, j = validate(positions, velocities, masses, prm, pockets)
    if code == OK:
        code, i, j = validate_spins(angular, prm[P_RADIUS])
    if code == OK:
        reach2, lightest = reachable_speed2_spin(velocities, angular, masses, prm[P_RADIUS])
        if not speed_allowed(reach2, prm[P_DECEL]):
            return TOO_ENERGETIC, lightest, -1
    return code, i, j


@level_method(level.start, SpinLevel)
def _start(level, positions, velocities, angular, prm):
    n = positions.shape[0]
    st = np.zeros((n, SCOL), dtype=np.float64)
    ms = np.zeros(n, dtype=np.int8)
    for i in range(n):
        set_anchor(
            st, ms, i, 0.0, positions[i, 0], positions[i, 1], velocities[i, 0],
            velocities[i, 1], angular[i, 0], angular[i, 1], angular[i, 2], prm, CLASSIFY,
        )  # fmt: skip
    return st, ms


@level_method(level.impact, SpinLevel)
def _impact_event(level, st, ms, masses, i, j, now, repeats, prm, pockets, changed, out):
    if _impact(st, ms, masses, i, j, now, prm, repeats, out):
        return stick(st, ms, masses, i, now, prm, pockets, changed)
    changed[0] = i
    changed[1] = j
    return 2


@level_method(level.cushion, SpinLevel)
def _cushion(level, st, ms, kind, i, j, now, repeats, prm, pockets, out):
    x, y, vx, vy, wx, wy, wz = state_at(st, ms, i, now, prm)
    if kind == CUSHION:
        nx, ny, e = RAIL_NX[j], RAIL_NY[j], prm[P_E_CUSHION]
    else:
        nx, ny = jaw_normal(pockets, kind, j, x, y)
        e = prm[P_E_JAW]
    if wedged_ball(x, y, vx, vy, repeats, prm, pockets):
        set_anchor(st, ms, i, now, x, y, 0.0, 0.0, 0.0, 0.0, wz, prm, CLASSIFY)
        return
    cushion_spin(
        vx, vy, wx, wy, wz, nx, ny, prm[P_RADIUS], prm[S_CUSHION_HEIGHT], e,
        prm[S_CUSHION_FRICTION], int(prm[S_CUSHION_MODEL]), prm[S_OMEGA_RATIO], out,
    )  # fmt: skip
    pressed = pressed_roll(out, nx, ny, prm[P_RADIUS], prm[S_SLIDE_DECEL])
    mode = FORCE_ROLL if pressed else CLASSIFY
    set_anchor(st, ms, i, now, x, y, out[0], out[1], out[2], out[3], out[4], prm, mode)


@level_method(level.capture, SpinLevel)
def _capture(level, st, ms, i, now, prm):
    x, y, _, _, _, _, _ = state_at(st, ms, i, now, prm)
    set_potted(st, ms, i, now, x, y)


@level_method(level.settle, SpinLevel)
def _settle(level, st, ms, kind, i, now, prm):
    x, y, vx, vy, wx, wy, wz = state_at(st, ms, i, now, prm)
    if kind == SLIDE_ROLL:
        set_anchor(st, ms, i, now, x, y, vx, vy, wx, wy, wz, prm, FORCE_ROLL)
    else:  # STOP, ROLL_SPIN (a rolling ball rests), SPIN_STOP
        if ms[i] == ROLLING:
            x, y = rest_point(st, i)
        else:
            wz = 0.0
        set_anchor(st, ms, i, now, x, y, 0.0, 0.0, 0.0, 0.0, wz, prm, CLASSIFY)
    return False  # a transition changes the path: every pair of the ball is re-predicted


@level_method(level.moving, SpinLevel)
def _moving(level, ms, i):
    return moving(ms[i])


@level_method(level.halt, SpinLevel)
def _halt(level, st, ms, i, now, prm):
    x, y, _, _, _, _, wz = state_at(st, ms, i, now, prm)
    set_anchor(st, ms, i, now, x, y, 0.0, 0.0, 0.0, 0.0, wz, prm, CLASSIFY)


@level_method(level.new_segments, SpinLevel, inline=False)
def _new_segments(level, capacity):
    return new_segment_log(capacity, SEG_COLS)


@level_method(level.log_segment, SpinLevel, inline=False)
def _log_segment(level, log, row, k, now, st, ms):
    # A still or potted ball's anchor holds zero velocity, surface spin and acceleration.
    log_anchor(log, row, k, now, st, SEGMENT_COLUMNS, ms[k] == POTTED)


@level_method(level.check_scene, SpinLevel)
def _check_scene(level, positions, velocities, angular, masses, prm, pockets):
    return validate_spin_scene(positions, velocities, angular, masses, prm, pockets)


@level_method(level.strike, SpinLevel)
def _strike(level, speed, angle, a, b, elevation, prm, out):
    cue_strike(
        speed, angle, a, b, elevation, prm[P_RADIUS], prm[P_MASS], prm[S_END_MASS],
        prm[S_TIP_RADIUS], out,
    )  # fmt: skip


@level_method(level.tail_sizes, SpinLevel)
def _tail_sizes(level):
    return SPIN_TAIL_FLOATS, SPIN_TAIL_INTS


@level_method(level.write_tails, SpinLevel)
def _write_tails(level, floats, ints, f, k, st, ms, now, prm):
    # The final angular velocities (N, 3), then the final motion states (N,).
    for i in range(st.shape[0]):
        _, _, _, _, wx, wy, wz = state_at(st, ms, i, now, prm)
        floats[f + 3 * i] = wx
        floats[f + 3 * i + 1] = wy
        floats[f + 3 * i + 2] = wz
        ints[k + i] = ms[i]


#: The level's entry points for Python (:mod:`~pool_env.sim.kernels.entries`).
ENTRIES = entries(SpinLevel)
