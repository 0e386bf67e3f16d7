"""Independent 50-digit reference simulator for the pool table model (a test oracle).

This module re-implements the physics of ``/work/shared/design/PHYSICS.md`` from scratch in
``mpmath`` at 50 significant digits. It deliberately shares no code with the simulator
kernels in ``pool_env/sim/kernels``: it only reads the attributes of a ``pool_env.sim.table.Table``
(and imports that class for type checking only), so a bug in a float64 kernel cannot hide in
both implementations at once.

Model (SI units):

* A ball centre lives in ``[R, L-R] x [R, W-R]``. A moving ball decelerates at
  ``a = mu_roll * g`` against its velocity along a straight segment,
  ``p(t) = p0 + u (v0 t - a t^2 / 2)``, until ``t_stop = v0 / a``; it never reverses.
* Ball-ball impact when ``|pb - pa| = 2R`` while approaching; tangential components are kept
  and the normal components follow momentum conservation with restitution ``e_ball``.
* Cushions: the rails are the centre lines ``x = R`` (0), ``x = L-R`` (1), ``y = R`` (2),
  ``y = W-R`` (3); only a ball moving into a rail bounces, ``v_n -> -e_cushion v_n``.
* Pockets: capture circles; a ball is potted where its centre enters the circle.
* Jaw tables (``table.jaws`` not empty): the rails are the finite segments
  ``table.rails``; each pocket has two straight facings (``"jaw"`` events, ``j = 2 k +
  side``) and two round points (``"point"``), and a fall line. A ball touches a segment
  (rail or facing) when its centre is ``R`` from the segment's line on the table side with
  the foot of the perpendicular inside the segment, and a point when its centre is
  ``R + tip_radius`` from the tip centre; both reflect the normal component (the
  segment's normal, or the line from the tip centre) with ``e_cushion`` (rails) or
  ``e_jaw``. A ball is potted (``"pocket"``) when its centre reaches the fall line (the
  segment across the throat between the two facings). Every
  piece is checked for every ball (no culling): these are read from the table's
  documented geometry (points, rail ends, tip centres, facings, fall lines) and offset by
  ``R`` here, at 50 digits.

Departures from the printed seed document (``seed/000_c5d533347adfb131.txt``), as required
by PHYSICS.md:

* The seed's restitution term has the wrong sign (``- m_b e (v_ib - v_ia)``); with that sign
  and ``e = 1``, equal masses pass through each other. :func:`_impact` uses
  ``+ m_b e (u_b - u_a)`` so that the separation speed is ``e`` times the approach speed.
* The seed rotates back with ``sin(phi + 90)`` and ``cos(phi + 90)`` swapped. We never rotate
  at all: the impulse is applied along the unit line of centres ``n``, which is the same
  physics without the trigonometry.
* The seed's ``theta = atan(vy / vx)`` loses the quadrant; we carry unit vectors instead.

Numerics (why this is an oracle and not another kernel):

* Every input float is converted exactly (``mpf(float)`` is exact) and all arithmetic runs
  at 50 digits inside ``mp.workdps(50)``, so rounding is ~1e-50 relative, 35 orders below
  float64.
* Ball-cushion and ball-pocket events are solved in closed form in the arc length ``s`` of
  the straight path; ``t`` follows from ``t = 2 s / (v + sqrt(v^2 - 2 a s))``, which has no
  cancellation.
* A pair with one ball resting is a quadratic in the arc length of the moving ball, solved
  in the cancellation-free form ``s = c / (-b + sqrt(b^2 - c))``.
* A pair with both balls moving is a quartic in time. Its real roots are *isolated* rather
  than computed as complex roots: the critical points of a polynomial are the sign changes
  of its derivative, found recursively (quartic -> cubic -> quadratic -> linear), so the
  window splits into pieces on which the gap is monotone; the first piece on which the gap
  decreases to zero holds the event, which is then refined by bracketed, safeguarded Newton
  iteration. No step divides by a leading coefficient, so the degree drops (equal
  directions, equal velocities) need no special case.
* Each pair is predicted only up to the earlier stop of its two balls. Stops are events;
  after every event everything is re-predicted, so the second phase of a pair (one ball at
  rest) is handled by the one-ball-resting quadratic after the stop event.
* Contact rule: a touching or overlapping state that is approaching (a rail, a ball or a
  pocket circle) is an event *now*; a separating one is no event. A touch with zero
  approach speed (exact tangency, reaching a rail exactly as the ball stops) is not an
  impact.
* Events are ordered by ``(time, kind, i, j)`` with ``pocket < ball < cushion < stop``.
  Exact ties of the ideal model show up at 50 digits as times ~1e-48 s apart, so candidates
  within :data:`TIE_TOLERANCE` (1e-30 s) of the earliest are treated as simultaneous and
  ordered by ``(kind, i, j)``; such choices are listed in ``ReferenceResult.near_ties`` so
  a test can see them rather than have them happen silently.

Choices where the model leaves room (a kernel may differ here; compare with care):

* A ball brought exactly to rest by an event (a head-on exchange with ``e = 1``, a square
  hit on a rail with ``e_cushion = 0``) has no separate ``"stop"`` event.
* The corner capture circles reach the rail corners, so a ball may *start* inside one. It
  is potted at once if it moves towards the pocket centre (the contact rule), never if it
  rests there or moves outwards until it re-enters.
* Zeno cascades (a ball pressed against a rail with ``e_cushion = 0``, touching chains)
  are not regularised: the events pile up at one instant until ``max_events`` raises
  :class:`ReferenceSimulationError`. The reference is meant for scenes with a few impacts.

The reference is a test oracle: it is O(N^2) per event and slow, but a 3-ball, 3-collision
scene takes ~10 ms.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt
from mpmath import mp, mpf

if TYPE_CHECKING:
    # Type checking only: at run time the reference reads the table's attributes and runs
    # no code from pool_env at all.
    from pool_env.sim.table import Table

#: Working precision in significant decimal digits.
DPS = 50

#: Candidate events closer than this (in seconds) are simultaneous in the ideal model.
#: 50-digit rounding separates true ties by ~1e-48 s; distinct events in the hard cases are
#: at least 1e-15 s apart, so 1e-30 s sits safely between the two.
TIE_TOLERANCE = "1e-30"

#: Initial overlaps and rail violations up to this many metres are accepted (float inputs
#: built as ``x + 2R`` can overlap by ~1e-17 m); the contact rule then resolves them.
INPUT_TOLERANCE = 1e-9

#: Processing order of event kinds at equal times.
KIND_ORDER: dict[str, int] = {
    "pocket": 0,
    "ball": 1,
    "cushion": 2,
    "stop": 3,
    "jaw": 4,
    "point": 5,
}

Vec = tuple[mpf, mpf]
Event = tuple[mpf, str, int, int]


class ReferenceSimulationError(RuntimeError):
    """The scene leaves what the reference can resolve (event cap, sustained contact)."""


# --------------------------------------------------------------------------------------
# Small vector and polynomial helpers (coefficient lists are in ascending powers).
# --------------------------------------------------------------------------------------


def _dot(p: Vec, q: Vec) -> mpf:
    return p[0] * q[0] + p[1] * q[1]


def _sub(p: Vec, q: Vec) -> Vec:
    return (p[0] - q[0], p[1] - q[1])


def _axpy(alpha: mpf, u: Vec, p: Vec) -> Vec:
    """Return ``p + alpha * u``."""
    return (p[0] + alpha * u[0], p[1] + alpha * u[1])


def _horner(c: Sequence[mpf], x: mpf) -> mpf:
    acc = mpf(0)
    for coef in reversed(c):
        acc = acc * x + coef
    return acc


def _deriv(c: Sequence[mpf]) -> list[mpf]:
    return [k * c[k] for k in range(1, len(c))]


def _trim(c: Sequence[mpf]) -> list[mpf]:
    """Drop exactly-zero leading coefficients: the only degree drops that are real."""
    out = list(c)
    while out and out[-1] == 0:
        out.pop()
    return out


def _refine(c: Sequence[mpf], lo: mpf, hi: mpf, flo: mpf, fhi: mpf) -> tuple[mpf, mpf]:
    """Shrink a sign-change bracket of a polynomial to ~50 digits.

    Safeguarded Newton: a Newton step is taken only when it stays inside the bracket and is
    shorter than half of it, and the bracket is bisected whenever four iterations have not
    halved it, so convergence is guaranteed and usually quadratic. Newton approaches a root
    from one side; once its step is below the tolerance, the next iterate is placed just
    past the root so that the bracket closes from both sides (callers rely on the bracket,
    not on the last iterate).

    Args:
        c: Polynomial coefficients, ascending powers.
        lo: Left end of the bracket.
        hi: Right end of the bracket, ``hi > lo``.
        flo: ``c(lo)``, non-zero.
        fhi: ``c(hi)``, non-zero and of the opposite sign to ``flo``.

    Returns:
        ``(x_lo, x_hi)``: the final bracket, ``x_lo`` on the side with the sign of ``flo``
        and ``x_hi`` on the side with the sign of ``fhi`` (equal if an exact zero was hit).
    """
    dc = _deriv(c)
    neg_left = flo < 0
    x = (lo + hi) / 2
    checkpoint = hi - lo
    for it in range(1, 4000):
        fx = _horner(c, x)
        if fx == 0:
            return x, x
        if (fx < 0) == neg_left:
            lo = x
        else:
            hi = x
        width = hi - lo
        tol = mp.eps * 64 * (abs(lo) + abs(hi)) + mpf("1e-80")
        if width <= tol:
            break
        dfx = _horner(dc, x)
        step = fx / dfx if dfx != 0 else None
        if it % 4 == 0:
            stalled = width > checkpoint / 2
            checkpoint = width
        else:
            stalled = False
        if step is None or stalled or not (abs(step) < width / 2 and lo < x - step < hi):
            x = lo + width / 2
        elif abs(step) <= tol:
            # Converged from one side: probe just beyond the root to close the bracket.
            probe = x - step - (tol if step > 0 else -tol)
            x = probe if lo < probe < hi else lo + width / 2
        else:
            x = x - step
    return lo, hi


def _sign_changes(c: Sequence[mpf], lo: mpf, hi: mpf) -> list[mpf]:
    """Points in ``(lo, hi)`` where a polynomial changes sign (or is exactly zero).

    Recursive real-root isolation: the sign changes of ``c'`` split ``[lo, hi]`` into pieces
    on which ``c`` is monotone, and each piece holds at most one root, which is bracketed and
    refined. Extra points (exact zeros without a sign change) are harmless to the callers,
    who only use the result to cut the window into monotone pieces.

    Args:
        c: Polynomial coefficients, ascending powers.
        lo: Left end of the window.
        hi: Right end of the window.

    Returns:
        The points, sorted ascending.
    """
    c = _trim(c)
    if len(c) <= 1:
        return []
    if len(c) == 2:
        r = -c[0] / c[1]
        return [r] if lo < r < hi else []
    pts = [lo, *_sign_changes(_deriv(c), lo, hi), hi]
    vals = [_horner(c, x) for x in pts]
    out: list[mpf] = []
    for k in range(len(pts) - 1):
        if k > 0 and vals[k] == 0:
            out.append(pts[k])
        f0, f1 = vals[k], vals[k + 1]
        if f0 != 0 and f1 != 0 and (f0 < 0) != (f1 < 0):
            a, b = _refine(c, pts[k], pts[k + 1], f0, f1)
            out.append((a + b) / 2)
    return out


def _first_contact(g: Sequence[mpf], lo: mpf, hi: mpf) -> mpf | None:
    """First point in ``[lo, hi]`` where the gap ``g`` reaches zero while decreasing.

    Args:
        g: Gap polynomial ``|d|^2 - 4R^2`` (ascending powers); negative means overlap.
        lo: Start of the validity window.
        hi: End of the validity window.

    Returns:
        The contact time (on the ``g <= 0`` side of the root, within ~1e-50 relative), or
        ``None`` if the gap does not close while approaching inside the window.

    Raises:
        ReferenceSimulationError: If the balls overlap and start approaching with zero
            approach speed (sustained contact, which the event model cannot express).
    """
    if not hi > lo:
        return None
    dg = _deriv(g)
    pts = [lo, *_sign_changes(dg, lo, hi), hi]
    vals = [_horner(g, x) for x in pts]
    for k in range(len(pts) - 1):
        x0, x1, f0, f1 = pts[k], pts[k + 1], vals[k], vals[k + 1]
        if not f1 < f0:
            continue  # separating (or constant) on this piece: no impact
        if f0 <= 0:
            # Touching or overlapping at the start of a closing piece. At the window start
            # this is the contact rule's "approaching means collide now".
            if k == 0 and _horner(dg, x0) < 0:
                return x0
            raise ReferenceSimulationError(
                "balls in contact start closing with zero approach speed (sustained "
                "contact); the event model cannot resolve it"
            )
        if f1 == 0:
            root = x1
        elif f1 < 0:
            _, root = _refine(g, x0, x1, f0, f1)
        else:
            continue
        if _horner(dg, root) < 0:
            return root
        # A tangential touch (g' = 0 where g = 0) transfers no impulse: not an impact.
    return None


def _gap_poly(p_i: Vec, v_i: Vec, acc_i: Vec, p_j: Vec, v_j: Vec, acc_j: Vec, r: mpf) -> list[mpf]:
    """Gap ``|p_j(tau) - p_i(tau)|^2 - (2r)^2`` for ``p(tau) = p + v tau + acc tau^2 / 2``.

    Args:
        p_i: Position of ball i at ``tau = 0``.
        v_i: Velocity of ball i at ``tau = 0``.
        acc_i: Constant acceleration of ball i (``-a u`` moving, zero resting).
        p_j: Position of ball j at ``tau = 0``.
        v_j: Velocity of ball j at ``tau = 0``.
        acc_j: Constant acceleration of ball j.
        r: Ball radius.

    Returns:
        Coefficients of the (at most) quartic, ascending powers of ``tau``.
    """
    d0 = _sub(p_j, p_i)
    d1 = _sub(v_j, v_i)
    d2 = ((acc_j[0] - acc_i[0]) / 2, (acc_j[1] - acc_i[1]) / 2)
    return [
        _dot(d0, d0) - 4 * r * r,
        2 * _dot(d0, d1),
        _dot(d1, d1) + 2 * _dot(d0, d2),
        2 * _dot(d1, d2),
        _dot(d2, d2),
    ]


# --------------------------------------------------------------------------------------
# Simulation state
# --------------------------------------------------------------------------------------


@dataclass
class _Ball:
    """One ball's current trajectory piece, anchored at its own last event."""

    t0: mpf
    p0: Vec
    speed: mpf  # speed at t0; 0 means resting
    u: Vec  # unit direction of travel, (0, 0) when resting
    t_stop: mpf
    rest: Vec
    pocket: int = -1
    # (t0, p0, speed, u, t_stop, rest) of every piece, for positions_at().
    history: list[tuple[mpf, Vec, mpf, Vec, mpf, Vec]] = field(default_factory=list)


@dataclass
class _Candidate:
    time: mpf
    kind: str
    i: int
    j: int

    def order_key(self) -> tuple[int, int, int]:
        return (KIND_ORDER[self.kind], self.i, self.j)


def _anchor(ball: _Ball, t: mpf, p: Vec, v: Vec, decel: mpf) -> None:
    """Start a new trajectory piece of ``ball`` at time ``t``, position ``p``, velocity ``v``."""
    speed = mp.sqrt(_dot(v, v))
    if speed > 0:
        u = (v[0] / speed, v[1] / speed)
        t_stop = t + speed / decel
        rest = _axpy(speed * speed / (2 * decel), u, p)
    else:
        u = (mpf(0), mpf(0))
        t_stop = t
        rest = p
    ball.t0, ball.p0, ball.speed, ball.u, ball.t_stop, ball.rest = t, p, speed, u, t_stop, rest
    ball.history.append((t, p, speed, u, t_stop, rest))


def _state(piece: tuple[mpf, Vec, mpf, Vec, mpf, Vec], t: mpf, decel: mpf) -> tuple[Vec, mpf, Vec]:
    """Position, speed and direction at time ``t`` on a trajectory piece."""
    t0, p0, speed, u, t_stop, rest = piece
    if speed == 0 or t >= t_stop:
        return rest, mpf(0), u
    tau = t - t0
    if tau <= 0:
        return p0, speed, u
    return _axpy(speed * tau - decel * tau * tau / 2, u, p0), speed - decel * tau, u


def _time_for_distance(t_now: mpf, w: mpf, s: mpf, decel: mpf) -> mpf:
    """Time at which a ball at speed ``w`` at ``t_now`` has rolled a further distance ``s``."""
    if s <= 0:
        return t_now
    # s = w t - a t^2 / 2 solved without cancellation.
    return t_now + 2 * s / (w + mp.sqrt(max(w * w - 2 * decel * s, mpf(0))))


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
    _pieces: list[list[tuple[mpf, Vec, mpf, Vec, mpf, Vec]]] = field(repr=False)
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
                out.append(_state(piece, t, self._decel)[0])
            return out


class _Simulator:
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
        self.e_jaw = mpf(table.e_jaw)
        self.jaw_table = len(table.jaws) > 0
        # Capture circles pot only on tables without jaws (on a jaw table they summarise).
        circles = [] if self.jaw_table else table.pockets
        self.pockets = [tuple(mpf(float(x)) for x in row) for row in circles]
        # Finite segments (a ball-centre line R from the nose, on the free side):
        # (kind, j, start, unit direction, free-side unit normal, length, restitution).
        self.segments: list[tuple[str, int, Vec, Vec, Vec, mpf, mpf]] = []
        self.tips: list[tuple[int, Vec, mpf]] = []  # (j, centre, contact radius)
        # (pocket, middle of the fall line, unit normal to the table, half its length)
        self.falls: list[tuple[int, Vec, Vec, mpf]] = []
        if self.jaw_table:
            self._build_jaws(table)
        # (rail index, axis, coordinate of the centre line, outward direction)
        self.rails = [
            (0, 0, self.R, -1),
            (1, 0, self.L - self.R, 1),
            (2, 1, self.R, -1),
            (3, 1, self.W - self.R, 1),
        ]
        self.masses = masses
        self.tie = mpf(TIE_TOLERANCE)
        self.balls: list[_Ball] = []
        zero = mpf(0)
        for p, v in zip(positions, velocities, strict=True):
            ball = _Ball(zero, p, zero, (zero, zero), zero, p)
            _anchor(ball, zero, p, v, self.decel)
            self.balls.append(ball)
        self.captures: list[tuple[mpf, Vec] | None] = [None] * len(self.balls)

    def _build_jaws(self, table: Table) -> None:
        """Rails, facings, points and fall lines of a jaw table, offset by ``R``."""
        centre = (self.L / 2, self.W / 2)
        for a, b in table.rails:
            start = (mpf(float(a[0])), mpf(float(a[1])))
            end = (mpf(float(b[0])), mpf(float(b[1])))
            # Rail lines as the kernel numbers them: 0 x = R, 1 x = L - R, 2 y = R, 3 y = W - R.
            axis = 1 if start[1] == end[1] else 0
            index = (2 * axis) + (0 if start[axis] == 0 else 1)
            # The free side of a rail faces the middle of the table.
            self._add_segment("cushion", index, start, end, centre, self.e_cushion)
        for k, jaw in enumerate(table.jaws):
            pts = [(mpf(float(p[0])), mpf(float(p[1]))) for p in jaw.points]
            for side in range(2):
                a, b = jaw.facings[side]
                start = (mpf(float(a[0])), mpf(float(a[1])))
                end = (mpf(float(b[0])), mpf(float(b[1])))
                # The free side of a facing faces the other point, across the throat.
                self._add_segment("jaw", 2 * k + side, start, end, pts[1 - side], self.e_jaw)
                c = jaw.tip_centres[side]
                tip = (mpf(float(c[0])), mpf(float(c[1])))
                self.tips.append((2 * k + side, tip, mpf(float(jaw.tip_radius)) + self.R))
            f0, f1 = jaw.fall_line
            end0 = (mpf(float(f0[0])), mpf(float(f0[1])))
            end1 = (mpf(float(f1[0])), mpf(float(f1[1])))
            point = ((end0[0] + end1[0]) / 2, (end0[1] + end1[1]) / 2)  # the middle
            span = _sub(end1, end0)
            norm = mp.sqrt(_dot(span, span))
            normal = (-span[1] / norm, span[0] / norm)
            # Towards the table: the side of the mouth's points.
            if _dot(_sub(pts[0], point), normal) < 0:
                normal = (-normal[0], -normal[1])
            self.falls.append((k, point, normal, norm / 2))

    def _add_segment(self, kind: str, j: int, start: Vec, end: Vec, free_side: Vec, e: mpf) -> None:
        span = _sub(end, start)
        length = mp.sqrt(_dot(span, span))
        d = (span[0] / length, span[1] / length)
        n = (-d[1], d[0])
        if _dot(_sub(free_side, start), n) < 0:
            n = (-n[0], -n[1])
        self.segments.append((kind, j, _axpy(self.R, n, start), d, n, length, e))

    def _jaw_events(self, i: int, t_now: mpf, p: Vec, w: mpf, u: Vec) -> list[_Candidate]:
        """Rail, facing, point and fall-line candidates of a moving ball on a jaw table."""
        out = []
        s_rem = w * w / (2 * self.decel)
        for kind, j, a, d, n, length, _ in self.segments:
            un = _dot(u, n)
            if un >= 0:
                continue  # moving away from (or along) the segment
            # On or a hair beyond the line while moving in: contact now (the clamp).
            s = max(_dot(_sub(p, a), n) / -un, mpf(0))
            along = _dot(_sub(_axpy(s, u, p), a), d)
            if 0 <= along <= length and s < s_rem:
                out.append(_Candidate(_time_for_distance(t_now, w, s, self.decel), kind, i, j))
        for j, c, rho in self.tips:
            q = _sub(p, c)
            b = _dot(u, q)
            if b >= 0:
                continue
            cc = _dot(q, q) - rho * rho
            if cc <= 0:
                s = mpf(0)
            else:
                disc = b * b - cc
                if disc <= 0:
                    continue  # a miss or an exact tangential graze (no impulse)
                s = cc / (-b + mp.sqrt(disc))
            if s < s_rem:
                out.append(_Candidate(_time_for_distance(t_now, w, s, self.decel), "point", i, j))
        for k, f, n, length in self.falls:
            delta = _dot(_sub(p, f), n)
            if delta <= 0:
                s = mpf(0)
            else:
                un = _dot(u, n)
                if un >= 0:
                    continue
                s = delta / -un
            # The fall line is the segment across the throat, between the two facings.
            along = _dot(_sub(_axpy(s, u, p), f), (n[1], -n[0]))
            if abs(along) <= length and s <= s_rem:
                out.append(_Candidate(_time_for_distance(t_now, w, s, self.decel), "pocket", i, k))
        return out

    def _normal_of(self, kind: str, j: int, p: Vec) -> tuple[Vec, mpf]:
        """Free-side unit normal and restitution of the cushion piece ``(kind, j)`` at ``p``."""
        if kind == "point":
            for jj, c, _ in self.tips:
                if jj == j:
                    q = _sub(p, c)
                    norm = mp.sqrt(_dot(q, q))
                    return (q[0] / norm, q[1] / norm), self.e_jaw
        for kk, jj, _, _, n, _, e in self.segments:
            if kk == kind and jj == j:
                return n, e
        raise ReferenceSimulationError(f"no cushion piece {kind} {j}")

    # -- state -------------------------------------------------------------------------

    def state(self, i: int, t: mpf) -> tuple[Vec, mpf, Vec]:
        b = self.balls[i]
        return _state((b.t0, b.p0, b.speed, b.u, b.t_stop, b.rest), t, self.decel)

    def velocity(self, i: int, t: mpf) -> Vec:
        if self.balls[i].pocket >= 0:
            return (mpf(0), mpf(0))
        _, w, u = self.state(i, t)
        return (w * u[0], w * u[1])

    def active(self) -> list[int]:
        return [i for i, b in enumerate(self.balls) if b.pocket < 0]

    # -- prediction --------------------------------------------------------------------

    def own_events(self, i: int, t_now: mpf) -> list[_Candidate]:
        """Stop, cushion and pocket candidates of one moving ball."""
        ball = self.balls[i]
        out = [_Candidate(max(ball.t_stop, t_now), "stop", i, -1)]
        p, w, u = self.state(i, t_now)
        if w <= 0:
            return out
        if self.jaw_table:
            return out + self._jaw_events(i, t_now, p, w, u)
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
                    _Candidate(_time_for_distance(t_now, w, s, self.decel), "cushion", i, index)
                )
        for k, (cx, cy, cr) in enumerate(self.pockets):
            q = (p[0] - cx, p[1] - cy)
            b = _dot(u, q)
            if b >= 0:
                continue  # moving away from (or tangentially past) the pocket centre
            c = _dot(q, q) - cr * cr
            if c <= 0:
                s = mpf(0)  # on or inside the circle and moving inwards: captured now
            else:
                disc = b * b - c
                if disc <= 0:
                    continue  # misses, or only grazes the circle without entering
                s = c / (-b + mp.sqrt(disc))
            if s <= s_rem:
                out.append(_Candidate(_time_for_distance(t_now, w, s, self.decel), "pocket", i, k))
        return out

    def pair_event(self, i: int, j: int, t_now: mpf, horizon: mpf) -> _Candidate | None:
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
            q = _sub(p_m, p_r)
            b = _dot(u, q)
            if b >= 0:
                return None  # the gap only grows along the path
            c = _dot(q, q) - 4 * self.R * self.R
            if c <= 0:
                s = mpf(0)  # touching or overlapping and approaching: collide now
            else:
                disc = b * b - c
                if disc <= 0:
                    return None  # a miss or an exact tangential graze (no impulse)
                s = c / (-b + mp.sqrt(disc))
                if not s < w * w / (2 * self.decel):
                    return None  # the mover stops before (or exactly at) contact
            t = _time_for_distance(t_now, w, s, self.decel)
            return _Candidate(t, "ball", i, j) if t <= horizon else None
        # Both move: a quartic in tau = t - t_now, valid until either ball stops.
        end = min(self.balls[i].t_stop, self.balls[j].t_stop, horizon) - t_now
        acc_i = (-self.decel * u_i[0], -self.decel * u_i[1])
        acc_j = (-self.decel * u_j[0], -self.decel * u_j[1])
        g = _gap_poly(
            p_i,
            (w_i * u_i[0], w_i * u_i[1]),
            acc_i,
            p_j,
            (w_j * u_j[0], w_j * u_j[1]),
            acc_j,
            self.R,
        )
        tau = _first_contact(g, mpf(0), end)
        return None if tau is None else _Candidate(t_now + tau, "ball", i, j)

    def _reachable(
        self, p_i: Vec, w_i: mpf, u_i: Vec, p_j: Vec, w_j: mpf, u_j: Vec, window: mpf
    ) -> bool:
        """Cheap cull: can the boxes swept by the two balls within ``window`` touch?"""
        boxes = []
        for p, w, u in ((p_i, w_i, u_i), (p_j, w_j, u_j)):
            t = min(window, w / self.decel) if w > 0 else mpf(0)
            s = w * t - self.decel * t * t / 2 if t > 0 else mpf(0)
            q = _axpy(s, u, p)
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

    def apply(self, ev: _Candidate) -> None:
        t, i = ev.time, ev.i
        ball = self.balls[i]
        if ev.kind == "stop":
            _anchor(ball, t, ball.rest, (mpf(0), mpf(0)), self.decel)
        elif ev.kind in ("jaw", "point") or (ev.kind == "cushion" and self.jaw_table):
            p, w, u = self.state(i, t)
            n, e = self._normal_of(ev.kind, ev.j, p)
            v = (w * u[0], w * u[1])
            vn = _dot(v, n)
            if vn < 0:  # only a velocity into the cushion is reflected
                v = _axpy(-(1 + e) * vn, n, v)
            _anchor(ball, t, p, v, self.decel)
        elif ev.kind == "cushion":
            p, w, u = self.state(i, t)
            v = [w * u[0], w * u[1]]
            axis = self.rails[ev.j][1]
            v[axis] = -self.e_cushion * v[axis]
            _anchor(ball, t, p, (v[0], v[1]), self.decel)
        elif ev.kind == "pocket":
            p, _, _ = self.state(i, t)
            ball.pocket = ev.j
            self.captures[i] = (t, p)
        else:
            self._impact(i, ev.j, t)

    def _impact(self, i: int, j: int, t: mpf) -> None:
        """Ball-ball impact with the corrected seed formulas (see the module docstring)."""
        p_i, _, _ = self.state(i, t)
        p_j, _, _ = self.state(j, t)
        v_i, v_j = self.velocity(i, t), self.velocity(j, t)
        d = _sub(p_j, p_i)
        dist = mp.sqrt(_dot(d, d))
        n = (d[0] / dist, d[1] / dist)
        ua, ub = _dot(v_i, n), _dot(v_j, n)
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
        _anchor(self.balls[i], t, p_i, _axpy(ua_new - ua, n, v_i), self.decel)
        _anchor(self.balls[j], t, p_j, _axpy(ub_new - ub, n, v_j), self.decel)

    # -- main loop ---------------------------------------------------------------------

    def run(self, max_events: int) -> ReferenceResult:
        n_balls = len(self.balls)
        t_now = mpf(0)
        events: list[Event] = []
        before: list[list[Vec]] = []
        after: list[list[Vec]] = []
        near_ties: list[int] = []
        while True:
            active = self.active()
            moving = [i for i in active if self.balls[i].speed > 0]
            cands: list[_Candidate] = []
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
            chosen = min(group, key=_Candidate.order_key)
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


def _as_pairs(name: str, values: npt.ArrayLike, n: int | None) -> list[tuple[float, float]]:
    arr = np.asarray(values, dtype=np.float64)
    if arr.ndim != 2 or arr.shape[1] != 2:
        raise ValueError(f"{name} must have shape (N, 2), got {arr.shape}")
    if n is not None and arr.shape[0] != n:
        raise ValueError(f"{name} has {arr.shape[0]} rows, expected {n}")
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} must be finite")
    return [(float(x), float(y)) for x, y in arr]


def reference_simulate(
    table: Table,
    positions: npt.ArrayLike,
    velocities: npt.ArrayLike,
    masses: npt.ArrayLike | None = None,
    max_events: int = 200,
) -> ReferenceResult:
    """Simulate a shot to rest at 50 significant digits.

    Args:
        table: The table (only its attributes are read).
        positions: ``(N, 2)`` ball centres (floats or an array).
        velocities: ``(N, 2)`` initial velocities (m/s).
        masses: ``(N,)`` masses (kg); ``None`` gives every ball ``table.ball_mass``.
        max_events: Hard cap on the number of events.

    Returns:
        A :class:`ReferenceResult`. Its numbers are ``mpf`` values carrying 50 digits; do
        arithmetic on them inside ``mp.workdps(50)`` to keep that precision.

    Raises:
        ValueError: On malformed input, a ball outside the rails or overlapping another by
            more than :data:`INPUT_TOLERANCE`, or a non-positive mass.
        ReferenceSimulationError: If the event cap is exceeded or a sustained contact arises.
    """
    pos = _as_pairs("positions", positions, None)
    vel = _as_pairs("velocities", velocities, len(pos))
    if masses is None:
        mass = [float(table.ball_mass)] * len(pos)
    else:
        mass = [float(m) for m in np.asarray(masses, dtype=np.float64).reshape(-1)]
        if len(mass) != len(pos):
            raise ValueError(f"masses has {len(mass)} entries, expected {len(pos)}")
        if not all(math.isfinite(m) and m > 0 for m in mass):
            raise ValueError("masses must be positive and finite")
    with mp.workdps(DPS):
        p_mp = [(mpf(x), mpf(y)) for x, y in pos]
        v_mp = [(mpf(x), mpf(y)) for x, y in vel]
        r = mpf(table.ball_radius)
        tol = mpf(INPUT_TOLERANCE)
        # A jaw table's throats lie beyond the rail lines, within a mouth's width of the
        # middle of the mouth (a coarse check: the oracle is not a validator).
        mouths = [
            ((mpf(float(j.points[0][0])) + mpf(float(j.points[1][0]))) / 2,
             (mpf(float(j.points[0][1])) + mpf(float(j.points[1][1]))) / 2,
             mpf(float(math.dist(j.points[0], j.points[1]))))
            for j in table.jaws
        ]  # fmt: skip
        for k, (x, y) in enumerate(p_mp):
            if not (
                r - tol <= x <= mpf(table.length) - r + tol
                and r - tol <= y <= mpf(table.width) - r + tol
            ) and not any((x - mx) ** 2 + (y - my) ** 2 < w * w for mx, my, w in mouths):
                raise ValueError(f"ball {k} at ({float(x)}, {float(y)}) is outside the rails")
        for i in range(len(p_mp)):
            for j in range(i + 1, len(p_mp)):
                d = _sub(p_mp[j], p_mp[i])
                if mp.sqrt(_dot(d, d)) < 2 * r - tol:
                    raise ValueError(f"balls {i} and {j} overlap")
        sim = _Simulator(table, p_mp, v_mp, [mpf(m) for m in mass])
        return sim.run(max_events)
