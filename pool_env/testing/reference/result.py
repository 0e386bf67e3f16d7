"""What the reference returns: final state, events, and the exact trajectory for queries."""

from __future__ import annotations

from dataclasses import dataclass, field

from mpmath import mp, mpf

from pool_env.testing.reference.model import DPS, Event, Vec
from pool_env.testing.reference.pieces import Piece, state_at


@dataclass
class ReferenceResult:
    """Outcome of :func:`reference_simulate` (all numbers are 50-digit ``mpf``).

    Attributes:
        positions: Final ``(x, y)`` of each ball; a potted ball keeps its capture point.
        pocketed: ``-1`` for a ball on the table, else the index of the pocket that took it.
        events: Chronological ``(time, kind, i, j)``; ``kind`` is ``"ball"`` (``j`` the other
            ball, ``i < j``), ``"cushion"`` (``j`` the rail: 0 ``x=R``, 1 ``x=L-R``,
            2 ``y=R``, 3 ``y=W-R``), ``"pocket"`` (``j`` the pocket) or ``"stop"``
            (``j = -1``).
        duration: Time at which everything rests (the last event's time, 0 if none).
        near_ties: Indices into ``events`` of events chosen among several candidates within
            :data:`TIE_TOLERANCE` of each other, i.e. by the ``(kind, i, j)`` order rather
            than by time. Empty for scenes without simultaneous events.
    """

    positions: list[Vec]
    pocketed: list[int]
    events: list[Event]
    duration: mpf
    near_ties: list[int]
    _before: list[list[Vec]] = field(repr=False)
    _after: list[list[Vec]] = field(repr=False)
    _pieces: list[list[Piece]] = field(repr=False)
    _captures: list[tuple[mpf, Vec] | None] = field(repr=False)
    _decel: mpf = field(repr=False)

    def first_velocities_after(self, k: int) -> list[Vec]:
        """Velocities of all balls right after event ``k`` (potted balls: zero).

        Args:
            k: Event index into ``events``.

        Returns:
            ``N`` velocity pairs at the time of event ``k``, after it was applied.
        """
        return list(self._after[k])

    def velocities_after(self, k: int) -> list[Vec]:
        """Alias of :meth:`first_velocities_after`."""
        return self.first_velocities_after(k)

    def velocities_before(self, k: int) -> list[Vec]:
        """Velocities of all balls at the time of event ``k``, before it was applied.

        Args:
            k: Event index into ``events``.

        Returns:
            ``N`` velocity pairs (potted balls: zero).
        """
        return list(self._before[k])

    def positions_at(self, t: float | mpf) -> list[Vec]:
        """Exact positions of all balls at time ``t`` (potted balls: their capture point).

        Args:
            t: Time in seconds, ``0 <= t`` (after ``duration`` everything rests).

        Returns:
            ``N`` position pairs.
        """
        with mp.workdps(DPS):
            t = mpf(t)
            out: list[Vec] = []
            for pieces, capture in zip(self._pieces, self._captures, strict=True):
                if capture is not None and t >= capture[0]:
                    out.append(capture[1])
                    continue
                piece = pieces[0]
                for cand in pieces:
                    if cand[0] <= t:
                        piece = cand
                out.append(state_at(piece, t, self._decel)[0])
            return out
