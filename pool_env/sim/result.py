"""Shot results: plain data plus exact positions at any time."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from pool_env.sim.kernels import packing
from pool_env.sim.kernels.kinds import CUSHION_KINDS, KIND_NAMES, EventKind
from pool_env.sim.kernels.spin.level import SEG_COLS as SPIN_SEG_COLS
from pool_env.sim.kernels.spin.state import POTTED, STATIONARY
from pool_env.sim.kernels.spin.timeline import spin_positions_at, spin_positions_at_many
from pool_env.sim.kernels.timeline import positions_at as _positions_at
from pool_env.sim.kernels.timeline import positions_at_many as _positions_at_many

__all__ = ["CUSHION_KINDS", "KIND_NAMES", "Event", "EventKind", "ShotResult", "SpinShotResult"]


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
            are all cushions for the rules (:data:`CUSHION_KINDS`). On a spin table also
            the transitions of ball ``i`` (``j = -1``): ``"slide_roll"``, ``"roll_spin"``
            (it rests, spinning in place) and ``"spin_stop"``.
        i: The ball.
        j: The other ball, the rail, the pocket, or -1.
    """

    time: float
    kind: EventKind
    i: int
    j: int


class ShotResult:
    """The outcome of :func:`pool_env.simulate`: final state, events, exact trajectories.

    The compiled loop hands back one flat buffer
    (:func:`~pool_env.sim.kernels.packing.pack_shot`); the result owns it, and every array
    attribute below is a view into it made on access (a shot costs only the fields that
    are read).

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
        second_hit: ``(N,)`` ints: the second distinct ball each ball touched, -1 if none.
        cushions_at_second: ``(N,)`` ints: each ball's own cushion impacts from the shot's
            start up to its second distinct ball contact (-1 without one): a carom's count.
        pocket_order: ``(N,)`` ints: 0 for the first ball to drop, 1 for the next, and so
            on; -1 for a ball left on the table.
        event_times, event_kinds, event_i, event_j: The events as arrays (kinds are int
            codes into :data:`KIND_NAMES`; all empty if not recorded).
        event_first_segment: For each event, the first row it wrote in :attr:`segments`
            (the rows up to the next event's are the balls it re-anchored).
    """

    __slots__ = (
        "_deceleration",
        "_floats",
        "_int_part",
        "_n_floats",
        "_n_logged",
        "_n_segments",
        "duration",
        "first_contact",
        "hit_event_cap",
        "n_balls",
        "n_events",
        "recorded",
    )

    #: Columns of a segment state (``x, y, vx, vy`` on the roll level).
    _SEG_WIDTH = 4

    def __init__(self, raw: tuple, n_balls: int, deceleration: float, recorded: bool) -> None:
        """Take over what :func:`~pool_env.sim.kernels.loop.packed_shot` returned.

        Args:
            raw: Its tuple, for a valid scene.
            n_balls: The number of balls ``N``.
            deceleration: The table's rolling deceleration (for :meth:`positions_at`).
            recorded: Whether the events and segments were logged.
        """
        _, _, _, buffer, n_floats, n_events, n_segments, first_i, first_j, capped, duration = raw
        self._floats = buffer  # the float readers index the buffer from its start
        self._n_floats = n_floats
        self._int_part: NDArray[np.int64] | None = None  # made on the first int read
        self.n_balls = n_balls
        self.n_events = n_events
        self._n_logged = n_events if recorded else 0
        self._n_segments = n_segments
        self.first_contact = (first_i, first_j) if first_i >= 0 else None
        self.hit_event_cap = capped
        self.duration = duration
        self._deceleration = deceleration
        self.recorded = recorded

    @property
    def _ints(self) -> NDArray[np.int64]:
        """The buffer's int64 part (a view, made once)."""
        ints = self._int_part
        if ints is None:
            ints = self._int_part = packing.int_view(self._floats, self._n_floats)
        return ints

    def _ball_row(self, row: int) -> NDArray[np.int64]:
        return packing.ball_row(self._ints, self.n_balls, row)

    def _event_row(self, row: int) -> NDArray[np.int64]:
        return packing.event_row(self._ints, self.n_balls, self._n_logged, row)

    @property
    def positions(self) -> NDArray[np.float64]:
        """``(N, 2)`` final positions; a potted ball keeps its capture point."""
        return packing.final_positions(self._floats, self.n_balls)

    @property
    def pocketed(self) -> NDArray[np.int64]:
        """``(N,)`` the pocket each ball dropped into, -1 if none."""
        return self._ball_row(packing.BALL_POCKET)

    @property
    def pocket_order(self) -> NDArray[np.int64]:
        """``(N,)`` the order in which the balls dropped (0 first), -1 on the table."""
        return self._ball_row(packing.BALL_POCKET_ORDER)

    @property
    def first_hit(self) -> NDArray[np.int64]:
        """``(N,)`` the first ball each ball touched, -1 if none."""
        return self._ball_row(packing.BALL_FIRST_HIT)

    @property
    def cushions_after_contact(self) -> NDArray[np.int64]:
        """``(N,)`` each ball's cushion impacts after the shot's first ball-ball impact."""
        return self._ball_row(packing.BALL_CUSHIONS)

    @property
    def second_hit(self) -> NDArray[np.int64]:
        """``(N,)`` the second distinct ball each ball touched, -1 if none."""
        return self._ball_row(packing.BALL_SECOND_HIT)

    @property
    def cushions_at_second(self) -> NDArray[np.int64]:
        """``(N,)`` each ball's own cushion impacts up to its second distinct ball contact.

        Rails, jaw facings and points, counted from the shot's start; an impact at the
        very instant of that contact counts. -1 for a ball that touched fewer than two
        distinct balls. A carom's point reads it on the cue ball.
        """
        return self._ball_row(packing.BALL_CUSHIONS_AT_SECOND)

    @property
    def stopped_by_cap(self) -> NDArray[np.bool_]:
        """``(N,)`` booleans: the balls still moving when the event cap stopped them."""
        return self._ball_row(packing.BALL_STOPPED) != 0

    @property
    def event_times(self) -> NDArray[np.float64]:
        """``(E,)`` event times (s), chronological; empty if not recorded."""
        return packing.event_times(self._floats, self.n_balls, self._n_logged)

    @property
    def event_kinds(self) -> NDArray[np.int64]:
        """``(E,)`` event kind codes into :data:`KIND_NAMES`."""
        return self._event_row(0)

    @property
    def event_i(self) -> NDArray[np.int64]:
        """``(E,)`` the ball of each event."""
        return self._event_row(1)

    @property
    def event_j(self) -> NDArray[np.int64]:
        """``(E,)`` the other ball, rail, facing, point or pocket of each event (-1: none)."""
        return self._event_row(2)

    @property
    def event_first_segment(self) -> NDArray[np.int64]:
        """``(E,)`` the first row of :attr:`segments` each event wrote."""
        return self._event_row(3)

    @property
    def events(self) -> list[Event]:
        """The events in chronological order (built on access; empty if not recorded)."""
        return [
            Event(float(t), KIND_NAMES[k], int(i), int(j))
            for t, k, i, j in zip(
                self.event_times, self.event_kinds, self.event_i, self.event_j, strict=True
            )
        ]

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
        return _positions_at_many(*self._segment_views(), self.n_balls, times, self._deceleration)

    @property
    def segments(self) -> tuple[NDArray, NDArray, NDArray, NDArray]:
        """The trajectory log ``(ball, t, state, potted)``, chronological.

        Row ``r`` says ball ``ball[r]`` is re-anchored at time ``t[r]`` with
        ``state[r] = (x, y, vx, vy)`` (``potted[r]``: captured there). From an anchor a ball
        decelerates along its velocity until it rests. Empty if not recorded.
        """
        ball, t, state, potted = self._segment_views()
        return ball, t, state, potted != 0

    def _segment_views(self) -> tuple[NDArray, NDArray, NDArray, NDArray]:
        """The segment log as views: balls, times, states and potted flags (0 or 1)."""
        return packing.segment_views(
            self._floats, self._ints, self.n_balls, self._n_logged, self._n_segments,
            self._SEG_WIDTH,
        )  # fmt: skip

    @property
    def angular_velocities(self) -> NDArray[np.float64]:
        """``(N, 3)`` final angular velocities (rad/s): zero on the roll level (no spin)."""
        return np.zeros((self.n_balls, 3))

    @property
    def motion_states(self) -> NDArray[np.int8]:
        """``(N,)`` final motion states (:data:`~pool_env.sim.kernels.spin.state.STATE_NAMES`).

        On the roll level every ball ends at rest (``STATIONARY``) or ``POTTED``.
        """
        return np.where(self.pocketed >= 0, POTTED, STATIONARY).astype(np.int8)

    def pocketed_at(self, t: float) -> NDArray[np.bool_]:
        """``(N,)`` booleans: which balls are potted by time ``t``."""
        return self._frame(t)[1]

    def _frame(self, t: float) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        """Positions and potted flags at ``t`` (checked against ``[0, duration]``)."""
        t = self._check_time(t)
        return _positions_at(*self._segment_views(), self.n_balls, t, self._deceleration)

    def __repr__(self) -> str:
        potted = [int(i) for i in np.flatnonzero(self.pocketed >= 0)]
        return (
            f"ShotResult(n_balls={self.n_balls}, n_events={self.n_events}, "
            f"duration={self.duration:.4f}, potted={potted}, hit_event_cap={self.hit_event_cap})"
        )


class SpinShotResult(ShotResult):
    """A :class:`ShotResult` of the spin level (``Table(model="spin")``).

    As :class:`ShotResult`, with the final :attr:`angular_velocities` and
    :attr:`motion_states`, the transition events, segment states of nine columns
    ``(x, y, vx, vy, wx, wy, wz, ax, ay)`` (a ball follows ``p + v tau + acc tau^2 / 2`` from
    each of its rows: sliding paths are parabolas), and :meth:`positions_at` exact on them.
    """

    __slots__ = ()
    _SEG_WIDTH = SPIN_SEG_COLS

    def _tail(self) -> tuple[int, int]:
        return packing.tail_starts(self.n_balls, self._n_logged, self._n_segments, self._SEG_WIDTH)

    @property
    def angular_velocities(self) -> NDArray[np.float64]:
        """``(N, 3)`` final angular velocities ``(wx, wy, wz)`` (rad/s)."""
        f, _ = self._tail()
        return self._floats[f : f + 3 * self.n_balls].reshape(self.n_balls, 3)

    @property
    def motion_states(self) -> NDArray[np.int64]:
        """``(N,)`` final motion states (codes of ``spin.state.STATE_NAMES``)."""
        _, k = self._tail()
        return self._ints[k : k + self.n_balls]

    def positions_at_many(self, times: NDArray[np.float64]) -> tuple[NDArray, NDArray]:
        """Positions ``(T, N, 2)`` and potted flags ``(T, N)`` at each of ``times``."""
        times = np.ascontiguousarray(times, dtype=np.float64).reshape(-1)
        if not self.recorded:
            self._check_time(0.0)
        if times.size and not (times.min() >= 0.0 and times.max() <= self.duration):
            raise ValueError(f"times must lie in [0, duration={self.duration}]")
        return spin_positions_at_many(*self._segment_views(), self.n_balls, times)

    def _frame(self, t: float) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        t = self._check_time(t)
        return spin_positions_at(*self._segment_views(), self.n_balls, t)
