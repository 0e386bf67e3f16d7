"""The event loop (compiled): one call simulates a whole shot to rest.

State is arrays: the ball anchors, each ball's next own event (cushion, pocket or stop), and
an upper-triangular matrix of pair impact times. After an event only the balls it touched
are re-predicted: their own events and their pairs with every other ball. A stop leaves
every prediction valid (the pair predictions already include each ball's rest phase).

Simultaneous events are taken in the fixed total order (time, kind, first id, second id)
with kinds ordered pocket < ball < cushion < stop < jaw < point, which makes reruns
bit-for-bit identical (:mod:`~pool_env.sim.kernels.sequence`, shared with the spin loop, as
is the scene validation of :mod:`~pool_env.sim.kernels.validation`).
A touching rack hit by the cue ball is therefore resolved as a deterministic sequence of
pairwise impacts at the same instant, each re-predicting the balls it changed: the
sequential-impulse rule. With three or more balls in contact, momentum and restitution do
not fix the outcome, so some such rule has to be chosen; this one conserves momentum and
never adds energy.

A hard cap on the number of events ends a pathological shot: every ball is stopped where it
is at that instant, and the result reports it and which balls were still moving then.
"""

from __future__ import annotations

from collections import namedtuple

import numpy as np

from pool_env.sim.jit import kernel
from pool_env.sim.kernels.jaws import (
    JAW_COLS,
    jaw_impact,
    unpress_lump,
)
from pool_env.sim.kernels.kinds import CUSHION, JAW, POCKET, POINT, STOP
from pool_env.sim.kernels.motion import (
    MOVING,
    NCOL,
    POTTED,
    PX,
    PY,
    rest_point,
    set_anchor,
    state_at,
)
from pool_env.sim.kernels.packing import (
    BALL_CUSHIONS,
    BALL_FIRST_HIT,
    BALL_POCKET,
    BALL_POCKET_ORDER,
    BALL_STOPPED,
    N_BALL_ROWS,
    invalid_shot,
    pack_shot,
)
from pool_env.sim.kernels.params import P_DECEL, P_MASS
from pool_env.sim.kernels.predict import predict_own, predict_pair
from pool_env.sim.kernels.record import (
    grown_event_log,
    grown_segment_log,
    log_event,
    log_segment,
    new_event_log,
    new_segment_log,
    trim_events,
    trim_segments,
)
from pool_env.sim.kernels.resolve import (
    CONTACT_TOL,
    V_REST,
    V_ZENO,
    ZENO_WINDOW,
    ball_ball,
    cushion,
    stick_cluster,
)
from pool_env.sim.kernels.roots import INF
from pool_env.sim.kernels.sequence import next_event, tally
from pool_env.sim.kernels.validation import OK, validate

#: What :func:`run_shot` returns, by name.
#:
#: * ``positions`` ``(N, 2)``: final positions (a potted ball keeps its capture point).
#: * ``pocketed`` ``(N,)``: the pocket each ball dropped into, -1 if none.
#: * ``pocket_order`` ``(N,)``: 0 for the first ball to drop, 1 for the next, ...; -1 if none.
#: * ``first_i``, ``first_j``: the shot's first ball-ball impact (``i < j``), -1 if none.
#: * ``first_hit`` ``(N,)``: the first ball each ball touched, -1 if none. For the struck
#:   ball of a shot that is the rules' first contact.
#: * ``cushions_after_contact`` ``(N,)``: each ball's cushion impacts (rails, jaw facings and
#:   points) after the shot's first ball-ball impact (all zero if there was none). With one
#:   ball struck, that impact is the cue ball's first contact: the "rail after contact" of
#:   the rules.
#: * ``n_events``, ``duration`` (s), ``capped`` (the event cap was reached).
#: * ``stopped_by_cap`` ``(N,)``: 1 for each ball still moving when the cap stopped it.
#: * ``events``: an :data:`~pool_env.sim.kernels.record.EventLog`, ``segments``: a
#:   :data:`~pool_env.sim.kernels.record.SegmentLog`, both chronological and empty unless
#:   recorded.
ShotOutput = namedtuple(
    "ShotOutput",
    [
        "positions",
        "pocketed",
        "pocket_order",
        "first_i",
        "first_j",
        "first_hit",
        "cushions_after_contact",
        "n_events",
        "duration",
        "capped",
        "stopped_by_cap",
        "events",
        "segments",
    ],
)


@kernel
def _repredict_pairs(st, status, k, now, params, own, caps, pair):
    n = st.shape[0]
    for j in range(n):
        if j == k:
            continue
        lo, hi = (k, j) if k < j else (j, k)
        pair[lo, hi] = predict_pair(st, status, lo, hi, now, params, own, caps)


@kernel
def _shoot(positions, velocities, masses, params, pockets, max_events, record):
    """Simulate one shot to rest: the event loop itself.

    Args:
        positions: ``(N, 2)`` ball centres (validated).
        velocities: ``(N, 2)`` initial velocities.
        masses: ``(N,)`` masses, or an empty array for the table's ball mass.
        params: The table's flat parameter array (``Table.params``).
        pockets: ``Table.pocket_geometry``: ``(K, 3)`` capture circles or the jaw rows.
        max_events: Event cap.
        record: Whether to log events and trajectory segments (off for batched training).

    Returns:
        ``(st, balls, first_i, first_j, n_events, duration, capped, events, segments,
        n_segments)``: the final ball anchors (``st``, columns of
        :mod:`~pool_env.sim.kernels.motion`), the per-ball rows (``BALL_POCKET``, ...), the
        shot's first ball-ball impact, the event count, the time of the last event, whether
        the cap was reached, and the two logs with room to spare (their first ``n_events``
        and ``n_segments`` rows are the shot's; empty unless ``record``).
    """
    n = positions.shape[0]
    a = params[P_DECEL]
    if masses.shape[0] == 0:
        masses = np.full(n, params[P_MASS])
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
    pair_last = np.full((n, n), -INF, dtype=np.float64)  # time of each pair's last impact
    pair_repeats = np.zeros((n, n), dtype=np.int64)  # impacts in a row within ZENO_WINDOW

    balls = np.full((N_BALL_ROWS, n), -1, dtype=np.int64)  # one allocation for four rows
    balls[BALL_CUSHIONS] = 0
    balls[BALL_STOPPED] = 0
    first_i = first_j = -1

    events = new_event_log(16 if record else 0)
    segments = new_segment_log(max(2 * n, 16) if record else 0)
    n_seg = 0
    if record:
        for i in range(n):
            log_segment(segments, n_seg, i, 0.0, st, status)
            n_seg += 1

    n_ev = 0
    now = 0.0
    capped = False
    changed = np.empty(n, dtype=np.int64)  # balls re-anchored by the current event
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

        n_changed = 0
        if bkind == STOP:
            x, y = rest_point(st, bi, a)
            set_anchor(st, status, bi, now, x, y, 0.0, 0.0, a, V_REST)
            predict_own(st, status, bi, params, pockets, own, caps)
        elif bkind == POCKET:
            x, y, _, _ = state_at(st, status, bi, now, a)
            set_anchor(st, status, bi, now, x, y, 0.0, 0.0, a, V_REST)
            status[bi] = POTTED
            predict_own(st, status, bi, params, pockets, own, caps)
            for j in range(n):
                lo, hi = (bi, j) if bi < j else (j, bi)
                pair[lo, hi] = INF
            changed[0] = bi
            n_changed = 1
        elif bkind == CUSHION or bkind == JAW or bkind == POINT:  # noqa: SIM109 (numba)
            if bkind == CUSHION:
                cushion(st, status, bi, bj, now, params)
            else:
                jaw_impact(st, status, bi, bkind, bj, now, params, pockets, V_REST)
            predict_own(st, status, bi, params, pockets, own, caps)
            _repredict_pairs(st, status, bi, now, params, own, caps, pair)
            changed[0] = bi
            n_changed = 1
        else:
            if now - pair_last[bi, bj] <= ZENO_WINDOW:
                pair_repeats[bi, bj] += 1
            else:
                pair_repeats[bi, bj] = 1
            pair_last[bi, bj] = now
            if ball_ball(st, status, masses, bi, bj, now, params, pair_repeats[bi, bj]):
                n_changed = stick_cluster(st, status, masses, bi, now, params, changed)
                if pockets.shape[1] == JAW_COLS:
                    unpress_lump(
                        st, status, changed, n_changed, now, params, pockets, V_ZENO,
                        CONTACT_TOL, V_REST,
                    )  # fmt: skip
            else:
                changed[0] = bi
                changed[1] = bj
                n_changed = 2
            for c in range(n_changed):
                predict_own(st, status, changed[c], params, pockets, own, caps)
            for c in range(n_changed):
                _repredict_pairs(st, status, changed[c], now, params, own, caps, pair)
        if record:
            if n_seg + n_changed > segments.t.shape[0]:
                segments = grown_segment_log(segments)  # doubles: room for N more at least
            for c in range(n_changed):
                log_segment(segments, n_seg, changed[c], now, st, status)
                n_seg += 1
    if capped:
        for i in range(n):
            if status[i] == MOVING:
                balls[BALL_STOPPED, i] = 1
                x, y, _, _ = state_at(st, status, i, now, a)
                set_anchor(st, status, i, now, x, y, 0.0, 0.0, a, V_REST)
                if record:
                    if n_seg == segments.t.shape[0]:
                        segments = grown_segment_log(segments)
                    log_segment(segments, n_seg, i, now, st, status)
                    n_seg += 1
    return st, balls, first_i, first_j, n_ev, now, capped, events, segments, n_seg


@kernel
def run_shot(positions, velocities, masses, params, pockets, max_events, record):
    """Simulate one shot to rest, for compiled callers (the batch).

    Args:
        positions, velocities, masses, params, pockets, max_events, record: As for
            :func:`_shoot` (``positions`` validated).

    Returns:
        A :data:`ShotOutput`; its logs are empty unless ``record``.
    """
    st, balls, first_i, first_j, n_ev, now, capped, events, segments, n_seg = _shoot(
        positions, velocities, masses, params, pockets, max_events, record
    )
    n = positions.shape[0]
    final = np.empty((n, 2), dtype=np.float64)
    for i in range(n):
        final[i, 0] = st[i, PX]
        final[i, 1] = st[i, PY]
    return ShotOutput(
        final,
        balls[BALL_POCKET],
        balls[BALL_POCKET_ORDER],
        first_i,
        first_j,
        balls[BALL_FIRST_HIT],
        balls[BALL_CUSHIONS],
        n_ev,
        now,
        capped,
        balls[BALL_STOPPED],
        trim_events(events, n_ev if record else 0),
        trim_segments(segments, n_seg),
    )


@kernel
def packed_shot(positions, velocities, masses, params, pockets, max_events, record):
    """Validate and simulate one shot in a single call, for Python: the lean path.

    The whole result comes back in one flat buffer, laid out by
    :func:`~pool_env.sim.kernels.packing.pack_shot` (the roll level has no tails);
    :class:`~pool_env.sim.result.ShotResult` takes it over and reads its fields from it
    as views.

    Args:
        positions, velocities, masses, params, pockets, max_events, record: As for
            :func:`_shoot` (``record`` a bool).

    Returns:
        ``(code, i, j, buffer, n_floats, n_events, n_segments, first_i, first_j, capped,
        duration)``: the validation code (``OK``, or the problem with balls ``i``, ``j``
        and then nothing is simulated and the buffer is empty), the packed buffer and the
        length of its float part, the
        event count (the log holds them all if ``record``, none otherwise), the logged
        segments, the shot's first ball-ball impact (-1 if none), whether the event cap
        was reached and the duration (s).
    """
    code, ci, cj = validate(positions, velocities, masses, params, pockets)
    if code != OK:
        return invalid_shot(code, ci, cj)
    st, balls, first_i, first_j, n_ev, now, capped, events, segments, n_seg = _shoot(
        positions, velocities, masses, params, pockets, max_events, record
    )
    n_log = n_ev if record else 0
    buffer, _, n_floats, _, _ = pack_shot(st, balls, events, n_log, segments, n_seg, 0, 0)
    return OK, -1, -1, buffer, n_floats, n_ev, n_seg, first_i, first_j, capped, now
