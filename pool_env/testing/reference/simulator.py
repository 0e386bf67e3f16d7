"""The reference's event loop: predict every candidate, resolve the earliest, repeat.

After every event everything is re-predicted. Each pair is predicted only up to the earlier
stop of its two balls (stops are events), so the second phase of a pair (one ball at rest)
is handled by the one-ball-resting quadratic after the stop event.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from mpmath import mp, mpf

from pool_env.testing.reference.jaw_cushions import JawGeometry
from pool_env.testing.reference.model import (
    TIE_TOLERANCE,
    Event,
    ReferenceSimulationError,
    Vec,
    axpy,
    dot,
    sub,
)
from pool_env.testing.reference.pieces import Ball, Candidate, anchor, state_at, time_for_distance
from pool_env.testing.reference.result import ReferenceResult
from pool_env.testing.reference.roots import circle_entry, first_contact, gap_poly

if TYPE_CHECKING:
    # Type checking only: at run time the reference reads the table's attributes and runs
    # no code from pool_env at all.
    from pool_env.sim.table import Table


class Simulator:
    """The event loop of the reference model (not part of the public API)."""

    def __init__(
        self,
        table: Table,
        positions: list[Vec],
        velocities: list[Vec],
        masses: list[mpf],
    ) -> None:
        self.R = mpf(table.ball_radius)
        self.L = mpf(table.length)
        self.W = mpf(table.width)
        # Exact product of the two floats: the model's a = mu_roll * g, not a rounded copy.
        self.decel = mpf(table.mu_roll) * mpf(table.g)
        self.e_ball = mpf(table.e_ball)
        self.e_cushion = mpf(table.e_cushion)
        # The cushion pieces of a jaw table; None: the four straight rails and the circles.
        self.jaws = (
            JawGeometry(table, self.R, self.e_cushion, mpf(table.e_jaw)) if table.jaws else None
        )
        # Capture circles pot only on tables without jaws (on a jaw table they summarise).
        circles = [] if self.jaws is not None else table.pockets
        self.pockets = [tuple(mpf(float(x)) for x in row) for row in circles]
        # (rail index, axis, coordinate of the centre line, outward direction)
        self.rails = [
            (0, 0, self.R, -1),
            (1, 0, self.L - self.R, 1),
            (2, 1, self.R, -1),
            (3, 1, self.W - self.R, 1),
        ]
        self.masses = masses
        self.tie = mpf(TIE_TOLERANCE)
        self.balls: list[Ball] = []
        zero = mpf(0)
        for p, v in zip(positions, velocities, strict=True):
            ball = Ball(zero, p, zero, (zero, zero), zero, p)
            anchor(ball, zero, p, v, self.decel)
            self.balls.append(ball)
        self.captures: list[tuple[mpf, Vec] | None] = [None] * len(self.balls)

    # -- state -------------------------------------------------------------------------

    def state(self, i: int, t: mpf) -> tuple[Vec, mpf, Vec]:
        """Position, speed and unit direction of ball ``i`` at ``t`` (on its current piece)."""
        b = self.balls[i]
        return state_at((b.t0, b.p0, b.speed, b.u, b.t_stop, b.rest), t, self.decel)

    def velocity(self, i: int, t: mpf) -> Vec:
        """Velocity of ball ``i`` at ``t`` (zero once potted)."""
        if self.balls[i].pocket >= 0:
            return (mpf(0), mpf(0))
        _, w, u = self.state(i, t)
        return (w * u[0], w * u[1])

    def active(self) -> list[int]:
        """The balls still on the table."""
        return [i for i, b in enumerate(self.balls) if b.pocket < 0]

    # -- prediction --------------------------------------------------------------------

    def own_events(self, i: int, t_now: mpf) -> list[Candidate]:
        """Stop, cushion and pocket candidates of one moving ball."""
        ball = self.balls[i]
        out = [Candidate(max(ball.t_stop, t_now), "stop", i, -1)]
        p, w, u = self.state(i, t_now)
        if w <= 0:
            return out
        if self.jaws is not None:
            return out + self.jaws.events(i, t_now, p, w, u, self.decel)
        s_rem = w * w / (2 * self.decel)
        for index, axis, line, outward in self.rails:
            # Only a ball moving into the rail can hit it (a ball rolling along it cannot).
            if u[axis] * outward <= 0:
                continue
            # Clamp: a ball on or a hair beyond the rail, moving in, bounces now.
            s = max((line - p[axis]) / u[axis], mpf(0))
            # Reaching the rail exactly as the ball stops is no impact (zero normal speed).
            if s < s_rem:
                out.append(
                    Candidate(time_for_distance(t_now, w, s, self.decel), "cushion", i, index)
                )
        for k, (cx, cy, cr) in enumerate(self.pockets):
            # Captured where the centre enters the circle (at once if inside, moving in).
            s_pot = circle_entry(p, u, (cx, cy), cr * cr)
            if s_pot is not None and s_pot <= s_rem:
                t_pot = time_for_distance(t_now, w, s_pot, self.decel)
                out.append(Candidate(t_pot, "pocket", i, k))
        return out

    def pair_event(self, i: int, j: int, t_now: mpf, horizon: mpf) -> Candidate | None:
        """First impact of balls ``i < j`` in ``[t_now, min(horizon, first stop)]``."""
        p_i, w_i, u_i = self.state(i, t_now)
        p_j, w_j, u_j = self.state(j, t_now)
        if w_i <= 0 and w_j <= 0:
            return None
        if not self._reachable(p_i, w_i, u_i, p_j, w_j, u_j, horizon - t_now):
            return None
        if w_i <= 0 or w_j <= 0:
            # One ball rests: a quadratic in the arc length of the moving one.
            if w_i > 0:
                p_m, w, u, p_r = p_i, w_i, u_i, p_j
            else:
                p_m, w, u, p_r = p_j, w_j, u_j, p_i
            # Touching or overlapping and approaching: collide now (s = 0); None: the gap
            # only grows along the path, or a miss, or an exact tangential graze.
            s = circle_entry(p_m, u, p_r, 4 * self.R * self.R)
            if s is None or not s < w * w / (2 * self.decel):
                return None  # (or the mover stops before, or exactly at, contact)
            t = time_for_distance(t_now, w, s, self.decel)
            return Candidate(t, "ball", i, j) if t <= horizon else None
        # Both move: a quartic in tau = t - t_now, valid until either ball stops.
        end = min(self.balls[i].t_stop, self.balls[j].t_stop, horizon) - t_now
        acc_i = (-self.decel * u_i[0], -self.decel * u_i[1])
        acc_j = (-self.decel * u_j[0], -self.decel * u_j[1])
        g = gap_poly(
            p_i,
            (w_i * u_i[0], w_i * u_i[1]),
            acc_i,
            p_j,
            (w_j * u_j[0], w_j * u_j[1]),
            acc_j,
            self.R,
        )
        tau = first_contact(g, mpf(0), end)
        return None if tau is None else Candidate(t_now + tau, "ball", i, j)

    def _reachable(
        self, p_i: Vec, w_i: mpf, u_i: Vec, p_j: Vec, w_j: mpf, u_j: Vec, window: mpf
    ) -> bool:
        """Cheap cull: can the boxes swept by the two balls within ``window`` touch?"""
        boxes = []
        for p, w, u in ((p_i, w_i, u_i), (p_j, w_j, u_j)):
            t = min(window, w / self.decel) if w > 0 else mpf(0)
            s = w * t - self.decel * t * t / 2 if t > 0 else mpf(0)
            q = axpy(s, u, p)
            boxes.append((min(p[0], q[0]), max(p[0], q[0]), min(p[1], q[1]), max(p[1], q[1])))
        (ax0, ax1, ay0, ay1), (bx0, bx1, by0, by1) = boxes
        # Margin far above rounding so that the cull never drops a touching pair.
        reach = 2 * self.R + mpf("1e-20")
        return (
            bx0 - ax1 <= reach
            and ax0 - bx1 <= reach
            and by0 - ay1 <= reach
            and (ay0 - by1 <= reach)
        )

    # -- event handling ----------------------------------------------------------------

    def apply(self, ev: Candidate) -> None:
        """Resolve the chosen event: start new trajectory pieces, or pot the ball."""
        t, i = ev.time, ev.i
        ball = self.balls[i]
        if ev.kind == "stop":
            anchor(ball, t, ball.rest, (mpf(0), mpf(0)), self.decel)
        elif self.jaws is not None and ev.kind in ("cushion", "jaw", "point"):
            p, w, u = self.state(i, t)
            n, e = self.jaws.normal_of(ev.kind, ev.j, p)
            v = (w * u[0], w * u[1])
            vn = dot(v, n)
            if vn < 0:  # only a velocity into the cushion is reflected
                v = axpy(-(1 + e) * vn, n, v)
            anchor(ball, t, p, v, self.decel)
        elif ev.kind == "cushion":
            p, w, u = self.state(i, t)
            v = [w * u[0], w * u[1]]
            axis = self.rails[ev.j][1]
            v[axis] = -self.e_cushion * v[axis]
            anchor(ball, t, p, (v[0], v[1]), self.decel)
        elif ev.kind == "pocket":
            p, _, _ = self.state(i, t)
            ball.pocket = ev.j
            self.captures[i] = (t, p)
        else:
            self._impact(i, ev.j, t)

    def _impact(self, i: int, j: int, t: mpf) -> None:
        """Ball-ball impact with the corrected seed formulas (see the package docstring)."""
        p_i, _, _ = self.state(i, t)
        p_j, _, _ = self.state(j, t)
        v_i, v_j = self.velocity(i, t), self.velocity(j, t)
        d = sub(p_j, p_i)
        dist = mp.sqrt(dot(d, d))
        n = (d[0] / dist, d[1] / dist)
        ua, ub = dot(v_i, n), dot(v_j, n)
        if not ua - ub > 0:
            raise ReferenceSimulationError(
                f"impact of balls {i} and {j} at t={mp.nstr(t, 17)} s is not approaching"
            )
        ma, mb, e = self.masses[i], self.masses[j], self.e_ball
        # Seed: v_fa = (ma v_ia + mb v_ib - mb e (v_ib - v_ia)) / (ma + mb): the sign of the
        # restitution term is wrong there; "+" makes (ub' - ua') = e (ua - ub).
        ua_new = (ma * ua + mb * ub + mb * e * (ub - ua)) / (ma + mb)
        ub_new = (ma * ua + mb * ub + ma * e * (ua - ub)) / (ma + mb)
        # Tangential parts are untouched: add the normal change along n (no rotate-back, so
        # the seed's swapped sin/cos(phi + 90) has no counterpart here).
        anchor(self.balls[i], t, p_i, axpy(ua_new - ua, n, v_i), self.decel)
        anchor(self.balls[j], t, p_j, axpy(ub_new - ub, n, v_j), self.decel)

    # -- main loop ---------------------------------------------------------------------

    def run(self, max_events: int) -> ReferenceResult:
        """Resolve events, earliest first, until every ball rests or is potted.

        Args:
            max_events: Hard cap on the number of events.

        Returns:
            The outcome (see :class:`ReferenceResult`).

        Raises:
            ReferenceSimulationError: If more than ``max_events`` events happen.
        """
        n_balls = len(self.balls)
        t_now = mpf(0)
        events: list[Event] = []
        before: list[list[Vec]] = []
        after: list[list[Vec]] = []
        near_ties: list[int] = []
        while True:
            active = self.active()
            moving = [i for i in active if self.balls[i].speed > 0]
            cands: list[Candidate] = []
            for i in moving:
                cands.extend(self.own_events(i, t_now))
            if not cands:
                break  # nothing moves: every ball rests (or is potted)
            # Pair events later than the earliest known candidate (plus the tie window)
            # can never be chosen: searching only up to there keeps the reference fast.
            horizon = min(c.time for c in cands) + self.tie
            for a_idx, i in enumerate(active):
                for j in active[a_idx + 1 :]:
                    if self.balls[i].speed <= 0 and self.balls[j].speed <= 0:
                        continue
                    cand = self.pair_event(i, j, t_now, horizon)
                    if cand is not None:
                        cands.append(cand)
                        horizon = min(horizon, cand.time + self.tie)
            t_min = min(c.time for c in cands)
            group = [c for c in cands if c.time <= t_min + self.tie]
            chosen = min(group, key=Candidate.order_key)
            if len(events) >= max_events:
                raise ReferenceSimulationError(
                    f"more than max_events={max_events} events by t={mp.nstr(t_now, 17)} s "
                    "(Zeno-like cascade?)"
                )
            if len(group) > 1:
                near_ties.append(len(events))
            # Chosen from a tie group, an event may sit up to the tie window before the
            # clock; time never runs backwards.
            chosen.time = max(chosen.time, t_now)
            t_now = chosen.time
            before.append([self.velocity(k, t_now) for k in range(n_balls)])
            self.apply(chosen)
            after.append([self.velocity(k, t_now) for k in range(n_balls)])
            events.append((chosen.time, chosen.kind, chosen.i, chosen.j))
        positions: list[Vec] = []
        for k, ball in enumerate(self.balls):
            capture = self.captures[k]
            positions.append(capture[1] if capture is not None else ball.rest)
        return ReferenceResult(
            positions=positions,
            pocketed=[b.pocket for b in self.balls],
            events=events,
            duration=events[-1][0] if events else mpf(0),
            near_ties=near_ties,
            _before=before,
            _after=after,
            _pieces=[b.history for b in self.balls],
            _captures=list(self.captures),
            _decel=self.decel,
        )
