"""Recording a shot (compiled): the event log and the trajectory-segment log.

Only recorded shots (``simulate(record=True)``) write these; the training path skips them
entirely. Each log is a named tuple of arrays with room to spare; a writer checks the
capacity first and swaps in a grown copy when it is full (``grown_event_log``), so the
common write is a plain store.
"""

from __future__ import annotations

from collections import namedtuple

import numpy as np

from pool_env.sim.jit import inline_kernel, kernel

#: The events of a shot, one row each: time, kind code, the two ids, and the first row of
#: the segment log the event wrote (the rows up to the next event's are the balls it moved).
EventLog = namedtuple("EventLog", ["t", "kind", "i", "j", "first_segment"])

#: Trajectory anchors, one row each: ball ``ball`` follows ``state`` from time ``t`` on
#: (``potted``: it was captured there). The columns of ``state`` are the model level's:
#: ``x, y, vx, vy`` on the roll level, with spin and acceleration on the spin level.
SegmentLog = namedtuple("SegmentLog", ["ball", "t", "state", "potted"])


@kernel
def _grow(arr, n):
    """``arr`` if it has room for index ``n``, else a copy with twice the capacity."""
    if n < arr.shape[0]:
        return arr
    out = np.empty((max(2 * arr.shape[0], 16),) + arr.shape[1:], dtype=arr.dtype)
    out[:n] = arr[:n]
    return out


@inline_kernel
def new_event_log(capacity):
    """An empty :data:`EventLog` with room for ``capacity`` rows."""
    return EventLog(
        np.empty(capacity, dtype=np.float64),
        np.empty(capacity, dtype=np.int8),
        np.empty(capacity, dtype=np.int64),
        np.empty(capacity, dtype=np.int64),
        np.empty(capacity, dtype=np.int64),
    )


@kernel
def grown_event_log(log):
    """``log`` with twice the capacity (the rows so far copied)."""
    n = log.t.shape[0]
    return EventLog(
        _grow(log.t, n), _grow(log.kind, n), _grow(log.i, n), _grow(log.j, n),
        _grow(log.first_segment, n),
    )  # fmt: skip


@kernel
def log_event(log, row, t, kind, i, j, first_segment):
    """Write event ``row`` (below the log's capacity: see :func:`grown_event_log`)."""
    log.t[row] = t
    log.kind[row] = kind
    log.i[row] = i
    log.j[row] = j
    log.first_segment[row] = first_segment


@inline_kernel
def new_segment_log(capacity, width):
    """An empty :data:`SegmentLog` with room for ``capacity`` rows of ``width`` columns."""
    return SegmentLog(
        np.empty(capacity, dtype=np.int64),
        np.empty(capacity, dtype=np.float64),
        np.empty((capacity, width), dtype=np.float64),
        np.zeros(capacity, dtype=np.bool_),
    )


@kernel
def grown_segment_log(log):
    """``log`` with twice the capacity (the rows so far copied)."""
    n = log.t.shape[0]
    return SegmentLog(
        _grow(log.ball, n), _grow(log.t, n), _grow(log.state, n), _grow(log.potted, n)
    )


@kernel
def log_anchor(log, row, k, now, st, columns, potted):
    """Write segment ``row`` (below the capacity): ball ``k`` re-anchored at ``now``.

    ``columns`` are the columns of the level's anchor array ``st`` that a segment row
    holds, in order; ``potted`` whether the ball was captured there.
    """
    log.ball[row] = k
    log.t[row] = now
    for c in range(len(columns)):
        log.state[row, c] = st[k, columns[c]]
    log.potted[row] = potted


@inline_kernel
def trim_events(log, n):
    """Copies of the first ``n`` rows (exactly sized, owned by the caller)."""
    return EventLog(
        log.t[:n].copy(),
        log.kind[:n].copy(),
        log.i[:n].copy(),
        log.j[:n].copy(),
        log.first_segment[:n].copy(),
    )


@inline_kernel
def trim_segments(log, n):
    """Copies of the first ``n`` rows (exactly sized, owned by the caller)."""
    return SegmentLog(
        log.ball[:n].copy(), log.t[:n].copy(), log.state[:n].copy(), log.potted[:n].copy()
    )
