"""The event loop (compiled): one call simulates a whole shot to rest.

State is arrays: the ball anchors, each ball's next own event (cushion, pocket or stop), and
an upper-triangular matrix of pair impact times. After an event only the balls it touched
are re-predicted: their own events and their pairs with every other ball. A stop leaves
every prediction valid (the pair predictions already include each ball's rest phase).

Simultaneous events are taken in the fixed total order (time, kind, first id, second id)
with kinds ordered pocket < ball < cushion < stop, which makes reruns bit-for-bit identical.
A touching rack hit by the cue ball is therefore resolved as a deterministic sequence of
pairwise impacts at the same instant, each re-predicting the balls it changed: the
sequential-impulse rule. With three or more balls in contact, momentum and restitution do
not fix the outcome, so some such rule has to be chosen; this one conserves momentum and
never adds energy.

A hard cap on the number of events ends a pathological shot: every ball is stopped where it
is at that instant, and the result reports it.
"""

from __future__ import annotations

import numpy as np

from pool_env.sim.kernels._jit import kernel
from pool_env.sim.kernels.motion import (
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
)
from pool_env.sim.kernels.predict import (
    BALL,
    CUSHION,
    EV_ARG,
    EV_KIND,
    EV_T,
    POCKET,
    STOP,
    predict_own,
    predict_pair,
)
from pool_env.sim.kernels.resolve import V_REST, ZENO_WINDOW, ball_ball, cushion, stick_cluster
from pool_env.sim.kernels.roots import INF

# Tolerance of input validation: rounding in a rack or a position read back from a result
# may leave a ball a hair over a rail or another ball.
POS_TOL = 1e-9

# Validation codes.
OK, BAD_POSITION, BAD_VELOCITY, BAD_MASS, OFF_TABLE, OVERLAP, IN_POCKET = range(7)


@kernel
def validate(positions, velocities, masses, params, pockets):
    """Check a scene; return ``(code, i, j)`` naming the first problem (``OK`` if none)."""
    length, width, radius = params[0], params[1], params[2]
    n = positions.shape[0]
    for i in range(n):
        if not (np.isfinite(positions[i, 0]) and np.isfinite(positions[i, 1])):
            return BAD_POSITION, i, -1
        if not (np.isfinite(velocities[i, 0]) and np.isfinite(velocities[i, 1])):
            return BAD_VELOCITY, i, -1
        if masses.shape[0] and not (masses[i] > 0.0 and np.isfinite(masses[i])):
            return BAD_MASS, i, -1
    for i in range(n):
        x, y = positions[i, 0], positions[i, 1]
        if (
            x < radius - POS_TOL
            or x > length - radius + POS_TOL
            or y < radius - POS_TOL
            or y > width - radius + POS_TOL
        ):
            return OFF_TABLE, i, -1
        for k in range(pockets.shape[0]):
            dx = x - pockets[k, 0]
            dy = y - pockets[k, 1]
            if dx * dx + dy * dy <= pockets[k, 2] * pockets[k, 2]:
                return IN_POCKET, i, k
    min_d2 = (2.0 * radius - POS_TOL) ** 2
    for i in range(n):
        for j in range(i + 1, n):
            dx = positions[j, 0] - positions[i, 0]
            dy = positions[j, 1] - positions[i, 1]
            if dx * dx + dy * dy < min_d2:
                return OVERLAP, i, j
    return OK, -1, -1


@kernel
def _earlier(t, kind, i, j, bt, bkind, bi, bj):
    """The total order of events: (time, kind, first id, second id)."""
    if t != bt:
        return t < bt
    if kind != bkind:
        return kind < bkind
    if i != bi:
        return i < bi
    return j < bj


@kernel
def _grow(arr, n):
    """``arr`` if it has room for index ``n``, else a copy with twice the capacity."""
    if n < arr.shape[0]:
        return arr
    out = np.empty((max(2 * arr.shape[0], 16),) + arr.shape[1:], dtype=arr.dtype)
    out[:n] = arr[:n]
    return out


@kernel
def _log_segment(seg_ball, seg_t, seg_state, seg_potted, row, k, now, st, status):
    """Record that ball ``k``'s trajectory is re-anchored at ``now``."""
    seg_ball[row] = k
    seg_t[row] = now
    seg_state[row, 0] = st[k, PX]
    seg_state[row, 1] = st[k, PY]
    seg_state[row, 2] = st[k, VX]
    seg_state[row, 3] = st[k, VY]
    seg_potted[row] = status[k] == POTTED


@kernel
def _repredict_pairs(st, status, k, now, params, own, caps, pair):
    n = st.shape[0]
    for j in range(n):
        if j == k:
            continue
        lo, hi = (k, j) if k < j else (j, k)
        pair[lo, hi] = predict_pair(st, status, lo, hi, now, params, own, caps)


@kernel
def run_shot(positions, velocities, masses, params, pockets, max_events, record):
    """Simulate one shot to rest.

    Args:
        positions: ``(N, 2)`` ball centres (validated).
        velocities: ``(N, 2)`` initial velocities.
        masses: ``(N,)`` masses, or an empty array for the table's ball mass.
        params: The table's flat parameter array (``Table.params``).
        pockets: ``(K, 3)`` capture circles.
        max_events: Event cap.
        record: Whether to log events and trajectory segments (off for batched training).

    Returns:
        ``(final_positions, pocketed, n_events, duration, capped, first_i, first_j,
        ev_t, ev_kind, ev_i, ev_j, ev_seg, seg_ball, seg_t, seg_state, seg_potted)`` where
        the ``ev_*`` arrays list events chronologically (``ev_seg``: the first segment row
        each event wrote) and each segment row anchors a ball's trajectory from ``seg_t`` on
        (``seg_state`` holds x, y, vx, vy).
    """
    n = positions.shape[0]
    a = params[3]
    if masses.shape[0] == 0:
        masses = np.full(n, params[6])
    st = np.zeros((n, NCOL), dtype=np.float64)
    status = np.zeros(n, dtype=np.int8)
    for i in range(n):
        # No rest threshold on the cue: any positive speed moves the ball.
        set_anchor(
            st,
            status,
            i,
            0.0,
            positions[i, 0],
            positions[i, 1],
            velocities[i, 0],
            velocities[i, 1],
            a,
            0.0,
        )
    own = np.empty((n, 4), dtype=np.float64)
    caps = np.empty((n, 4), dtype=np.float64)
    for i in range(n):
        predict_own(st, status, i, params, pockets, own, caps)
    pair = np.full((n, n), INF, dtype=np.float64)
    for i in range(n):
        for j in range(i + 1, n):
            pair[i, j] = predict_pair(st, status, i, j, 0.0, params, own, caps)
    pocketed = np.full(n, -1, dtype=np.int64)
    pair_last = np.full((n, n), -INF, dtype=np.float64)  # time of each pair's last impact
    pair_repeats = np.zeros((n, n), dtype=np.int64)  # impacts in a row within ZENO_WINDOW

    ev_t = np.empty(16 if record else 0, dtype=np.float64)
    ev_kind = np.empty(16 if record else 0, dtype=np.int8)
    ev_i = np.empty(16 if record else 0, dtype=np.int64)
    ev_j = np.empty(16 if record else 0, dtype=np.int64)
    ev_seg = np.empty(16 if record else 0, dtype=np.int64)  # first segment row of each event
    n_seg = n if record else 0
    seg_cap = max(2 * n, 16) if record else 0
    seg_ball = np.empty(seg_cap, dtype=np.int64)
    seg_t = np.empty(seg_cap, dtype=np.float64)
    seg_state = np.empty((seg_cap, 4), dtype=np.float64)
    seg_potted = np.zeros(seg_cap, dtype=np.bool_)
    if record:
        for i in range(n):
            seg_ball[i] = i
            seg_t[i] = 0.0
            seg_state[i, 0] = st[i, PX]
            seg_state[i, 1] = st[i, PY]
            seg_state[i, 2] = st[i, VX]
            seg_state[i, 3] = st[i, VY]

    n_ev = 0
    now = 0.0
    capped = False
    first_i = -1
    first_j = -1
    changed = np.empty(n, dtype=np.int64)  # balls re-anchored by the current event
    while True:
        bt, bkind, bi, bj = INF, 99, n, n
        for i in range(n):
            t = own[i, EV_T]
            if t < INF:
                kind = int(own[i, EV_KIND])
                arg = int(own[i, EV_ARG])
                if _earlier(t, kind, i, arg, bt, bkind, bi, bj):
                    bt, bkind, bi, bj = t, kind, i, arg
        for i in range(n):
            for j in range(i + 1, n):
                t = pair[i, j]
                if t < INF and _earlier(t, BALL, i, j, bt, bkind, bi, bj):
                    bt, bkind, bi, bj = t, BALL, i, j
        if bt == INF:
            break
        if n_ev >= max_events:
            capped = True
            break
        now = bt
        if record:
            ev_t = _grow(ev_t, n_ev)
            ev_kind = _grow(ev_kind, n_ev)
            ev_i = _grow(ev_i, n_ev)
            ev_j = _grow(ev_j, n_ev)
            ev_seg = _grow(ev_seg, n_ev)
            ev_seg[n_ev] = n_seg
            ev_t[n_ev] = now
            ev_kind[n_ev] = bkind
            ev_i[n_ev] = bi
            ev_j[n_ev] = bj
        n_ev += 1

        n_changed = 0
        if bkind == STOP:
            x, y = rest_point(st, bi, a)
            set_anchor(st, status, bi, now, x, y, 0.0, 0.0, a, V_REST)
            predict_own(st, status, bi, params, pockets, own, caps)
        elif bkind == POCKET:
            x, y, _, _ = state_at(st, status, bi, now, a)
            set_anchor(st, status, bi, now, x, y, 0.0, 0.0, a, V_REST)
            status[bi] = POTTED
            pocketed[bi] = bj
            predict_own(st, status, bi, params, pockets, own, caps)
            for j in range(n):
                lo, hi = (bi, j) if bi < j else (j, bi)
                pair[lo, hi] = INF
            changed[0] = bi
            n_changed = 1
        elif bkind == CUSHION:
            cushion(st, status, bi, bj, now, params)
            predict_own(st, status, bi, params, pockets, own, caps)
            _repredict_pairs(st, status, bi, now, params, own, caps, pair)
            changed[0] = bi
            n_changed = 1
        else:
            if first_i < 0:
                first_i, first_j = bi, bj
            if now - pair_last[bi, bj] <= ZENO_WINDOW:
                pair_repeats[bi, bj] += 1
            else:
                pair_repeats[bi, bj] = 1
            pair_last[bi, bj] = now
            if ball_ball(st, status, masses, bi, bj, now, params, pair_repeats[bi, bj]):
                n_changed = stick_cluster(st, status, masses, bi, now, params, changed)
            else:
                changed[0] = bi
                changed[1] = bj
                n_changed = 2
            for c in range(n_changed):
                predict_own(st, status, changed[c], params, pockets, own, caps)
            for c in range(n_changed):
                _repredict_pairs(st, status, changed[c], now, params, own, caps, pair)
        if record:
            for c in range(n_changed):
                seg_ball = _grow(seg_ball, n_seg)
                seg_t = _grow(seg_t, n_seg)
                seg_state = _grow(seg_state, n_seg)
                seg_potted = _grow(seg_potted, n_seg)
                _log_segment(
                    seg_ball, seg_t, seg_state, seg_potted, n_seg, changed[c], now, st, status
                )
                n_seg += 1
    if capped:
        for i in range(n):
            if status[i] == MOVING:
                x, y, _, _ = state_at(st, status, i, now, a)
                set_anchor(st, status, i, now, x, y, 0.0, 0.0, a, V_REST)
                if record:
                    seg_ball = _grow(seg_ball, n_seg)
                    seg_t = _grow(seg_t, n_seg)
                    seg_state = _grow(seg_state, n_seg)
                    seg_potted = _grow(seg_potted, n_seg)
                    _log_segment(seg_ball, seg_t, seg_state, seg_potted, n_seg, i, now, st, status)
                    n_seg += 1
    final = np.empty((n, 2), dtype=np.float64)
    for i in range(n):
        final[i, 0] = st[i, PX]
        final[i, 1] = st[i, PY]
    return (
        final,
        pocketed,
        n_ev,
        now,
        capped,
        first_i,
        first_j,
        ev_t[:n_ev].copy(),
        ev_kind[:n_ev].copy(),
        ev_i[:n_ev].copy(),
        ev_j[:n_ev].copy(),
        ev_seg[:n_ev].copy(),
        seg_ball[:n_seg].copy(),
        seg_t[:n_seg].copy(),
        seg_state[:n_seg].copy(),
        seg_potted[:n_seg].copy(),
    )


@kernel
def shoot_final(positions, velocities, masses, params, pockets, max_events, final, pocketed, meta):
    """Validate and simulate one shot in a single call, writing only the final state.

    The lean path for training loops: no event log, and nothing allocated for Python (each
    array handed back to Python costs a Python object).

    Args:
        positions, velocities, masses, params, pockets, max_events: As for :func:`run_shot`.
        final: ``(N, 2)`` output: final positions.
        pocketed: ``(N,)`` output: pockets (-1 on the table).
        meta: ``(7,)`` output: ``(code, i, j, n_events, capped, first_i, first_j)``, where
            ``code`` is the validation code (``OK``, or the problem with balls ``i, j``,
            and then nothing is simulated).

    Returns:
        The shot's duration (s).
    """
    code, i, j = validate(positions, velocities, masses, params, pockets)
    meta[0], meta[1], meta[2] = code, i, j
    if code != OK:
        return 0.0
    out = run_shot(positions, velocities, masses, params, pockets, max_events, False)
    final[:] = out[0]
    pocketed[:] = out[1]
    meta[3], meta[4], meta[5], meta[6] = out[2], out[4], out[5], out[6]
    return out[3]
