"""The event loop (compiled), written once for every model level: a whole shot to rest.

The loop is a strategy's client: a model level (:mod:`~pool_env.sim.kernels.level`) gives
the anchors, the predictions and the resolution of each event; the loop owns the order of
events, their re-prediction, the Zeno counters, the event cap and recording. numba
compiles one specialised loop per level marker (``ROLL``, ``SPIN``).

State is arrays: the ball anchors, each ball's next own event (cushion, jaw, pocket or a
transition of its motion state), and an upper-triangular matrix of pair impact times.
After an event only the balls it changed are re-predicted: their own events and their
pairs with every other ball.

Simultaneous events are taken in the fixed total order (time, kind, first id, second id)
with kinds ordered as :mod:`~pool_env.sim.kernels.kinds` numbers them, which makes reruns
bit-for-bit identical (:mod:`~pool_env.sim.kernels.sequence`). A touching rack hit by the
cue ball is therefore resolved as a deterministic sequence of pairwise impacts at the same
instant, each re-predicting the balls it changed: the sequential-impulse rule. With three
or more balls in contact, momentum and restitution do not fix the outcome, so some such
rule has to be chosen; this one conserves momentum and never adds energy.

The loop counts each contact's repeats within ``ZENO_WINDOW`` (a pair of balls, or a ball
with any cushion) and hands the count to the level, whose Zeno rules use it. Each kind of
event is its own call into the level (:func:`~pool_env.sim.kernels.level.impact`,
``cushion``, ``capture``, ``settle``), small enough to inline: one resolution function
branching over every kind cost the roll level 15% per event when inlined whole. A hard cap on
the number of events ends a pathological shot: every ball is stopped where it is at that
instant, and the result reports it and which balls were still moving then.
"""

from __future__ import annotations

import numpy as np

from pool_env.sim.jit import kernel
from pool_env.sim.kernels.contact import ZENO_WINDOW
from pool_env.sim.kernels.kinds import BALL, CUSHION, JAW, POCKET, POINT
from pool_env.sim.kernels.level import (
    capture,
    check_scene,
    cushion,
    halt,
    impact,
    log_segment,
    moving,
    new_segments,
    predict_own,
    predict_pair,
    settle,
    start,
    strike,
    tail_sizes,
    write_tails,
)
from pool_env.sim.kernels.packing import (
    BALL_CUSHIONS,
    BALL_CUSHIONS_AT_SECOND,
    BALL_STOPPED,
    N_BALL_ROWS,
    invalid_shot,
    pack_shot,
)
from pool_env.sim.kernels.params import P_MASS
from pool_env.sim.kernels.record import grown_event_log, grown_segment_log, log_event, new_event_log
from pool_env.sim.kernels.roots import INF
from pool_env.sim.kernels.sequence import close_tally, next_event, tally
from pool_env.sim.kernels.validation import OK


@kernel
def _repredict_pairs(level, st, ms, k, now, prm, own, boxes, pair):
    for j in range(st.shape[0]):
        if j != k:
            lo, hi = (k, j) if k < j else (j, k)
            pair[lo, hi] = predict_pair(level, st, ms, lo, hi, now, prm, own, boxes)


@kernel
def shoot(level, positions, velocities, angular, masses, prm, pockets, max_events, record):
    """Simulate one shot to rest (inputs valid): the event loop itself.

    Args:
        level: The model level's marker (``ROLL`` or ``SPIN``).
        positions: ``(N, 2)`` ball centres.
        velocities: ``(N, 2)`` initial velocities.
        angular: ``(N, 3)`` initial angular velocities (zeros on a level without spin).
        masses: ``(N,)`` masses, or an empty array for the table's ball mass.
        prm: The level's flat parameter array (``Table.params``, ``Table.spin_params``).
        pockets: ``Table.pocket_geometry``: ``(K, 3)`` capture circles or the jaw rows.
        max_events: Event cap.
        record: Whether to log events and trajectory segments (off for batches).

    Returns:
        ``(st, ms, balls, first_i, first_j, n_events, duration, capped, events, segments,
        n_segments)``: the final anchors and motion states, the per-ball rows
        (``BALL_POCKET``, ... of :mod:`~pool_env.sim.kernels.packing`), the shot's first
        ball-ball impact, the event count, the time of the last event, whether the cap was
        reached, and the two logs with room to spare (their first ``n_events`` and
        ``n_segments`` rows are the shot's; empty unless ``record``).
    """
    n = positions.shape[0]
    if masses.shape[0] == 0:
        masses = np.full(n, prm[P_MASS])
    st, ms = start(level, positions, velocities, angular, prm)
    own = np.empty((n, 4), dtype=np.float64)
    boxes = np.empty((n, 4), dtype=np.float64)
    for i in range(n):
        predict_own(level, st, ms, i, prm, pockets, own, boxes)
    pair = np.full((n, n), INF, dtype=np.float64)
    for i in range(n):
        for j in range(i + 1, n):
            pair[i, j] = predict_pair(level, st, ms, i, j, 0.0, prm, own, boxes)
    # Pairs (i < j) fill the upper triangle; the diagonal counts each ball's cushion impacts.
    pair_last = np.full((n, n), -INF, dtype=np.float64)  # time of each contact's last impact
    pair_repeats = np.zeros((n, n), dtype=np.int64)  # impacts in a row within ZENO_WINDOW
    balls = np.full((N_BALL_ROWS, n), -1, dtype=np.int64)  # one allocation for the rows
    balls[BALL_CUSHIONS] = 0
    balls[BALL_STOPPED] = 0
    balls[BALL_CUSHIONS_AT_SECOND] = 0  # counts until the second contact; -1 if none
    t_second = np.full(n, INF)  # each ball's second distinct contact's time
    first_i = first_j = -1
    events = new_event_log(16 if record else 0)
    segments = new_segments(level, max(2 * n, 16) if record else 0)
    n_seg = 0
    if record:
        for i in range(n):
            log_segment(level, segments, n_seg, i, 0.0, st, ms)
            n_seg += 1
    out = np.empty(10, dtype=np.float64)  # the level's scratch space
    changed = np.empty(n, dtype=np.int64)  # balls re-anchored by the current event
    n_ev = 0
    now = 0.0
    capped = False
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
        first_i, first_j = tally(bkind, bi, bj, now, balls, t_second, first_i, first_j)
        repeats = 0
        if bkind == BALL or bkind == CUSHION or bkind == JAW or bkind == POINT:  # noqa: SIM109 (numba)
            other = bj if bkind == BALL else bi
            if now - pair_last[bi, other] <= ZENO_WINDOW:
                pair_repeats[bi, other] += 1
            else:
                pair_repeats[bi, other] = 1
            pair_last[bi, other] = now
            repeats = pair_repeats[bi, other]
        if bkind == BALL:
            n_changed = impact(
                level, st, ms, masses, bi, bj, now, repeats, prm, pockets, changed, out
            )
            for c in range(n_changed):
                predict_own(level, st, ms, changed[c], prm, pockets, own, boxes)
            for c in range(n_changed):
                _repredict_pairs(level, st, ms, changed[c], now, prm, own, boxes, pair)
        else:  # one ball's event: it alone is re-anchored
            changed[0] = bi
            n_changed = 1
            if bkind == POCKET:
                capture(level, st, ms, bi, now, prm)
            elif bkind == CUSHION or bkind == JAW or bkind == POINT:  # noqa: SIM109 (numba)
                cushion(level, st, ms, bkind, bi, bj, now, repeats, prm, pockets, out)
            elif settle(level, st, ms, bkind, bi, now, prm):
                n_changed = 0  # its pair predictions hold: no re-prediction, no segment
            predict_own(level, st, ms, bi, prm, pockets, own, boxes)
            if n_changed:
                _repredict_pairs(level, st, ms, bi, now, prm, own, boxes, pair)
        if record:
            if n_seg + n_changed > segments.t.shape[0]:
                segments = grown_segment_log(segments)  # doubles: room for N more at least
            for c in range(n_changed):
                log_segment(level, segments, n_seg, changed[c], now, st, ms)
                n_seg += 1
    if capped:
        for i in range(n):
            if moving(level, ms, i):
                balls[BALL_STOPPED, i] = 1
                halt(level, st, ms, i, now, prm)
                if record:
                    if n_seg == segments.t.shape[0]:
                        segments = grown_segment_log(segments)
                    log_segment(level, segments, n_seg, i, now, st, ms)
                    n_seg += 1
    close_tally(balls)
    return st, ms, balls, first_i, first_j, n_ev, now, capped, events, segments, n_seg


@kernel
def packed_shot(level, positions, velocities, angular, masses, prm, pockets, max_events, record):
    """Validate and simulate one shot in a single call, for Python: the lean path.

    The whole result comes back in one flat buffer, laid out by
    :func:`~pool_env.sim.kernels.packing.pack_shot` with the level's per-ball tails (the
    spin level's final angular velocities and motion states; the roll level has none);
    :class:`~pool_env.sim.result.ShotResult` takes it over and reads its fields from it
    as views.

    Args:
        level, positions, velocities, angular, masses, prm, pockets, max_events, record: As
            for :func:`shoot` (``record`` a bool), the inputs unchecked.

    Returns:
        ``(code, i, j, buffer, n_floats, n_events, n_segments, first_i, first_j, capped,
        duration)``: the validation code (``OK``, or the problem with balls ``i``, ``j``,
        and then nothing is simulated and the buffer is empty), the packed buffer and the
        length of its float part, the event count (the log holds them all if
        ``record``, none otherwise), the logged segments, the shot's first ball-ball impact
        (-1 if none), whether the event cap was reached and the duration (s).
    """
    code, ci, cj = check_scene(level, positions, velocities, angular, masses, prm, pockets)
    if code != OK:
        return invalid_shot(code, ci, cj)
    st, ms, balls, first_i, first_j, n_ev, now, capped, events, segments, n_seg = shoot(
        level, positions, velocities, angular, masses, prm, pockets, max_events, record
    )
    n_log = n_ev if record else 0
    tail_floats, tail_ints = tail_sizes(level)
    floats, ints, n_floats, f, k = pack_shot(
        st, balls, events, n_log, segments, n_seg, tail_floats, tail_ints
    )
    write_tails(level, floats, ints, f, k, st, ms, now, prm)
    return OK, -1, -1, floats, n_floats, n_ev, n_seg, first_i, first_j, capped, now


@kernel
def packed_strike(
    level, positions, cue, speed, angle, a, b, elevation, masses, prm, pockets, max_events,
    record,
):  # fmt: skip
    """:func:`packed_shot` of a cue strike: ball ``cue`` struck, the others at rest.

    The strike (the level's :func:`~pool_env.sim.kernels.level.strike`) runs inside the
    one compiled call: from Python it cost two arrays and a call of its own, about a tenth
    of a two-ball shot. Returns as :func:`packed_shot`.
    """
    n = positions.shape[0]
    velocities = np.zeros((n, 2))
    angular = np.zeros((n, 3))
    out = np.empty(5)
    strike(level, speed, angle, a, b, elevation, prm, out)
    velocities[cue, 0], velocities[cue, 1] = out[0], out[1]
    angular[cue, 0], angular[cue, 1], angular[cue, 2] = out[2], out[3], out[4]
    return packed_shot(
        level, positions, velocities, angular, masses, prm, pockets, max_events, record
    )
