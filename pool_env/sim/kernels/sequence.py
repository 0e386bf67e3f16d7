"""The event sequence of both levels (compiled): which event comes next, what the rules read.

Simultaneous events are taken in one fixed total order, (time, kind, first id, second id)
(:func:`next_event`), which makes reruns bit-for-bit identical; each event taken updates
the per-ball rows the rules read (:func:`tally`: pocketing order, first and second
contacts, cushion impacts after the first contact and up to each ball's second contact).
The one event loop (:mod:`~pool_env.sim.kernels.loop`) runs on these for every model
level.
"""

from __future__ import annotations

from pool_env.sim.jit import inline_kernel, kernel
from pool_env.sim.kernels.kinds import (
    BALL,
    CUSHION,
    EV_ARG,
    EV_KIND,
    EV_T,
    JAW,
    NO_EVENT,
    POCKET,
    POINT,
)
from pool_env.sim.kernels.packing import (
    BALL_CUSHIONS,
    BALL_CUSHIONS_AT_SECOND,
    BALL_FIRST_HIT,
    BALL_POCKET,
    BALL_POCKET_ORDER,
    BALL_SECOND_HIT,
)
from pool_env.sim.kernels.roots import INF


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


@inline_kernel
def next_event(own, pair):
    """The next event ``(t, kind, i, j)`` in the total order; ``t = INF`` if none is left.

    ``own`` holds each ball's own next event (columns ``EV_T``, ``EV_KIND``, ``EV_ARG``),
    ``pair`` the impact time of each pair ``i < j`` (upper triangle). Both levels' loops
    select with this.
    """
    n = own.shape[0]
    bt, bkind, bi, bj = INF, NO_EVENT, n, n
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
    return bt, bkind, bi, bj


@inline_kernel
def tally(kind, i, j, now, balls, t_second, first_i, first_j):
    """Update what the rules read from a shot with event ``(kind, i, j)`` at time ``now``.

    ``balls`` holds the per-ball rows (``BALL_POCKET``, ...); ``t_second`` each ball's
    time of its second distinct ball contact (``INF`` before it): its cushion impacts are
    counted up to and including that instant (a cushion impact at the very time of the
    contact comes after it in the event order, yet counts, as ``time <= t`` does);
    ``(first_i, first_j)`` is the shot's first ball-ball impact so far (-1 before it),
    returned updated.
    """
    if kind == POCKET:
        order = 0
        for k in range(balls.shape[1]):
            if balls[BALL_POCKET, k] >= 0:
                order += 1
        balls[BALL_POCKET, i] = j
        balls[BALL_POCKET_ORDER, i] = order
    elif kind == CUSHION or kind == JAW or kind == POINT:  # noqa: SIM109 (numba)
        if first_i >= 0:  # a jaw facing or point is a cushion for the rules
            balls[BALL_CUSHIONS, i] += 1
        if now <= t_second[i]:
            balls[BALL_CUSHIONS_AT_SECOND, i] += 1
    elif kind == BALL:
        if first_i < 0:
            first_i, first_j = i, j
        _touch(i, j, now, balls, t_second)
        _touch(j, i, now, balls, t_second)
    return first_i, first_j


@inline_kernel
def _touch(i, j, now, balls, t_second):
    """Ball ``i`` touches ball ``j``: its first, or its second distinct, ball contact."""
    first = balls[BALL_FIRST_HIT, i]
    if first < 0:
        balls[BALL_FIRST_HIT, i] = j
    elif first != j and balls[BALL_SECOND_HIT, i] < 0:
        balls[BALL_SECOND_HIT, i] = j
        t_second[i] = now


@inline_kernel
def close_tally(balls):
    """End a shot's rows: a ball without a second distinct contact gets -1 cushions there."""
    for i in range(balls.shape[1]):
        if balls[BALL_SECOND_HIT, i] < 0:
            balls[BALL_CUSHIONS_AT_SECOND, i] = -1
