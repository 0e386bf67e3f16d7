"""Shot results: plain data plus exact positions at any time."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import NDArray

from pool_env.sim.kernels import loop
from pool_env.sim.kernels.loop import ShotOutput
from pool_env.sim.kernels.timeline import positions_at as _positions_at
from pool_env.sim.kernels.timeline import positions_at_many as _positions_at_many

EventKind = Literal["pocket", "ball", "cushion", "stop", "jaw", "point"]

# Shared read-only empty logs of unrecorded results (no allocation per shot).
_EMPTY_F = np.empty(0, dtype=np.float64)
_EMPTY_I = np.empty(0, dtype=np.int64)
_EMPTY_KIND = np.empty(0, dtype=np.int8)
_EMPTY_STATE = np.empty((0, 4), dtype=np.float64)
_EMPTY_BOOL = np.empty(0, dtype=np.bool_)
for _array in (_EMPTY_F, _EMPTY_I, _EMPTY_KIND, _EMPTY_STATE, _EMPTY_BOOL):
    _array.setflags(write=False)

#: Event kind codes of the compiled loop, in tie-breaking order.
KIND_NAMES: tuple[EventKind, ...] = ("pocket", "ball", "cushion", "stop", "jaw", "point")
#: Kinds that are cushion contacts for the rules (a rail, a jaw facing, a jaw point).
CUSHION_KINDS: tuple[EventKind, ...] = ("cushion", "jaw", "point")


@dataclass(frozen=True, slots=True)
class Event:
    """One event of a shot.

    Attributes:
        time: Seconds since the shot began.
        kind: ``"ball"`` (impact of balls ``i`` and ``j``, ``i < j``), ``"cushion"`` (ball
            ``i`` hits rail ``j``: 0 is ``x = R``, 1 ``x = L - R``, 2 ``y = R``, 3
            ``y = W - R``; on a jaw table only the straight part of a rail between two
            pockets), ``"jaw"`` (ball ``i`` hits the facing ``j = 2 k + side`` of pocket
            ``k``, ``side`` 0 or 1 as in ``Table.jaws[k]``), ``"point"`` (ball ``i`` hits
            the point (round tip) ``j = 2 k + side``), ``"pocket"`` (ball ``i`` captured by
            pocket ``j``: its centre entered the capture circle or reached the fall line)
            or ``"stop"`` (ball ``i`` comes to rest; ``j = -1``). Rails, facings and points
            are all cushions for the rules (:data:`CUSHION_KINDS`).
        i: The ball.
        j: The other ball, the rail, the pocket, or -1.
    """

    time: float
    kind: EventKind
    i: int
    j: int


class ShotResult:
    """The outcome of :func:`pool_env.simulate`: final state, events, exact trajectories.

    Attributes:
        positions: ``(N, 2)`` final positions; a potted ball keeps its capture point.
        pocketed: ``(N,)`` ints: -1 on the table, ``k`` captured by pocket ``k``.
        duration: Seconds until everything rests.
        n_events: Number of events.
        recorded: Whether events and trajectories were kept (``simulate(record=...)``).
        hit_event_cap: True if the shot reached ``max_events``; every ball was then stopped
            where it was at that instant.
        stopped_by_cap: ``(N,)`` booleans: the balls that were still moving when the cap
            stopped them (all False under the cap). A ball far from the runaway cluster
            that the cap froze mid-roll is flagged here, never silently.
        first_contact: ``(i, j)`` of the first ball-ball impact, or ``None``.
        first_hit: ``(N,)`` ints: the first ball each ball touched, -1 if none. For the
            struck ball (``first_hit[cue]``) that is the first contact the rules judge.
        cushions_after_contact: ``(N,)`` ints: each ball's cushion impacts after the shot's
            first ball-ball impact (all zero without one). With one ball struck (as by
            :func:`pool_env.shoot`) that impact is the cue ball's first contact, so a rail
            hit before it is not counted: the "rail after contact" of the rules.
        pocket_order: ``(N,)`` ints: 0 for the first ball to drop, 1 for the next, and so
            on; -1 for a ball left on the table.
        event_times, event_kinds, event_i, event_j: The events as arrays (kinds are codes
            into :data:`KIND_NAMES`).
        event_first_segment: For each event, the first row it wrote in :attr:`segments`
            (the rows up to the next event's are the balls it re-anchored).
    """

    __slots__ = (
        "_deceleration",
        "_seg_ball",
        "_seg_potted",
        "_seg_state",
        "_seg_t",
        "cushions_after_contact",
        "duration",
        "event_first_segment",
        "event_i",
        "event_j",
        "event_kinds",
        "event_times",
        "first_contact",
        "first_hit",
        "hit_event_cap",
        "n_events",
        "pocket_order",
        "pocketed",
        "positions",
        "recorded",
        "stopped_by_cap",
    )

    def __init__(self, raw: ShotOutput, deceleration: float, recorded: bool = True) -> None:
        """Wrap the kernel's :data:`~pool_env.sim.kernels.loop.ShotOutput` (taken over)."""
        self.positions = raw.positions
        self.pocketed = raw.pocketed
        self.pocket_order = raw.pocket_order
        self.first_hit = raw.first_hit
        self.cushions_after_contact = raw.cushions_after_contact
        self.n_events = int(raw.n_events)
        self.duration = float(raw.duration)
        self.hit_event_cap = bool(raw.capped)
        self.stopped_by_cap = raw.stopped_by_cap.astype(np.bool_)
        first_i, first_j = int(raw.first_i), int(raw.first_j)
        self.first_contact = (first_i, first_j) if first_i >= 0 else None
        events, segments = raw.events, raw.segments
        self.event_times, self.event_kinds = events.t, events.kind
        self.event_i, self.event_j = events.i, events.j
        self.event_first_segment = events.first_segment
        self._seg_ball, self._seg_t = segments.ball, segments.t
        self._seg_state, self._seg_potted = segments.state, segments.potted
        self._deceleration = deceleration
        self.recorded = recorded

    @classmethod
    def unrecorded(
        cls,
        final: NDArray[np.float64],
        balls: NDArray[np.int64],
        meta: NDArray[np.int64],
        duration: float,
        deceleration: float,
    ) -> ShotResult:
        """A result without events or trajectories (``simulate(record=False)``).

        ``balls`` and ``meta`` are the per-ball rows and the meta slots written by
        :func:`~pool_env.sim.kernels.loop.shoot_final` (the result takes them over).
        """
        self = cls.__new__(cls)  # attribute by attribute: this runs once per training step
        self.positions = final
        self.pocketed = balls[loop.BALL_POCKET]
        self.pocket_order = balls[loop.BALL_POCKET_ORDER]
        self.first_hit = balls[loop.BALL_FIRST_HIT]
        self.cushions_after_contact = balls[loop.BALL_CUSHIONS]
        self.stopped_by_cap = balls[loop.BALL_STOPPED].astype(np.bool_)
        counts = meta[loop.META_EVENTS : loop.META_FIRST_J + 1].tolist()
        self.n_events, capped, first_i, first_j = counts
        self.duration = duration
        self.hit_event_cap = bool(capped)
        self.first_contact = (first_i, first_j) if first_i >= 0 else None
        self.event_times = self._seg_t = _EMPTY_F
        self.event_kinds = _EMPTY_KIND
        self.event_i = self.event_j = self.event_first_segment = self._seg_ball = _EMPTY_I
        self._seg_state = _EMPTY_STATE
        self._seg_potted = _EMPTY_BOOL
        self._deceleration = deceleration
        self.recorded = False
        return self

    @property
    def events(self) -> list[Event]:
        """The events in chronological order (built on access; empty if not recorded)."""
        return [
            Event(float(t), KIND_NAMES[k], int(i), int(j))
            for t, k, i, j in zip(
                self.event_times, self.event_kinds, self.event_i, self.event_j, strict=True
            )
        ]

    @property
    def n_balls(self) -> int:
        """Number of balls in the scene."""
        return int(self.positions.shape[0])

    def _check_time(self, t: float) -> float:
        if not self.recorded:
            raise ValueError("this shot was simulated with record=False: no trajectories kept")
        t = float(t)
        if not (0.0 <= t <= self.duration):
            raise ValueError(f"t must lie in [0, duration={self.duration}], got {t!r}")
        return t

    def positions_at(self, t: float) -> NDArray[np.float64]:
        """Exact ``(N, 2)`` positions at time ``t`` in ``[0, duration]``.

        A ball potted by then sits at its capture point (see :meth:`pocketed_at`).

        Raises:
            ValueError: If ``t`` lies outside ``[0, duration]`` or is not a number.
        """
        return self._frame(t)[0]

    def positions_at_many(self, times: NDArray[np.float64]) -> tuple[NDArray, NDArray]:
        """Positions ``(T, N, 2)`` and potted flags ``(T, N)`` at each of ``times``.

        One compiled call for many frames (animations, invariant checks).

        Raises:
            ValueError: If a time lies outside ``[0, duration]``.
        """
        times = np.ascontiguousarray(times, dtype=np.float64).reshape(-1)
        if not self.recorded:
            self._check_time(0.0)
        if times.size and not (times.min() >= 0.0 and times.max() <= self.duration):
            raise ValueError(f"times must lie in [0, duration={self.duration}]")
        return _positions_at_many(*self.segments, self.n_balls, times, self._deceleration)

    @property
    def segments(self) -> tuple[NDArray, NDArray, NDArray, NDArray]:
        """The trajectory log ``(ball, t, state, potted)``, chronological.

        Row ``r`` says ball ``ball[r]`` is re-anchored at time ``t[r]`` with
        ``state[r] = (x, y, vx, vy)`` (``potted[r]``: captured there). From an anchor a ball
        decelerates along its velocity until it rests. Empty if not recorded.
        """
        return self._seg_ball, self._seg_t, self._seg_state, self._seg_potted

    def pocketed_at(self, t: float) -> NDArray[np.bool_]:
        """``(N,)`` booleans: which balls are potted by time ``t``."""
        return self._frame(t)[1]

    def _frame(self, t: float) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        """Positions and potted flags at ``t`` (checked against ``[0, duration]``)."""
        return _positions_at(*self.segments, self.n_balls, self._check_time(t), self._deceleration)

    def __repr__(self) -> str:
        potted = [int(i) for i in np.flatnonzero(self.pocketed >= 0)]
        return (
            f"ShotResult(n_balls={self.n_balls}, n_events={self.n_events}, "
            f"duration={self.duration:.4f}, potted={potted}, hit_event_cap={self.hit_event_cap})"
        )
