"""The packed result layout of both levels: one place packs a shot, one reads it back.

Every array handed back to Python costs a Python object (about 0.4 us each, and a named
tuple about a microsecond more), so a single shot comes back in one flat float64 buffer:
its first ``n_floats`` values are the float blocks, and the rest, read as int64 (the same
bytes, :func:`int_view`), the int blocks. For ``N`` balls, ``E`` logged events, ``S``
logged segments of ``W`` columns (``E = S = 0`` unless recorded; ``W`` is 4 on the roll
level, ``x, y, vx, vy``, and 9 on the spin level, ``x, y, vx, vy, wx, wy, wz, ax, ay``):

* ``floats`` (the buffer's start): final positions ``(N, 2)``; event times ``(E,)``;
  segment times ``(S,)``; segment states ``(S, W)``; then the level's tail (the spin
  level: final angular velocities ``(N, 3)``).
* ``ints`` (the rest): the per-ball rows ``(N_BALL_ROWS, N)``; the event rows ``(4, E)``
  (kind code of :mod:`~pool_env.sim.kernels.kinds`, ``i``, ``j``, first segment row); the
  segment rows ``(2, S)`` (ball, 1 if potted there); then the level's tail (the spin level:
  final motion states ``(N,)``).

The float readers index the buffer from its start, so the buffer itself serves as
``floats``. A batch of ``B`` tables keeps the same per-ball rows, one array per row
(:data:`BatchOutput`), written by :func:`store_table` from the same loop outputs that
:func:`pack_shot` packs. The readers of the flat arrays (:func:`ball_row`, ...,
:func:`tail_starts`) follow the packer here, so the layout lives in this module alone.
"""

from __future__ import annotations

from collections import namedtuple

import numpy as np

from pool_env.sim.jit import kernel

#: Rows of the per-ball results (``N_BALL_ROWS`` of them): the pocket each ball dropped
#: into, its place in the pocketing order, the first ball it touched, its cushion impacts
#: after the first contact, 1 if the event cap stopped it, the second distinct ball it
#: touched (-1: none), and its own cushion impacts (rails, jaw facings and points) from
#: the shot's start up to that second contact (-1: no second contact).
BALL_POCKET, BALL_POCKET_ORDER, BALL_FIRST_HIT, BALL_CUSHIONS, BALL_STOPPED = range(5)
BALL_SECOND_HIT, BALL_CUSHIONS_AT_SECOND = 5, 6
N_BALL_ROWS = 7
#: Rows of a logged event in ``ints``: kind code, ``i``, ``j``, first segment row.
N_EVENT_ROWS = 4
#: Columns of the spin level's tails: angular velocities in ``floats``, motion states in
#: ``ints`` (per ball).
SPIN_TAIL_FLOATS, SPIN_TAIL_INTS = 3, 1


@kernel
def invalid_shot(code, i, j):
    """The packed result of a scene that failed validation: nothing simulated."""
    return code, i, j, np.empty(0, dtype=np.float64), 0, 0, 0, -1, -1, False, 0.0


@kernel
def pack_shot(st, balls, events, n_log, segments, n_seg, tail_floats, tail_ints):
    """Pack a shot's outputs into the one flat buffer of the module docstring.

    Args:
        st: ``(N, C)`` final ball anchors (columns 0 and 1 are ``x, y`` on both levels).
        balls: ``(N_BALL_ROWS, N)`` per-ball rows.
        events: The event log (its first ``n_log`` rows are packed).
        n_log: Logged events ``E``.
        segments: The segment log (its first ``n_seg`` rows are packed; ``W`` columns).
        n_seg: Logged segments ``S``.
        tail_floats, tail_ints: Values per ball the caller writes after the blocks, into
            ``floats`` and ``ints`` (0 on the roll level).

    Returns:
        ``(buffer, ints, n_floats, f_tail, k_tail)``: the buffer (its start is ``floats``),
        its int64 part as a view, the length of its float part, and where the tails start
        in ``floats`` and ``ints``.
    """
    n = st.shape[0]
    w = segments.state.shape[1]
    n_floats = 2 * n + n_log + (1 + w) * n_seg + tail_floats * n
    n_ints = N_BALL_ROWS * n + N_EVENT_ROWS * n_log + 2 * n_seg + tail_ints * n
    floats = np.empty(n_floats + n_ints, dtype=np.float64)
    ints = floats[n_floats:].view(np.int64)  # the same bytes: one array for Python
    for i in range(n):  # positions (N, 2), then the per-ball rows (N_BALL_ROWS, N)
        floats[2 * i] = st[i, 0]
        floats[2 * i + 1] = st[i, 1]
        for row in range(N_BALL_ROWS):
            ints[row * n + i] = balls[row, i]
    f, k = 2 * n, N_BALL_ROWS * n
    for e in range(n_log):  # event times, then the event rows: kind, i, j, first segment
        floats[f + e] = events.t[e]
        ints[k + e] = events.kind[e]
        ints[k + n_log + e] = events.i[e]
        ints[k + 2 * n_log + e] = events.j[e]
        ints[k + 3 * n_log + e] = events.first_segment[e]
    f, k = f + n_log, k + N_EVENT_ROWS * n_log
    for r in range(n_seg):  # segment times, then states (S, W); balls, then potted flags
        floats[f + r] = segments.t[r]
        for c in range(w):
            floats[f + n_seg + w * r + c] = segments.state[r, c]
        ints[k + r] = segments.ball[r]
        ints[k + n_seg + r] = segments.potted[r]
    return floats, ints, n_floats, f + (1 + w) * n_seg, k + 2 * n_seg


# The readers of pack_shot's arrays: plain Python (a result reads its fields from Python,
# where a compiled call or a fresh object per read would cost more than the slicing).


def int_view(buffer: np.ndarray, n_floats: int) -> np.ndarray:
    """The int64 part of a packed buffer whose float part holds ``n_floats`` values, a view."""
    return buffer[n_floats:].view(np.int64)


def ball_row(ints: np.ndarray, n: int, row: int) -> np.ndarray:
    """Per-ball row ``row`` (``BALL_POCKET``, ...) of a packed shot of ``n`` balls, a view."""
    return ints[row * n : (row + 1) * n]


def final_positions(floats: np.ndarray, n: int) -> np.ndarray:
    """``(N, 2)`` final positions of a packed shot, a view."""
    return floats[: 2 * n].reshape(n, 2)


def event_times(floats: np.ndarray, n: int, n_log: int) -> np.ndarray:
    """``(E,)`` event times of a packed shot, a view."""
    return floats[2 * n : 2 * n + n_log]


def event_row(ints: np.ndarray, n: int, n_log: int, row: int) -> np.ndarray:
    """Event row ``row`` (0 kind, 1 ``i``, 2 ``j``, 3 first segment row), a view."""
    start = N_BALL_ROWS * n + row * n_log
    return ints[start : start + n_log]


def segment_views(
    floats: np.ndarray, ints: np.ndarray, n: int, n_log: int, n_seg: int, width: int
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The segment log as views: balls, times, ``(S, W)`` states, potted flags (0 or 1)."""
    f = 2 * n + n_log
    k = N_BALL_ROWS * n + N_EVENT_ROWS * n_log
    state = floats[f + n_seg : f + (1 + width) * n_seg].reshape(n_seg, width)
    return ints[k : k + n_seg], floats[f : f + n_seg], state, ints[k + n_seg : k + 2 * n_seg]


def tail_starts(n: int, n_log: int, n_seg: int, width: int) -> tuple[int, int]:
    """Where the level's tails start in ``floats`` and ``ints`` (as :func:`pack_shot`)."""
    f = 2 * n + n_log + (1 + width) * n_seg
    return f, N_BALL_ROWS * n + N_EVENT_ROWS * n_log + 2 * n_seg


#: What a batch returns, by name; ball indices count all ``N`` balls of a table.
#:
#: * ``positions`` ``(B, N, 2)``; ``pocketed``, ``pocket_order``, ``first_hit``,
#:   ``cushions_after_contact``, ``stopped_by_cap``, ``second_hit``,
#:   ``cushions_at_second`` ``(B, N)``: the per-ball rows of a single shot
#:   (``BALL_POCKET``, ...), per table (an inactive ball keeps its input position, -1, 0,
#:   False and -1).
#: * ``n_events`` ``(B,)``, ``capped`` ``(B,)``.
#: * ``first_contact`` ``(B, 2)``: each table's first ball-ball impact, -1 if none.
#: * ``error`` ``(B, 3)``: a validation code and its ball indices (a pocket index for
#:   ``IN_POCKET``), ``(OK, -1, -1)`` when the table was valid (an invalid table is not
#:   simulated).
BatchOutput = namedtuple(
    "BatchOutput",
    [
        "positions",
        "pocketed",
        "pocket_order",
        "first_hit",
        "cushions_after_contact",
        "n_events",
        "capped",
        "first_contact",
        "error",
        "stopped_by_cap",
        "second_hit",
        "cushions_at_second",
    ],
)


@kernel
def allocate_batch(positions):
    """A :data:`BatchOutput` for ``(B, N, 2)`` input positions (every table still unrun)."""
    n_tables, n_balls = positions.shape[0], positions.shape[1]
    return BatchOutput(
        positions.copy(),
        np.full((n_tables, n_balls), -1, dtype=np.int64),
        np.full((n_tables, n_balls), -1, dtype=np.int64),
        np.full((n_tables, n_balls), -1, dtype=np.int64),
        np.zeros((n_tables, n_balls), dtype=np.int64),
        np.zeros(n_tables, dtype=np.int64),
        np.zeros(n_tables, dtype=np.bool_),
        np.full((n_tables, 2), -1, dtype=np.int64),
        np.zeros((n_tables, 3), dtype=np.int64),
        np.zeros((n_tables, n_balls), dtype=np.bool_),
        np.full((n_tables, n_balls), -1, dtype=np.int64),
        np.full((n_tables, n_balls), -1, dtype=np.int64),
    )


@kernel
def batch_fields(out):
    """``out`` as a plain tuple: numba's ``prange`` cannot hand a named tuple to its threads."""
    return (
        out[0], out[1], out[2], out[3], out[4], out[5], out[6], out[7], out[8], out[9],
        out[10], out[11],
    )  # fmt: skip


@kernel
def store_table(out, b, index, st, balls, first_i, first_j, n_ev, capped):
    """Write one table's loop outputs (as :func:`pack_shot` takes them) into batch row ``b``.

    ``index`` maps the simulated balls to the table's ``N`` (the active ones).
    """
    for k in range(index.shape[0]):
        ball = index[k]
        out.positions[b, ball, 0] = st[k, 0]
        out.positions[b, ball, 1] = st[k, 1]
        out.pocketed[b, ball] = balls[BALL_POCKET, k]
        out.pocket_order[b, ball] = balls[BALL_POCKET_ORDER, k]
        hit = balls[BALL_FIRST_HIT, k]
        out.first_hit[b, ball] = index[hit] if hit >= 0 else -1
        out.cushions_after_contact[b, ball] = balls[BALL_CUSHIONS, k]
        out.stopped_by_cap[b, ball] = balls[BALL_STOPPED, k] != 0
        second = balls[BALL_SECOND_HIT, k]
        out.second_hit[b, ball] = index[second] if second >= 0 else -1
        out.cushions_at_second[b, ball] = balls[BALL_CUSHIONS_AT_SECOND, k]
    out.n_events[b] = n_ev
    out.capped[b] = capped
    if first_i >= 0:
        out.first_contact[b, 0] = index[first_i]
        out.first_contact[b, 1] = index[first_j]


@kernel
def store_error(out, b, index, code, i, j, pocket):
    """Record table ``b``'s validation failure (``pocket``: ``j`` is a pocket index)."""
    out.error[b, 0] = code
    out.error[b, 1] = index[i] if i >= 0 else -1
    out.error[b, 2] = index[j] if j >= 0 and not pocket else j  # a pocket index stays
