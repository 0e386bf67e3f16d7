"""The event sequence of both levels (compiled): which event comes next, what the rules read.

Simultaneous events are taken in one fixed total order, (time, kind, first id, second id)
(:func:`next_event`), which makes reruns bit-for-bit identical; each event taken updates
the per-ball rows the rules read (:func:`tally`: pocketing order, first contacts, cushion
impacts after the first contact). The one event loop (:mod:`~pool_env.sim.kernels.loop`)
runs on these for every model level.
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
    BALL_FIRST_HIT,
    BALL_POCKET,
    BALL_POCKET_ORDER,
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
def tally(kind, i, j, balls, first_i, first_j):
    """Update what the rules read from a shot with event ``(kind, i, j)``.

    ``balls`` holds the per-ball rows (``BALL_POCKET``, ...); ``(first_i, first_j)`` is the
    shot's first ball-ball impact so far (-1 before it), returned updated.
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
    elif kind == BALL:
        if first_i < 0:
            first_i, first_j = i, j
        if balls[BALL_FIRST_HIT, i] < 0:
            balls[BALL_FIRST_HIT, i] = j
        if balls[BALL_FIRST_HIT, j] < 0:
            balls[BALL_FIRST_HIT, j] = i
    return first_i, first_j
