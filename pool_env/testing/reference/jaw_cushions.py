"""The cushions of a jaw table at 50 digits: rails, facings, points and fall lines.

Read from the table's documented geometry (points, rail ends, tip centres, facings, fall
lines) and offset by ``R`` here. Every piece is checked for every ball (no culling).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from mpmath import mp, mpf

from pool_env.testing.reference.model import ReferenceSimulationError, Vec, axpy, dot, sub
from pool_env.testing.reference.pieces import Candidate, time_for_distance
from pool_env.testing.reference.roots import circle_entry

if TYPE_CHECKING:
    # Type checking only: at run time the reference reads the table's attributes and runs
    # no code from pool_env at all.
    from pool_env.sim.table import Table


class JawGeometry:
    """The ball-centre lines of a jaw table's cushion pieces, and the events they make."""

    def __init__(self, table: Table, r: mpf, e_cushion: mpf, e_jaw: mpf) -> None:
        """Rails, facings, points and fall lines of ``table``, offset by the ball radius ``r``.

        Args:
            table: A table with jaws (only its attributes are read).
            r: Ball radius at 50 digits.
            e_cushion: Restitution of the rails.
            e_jaw: Restitution of the facings and points.
        """
        self.R = r
        self.e_jaw = e_jaw
        # Finite segments (a ball-centre line R from the nose, on the free side):
        # (kind, j, start, unit direction, free-side unit normal, length, restitution).
        self.segments: list[tuple[str, int, Vec, Vec, Vec, mpf, mpf]] = []
        self.tips: list[tuple[int, Vec, mpf]] = []  # (j, centre, contact radius)
        # (pocket, middle of the fall line, unit normal to the table, half its length)
        self.falls: list[tuple[int, Vec, Vec, mpf]] = []
        centre = (mpf(table.length) / 2, mpf(table.width) / 2)
        for a, b in table.rails:
            start = (mpf(float(a[0])), mpf(float(a[1])))
            end = (mpf(float(b[0])), mpf(float(b[1])))
            # Rail lines as the kernel numbers them: 0 x = R, 1 x = L - R, 2 y = R, 3 y = W - R.
            axis = 1 if start[1] == end[1] else 0
            index = (2 * axis) + (0 if start[axis] == 0 else 1)
            # The free side of a rail faces the middle of the table.
            self._add_segment("cushion", index, start, end, centre, e_cushion)
        for k, jaw in enumerate(table.jaws):
            pts = [(mpf(float(p[0])), mpf(float(p[1]))) for p in jaw.points]
            for side in range(2):
                a, b = jaw.facings[side]
                start = (mpf(float(a[0])), mpf(float(a[1])))
                end = (mpf(float(b[0])), mpf(float(b[1])))
                # The free side of a facing faces the other point, across the throat.
                self._add_segment("jaw", 2 * k + side, start, end, pts[1 - side], e_jaw)
                c = jaw.tip_centres[side]
                tip = (mpf(float(c[0])), mpf(float(c[1])))
                self.tips.append((2 * k + side, tip, mpf(float(jaw.tip_radius)) + r))
            f0, f1 = jaw.fall_line
            end0 = (mpf(float(f0[0])), mpf(float(f0[1])))
            end1 = (mpf(float(f1[0])), mpf(float(f1[1])))
            point = ((end0[0] + end1[0]) / 2, (end0[1] + end1[1]) / 2)  # the middle
            span = sub(end1, end0)
            norm = mp.sqrt(dot(span, span))
            normal = (-span[1] / norm, span[0] / norm)
            # Towards the table: the side of the mouth's points.
            if dot(sub(pts[0], point), normal) < 0:
                normal = (-normal[0], -normal[1])
            self.falls.append((k, point, normal, norm / 2))

    def _add_segment(self, kind: str, j: int, start: Vec, end: Vec, free_side: Vec, e: mpf) -> None:
        span = sub(end, start)
        length = mp.sqrt(dot(span, span))
        d = (span[0] / length, span[1] / length)
        n = (-d[1], d[0])
        if dot(sub(free_side, start), n) < 0:
            n = (-n[0], -n[1])
        self.segments.append((kind, j, axpy(self.R, n, start), d, n, length, e))

    def events(self, i: int, t_now: mpf, p: Vec, w: mpf, u: Vec, decel: mpf) -> list[Candidate]:
        """Rail, facing, point and fall-line candidates of ball ``i``, moving at ``t_now``.

        Args:
            i: The ball.
            t_now: The current time.
            p: Its position at ``t_now``.
            w: Its speed at ``t_now``, positive.
            u: Its unit direction of travel.
            decel: The rolling deceleration ``mu_roll * g``.

        Returns:
            The candidates within the ball's remaining run.
        """
        out = []
        s_rem = w * w / (2 * decel)
        for kind, j, a, d, n, length, _ in self.segments:
            un = dot(u, n)
            if un >= 0:
                continue  # moving away from (or along) the segment
            # On or a hair beyond the line while moving in: contact now (the clamp).
            s = max(dot(sub(p, a), n) / -un, mpf(0))
            along = dot(sub(axpy(s, u, p), a), d)
            if 0 <= along <= length and s < s_rem:
                out.append(Candidate(time_for_distance(t_now, w, s, decel), kind, i, j))
        for j, c, rho in self.tips:
            s_tip = circle_entry(p, u, c, rho * rho)
            if s_tip is not None and s_tip < s_rem:
                out.append(Candidate(time_for_distance(t_now, w, s_tip, decel), "point", i, j))
        for k, f, n, length in self.falls:
            delta = dot(sub(p, f), n)
            if delta <= 0:
                s = mpf(0)
            else:
                un = dot(u, n)
                if un >= 0:
                    continue
                s = delta / -un
            # The fall line is the segment across the throat, between the two facings.
            along = dot(sub(axpy(s, u, p), f), (n[1], -n[0]))
            if abs(along) <= length and s <= s_rem:
                out.append(Candidate(time_for_distance(t_now, w, s, decel), "pocket", i, k))
        return out

    def normal_of(self, kind: str, j: int, p: Vec) -> tuple[Vec, mpf]:
        """Free-side unit normal and restitution of the cushion piece ``(kind, j)`` at ``p``."""
        if kind == "point":
            for jj, c, _ in self.tips:
                if jj == j:
                    q = sub(p, c)
                    norm = mp.sqrt(dot(q, q))
                    return (q[0] / norm, q[1] / norm), self.e_jaw
        for kk, jj, _, _, n, _, e in self.segments:
            if kk == kind and jj == j:
                return n, e
        raise ReferenceSimulationError(f"no cushion piece {kind} {j}")
