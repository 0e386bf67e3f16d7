"""Independent 50-digit reference of the spin level (a test oracle), in mpmath.

An event-based simulator of balls that slide, roll and spin on a pocketless rectangular
table, written from scratch: it imports nothing from ``pool_env`` and shares no code with
``pool_env.sim`` (the table is read by attribute name only, duck-typed). The physics is in
:mod:`pool_env.testing.spin_physics_mp`; this module finds and orders the events.

* Rails are the centre lines ``x = R``, ``x = L - R``, ``y = R``, ``y = W - R``; a ball
  moving into one bounces (Han 2005). Positions are quadratic in time within a motion
  state, so a rail contact is a quadratic, solved in closed form at 50 digits.
* Ball-ball contact is the first root of the quartic gap ``|d(t)|^2 - 4 R^2`` where the
  balls approach, within the window where both keep their motion states. Roots come from
  ``mpmath.polyroots`` at 50 digits plus 200 bits; real ones are Newton-polished on the
  real polynomial. A touching or overlapping pair that approaches collides now.
* Transitions (sliding -> rolling, rolling -> spinning or rest, spinning -> rest) are
  events at their closed-form times.
* A ball given as input with a slip below 1e-12 of its speed rolls (float inputs of a
  rolling ball carry rounding); after that, rolling means zero slip at 50 digits.
* Events at one instant (within 1e-30 s) are taken in the order ball, cushion,
  transition, then by ball index; event kinds are ``"ball"``, ``"cushion"`` (``j`` the rail:
  0 ``x = R``, 1 ``x = L - R``, 2 ``y = R``, 3 ``y = W - R``), ``"slide_roll"``,
  ``"roll_spin"``, ``"stop"``, ``"spin_stop"`` (``j = -1``).

Slow (O(N^2) root finding per event), meant for scenes with a few impacts.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt
from mpmath import mp, mpf

from pool_env.testing import spin_physics_mp as ph

DPS = 50
TIE = mpf("1e-30")
PARAM_NAMES = ("length", "width", "ball_radius", "g", "mu_slide", "mu_roll", "spin_decel",
               "e_ball", "e_cushion", "cushion_friction", "cushion_height", "cue_tip_radius",
               "cue_end_mass")  # fmt: skip


class SpinReferenceError(RuntimeError):
    """The scene leaves what the reference resolves (event cap, sustained contact)."""


@dataclass
class SpinReferenceResult:
    """Final state and events of a reference run (``mpf`` values carrying 50 digits).

    Attributes:
        positions: Final centres.
        velocities: Final velocities (zero at rest).
        angular_velocities: Final angular velocities.
        states: Final motion states.
        events: ``(time, kind, i, j)`` in order.
        before: Per event, every ball's ``(p, v, w)`` just before it is resolved.
        after: Per event, every ball's ``(p, v, w)`` just after.
    """

    positions: list[ph.Vec2]
    velocities: list[ph.Vec2]
    angular_velocities: list[ph.Vec3]
    states: list[int]
    events: list[tuple[mpf, str, int, int]]
    before: list[list[tuple[ph.Vec2, ph.Vec2, ph.Vec3]]]
    after: list[list[tuple[ph.Vec2, ph.Vec2, ph.Vec3]]]


def params_from(table: Any, **overrides: Any) -> dict:
    """The reference's parameters, read by name from a table-like object (or overrides).

    Args:
        table: Any object with the contract's attribute names (``length``, ``width``,
            ``ball_radius``, ``g``, ``mu_slide``, ``mu_roll``, ``spin_decel``, ``e_ball``,
            ``e_cushion``, ``ball_friction``, ``cushion_friction``, ``cushion_height``,
            ``cue_tip_radius``, ``cue_end_mass``); ``None`` to give everything as overrides.
        **overrides: Values that replace or supply attributes; ``throw`` (``"coulomb"``,
            the default, or ``"pooltool"``) picks the friction impulse's size (see
            :mod:`pool_env.testing.spin_physics_mp`).

    Returns:
        A dict of ``mpf`` values (``ball_friction`` stays ``"alciatore"`` or an ``mpf``).
    """
    raw = {k: getattr(table, k, None) for k in (*PARAM_NAMES, "ball_friction")}
    raw.update({k: v for k, v in overrides.items() if k != "throw"})
    missing = [k for k, v in raw.items() if v is None]
    if missing:
        raise ValueError(f"missing parameters: {missing}")
    prm: dict = {k: mpf(float(raw[k])) for k in PARAM_NAMES}
    bf = raw["ball_friction"]
    prm["ball_friction"] = bf if bf == "alciatore" else mpf(float(bf))
    prm["R"] = prm["ball_radius"]
    prm["throw"] = overrides.get("throw", "coulomb")
    if prm["throw"] not in ("coulomb", "pooltool"):
        raise ValueError(f"throw must be 'coulomb' or 'pooltool', got {prm['throw']!r}")
    return prm


def _quad_roots(a: mpf, b: mpf, c: mpf) -> list[mpf]:
    """Real roots of ``a x^2 + b x + c`` without cancellation (``a`` may be 0)."""
    if a == 0:
        return [] if b == 0 else [-c / b]
    disc = b * b - 4 * a * c
    if disc < 0:
        return []
    q = -(b + mp.sign(b if b != 0 else 1) * mp.sqrt(disc)) / 2
    out = [q / a]
    if q != 0:
        out.append(c / q)
    return sorted(out)


def _poly(c: list[mpf], x: mpf) -> mpf:
    acc = mpf(0)
    for coef in reversed(c):  # ascending coefficients
        acc = acc * x + coef
    return acc


def _real_roots(c: list[mpf]) -> list[mpf]:
    """Real roots of a polynomial (ascending coefficients, degree <= 4), polished."""
    c = list(c)
    while c and c[-1] == 0:
        c.pop()
    if len(c) <= 1:
        return []
    if len(c) <= 3:
        return _quad_roots(c[2] if len(c) == 3 else mpf(0), c[1], c[0])
    with mp.workdps(DPS + 60):
        try:
            zs = mp.polyroots(list(reversed(c)), maxsteps=400, extraprec=400)
        except mp.NoConvergence as exc:  # pragma: no cover - would be a reference defect
            raise SpinReferenceError(f"polyroots did not converge: {exc}") from exc
        dc = [k * c[k] for k in range(1, len(c))]
        out = []
        for z in zs:
            x = mp.re(z)
            if abs(mp.im(z)) > mpf("1e-40") * (1 + abs(x)):
                continue
            for _ in range(8):  # Newton on the real polynomial
                d = _poly(dc, x)
                if d == 0:
                    break
                x -= _poly(c, x) / d
            out.append(+x)
    return sorted(out)


class _Sim:
    def __init__(self, prm: dict, p: list, v: list, w: list, masses: list) -> None:
        self.prm, self.m = prm, masses
        r = prm["R"]
        self.lines = (  # (axis, value, outward sign, inward unit normal)
            (0, r, -1, (mpf(1), mpf(0))),
            (0, prm["length"] - r, 1, (mpf(-1), mpf(0))),
            (1, r, -1, (mpf(0), mpf(1))),
            (1, prm["width"] - r, 1, (mpf(0), mpf(-1))),
        )
        zero = mpf(0)
        self.pieces = [
            ph.Piece(zero, p[i], v[i], w[i], self._input_state(v[i], w[i]), prm)
            for i in range(len(p))
        ]

    def _input_state(self, v: ph.Vec2, w: ph.Vec3) -> int:
        """A float input that rolls to rounding (slip <= 1e-12 of the speeds) rolls."""
        r = self.prm["R"]
        u = ph.norm(ph.slip(v, w, r))
        scale = max(ph.norm(v), r * ph.norm((w[0], w[1])))
        if 0 < u <= mpf("1e-12") * scale:
            return ph.ROLLING
        return ph.state_of(v, w, r)

    def at(self, i: int, t: mpf) -> tuple[ph.Vec2, ph.Vec2, ph.Vec3]:
        return self.pieces[i].at(t, self.prm)

    def end(self, i: int) -> mpf | None:
        pc = self.pieces[i]
        return None if pc.duration is None else pc.t0 + pc.duration

    def moving(self, i: int) -> bool:
        return self.pieces[i].state in (ph.SLIDING, ph.ROLLING)

    def rail_events(self, i: int, t: mpf) -> list[tuple[mpf, str, int, int]]:
        if not self.moving(i):
            return []
        p, v, _ = self.at(i, t)
        acc, limit = self.pieces[i].acc, self.end(i) - t
        out = []
        for j, (axis, line, out_sign, _) in enumerate(self.lines):
            gap = (p[axis] - line) * out_sign  # >= 0: on or beyond the rail line
            if gap >= 0 and v[axis] * out_sign > 0:
                out.append((t, "cushion", i, j))
                continue
            for tau in _quad_roots(acc[axis] / 2, v[axis], p[axis] - line):
                if 0 <= tau < limit and (v[axis] + acc[axis] * tau) * out_sign > 0:
                    out.append((t + tau, "cushion", i, j))
                    break
        return out

    def pair_event(self, i: int, j: int, t: mpf, horizon: mpf) -> tuple | None:
        if not (self.moving(i) or self.moving(j)):
            return None
        ends = [e for e in (self.end(i), self.end(j)) if e is not None]
        window = min([*ends, horizon]) - t
        pi, vi, _ = self.at(i, t)
        pj, vj, _ = self.at(j, t)
        ai, aj = self.pieces[i].acc, self.pieces[j].acc
        d0 = (pj[0] - pi[0], pj[1] - pi[1])
        d1 = (vj[0] - vi[0], vj[1] - vi[1])
        d2 = ((aj[0] - ai[0]) / 2, (aj[1] - ai[1]) / 2)
        r2 = 4 * self.prm["R"] ** 2
        # Cull: the distance cannot shrink by more than |d1| T + |d2| T^2 in the window.
        reach = ph.norm(d1) * window + ph.norm(d2) * window * window
        if ph.norm(d0) - reach > 2 * self.prm["R"] + mpf("1e-20"):
            return None
        g = [ph.dot(d0, d0) - r2, 2 * ph.dot(d0, d1), ph.dot(d1, d1) + 2 * ph.dot(d0, d2),
             2 * ph.dot(d1, d2), ph.dot(d2, d2)]  # fmt: skip
        dg = [k * g[k] for k in range(1, 5)]
        if g[0] <= 0:
            if g[1] < 0:
                return (t, "ball", i, j)  # touching or overlapping and approaching
            if g[0] < -mpf("1e-30") and g[1] == 0:
                raise SpinReferenceError(f"balls {i}, {j} overlap with no approach speed")
        for tau in _real_roots(g):
            if 0 < tau <= window and _poly(dg, tau) < 0:
                return (t + tau, "ball", i, j)
        return None

    def transition(self, i: int, t: mpf) -> None:
        pc, r = self.pieces[i], self.prm["R"]
        p, v, w = self.at(i, t)
        if pc.state == ph.SLIDING:
            new = ph.ROLLING
            if ph.norm(v) < mpf("1e-40"):  # slid to a stop in the same instant
                v, w = (mpf(0), mpf(0)), (mpf(0), mpf(0), w[2])
                new = ph.SPINNING if w[2] != 0 else ph.STATIONARY
            else:
                w = (-v[1] / r, v[0] / r, w[2])  # exactly rolling
        elif pc.state == ph.ROLLING:
            v, w = (mpf(0), mpf(0)), (mpf(0), mpf(0), w[2])
            new = ph.SPINNING if w[2] != 0 else ph.STATIONARY
        else:
            w = (mpf(0), mpf(0), mpf(0))
            new = ph.STATIONARY
        self.pieces[i] = ph.Piece(t, p, v, w, new, self.prm)

    def kind_of_transition(self, i: int, t: mpf) -> str:
        st = self.pieces[i].state
        if st == ph.SLIDING:
            return "slide_roll"
        if st == ph.SPINNING:
            return "spin_stop"
        wz = ph.spin_z(self.pieces[i].w[2], t - self.pieces[i].t0, self.prm["spin_decel"])
        return "roll_spin" if wz != 0 else "stop"

    def reanchor(self, i: int, t: mpf, v: ph.Vec2, w: ph.Vec3, p: ph.Vec2) -> None:
        self.pieces[i] = ph.Piece(t, p, v, w, ph.state_of(v, w, self.prm["R"]), self.prm)

    def apply(self, ev: tuple) -> tuple:
        t, kind, i, j = ev
        if kind == "ball":
            pi, vi, wi = self.at(i, t)
            pj, vj, wj = self.at(j, t)
            d = (pj[0] - pi[0], pj[1] - pi[1])
            dn = ph.norm(d)
            n = (d[0] / dn, d[1] / dn)
            vi2, wi2, vj2, wj2 = ph.ball_ball(vi, wi, vj, wj, n, self.m[i], self.m[j], self.prm)
            self.reanchor(i, t, vi2, wi2, pi)
            self.reanchor(j, t, vj2, wj2, pj)
            return ev
        if kind == "cushion":
            p, v, w = self.at(i, t)
            v2, w2 = ph.cushion_han(v, w, self.lines[j][3], self.m[i], self.prm)
            self.reanchor(i, t, v2, w2, p)
            return ev
        name = self.kind_of_transition(i, t)
        self.transition(i, t)
        return (t, name, i, -1)

    def snapshot(self, t: mpf) -> list[tuple[ph.Vec2, ph.Vec2, ph.Vec3]]:
        return [self.at(i, t) for i in range(len(self.pieces))]

    def run(self, max_events: int) -> list[tuple[mpf, str, int, int]]:
        t = mpf(0)
        events: list = []
        self.before: list = []
        self.after: list = []
        n = len(self.pieces)
        while True:
            cands = []
            for i in range(n):
                e = self.end(i)
                if e is not None:
                    cands.append((max(e, t), "transition", i, -1))
                cands.extend(self.rail_events(i, t))
            if not cands:
                return events
            horizon = min(c[0] for c in cands) + TIE
            for i in range(n):
                for j in range(i + 1, n):
                    ev = self.pair_event(i, j, t, horizon)
                    if ev is not None:
                        cands.append(ev)
                        horizon = min(horizon, ev[0] + TIE)
            t_min = min(c[0] for c in cands)
            group = [c for c in cands if c[0] <= t_min + TIE]
            kind_rank = {"ball": 0, "cushion": 1, "transition": 2}
            chosen = min(group, key=lambda c: (kind_rank[c[1]], c[2], c[3]))
            if len(events) >= max_events:
                raise SpinReferenceError(f"more than {max_events} events")
            t = max(chosen[0], t)
            self.before.append(self.snapshot(t))
            events.append(self.apply((t, chosen[1], chosen[2], chosen[3])))
            self.after.append(self.snapshot(t))


def _rows(name: str, a: npt.ArrayLike, n: int | None, width: int) -> np.ndarray:
    arr = np.asarray(a, dtype=np.float64)
    if arr.ndim != 2 or arr.shape[1] != width or (n is not None and arr.shape[0] != n):
        raise ValueError(f"{name} must have shape (N, {width}), got {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} must be finite")
    return arr


def spin_reference_simulate(
    table: Any,
    positions: npt.ArrayLike,
    velocities: npt.ArrayLike,
    angular_velocities: npt.ArrayLike | None = None,
    masses: npt.ArrayLike | None = None,
    max_events: int = 200,
    **overrides: Any,
) -> SpinReferenceResult:
    """Simulate a spin-level shot to rest at 50 digits on a pocketless table.

    Args:
        table: A table-like object (see :func:`params_from`); ``ball_mass`` is read too.
        positions: ``(N, 2)`` centres inside the rails.
        velocities: ``(N, 2)`` velocities (m/s).
        angular_velocities: ``(N, 3)`` (rad/s); ``None`` is zero spin.
        masses: ``(N,)`` masses; ``None`` gives every ball ``table.ball_mass``.
        max_events: Event cap.
        **overrides: Parameter overrides (see :func:`params_from`).

    Returns:
        A :class:`SpinReferenceResult`.

    Raises:
        ValueError: On malformed input or balls outside the rails or overlapping (> 1e-9 m).
        SpinReferenceError: On the event cap or a sustained contact.
    """
    pos = _rows("positions", positions, None, 2)
    n = pos.shape[0]
    vel = _rows("velocities", velocities, n, 2)
    ang = np.zeros((n, 3))
    if angular_velocities is not None:
        ang = _rows("angular_velocities", angular_velocities, n, 3)
    mass = [overrides.pop("ball_mass", None) or getattr(table, "ball_mass", None)] * n
    if masses is not None:
        mass = [float(x) for x in np.asarray(masses, dtype=np.float64).reshape(-1)]
    if len(mass) != n or not all(m is not None and m > 0 for m in mass):
        raise ValueError("masses must be N positive values")
    with mp.workdps(DPS):
        prm = params_from(table, **overrides)
        p = [(mpf(x), mpf(y)) for x, y in pos]
        r, tol = prm["R"], mpf("1e-9")
        for k, (x, y) in enumerate(p):
            if not (
                r - tol <= x <= prm["length"] - r + tol and r - tol <= y <= prm["width"] - r + tol
            ):
                raise ValueError(f"ball {k} is outside the rails")
            for q in p[:k]:
                if ph.norm((x - q[0], y - q[1])) < 2 * r - tol:
                    raise ValueError(f"ball {k} overlaps another")
        v_mp = [(mpf(a), mpf(b)) for a, b in vel]
        w_mp = [(mpf(a), mpf(b), mpf(c)) for a, b, c in ang]
        sim = _Sim(prm, p, v_mp, w_mp, [mpf(m) for m in mass])
        events = sim.run(max_events)
        t_end = events[-1][0] if events else mpf(0)
        finals = [sim.at(i, max(t_end, sim.pieces[i].t0)) for i in range(n)]
        return SpinReferenceResult(
            positions=[f[0] for f in finals],
            velocities=[f[1] for f in finals],
            angular_velocities=[f[2] for f in finals],
            states=[pc.state for pc in sim.pieces],
            events=events,
            before=sim.before,
            after=sim.after,
        )
