"""Three-cushion facts a carom player needs: the point, counted two ways, and the noise draws.

A point (UMB, "Rules of the game of billiards"; pooltool 0.6's ``three_cushion.is_point``):
the striker's cue ball meets both object balls and has touched at least three cushions
before it first meets the second one; a cushion impact at the very time of that meeting
counts (pooltool counts the cushion events with ``time <=`` the meeting's).

* :func:`points_of_rows` reads it from the batch rows of :func:`pool_env.sim.rollout`
  (``second_hit``, ``cushions_at_second``): what the search reads, thousands of shots a call;
* :func:`point_of_events` recounts it from a recorded shot's event log
  (:func:`pool_env.shoot` with ``record=True``): the independent judge of the evaluation and
  the tests, sharing no code with the rows.

:func:`noisy_rows` plays a shot as the env's execution noise would (aim, speed, tip
Gaussians; the speed clipped at 0 and the tip onto the miscue circle by the env's own rule,
:func:`pool_env.onto_tip_circle`).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray

from pool_env import Event, onto_tip_circle
from pool_env.sim.result import CUSHION_KINDS

__all__ = [
    "CUSHIONS_FOR_POINT",
    "near_scores",
    "noisy_rows",
    "point_of_events",
    "points_of_rows",
]

#: Cushions the cue ball must touch before it meets the second object ball.
CUSHIONS_FOR_POINT = 3


def point_of_events(events: Sequence[Event], cue: int) -> bool:
    """Whether a recorded shot is a point for cue ball ``cue`` (from its event log alone).

    Args:
        events: The shot's events in time order (``ShotResult.events``).
        cue: The striker's cue ball.

    Returns:
        True when ``cue`` met two distinct balls and touched at least
        :data:`CUSHIONS_FOR_POINT` cushions at or before the time it first met the second.
    """
    met: set[int] = set()
    second_time = None
    for event in events:
        if event.kind == "ball" and cue in (event.i, event.j):
            met.add(event.j if event.i == cue else event.i)
            if len(met) == 2:
                second_time = event.time
                break
    if second_time is None:
        return False
    cushions = sum(
        1
        for event in events
        if event.kind in CUSHION_KINDS and event.i == cue and event.time <= second_time
    )
    return cushions >= CUSHIONS_FOR_POINT


def points_of_rows(result: Any, cue: int) -> NDArray[np.bool_]:
    """``(S,)`` whether each shot of a rollout is a point for cue ball ``cue``.

    Args:
        result: A :class:`pool_env.sim.batch.BatchResult` (``rollout``'s), with its
            ``second_hit`` and ``cushions_at_second`` rows.
        cue: The striker's cue ball.
    """
    second = np.asarray(result.second_hit)[:, cue]
    cushions = np.asarray(result.cushions_at_second)[:, cue]
    return (second >= 0) & (cushions >= CUSHIONS_FOR_POINT)


def near_scores(result: Any, cue: int) -> NDArray[np.float64]:
    """``(S,)`` how close each shot of a rollout came to a point (higher is closer).

    Both balls met: the cushions before the second (capped at the three a point needs,
    so a point scores 3 and a two-cushion carom 2); one ball met: -1; none: -2.
    """
    second = np.asarray(result.second_hit)[:, cue]
    cushions = np.asarray(result.cushions_at_second)[:, cue]
    first = np.asarray(result.first_hit)[:, cue]
    both = np.minimum(cushions, CUSHIONS_FOR_POINT).astype(np.float64)
    return np.where(second >= 0, both, np.where(first >= 0, -1.0, -2.0))


def noisy_rows(
    rows: NDArray[np.float64],
    normals: NDArray[np.float64],
    sigmas: Sequence[float],
    tip_limit: float,
) -> NDArray[np.float64]:
    """The shots the env executes for ``rows`` under the draws ``normals``.

    Args:
        rows: ``(S, 5)`` intended shots ``(angle, speed, tip a, tip b, elevation)``.
        normals: ``(D, 4)`` standard normal draws (angle, speed, tip a, tip b), shared by
            every shot (common random numbers: candidates differ by their shot alone).
        sigmas: ``(angle rad, speed m/s, tip in R)``, the env's noise sigmas.
        tip_limit: The miscue circle's radius (fraction of R).

    Returns:
        ``(S * D, 5)`` executed shots, shot-major (shot ``s``'s draws are rows
        ``s * D .. s * D + D - 1``).
    """
    s_angle, s_speed, s_tip = (float(v) for v in sigmas)
    out = np.repeat(np.asarray(rows, dtype=np.float64), normals.shape[0], axis=0)
    z = np.tile(normals, (rows.shape[0], 1))
    out[:, 0] += s_angle * z[:, 0]
    out[:, 1] = np.maximum(out[:, 1] + s_speed * z[:, 1], 0.0)
    out[:, 2] += s_tip * z[:, 2]
    out[:, 3] += s_tip * z[:, 3]
    outside = np.flatnonzero(np.hypot(out[:, 2], out[:, 3]) > tip_limit)
    for k in outside:  # rare: the planner keeps its tips inside the circle
        out[k, 2], out[k, 3] = onto_tip_circle(out[k, 2], out[k, 3], tip_limit)
    return out
