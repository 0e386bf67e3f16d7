"""The event loop of the spin level (compiled): one call simulates a whole shot to rest.

A sibling of :mod:`~pool_env.sim.kernels.loop` (the roll level, whose code path this module
does not touch): the same structure (ball anchors, each ball's next own event, an
upper-triangular matrix of pair impact times, re-prediction of only the balls an event
changed), the same total order of simultaneous events (time, kind, first id, second id),
the same event cap and the same Zeno rules for ball-ball impacts, with:

* ball state with angular velocity and a motion state
  (:mod:`~pool_env.sim.kernels.spin_state`), motion on curved (parabolic) paths;
* the transitions as events at closed-form times: ``SLIDE_ROLL``, ``STOP`` (a rolling ball
  comes to rest), ``ROLL_SPIN`` (it comes to rest spinning in place), ``SPIN_STOP``
  (:mod:`~pool_env.sim.kernels.spin_predict`), ordered after the roll level's kinds;
* the closed-form resolution kernels of the spin level: ball-ball with throw
  (:mod:`~pool_env.sim.kernels.spin_collide`), Han 2005 cushions
  (:mod:`~pool_env.sim.kernels.spin_cushion`) for rails, jaw facings and jaw points (a
  point's normal runs from its tip's centre to the ball's), with ``e_jaw`` at the jaws.

The Zeno rules and the pressed-cushion rule: :mod:`~pool_env.sim.kernels.spin_zeno`.
"""

from __future__ import annotations

import math

import numpy as np

from pool_env.sim.jit import kernel
from pool_env.sim.kernels.jaws import jaw_normal
from pool_env.sim.kernels.kinds import BALL, CUSHION, JAW, POCKET, POINT, SLIDE_ROLL
from pool_env.sim.kernels.limits import MAX_SPEED, reachable_speed2_spin, speed_allowed
from pool_env.sim.kernels.packing import (
    BALL_CUSHIONS,
    BALL_STOPPED,
    N_BALL_ROWS,
    SPIN_TAIL_FLOATS,
    SPIN_TAIL_INTS,
    invalid_shot,
    pack_shot,
)
from pool_env.sim.kernels.params import (
    P_DECEL,
    P_E_BALL,
    P_E_CUSHION,
    P_E_JAW,
    P_MASS,
    P_RADIUS,
)
from pool_env.sim.kernels.record import (
    SegmentLog,
    grown_event_log,
    grown_segment_log,
    log_event,
    new_event_log,
)
from pool_env.sim.kernels.resolve import (
    V_ZENO,
    ZENO_REPEATS,
    ZENO_WINDOW,
)
from pool_env.sim.kernels.roots import INF
from pool_env.sim.kernels.sequence import next_event, tally
from pool_env.sim.kernels.spin_collide import ball_ball_spin
from pool_env.sim.kernels.spin_cushion import cushion_han
from pool_env.sim.kernels.spin_params import (
    S_CUSHION_FRICTION,
    S_CUSHION_HEIGHT,
    S_END_MASS,
    S_FRICTION_MODE,
    S_MU_BALL,
    S_TIP_RADIUS,
)
from pool_env.sim.kernels.spin_predict import predict_own, predict_pair
from pool_env.sim.kernels.spin_state import (
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
from pool_env.sim.kernels.spin_strike import cue_strike
from pool_env.sim.kernels.spin_zeno import RAIL_NX, RAIL_NY, pressed_roll, stick, wedged_ball
from pool_env.sim.kernels.validation import (
    BAD_SPIN,
    OK,
    SPIN_TOO_FAST,
    TOO_ENERGETIC,
    validate,
)

#: Columns of a spin segment row: ``x, y, vx, vy, wx, wy, wz, ax, ay`` at the row's time.
SEG_COLS = 9


@kernel
def _new_segments(capacity):
    return SegmentLog(
        np.empty(capacity, dtype=np.int64),
        np.empty(capacity, dtype=np.float64),
        np.empty((capacity, SEG_COLS), dtype=np.float64),
        np.zeros(capacity, dtype=np.bool_),
    )


@kernel
def _log_segment(log, row, k, now, st, ms):
    log.ball[row] = k
    log.t[row] = now
    # A still or potted ball's anchor holds zero velocity, surface spin and acceleration.
    for c, col in enumerate((PX, PY, VX, VY, WX, WY, WZ, AX, AY)):
        log.state[row, c] = st[k, col]
    log.potted[row] = ms[k] == POTTED


@kernel
def _repredict(st, ms, k, now, prm, own, boxes, pair):
    for j in range(st.shape[0]):
        if j != k:
            lo, hi = (k, j) if k < j else (j, k)
            pair[lo, hi] = predict_pair(st, ms, lo, hi, now, prm, own, boxes)


@kernel
def _impact(st, ms, masses, i, j, now, prm, repeats, out):
    """Resolve the impact of balls ``i`` and ``j``; return whether the pair must stick."""
    xi, yi, vxi, vyi, wxi, wyi, wzi = state_at(st, ms, i, now, prm)
    xj, yj, vxj, vyj, wxj, wyj, wzj = state_at(st, ms, j, now, prm)
    dx, dy = xj - xi, yj - yi
    dist = math.sqrt(dx * dx + dy * dy)
    nx, ny = dx / dist, dy / dist
    approach = (vxi - vxj) * nx + (vyi - vyj) * ny
    e = prm[P_E_BALL]
    e_eff = e if approach >= V_ZENO or (approach > 0.0 and repeats < 2) else 0.0
    ball_ball_spin(
        vxi, vyi, wxi, wyi, wzi, vxj, vyj, wxj, wyj, wzj, nx, ny, masses[i], masses[j],
        prm[P_RADIUS], e_eff, int(prm[S_FRICTION_MODE]), prm[S_MU_BALL], out,
    )  # fmt: skip
    set_anchor(st, ms, i, now, xi, yi, out[0], out[1], out[2], out[3], out[4], prm, CLASSIFY)
    set_anchor(st, ms, j, now, xj, yj, out[5], out[6], out[7], out[8], out[9], prm, CLASSIFY)
    return repeats >= ZENO_REPEATS


@kernel
def shoot_spin(positions, velocities, angular, masses, prm, pockets, max_events, record):
    """Simulate one spin shot to rest (inputs validated); see :func:`packed_spin_shot`.

    Returns:
        ``(st, ms, balls, first_i, first_j, n_events, now, capped, events, segments,
        n_segments)``: the final anchors and motion states, the per-ball rows of
        :mod:`~pool_env.sim.kernels.loop`, and as the roll loop's ``_shoot``.
    """
    n = positions.shape[0]
    if masses.shape[0] == 0:
        masses = np.full(n, prm[P_MASS])
    st = np.zeros((n, SCOL), dtype=np.float64)
    ms = np.zeros(n, dtype=np.int8)
    for i in range(n):
        set_anchor(
            st, ms, i, 0.0, positions[i, 0], positions[i, 1], velocities[i, 0],
            velocities[i, 1], angular[i, 0], angular[i, 1], angular[i, 2], prm, CLASSIFY,
        )  # fmt: skip
    own = np.empty((n, 4), dtype=np.float64)
    boxes = np.empty((n, 4), dtype=np.float64)
    for i in range(n):
        predict_own(st, ms, i, prm, pockets, own, boxes)
    pair = np.full((n, n), INF, dtype=np.float64)
    for i in range(n):
        for j in range(i + 1, n):
            pair[i, j] = predict_pair(st, ms, i, j, 0.0, prm, own, boxes)
    # Pairs (i < j) fill the upper triangle; the diagonal counts each ball's cushion impacts
    # in a row within ZENO_WINDOW (the single ball's jam rule, spin_zeno.wedged_ball).
    pair_last = np.full((n, n), -INF, dtype=np.float64)
    pair_repeats = np.zeros((n, n), dtype=np.int64)
    balls = np.full((N_BALL_ROWS, n), -1, dtype=np.int64)
    balls[BALL_CUSHIONS] = 0
    balls[BALL_STOPPED] = 0
    first_i = first_j = -1
    events = new_event_log(16 if record else 0)
    segments = _new_segments(max(2 * n, 16) if record else 0)
    n_seg = 0
    if record:
        for i in range(n):
            _log_segment(segments, n_seg, i, 0.0, st, ms)
            n_seg += 1
    out = np.empty(10, dtype=np.float64)
    changed = np.empty(n, dtype=np.int64)
    n_ev = 0
    now = 0.0
    capped = False
    e_c, f_c, h = prm[P_E_CUSHION], prm[S_CUSHION_FRICTION], prm[S_CUSHION_HEIGHT]
    e_jaw = prm[P_E_JAW]
    radius = prm[P_RADIUS]
    while True:
        bt, bkind, bi, bj = next_event(own, pair)
        if bt == INF:
            break
        if n_ev >= max_events:
            capped = True
            break
        now = bt
        if record:
            if n_ev == events.t.shape[0]:
                events = grown_event_log(events)
            log_event(events, n_ev, now, bkind, bi, bj, n_seg)
        n_ev += 1
        first_i, first_j = tally(bkind, bi, bj, balls, first_i, first_j)
        changed[0] = bi
        n_changed = 1
        if bkind == BALL:
            if now - pair_last[bi, bj] <= ZENO_WINDOW:
                pair_repeats[bi, bj] += 1
            else:
                pair_repeats[bi, bj] = 1
            pair_last[bi, bj] = now
            if _impact(st, ms, masses, bi, bj, now, prm, pair_repeats[bi, bj], out):
                n_changed = stick(st, ms, masses, bi, now, prm, pockets, changed)
            else:
                changed[1] = bj
                n_changed = 2
        else:
            x, y, vx, vy, wx, wy, wz = state_at(st, ms, bi, now, prm)
            if bkind == POCKET:
                set_potted(st, ms, bi, now, x, y)
            elif bkind == CUSHION or bkind == JAW or bkind == POINT:  # noqa: SIM109 (numba)
                if bkind == CUSHION:
                    nx, ny, e = RAIL_NX[bj], RAIL_NY[bj], e_c
                else:
                    nx, ny = jaw_normal(pockets, bkind, bj, x, y)
                    e = e_jaw
                if now - pair_last[bi, bi] <= ZENO_WINDOW:
                    pair_repeats[bi, bi] += 1
                else:
                    pair_repeats[bi, bi] = 1
                pair_last[bi, bi] = now
                if wedged_ball(x, y, vx, vy, pair_repeats[bi, bi], prm, pockets):
                    set_anchor(st, ms, bi, now, x, y, 0.0, 0.0, 0.0, 0.0, wz, prm, CLASSIFY)
                else:
                    cushion_han(vx, vy, wx, wy, wz, nx, ny, radius, h, e, f_c, out)
                    mode = FORCE_ROLL if pressed_roll(out, nx, ny, radius) else CLASSIFY
                    set_anchor(
                        st, ms, bi, now, x, y, out[0], out[1], out[2], out[3], out[4], prm, mode
                    )
            elif bkind == SLIDE_ROLL:
                set_anchor(st, ms, bi, now, x, y, vx, vy, wx, wy, wz, prm, FORCE_ROLL)
            else:  # STOP, ROLL_SPIN (a rolling ball rests), SPIN_STOP
                if ms[bi] == ROLLING:
                    x, y = rest_point(st, bi)
                else:
                    wz = 0.0
                set_anchor(st, ms, bi, now, x, y, 0.0, 0.0, 0.0, 0.0, wz, prm, CLASSIFY)
        for c in range(n_changed):
            predict_own(st, ms, changed[c], prm, pockets, own, boxes)
        for c in range(n_changed):
            _repredict(st, ms, changed[c], now, prm, own, boxes, pair)
        if record:
            if n_seg + n_changed > segments.t.shape[0]:
                segments = grown_segment_log(segments)
            for c in range(n_changed):
                _log_segment(segments, n_seg, changed[c], now, st, ms)
                n_seg += 1
    if capped:
        for i in range(n):
            if moving(ms[i]):
                balls[BALL_STOPPED, i] = 1
                x, y, _, _, _, _, wz = state_at(st, ms, i, now, prm)
                set_anchor(st, ms, i, now, x, y, 0.0, 0.0, 0.0, 0.0, wz, prm, CLASSIFY)
                if record:
                    if n_seg == segments.t.shape[0]:
                        segments = grown_segment_log(segments)
                    _log_segment(segments, n_seg, i, now, st, ms)
                    n_seg += 1
    return st, ms, balls, first_i, first_j, n_ev, now, capped, events, segments, n_seg


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


@kernel
def packed_spin_shot(positions, velocities, angular, masses, prm, pockets, max_events, record):
    """Validate and simulate one spin shot in a single call, for Python.

    The layout of :func:`~pool_env.sim.kernels.packing.pack_shot` with segment states of
    ``SEG_COLS`` columns and the spin level's tails: the final angular velocities
    ``(N, 3)`` in ``floats`` and the final motion states ``(N,)`` in ``ints``.

    Returns:
        As :func:`~pool_env.sim.kernels.loop.packed_shot`.
    """
    code, ci, cj = validate_spin_scene(positions, velocities, angular, masses, prm, pockets)
    if code != OK:
        return invalid_shot(code, ci, cj)
    st, ms, balls, first_i, first_j, n_ev, now, capped, events, segments, n_seg = shoot_spin(
        positions, velocities, angular, masses, prm, pockets, max_events, record
    )
    n_log = n_ev if record else 0
    floats, ints, n_floats, f, k = pack_shot(
        st, balls, events, n_log, segments, n_seg, SPIN_TAIL_FLOATS, SPIN_TAIL_INTS
    )
    for i in range(positions.shape[0]):
        _, _, _, _, wx, wy, wz = state_at(st, ms, i, now, prm)
        floats[f + 3 * i] = wx
        floats[f + 3 * i + 1] = wy
        floats[f + 3 * i + 2] = wz
        ints[k + i] = ms[i]
    return OK, -1, -1, floats, n_floats, n_ev, n_seg, first_i, first_j, capped, now


@kernel
def packed_spin_strike(
    positions, cue, speed, angle, a, b, elevation, masses, prm, pockets, max_events, record
):
    """:func:`packed_spin_shot` of a cue strike: ball ``cue`` struck, the others at rest.

    The strike (:func:`~pool_env.sim.kernels.spin_strike.cue_strike`, with the table's
    ball radius and mass, cue end mass and tip radius from ``prm``) runs inside the one
    compiled call: from Python it cost two arrays and a call of its own, about a tenth of
    a two-ball shot. Returns as :func:`packed_spin_shot`.
    """
    n = positions.shape[0]
    velocities = np.zeros((n, 2))
    angular = np.zeros((n, 3))
    out = np.empty(5)
    cue_strike(
        speed, angle, a, b, elevation, prm[P_RADIUS], prm[P_MASS], prm[S_END_MASS],
        prm[S_TIP_RADIUS], out,
    )  # fmt: skip
    velocities[cue, 0], velocities[cue, 1] = out[0], out[1]
    angular[cue, 0], angular[cue, 1], angular[cue, 2] = out[2], out[3], out[4]
    return packed_spin_shot(
        positions, velocities, angular, masses, prm, pockets, max_events, record
    )
