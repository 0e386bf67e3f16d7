"""Trajectory pieces: where a rolling ball is between two events, and the event candidates.

A ball decelerates at ``a = mu_roll * g`` along a straight segment from its last event,
``p(t) = p0 + u (v0 tau - a tau^2 / 2)`` with ``tau = t - t0``, until ``t_stop = t0 + v0 / a``.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from mpmath import mp, mpf

from pool_env.testing.reference.model import KIND_ORDER, Vec, axpy, dot

#: ``(t0, p0, speed, u, t_stop, rest)`` of one trajectory piece.
Piece = tuple[mpf, Vec, mpf, Vec, mpf, Vec]


@dataclass
class Ball:
    """One ball's current trajectory piece, anchored at its own last event."""

    t0: mpf
    p0: Vec
    speed: mpf  # speed at t0; 0 means resting
    u: Vec  # unit direction of travel, (0, 0) when resting
    t_stop: mpf
    rest: Vec
    pocket: int = -1
    # (t0, p0, speed, u, t_stop, rest) of every piece, for positions_at().
    history: list[Piece] = field(default_factory=list)


@dataclass
class Candidate:
    """A predicted event: ``(time, kind, i, j)`` as in ``ReferenceResult.events``."""

    time: mpf
    kind: str
    i: int
    j: int

    def order_key(self) -> tuple[int, int, int]:
        """The order among simultaneous candidates: kind (:data:`KIND_ORDER`), then balls."""
        return (KIND_ORDER[self.kind], self.i, self.j)


def anchor(ball: Ball, t: mpf, p: Vec, v: Vec, decel: mpf) -> None:
    """Start a new trajectory piece of ``ball`` at time ``t``, position ``p``, velocity ``v``."""
    speed = mp.sqrt(dot(v, v))
    if speed > 0:
        u = (v[0] / speed, v[1] / speed)
        t_stop = t + speed / decel
        rest = axpy(speed * speed / (2 * decel), u, p)
    else:
        u = (mpf(0), mpf(0))
        t_stop = t
        rest = p
    ball.t0, ball.p0, ball.speed, ball.u, ball.t_stop, ball.rest = t, p, speed, u, t_stop, rest
    ball.history.append((t, p, speed, u, t_stop, rest))


def state_at(piece: Piece, t: mpf, decel: mpf) -> tuple[Vec, mpf, Vec]:
    """Position, speed and direction at time ``t`` on a trajectory piece."""
    t0, p0, speed, u, t_stop, rest = piece
    if speed == 0 or t >= t_stop:
        return rest, mpf(0), u
    tau = t - t0
    if tau <= 0:
        return p0, speed, u
    return axpy(speed * tau - decel * tau * tau / 2, u, p0), speed - decel * tau, u


def time_for_distance(t_now: mpf, w: mpf, s: mpf, decel: mpf) -> mpf:
    """Time at which a ball at speed ``w`` at ``t_now`` has rolled a further distance ``s``."""
    if s <= 0:
        return t_now
    # s = w t - a t^2 / 2 solved without cancellation.
    return t_now + 2 * s / (w + mp.sqrt(max(w * w - 2 * decel * s, mpf(0))))
