"""Self-checks of the 50-digit reference simulator against closed forms and invariants.

The reference (``pool_env/testing/reference/``) is the oracle for the float64 kernels, so it
must be checked on its own: every expected value here is derived in the test from the model's
formulas, not taken from the reference.
"""

from __future__ import annotations

import ast
import math
import random
from pathlib import Path

import pytest
from mpmath import mp, mpf

from pool_env.sim.table import Table
from pool_env.testing import reference
from pool_env.testing.reference import ReferenceSimulationError, reference_simulate
from pool_env.testing.reference.roots import first_contact, gap_poly, horner, sign_changes

TIGHT = mpf("1e-40")  # agreement expected between two 50-digit computations
L, W, R = 2.54, 1.27, 0.028575


def decel(table: Table) -> mpf:
    return mpf(table.mu_roll) * mpf(table.g)


def assert_close(a: mpf, b: mpf, tol: mpf = TIGHT) -> None:
    with mp.workdps(50):
        assert abs(mpf(a) - mpf(b)) <= tol * max(1, abs(mpf(b))), (
            f"{mp.nstr(a, 30)} != {mp.nstr(b, 30)}"
        )


def assert_vec_close(p: tuple[mpf, mpf], q: tuple[mpf, mpf], tol: mpf = TIGHT) -> None:
    assert_close(p[0], q[0], tol)
    assert_close(p[1], q[1], tol)


def time_for_distance(v: mpf, s: mpf, a: mpf) -> mpf:
    return 2 * s / (v + mp.sqrt(v * v - 2 * a * s))


def kinds(res) -> list[tuple[str, int, int]]:
    return [(k, i, j) for _, k, i, j in res.events]


# -- free rolling ---------------------------------------------------------------------------


@pytest.mark.parametrize("angle_deg", [0, 45, 90, 135, 180, 200, 225, 270, 315])
@pytest.mark.parametrize("speed", [1e-6, 0.3])
def test_stop_distance_and_time_every_direction(angle_deg: float, speed: float) -> None:
    table = Table(pockets="none")
    p0 = (L / 2, W / 2)
    v0 = (speed * math.cos(math.radians(angle_deg)), speed * math.sin(math.radians(angle_deg)))
    res = reference_simulate(table, [p0], [v0])
    with mp.workdps(50):
        a = decel(table)
        vx, vy = mpf(v0[0]), mpf(v0[1])
        s = mp.sqrt(vx * vx + vy * vy)
        # rest = p0 + u v^2 / (2a) = p0 + v |v| / (2a)
        rest = (mpf(p0[0]) + vx * s / (2 * a), mpf(p0[1]) + vy * s / (2 * a))
        assert kinds(res) == [("stop", 0, -1)]
        assert_close(res.duration, s / a)
        assert_close(res.events[0][0], s / a)
        assert_vec_close(res.positions[0], rest)
        # Halfway in time the ball has covered 3/4 of the distance (v t - a t^2 / 2).
        half = res.positions_at(s / a / 2)[0]
        assert_vec_close(
            half, (mpf(p0[0]) + vx * s * 3 / (8 * a), mpf(p0[1]) + vy * s * 3 / (8 * a))
        )
        assert res.pocketed == [-1]
    assert mp.dps == 15  # the 50-digit context does not leak


def test_resting_scene_has_no_events() -> None:
    res = reference_simulate(Table(), [(1.0, 0.6), (1.5, 0.6)], [(0.0, 0.0), (0.0, 0.0)])
    assert res.events == []
    assert res.duration == 0
    assert res.pocketed == [-1, -1]


# -- ball-ball impacts -------------------------------------------------------------------


@pytest.mark.parametrize(
    ("direction", "start"),
    [
        ((1, 0), (0.5, 0.635)),
        ((-1, 0), (2.0, 0.635)),
        ((0, 1), (1.27, 0.2)),
        ((0, -1), (1.27, 1.0)),
    ],
)
def test_head_on_elastic_equal_masses_exchange_velocities(direction, start) -> None:
    table = Table(pockets="none", e_ball=1.0)
    gap = 0.4
    other = (start[0] + gap * direction[0], start[1] + gap * direction[1])
    speed = 1.2
    res = reference_simulate(
        table, [start, other], [(speed * direction[0], speed * direction[1]), (0.0, 0.0)]
    )
    assert res.events[0][1:] == ("ball", 0, 1)
    with mp.workdps(50):
        a = decel(table)
        s = mpf(gap) - 2 * mpf(R)
        # mpf(gap) differs from the float difference of the inputs; use the inputs' gap.
        d = abs(mpf(other[0]) - mpf(start[0])) + abs(mpf(other[1]) - mpf(start[1]))
        s = d - 2 * mpf(R)
        assert_close(res.events[0][0], time_for_distance(mpf(speed), s, a))
        w = mp.sqrt(mpf(speed) ** 2 - 2 * a * s)
        v_after = res.first_velocities_after(0)
        assert v_after[0] == (0, 0)  # the cue stops dead...
        assert_vec_close(v_after[1], (w * direction[0], w * direction[1]))  # ...and passes it on


def test_head_on_both_moving_exchange_velocities() -> None:
    """Both balls move (the quartic path): closed-form contact time and exact exchange."""
    table = Table(pockets="none", e_ball=1.0)
    x0, x1, v0, v1 = 0.8, 1.6, 1.0, 0.7
    res = reference_simulate(table, [(x0, 0.6), (x1, 0.6)], [(v0, 0.0), (-v1, 0.0)])
    assert res.events[0][1:] == ("ball", 0, 1)
    with mp.workdps(50):
        a = decel(table)
        # Gap along x: D - (v0 + v1) t + a t^2 = 0, smaller root without cancellation.
        d = mpf(x1) - mpf(x0) - 2 * mpf(R)
        vv = mpf(v0) + mpf(v1)
        t = 2 * d / (vv + mp.sqrt(vv * vv - 4 * a * d))
        assert_close(res.events[0][0], t)
        before, after = res.velocities_before(0), res.first_velocities_after(0)
        assert_close(before[0][0], mpf(v0) - a * t)
        assert_vec_close(after[0], before[1])
        assert_vec_close(after[1], before[0])


def test_oblique_inelastic_unequal_masses_match_formula() -> None:
    table = Table(pockets="none", e_ball=0.9)
    ma, mb = 0.17, 0.21
    b = 0.03  # lateral offset of the object ball, < 2R: an oblique hit
    pa, pb, v = (0.5, 0.6), (1.0, 0.6 + b), 1.5
    res = reference_simulate(table, [pa, pb], [(v, 0.0), (0.0, 0.0)], masses=[ma, mb])
    assert res.events[0][1:] == ("ball", 0, 1)
    with mp.workdps(50):
        a, e, r2 = decel(table), mpf(table.e_ball), 2 * mpf(R)
        dy = mpf(pb[1]) - mpf(pa[1])
        dx_contact = mp.sqrt(r2 * r2 - dy * dy)
        s = mpf(pb[0]) - mpf(pa[0]) - dx_contact
        assert_close(res.events[0][0], time_for_distance(mpf(v), s, a))
        w = mp.sqrt(mpf(v) ** 2 - 2 * a * s)
        n = (dx_contact / r2, dy / r2)
        ua = w * n[0]
        ua_new = ua * (ma - e * mb) / (mpf(ma) + mpf(mb))
        ub_new = ua * mpf(ma) * (1 + e) / (mpf(ma) + mpf(mb))
        after = res.first_velocities_after(0)
        assert_vec_close(after[0], (w + (ua_new - ua) * n[0], (ua_new - ua) * n[1]))
        assert_vec_close(after[1], (ub_new * n[0], ub_new * n[1]))
        # The gap at the event is exactly 2R.
        p = res.positions_at(res.events[0][0])
        assert_close(mp.sqrt((p[1][0] - p[0][0]) ** 2 + (p[1][1] - p[0][1]) ** 2), r2)


def _check_impact_invariants(table: Table, res, masses: list[float]) -> int:
    """Momentum, energy, restitution and contact at every ball-ball event; returns the count."""
    count = 0
    with mp.workdps(50):
        e = mpf(table.e_ball)
        for k, (t, kind, i, j) in enumerate(res.events):
            p = res.positions_at(t)
            for x, y in p:  # G: inside the rails at every event
                assert mpf(R) - TIGHT <= x <= mpf(L) - mpf(R) + TIGHT
                assert mpf(R) - TIGHT <= y <= mpf(W) - mpf(R) + TIGHT
            if kind != "ball":
                continue
            count += 1
            before, after = res.velocities_before(k), res.first_velocities_after(k)
            mi, mj = mpf(masses[i]), mpf(masses[j])
            for ax in (0, 1):  # P
                assert_close(
                    mi * after[i][ax] + mj * after[j][ax], mi * before[i][ax] + mj * before[j][ax]
                )

            def ke(v, mi=mi, mj=mj, i=i, j=j):
                return mi * (v[i][0] ** 2 + v[i][1] ** 2) + mj * (v[j][0] ** 2 + v[j][1] ** 2)

            assert ke(after) <= ke(before) * (1 + TIGHT)  # E
            d = (p[j][0] - p[i][0], p[j][1] - p[i][1])
            dist = mp.sqrt(d[0] ** 2 + d[1] ** 2)
            assert_close(dist, 2 * mpf(R))  # contact at the event
            n = (d[0] / dist, d[1] / dist)

            def rel(v, n=n, i=i, j=j):
                return (v[j][0] - v[i][0]) * n[0] + (v[j][1] - v[i][1]) * n[1]

            assert rel(before) < 0  # approaching
            assert_close(rel(after), -e * rel(before), TIGHT * 10)  # restitution
            # Tangential components unchanged.
            for b in (i, j):
                tb = -before[b][0] * n[1] + before[b][1] * n[0]
                ta = -after[b][0] * n[1] + after[b][1] * n[0]
                assert_close(ta, tb)
    return count


def _assert_no_overlap_between_events(res, samples: int = 400) -> None:
    """Brute force: sample positions densely; no pair may overlap (no missed impact)."""
    with mp.workdps(50):
        n = len(res.positions)
        for k in range(samples + 1):
            t = res.duration * k / samples
            p = res.positions_at(t)
            for i in range(n):
                if res.pocketed[i] >= 0:
                    continue
                for j in range(i + 1, n):
                    if res.pocketed[j] >= 0:
                        continue
                    d2 = (p[j][0] - p[i][0]) ** 2 + (p[j][1] - p[i][1]) ** 2
                    assert d2 >= (2 * mpf(R)) ** 2 * (1 - TIGHT), f"overlap at t={t}"


def test_random_three_ball_scenes_conserve_momentum_and_never_gain_energy() -> None:
    rng = random.Random(2024)
    impacts = 0
    for scene in range(8):
        table = Table(pockets="none" if scene % 2 else "standard")
        pos: list[tuple[float, float]] = []
        while len(pos) < 3:
            p = (rng.uniform(0.3, L - 0.3), rng.uniform(0.3, W - 0.3))
            if all(math.hypot(p[0] - q[0], p[1] - q[1]) > 3 * R for q in pos):
                pos.append(p)
        # Aim the cue at ball 1 (slightly off-centre) so that impacts happen.
        ang = math.atan2(pos[1][1] - pos[0][1], pos[1][0] - pos[0][0])
        ang += rng.uniform(-0.02, 0.02)
        speed = rng.uniform(1.5, 3.0)
        vel = [(speed * math.cos(ang), speed * math.sin(ang)), (0.0, 0.0), (0.0, 0.0)]
        if scene >= 4:  # all three moving: the quartic path
            vel[1] = (rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5))
            vel[2] = (rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5))
        masses = [rng.uniform(0.15, 0.2) for _ in range(3)]
        res = reference_simulate(table, pos, vel, masses=masses)
        impacts += _check_impact_invariants(table, res, masses)
        times = [ev[0] for ev in res.events]
        assert times == sorted(times)
        assert res.near_ties == []
        _assert_no_overlap_between_events(res)
    assert impacts >= 8


# -- cushions ---------------------------------------------------------------------------


def _fold(x: mpf, lo: mpf, hi: mpf) -> tuple[mpf, int]:
    """Reflect an unfolded coordinate back into [lo, hi]; also count the reflections."""
    span = hi - lo
    y = x - lo
    k = int(mp.floor(y / span))
    y -= k * span
    if k % 2:
        y = span - y
    return lo + y, abs(k)


@pytest.mark.parametrize(
    "v0", [(1.1, 0.37), (-0.9, 0.81), (0.45, -1.3), (-1.6, -0.7), (2.5, 0.0), (0.0, -1.4)]
)
def test_elastic_cushion_rebounds_match_mirror_construction(v0) -> None:
    table = Table(pockets="none", e_cushion=1.0)
    p0 = (1.1, 0.5)
    res = reference_simulate(table, [p0], [v0])
    with mp.workdps(50):
        a = decel(table)
        vx, vy = mpf(v0[0]), mpf(v0[1])
        s = mp.sqrt(vx * vx + vy * vy)
        ux, uy = mpf(p0[0]) + vx * s / (2 * a), mpf(p0[1]) + vy * s / (2 * a)
        rx, nx = _fold(ux, mpf(R), mpf(L) - mpf(R))
        ry, ny = _fold(uy, mpf(R), mpf(W) - mpf(R))
        assert nx + ny >= 1
        assert_vec_close(res.positions[0], (rx, ry))
        assert_close(res.duration, s / a)  # e = 1: the speed is unchanged by rebounds
        cushions = [j for _, k, _, j in res.events if k == "cushion"]
        assert sum(1 for j in cushions if j in (0, 1)) == nx
        assert sum(1 for j in cushions if j in (2, 3)) == ny


@pytest.mark.parametrize(
    ("p0", "v0", "rail"),
    [
        ((2.2, 0.6), (0.5, 0.2), 1),
        ((0.3, 0.6), (-0.5, 0.2), 0),
        ((1.2, 1.0), (0.1, 0.6), 3),
        ((1.2, 0.3), (-0.1, -0.6), 2),
    ],
)
def test_inelastic_cushion_rebound_matches_formula(p0, v0, rail: int) -> None:
    table = Table(pockets="none", e_cushion=0.7)
    res = reference_simulate(table, [p0], [v0])
    assert kinds(res) == [("cushion", 0, rail), ("stop", 0, -1)]
    with mp.workdps(50):
        a, e = decel(table), mpf(table.e_cushion)
        line = [mpf(R), mpf(L) - mpf(R), mpf(R), mpf(W) - mpf(R)][rail]
        axis = 0 if rail < 2 else 1
        v = [mpf(v0[0]), mpf(v0[1])]
        speed = mp.sqrt(v[0] ** 2 + v[1] ** 2)
        u = [v[0] / speed, v[1] / speed]
        s1 = (line - mpf(p0[axis])) / u[axis]
        t1 = time_for_distance(speed, s1, a)
        w1 = mp.sqrt(speed**2 - 2 * a * s1)
        hit = [mpf(p0[0]) + u[0] * s1, mpf(p0[1]) + u[1] * s1]
        v1 = [w1 * u[0], w1 * u[1]]
        v1[axis] *= -e
        w2 = mp.sqrt(v1[0] ** 2 + v1[1] ** 2)
        rest = (hit[0] + v1[0] * w2 / (2 * a), hit[1] + v1[1] * w2 / (2 * a))
        assert_close(res.events[0][0], t1)
        assert_vec_close(res.first_velocities_after(0)[0], (v1[0], v1[1]))
        assert_vec_close(res.positions[0], rest)
        assert_close(res.duration, t1 + w2 / a)


def test_45_degrees_into_square_corner_meets_both_rails() -> None:
    table = Table(pockets="none", e_cushion=0.85)
    res = reference_simulate(table, [(0.4, 0.4)], [(-0.3, -0.3)])
    # The two rails are hit at the same instant: ordered by rail index, flagged as a tie.
    assert kinds(res) == [("cushion", 0, 0), ("cushion", 0, 2), ("stop", 0, -1)]
    assert res.near_ties == [0]
    with mp.workdps(50):
        assert_close(res.events[0][0], res.events[1][0], mpf("1e-30"))
        a, e = decel(table), mpf(table.e_cushion)
        s = (mpf(0.4) - mpf(R)) * mp.sqrt(2)
        w = mp.sqrt(mpf(0.3) ** 2 * 2 - 2 * a * s)
        after = res.first_velocities_after(1)[0]
        assert_vec_close(after, (e * w / mp.sqrt(2), e * w / mp.sqrt(2)))
        assert_close(res.positions[0][0], res.positions[0][1])


def test_ball_rolling_along_rail_never_bounces() -> None:
    res = reference_simulate(Table(pockets="none"), [(0.5, R)], [(0.5, 0.0)])
    assert kinds(res) == [("stop", 0, -1)]


def test_ball_touching_rail_moving_into_it_bounces_now() -> None:
    res = reference_simulate(Table(pockets="none"), [(R, 0.6)], [(-0.5, 0.1)])
    assert res.events[0][1:] == ("cushion", 0, 0)
    assert res.events[0][0] == 0


# -- pockets ------------------------------------------------------------------------------


@pytest.mark.parametrize("k", range(6))
def test_straight_shot_into_each_pocket(k: int) -> None:
    table = Table(pockets="circles")
    cx, cy, cr = (float(x) for x in table.pockets[k])
    # Corners from the table centre; sides straight across from the centre line.
    p0 = (L / 2, W / 2) if k in (0, 2, 3, 5) else (L / 2, W / 2 + (0.3 if k == 1 else -0.3))
    d = math.hypot(cx - p0[0], cy - p0[1])
    v0 = (2.0 * (cx - p0[0]) / d, 2.0 * (cy - p0[1]) / d)
    res = reference_simulate(table, [p0], [v0])
    assert kinds(res) == [("pocket", 0, k)]
    assert res.pocketed == [k]
    with mp.workdps(50):
        # Captured where the centre line meets the circle: c + r (p0 - c) / |p0 - c| (the
        # float velocity is a hair off the exact direction, hence the looser tolerance).
        dd = mp.sqrt((mpf(p0[0]) - cx) ** 2 + (mpf(p0[1]) - cy) ** 2)
        entry = (cx + cr * (mpf(p0[0]) - cx) / dd, cy + cr * (mpf(p0[1]) - cy) / dd)
        assert_vec_close(res.positions[0], entry, mpf("1e-14"))
        assert res.duration == res.events[0][0]
        assert res.positions_at(res.duration + 1)[0] == res.positions[0]


@pytest.mark.parametrize(("offset", "potted"), [(-1e-9, True), (1e-9, False)])
def test_side_pocket_mouth_edge(offset: float, potted: bool) -> None:
    """A ball rolling straight at the rail is potted exactly inside the side-pocket mouth."""
    table = Table(pockets="circles")
    half_mouth = 2.5 * 0.0254  # side mouth 5 in (WPA), see pool_env.sim.table
    res = reference_simulate(table, [(L / 2 + half_mouth + offset, 0.4)], [(0.0, -1.5)])
    if potted:
        assert res.events[0][1:] == ("pocket", 0, 1)
        assert res.pocketed == [1]
    else:
        assert res.events[0][1:] == ("cushion", 0, 2)
        assert res.pocketed == [-1]


# -- root finding, degree drops and grazing -----------------------------------------------


def _first_contact_by_polyroots(g, hi):
    """Independent check: all complex roots (mpmath), the first real one where g' < 0."""
    coeffs = list(reversed(g))
    while coeffs and coeffs[0] == 0:
        coeffs.pop(0)
    if len(coeffs) < 2:
        return None
    roots = mp.polyroots(coeffs, maxsteps=200, extraprec=200)
    dg = [k * g[k] for k in range(1, len(g))]
    best = None
    for z in roots:
        x = mp.re(z)
        if abs(mp.im(z)) > mpf("1e-25") or not 0 <= x <= hi:
            continue
        if mp.polyval(list(reversed(dg)), x) < 0 and (best is None or x < best):
            best = x
    return best


def test_quartic_first_contact_agrees_with_polyroots() -> None:
    """Bracketed isolation against mpmath's complex roots, over each pair's whole window."""
    rng = random.Random(7)
    hits = 0
    with mp.workdps(50):
        a = mpf(0.0981)
        for _ in range(60):
            pi = (mpf(rng.uniform(0.2, 2.3)), mpf(rng.uniform(0.2, 1.0)))
            pj = (pi[0] + mpf(rng.uniform(-0.6, 0.6)), pi[1] + mpf(rng.uniform(-0.6, 0.6)))
            if (pj[0] - pi[0]) ** 2 + (pj[1] - pi[1]) ** 2 <= (2 * mpf(R)) ** 2:
                continue
            aim = float(mp.atan2(pj[1] - pi[1], pj[0] - pi[0]))
            vel, acc, speeds = [], [], []
            # Roughly head-on, so that most pairs meet before the first stop.
            for ang in (aim + rng.uniform(-0.1, 0.1), aim + math.pi + rng.uniform(-0.5, 0.5)):
                sp = mpf(rng.uniform(0.2, 2.0))
                u = (mp.cos(ang), mp.sin(ang))
                vel.append((sp * u[0], sp * u[1]))
                acc.append((-a * u[0], -a * u[1]))
                speeds.append(sp)
            g = gap_poly(pi, vel[0], acc[0], pj, vel[1], acc[1], mpf(R))
            hi = min(speeds) / a  # the quartic holds until the first stop
            got = first_contact(g, mpf(0), hi)
            want = _first_contact_by_polyroots(g, hi)
            assert (got is None) == (want is None)
            if got is not None:
                hits += 1
                assert_close(got, want, mpf("1e-35"))
                assert abs(horner(g, got)) < mpf("1e-45")
    assert hits >= 15


def test_sign_changes_handles_degree_drops_and_multiple_pieces() -> None:
    with mp.workdps(50):
        # (x - 1)(x - 2)(x - 3) with an exactly-zero quartic term.
        c = [mpf(-6), mpf(11), mpf(-6), mpf(1), mpf(0)]
        roots = sign_changes(c, mpf(0), mpf(4))
        assert len(roots) == 3
        for got, want in zip(roots, (1, 2, 3), strict=True):
            assert_close(got, mpf(want))
        assert sign_changes([mpf(3)], mpf(0), mpf(1)) == []


def test_resting_pair_quadratic_agrees_with_quartic_path() -> None:
    """The arc-length quadratic (one ball resting) against the general gap polynomial."""
    table = Table(pockets="none")
    pa, pb, v = (0.5, 0.6), (1.1, 0.64), (1.3, 0.05)
    res = reference_simulate(table, [pa, pb], [v, (0.0, 0.0)])
    assert res.events[0][1:] == ("ball", 0, 1)
    with mp.workdps(50):
        a = decel(table)
        vx, vy = mpf(v[0]), mpf(v[1])
        s = mp.sqrt(vx * vx + vy * vy)
        acc = (-a * vx / s, -a * vy / s)
        zero = (mpf(0), mpf(0))
        g = gap_poly(
            (mpf(pa[0]), mpf(pa[1])), (vx, vy), acc, (mpf(pb[0]), mpf(pb[1])), zero, zero, mpf(R)
        )
        assert_close(res.events[0][0], first_contact(g, mpf(0), s / a))


def test_same_line_same_direction_degree_drop() -> None:
    """Same direction: decelerations cancel, the gap is linear in t until a ball stops."""
    table = Table(pockets="none")
    x0, x1, v0, v1 = 0.5, 0.9, 1.5, 0.5
    res = reference_simulate(table, [(x0, 0.6), (x1, 0.6)], [(v0, 0.0), (v1, 0.0)])
    assert res.events[0][1:] == ("ball", 0, 1)
    with mp.workdps(50):
        t = (mpf(x1) - mpf(x0) - 2 * mpf(R)) / (mpf(v0) - mpf(v1))
        assert_close(res.events[0][0], t)


def test_side_by_side_same_velocity_no_phantom_hit() -> None:
    table = Table(pockets="none")
    res = reference_simulate(
        table, [(0.5, 0.6), (0.5, 0.6 + 2 * R + 1e-9)], [(0.5, 0.0), (0.5, 0.0)]
    )
    assert [k for _, k, _, _ in res.events] == ["stop", "stop"]
    # Same line, the rear ball slower: never meets the front one.
    res = reference_simulate(table, [(0.5, 0.6), (0.8, 0.6)], [(0.5, 0.0), (0.6, 0.0)])
    assert "ball" not in [k for _, k, _, _ in res.events]


@pytest.mark.parametrize(("factor", "hit"), [(1 - 1e-12, True), (1 + 1e-12, False)])
@pytest.mark.parametrize("both_moving", [False, True])
def test_grazing_hit_or_miss(factor: float, hit: bool, both_moving: bool) -> None:
    table = Table(pockets="none")
    offset = 2 * R * factor
    vb = (0.0, 0.0) if not both_moving else (0.3, 0.0)  # same direction: a degree drop
    res = reference_simulate(table, [(0.5, 0.6), (1.0, 0.6 + offset)], [(1.5, 0.0), vb])
    assert ("ball" in [k for _, k, _, _ in res.events]) == hit
    if both_moving:  # and a genuine quartic: the object ball moves obliquely
        res = reference_simulate(
            table, [(0.5, 0.6), (1.0, 0.6 + offset)], [(1.5, 0.0), (0.3, 1e-3)]
        )
        assert res.events[0][1] in ("ball", "cushion", "stop")


def test_touching_balls_closing_collide_at_once_and_opening_do_not() -> None:
    table = Table(pockets="none")
    # 1.0 + 2R rounds to a float gap of ~7e-17 m: the hit comes ~1e-16 s later.
    x1 = 1.0 + 2 * R
    res = reference_simulate(table, [(1.0, 0.6), (x1, 0.6)], [(0.5, 0.0), (0.0, 0.0)])
    assert res.events[0][1:] == ("ball", 0, 1)
    assert 0 < res.events[0][0] < 1e-15
    # One ulp closer, the float inputs overlap by ~1e-16 m: approaching means collide now.
    x1 = math.nextafter(x1, 0.0)
    with mp.workdps(50):
        assert mpf(x1) - 1 < 2 * mpf(R)
    for v1 in ((0.0, 0.0), (-0.2, 0.1)):  # onto a resting ball, and a moving one (quartic)
        res = reference_simulate(table, [(1.0, 0.6), (x1, 0.6)], [(0.5, 0.0), v1])
        assert res.events[0] == (0, "ball", 0, 1)
        assert_close(
            res.first_velocities_after(0)[1][0] - res.first_velocities_after(0)[0][0],
            mpf(table.e_ball) * (mpf(0.5) - mpf(v1[0])),
            mpf("1e-14"),
        )
    # Touching (or overlapping) and separating: no impact.
    for v0 in ((-0.5, 0.0), (0.0, 0.5)):
        res = reference_simulate(table, [(1.0, 0.6), (x1, 0.6)], [v0, (0.0, 0.0)])
        assert "ball" not in [k for _, k, _, _ in res.events]


# -- guard rails ----------------------------------------------------------------------------


def test_event_cap_raises() -> None:
    with pytest.raises(ReferenceSimulationError, match="max_events"):
        reference_simulate(Table(pockets="none"), [(1.0, 0.6)], [(3.0, 1.0)], max_events=2)


def test_bad_input_is_rejected() -> None:
    with pytest.raises(ValueError, match="overlap"):
        reference_simulate(Table(), [(1.0, 0.6), (1.01, 0.6)], [(0, 0), (0, 0)])
    with pytest.raises(ValueError, match="outside"):
        reference_simulate(Table(), [(0.01, 0.6)], [(0, 0)])
    with pytest.raises(ValueError, match="finite"):
        reference_simulate(Table(), [(1.0, 0.6)], [(float("nan"), 0)])


def test_three_ball_three_collision_scene() -> None:
    """The scene of the module docstring's cost figure (no timing asserted: CI is noisy)."""
    table = Table(e_cushion=0.85, pockets="circles")  # the table it was made for
    pos = [(0.6, 0.5), (1.2, 0.6), (1.6, 0.7)]
    vel = [(1.5, 0.2), (-0.3, 0.1), (-0.8, -0.3)]
    res = reference_simulate(table, pos, vel)
    assert sum(1 for _, k, _, _ in res.events if k == "ball") == 3
    _check_impact_invariants(table, res, [table.ball_mass] * 3)
    _assert_no_overlap_between_events(res)


@pytest.mark.parametrize(
    "module", sorted(p.name for p in Path(reference.__file__).parent.glob("*.py"))
)
def test_reference_imports_nothing_from_the_simulator(module: str) -> None:
    """Independence: a module imports its siblings and, for type checking only, Table."""
    src = (Path(reference.__file__).parent / module).read_text()
    tree = ast.parse(src)
    type_checking_nodes = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.If) and getattr(node.test, "id", None) == "TYPE_CHECKING":
            type_checking_nodes.update(id(n) for n in ast.walk(node))
    for node in ast.walk(tree):
        name = (node.module or "") if isinstance(node, ast.ImportFrom) else ""
        if name.startswith("pool_env") and not name.startswith("pool_env.testing.reference."):
            assert name == "pool_env.sim.table"
            assert [a.name for a in node.names] == ["Table"]
            assert id(node) in type_checking_nodes
        if isinstance(node, ast.Import):
            assert not any(a.name.startswith("pool_env") for a in node.names)


def test_reference_package_is_all_checked() -> None:
    """The independence check above reads every module of the package (a split stays checked)."""
    names = {p.name for p in Path(reference.__file__).parent.glob("*.py")}
    assert {"__init__.py", "simulator.py", "roots.py", "jaw_cushions.py"} <= names


def test_rerun_is_identical() -> None:
    pos = [(0.6, 0.5), (1.2, 0.6), (1.6, 0.7)]
    vel = [(1.5, 0.2), (-0.3, 0.1), (-0.8, -0.3)]
    a = reference_simulate(Table(), pos, vel)
    b = reference_simulate(Table(), pos, vel)
    assert a.events == b.events
    assert a.positions == b.positions
