"""The cue ball's first contact as the rules read it: simultaneous hits and the kitchen.

The simulator reports a shot's first ball-ball impact. Two rules need more, and only on
rare shots, so the fast path (no trajectories) stays as it is and those shots are replayed
with their trajectories (the simulator is deterministic: the replay is the same shot):

* **A simultaneous first contact.** When the cue ball meets two balls at the same instant,
  the simulator orders the impacts by ball number, so the same shot would be legal for
  solids and a foul for stripes. The rules decide by a rule that does not depend on the
  numbers, as referees do: the shooter gets the benefit. If any ball the cue ball met
  within :data:`SIMULTANEOUS` of its first contact is a legal first ball, the contact is
  legal (:func:`shooters_benefit` reads that ball as the first).
* **The kitchen.** With the cue ball in hand behind the head string, a first ball whose
  base lies behind the head string is a foul unless the cue ball crossed the line first
  (:func:`pool_env.game.games.wpa.rules.kitchen_foul`). The object ball rests until the cue
  ball meets it, so its base is its position before the shot; whether the cue ball
  crossed is read from its trajectory up to the contact: its centre's x moves
  monotonically along each straight segment, so the line was crossed exactly when some
  anchor before the contact (the start, each cushion impact, the contact itself) lies past
  it.

:func:`needs_replay` (compiled, one call per step) picks the
shots: a cue ball in hand behind the head string whose first ball lies behind it, or a
first ball that is not legal with a legal one within 4R of it (only then can both touch
the cue ball at once).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

from pool_env.game.games.wpa.params import HEAD_X, VARIANT
from pool_env.game.games.wpa.rack_state import BEHIND, SHOOTER, ball_on, legal_first, legal_targets
from pool_env.game.kernels.params import RADIUS
from pool_env.sim.jit import kernel
from pool_env.sim.result import KIND_NAMES, ShotResult
from pool_env.sim.simulate import simulate
from pool_env.sim.table import Table

#: Impacts of the cue ball within this time (s) of its first one are simultaneous. Far
#: above the rounding of event times (~2e-16 of the time, 2e-13 s after 1,000 s) and far
#: below what an eye or a camera can tell apart (a ball at 10 m/s moves 10 nm in 1e-9 s).
SIMULTANEOUS = 1e-9

_BALL = KIND_NAMES.index("ball")
# The common one-table answer, shared: the rules only read it. Writable, as every array the
# kernels get, so that numba keeps one compiled version of judge_rules.
_CROSSED = np.ones(1, dtype=np.bool_)


def first_contacts(shot: ShotResult, head_x: float) -> tuple[list[int], bool]:
    """What a recorded shot says about the cue ball's (row 0) first contact.

    Args:
        shot: A shot simulated with ``record=True``, the cue ball in row 0.
        head_x: The head string's x.

    Returns:
        ``(met, crossed)``: the rows the cue ball met within :data:`SIMULTANEOUS` of its
        first contact, in the simulator's order (empty: no contact), and whether its
        centre passed ``head_x`` before that contact.
    """
    kinds, ei, ej, times = shot.event_kinds, shot.event_i, shot.event_j, shot.event_times
    hits = np.flatnonzero((kinds == _BALL) & ((ei == 0) | (ej == 0)))
    if hits.size == 0:
        return [], False
    t1 = float(times[hits[0]])
    met: list[int] = []
    for e in hits[times[hits] <= t1 + SIMULTANEOUS].tolist():
        other = int(ej[e] if ei[e] == 0 else ei[e])
        if other not in met:
            met.append(other)
    ball, t, state, _ = shot.segments
    mine = (ball == 0) & (t <= t1)
    return met, bool((state[mine, 0] > head_x).any())


def shooters_benefit(
    game: int, rack: NDArray[np.int64], on_table: NDArray[np.bool_], met: Sequence[int]
) -> int:
    """The first ball the rules read among ``met`` (the balls met at the first instant).

    The first of them that ``rack``'s shooter may hit first, else the first of them.
    """
    legal = np.zeros(on_table.shape[0], dtype=np.bool_)
    legal_targets(game, rack, on_table, rack[SHOOTER], legal)
    return next((g for g in met if legal[g]), met[0])


def read_first(
    table: Table,
    params: NDArray[np.float64],
    game: int,
    positions: NDArray[np.float64],
    on_table: NDArray[np.bool_],
    rack: NDArray[np.int64],
    tables: NDArray[np.intp],
    balls: NDArray[np.intp],
    velocities: NDArray[np.float64],
    spins: NDArray[np.float64] | None,
    first: NDArray[np.int64],
    shot: ShotResult | None,
) -> NDArray[np.bool_]:
    """Settle the first contact of the shots that need it, before the rules judge them.

    Args:
        table: The table.
        params: The config's numbers.
        game: The rule code.
        positions: ``(B, N, 2)`` before the shot.
        on_table: ``(B, N)`` before the shot.
        rack: ``(B, N_RACK)`` before the shot.
        tables: ``(K,)`` the tables that shot.
        balls: ``(M,)`` ball number of each result column.
        velocities: ``(K, N, 2)`` the shots' initial velocities.
        spins: ``(K, N, 3)`` their angular velocities on a spin table (``None``: roll).
        first: ``(K, 2)`` result columns of the first impact; a simultaneous legal ball
            replaces the second (in place) when the simulator's first is not legal.
        shot: The one-table step's result, reused when it is recorded.

    Returns:
        ``(K,)`` whether the cue ball crossed the head string before its first contact
        (True where the rules do not read it).
    """
    replay = needs_replay(params, tables, balls, positions, on_table, rack, first)
    if tables.shape[0] == 1 and not replay[0]:
        return _CROSSED  # the common case: nothing to replay, nothing allocated
    crossed = np.ones(tables.shape[0], dtype=np.bool_)
    head_x = float(params[HEAD_X])
    for k in np.flatnonzero(replay).tolist():
        b = int(tables[k])
        rows = np.flatnonzero(on_table[b])
        recorded = shot if shot is not None and shot.recorded else None
        if recorded is None:
            ang = None if spins is None else spins[k, rows]
            recorded = simulate(
                table, positions[b, rows], velocities[k, rows], record=True,
                angular_velocities=ang,
            )  # fmt: skip
        met_rows, crossed[k] = first_contacts(recorded, head_x)
        met = [int(rows[r]) for r in met_rows]
        chosen = shooters_benefit(game, rack[b], on_table[b], met)
        first[k, 1] = int(np.flatnonzero(balls == chosen)[0])
    return crossed


@kernel
def needs_replay(params, tables, balls, positions, on_table, rack, first):
    """The shots whose first contact the rules cannot read from the fast path's outcome.

    Two cases, both rare: the cue ball was in hand behind the head string and its first
    ball lies behind the head string (did the cue ball cross the line first?), or its
    first ball is not a legal one and a legal ball lies within 4R of it (did the cue ball
    meet that one at the same instant?). :func:`read_first` replays those shots
    with their trajectories.

    Args:
        params: The config's numbers (the game, the ball radius, the head string's x).
        tables: ``(K,)`` the tables that shot.
        balls: ``(M,)`` ball number of each result column.
        positions: ``(B, N, 2)`` positions before the shot.
        on_table: ``(B, N)`` before the shot.
        rack: ``(B, N_RACK)`` before the shot.
        first: ``(K, 2)`` result columns of the first ball-ball impact (cue first), -1 none.

    Returns:
        ``(K,)`` booleans.
    """
    game, head_x = int(params[VARIANT]), params[HEAD_X]
    near = 4.0 * params[RADIUS] + 1e-6  # two resting balls both touching the cue ball
    out = np.zeros(tables.shape[0], dtype=np.bool_)
    for k in range(tables.shape[0]):
        if first[k, 0] < 0:
            continue
        b = tables[k]
        f = balls[first[k, 1]]
        if rack[b, BEHIND] != 0 and positions[b, f, 0] < head_x:
            out[k] = True
            continue
        player = rack[b, SHOOTER]
        on = ball_on(game, rack[b], on_table[b], player)
        if legal_first(game, rack[b], on_table[b], player, on, f):
            continue
        for g in range(1, on_table.shape[1]):
            if g != f and legal_first(game, rack[b], on_table[b], player, on, g):
                dx = positions[b, g, 0] - positions[b, f, 0]
                dy = positions[b, g, 1] - positions[b, f, 1]
                if dx * dx + dy * dy <= near * near:
                    out[k] = True
    return out
