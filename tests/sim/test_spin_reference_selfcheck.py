"""Self-checks of the 50-digit spin reference (pool_env/testing/spin_reference.py).

The reference is the oracle for the spin level, so it is checked on its own: every expected
value is derived here from the model's closed forms (docs/sources.md), not read from the reference.
"""

from __future__ import annotations

import math
from types import SimpleNamespace

import pytest
from mpmath import mp, mpf

from pool_env.testing import spin_physics_mp as ph
from pool_env.testing.spin_reference import (
    SpinReferenceError,
    _real_roots,
    spin_reference_simulate,
)

R, M, G = 0.028575, 0.170097, 9.81
TIGHT = mpf("1e-35")


def table(**kw: object) -> SimpleNamespace:
    """A big pocketless spin table (no rail reached unless a test wants one)."""
    base = dict(
        length=40.0, width=40.0, ball_radius=R, ball_mass=M, g=G, mu_slide=0.2,
        mu_roll=0.01, spin_decel=2.5 * 0.444 * G, e_ball=0.95, e_cushion=0.85,
        ball_friction="alciatore", cushion_friction=0.2, cushion_height=0.635 * 2 * R,
        cue_tip_radius=0.0106, cue_end_mass=M / 30,
    )  # fmt: skip
    base.update(kw)
    return SimpleNamespace(**base)


def close(a: mpf, b: mpf, tol: mpf = TIGHT) -> bool:
    with mp.workdps(50):
        return abs(mpf(a) - mpf(b)) <= tol * max(1, abs(mpf(b)))


def energy(v: ph.Vec2, w: ph.Vec3) -> mpf:
    m = mpf(M)
    i = mpf(2) / 5 * m * mpf(R) ** 2
    return m * ph.dot(v, v) / 2 + i * ph.dot(w, w) / 2


@pytest.mark.parametrize("angle_deg", [0.0, 37.0, 135.0, 250.0])
@pytest.mark.parametrize("v0", [0.5, 2.0])
def test_stun_slides_12v2_over_49mug_then_rolls_at_5_7(angle_deg: float, v0: float) -> None:
    c, s = math.cos(math.radians(angle_deg)), math.sin(math.radians(angle_deg))
    vel = (v0 * c, v0 * s)
    res = spin_reference_simulate(table(), [(20.0, 20.0)], [vel])
    assert [k for _, k, _, _ in res.events] == ["slide_roll", "stop"]
    with mp.workdps(50):
        v = mp.sqrt(mpf(vel[0]) ** 2 + mpf(vel[1]) ** 2)
        mus, mur, g = mpf(0.2) * mpf(G), mpf(0.01) * mpf(G), 1
        t_slide = 2 * v / (7 * mus)
        assert close(res.events[0][0], t_slide)
        _, v_roll, w_roll = res.after[0][0]
        assert close(ph.norm(v_roll), 5 * v / 7)  # 5/7 of the stun speed
        assert close(w_roll[0], -v_roll[1] / mpf(R)) and close(w_roll[1], v_roll[0] / mpf(R))
        dist = 12 * v**2 / (49 * mus) * g + (5 * v / 7) ** 2 / (2 * mur)
        assert close(res.events[1][0], t_slide + 5 * v / 7 / mur)
        end = res.positions[0]
        assert close(end[0], mpf(20) + dist * mpf(vel[0]) / v)
        assert close(end[1], mpf(20) + dist * mpf(vel[1]) / v)
    # At 2 m/s the slide is 0.50 m long and lasts 0.29 s (docs/sources.md, "Closed forms").
    if v0 == 2.0:
        assert abs(float(res.events[0][0]) - 0.2912) < 1e-4


@pytest.mark.parametrize("cut_deg", [10.0, 28.0, 48.6, 70.0])
def test_30_degree_rule_frictionless_elastic(cut_deg: float) -> None:
    """A rolling cue ball's path after a cut turns by atan(sin cos / (sin^2 + 2/5))."""
    phi = math.radians(cut_deg)
    speed = 1.5
    tb = table(ball_friction=0.0, e_ball=1.0)
    # Object ball at the origin's side: the line of centres at impact makes angle phi with
    # the cue ball's travel (+x); the cue ball starts 1 mm behind contact, rolling.
    obj = (20.0, 20.0)
    gap = 1e-3
    cue = (obj[0] - 2 * R * math.cos(phi) - gap, obj[1] + 2 * R * math.sin(phi))
    res = spin_reference_simulate(
        tb, [cue, obj], [(speed, 0.0), (0.0, 0.0)], [(0.0, speed / R, 0.0), (0.0, 0.0, 0.0)]
    )
    kinds = [(k, i) for _, k, i, _ in res.events]
    assert kinds[0] == ("ball", 0)
    k_roll = next(n for n, (k, i) in enumerate(kinds) if k == "slide_roll" and i == 0)
    _, v_after, _ = res.after[k_roll][0]
    with mp.workdps(50):
        turn = mp.atan2(v_after[1], v_after[0])  # away from the object ball (it is below)
        # The cut at impact from the exact line of centres (float inputs shift it ~1e-14).
        (p1, v1, _), (p2, _, _) = res.before[0]
        p = mp.atan2(p1[1] - p2[1], p2[0] - p1[0]) - mp.atan2(v1[1], v1[0])
        assert abs(p - mpf(cut_deg) * mp.pi / 180) < 1e-12
        expected = mp.atan(mp.sin(p) * mp.cos(p) / (mp.sin(p) ** 2 + mpf(2) / 5))
        assert close(turn, expected, mpf("1e-30"))
    if cut_deg == 28.0:
        assert abs(math.degrees(float(turn)) - 33.7) < 0.05


def test_stun_cue_ball_leaves_along_the_tangent_line() -> None:
    """The 90-degree rule: no spin at impact, frictionless balls, e = 1."""
    phi = math.radians(35.0)
    obj = (20.0, 20.0)
    cue = (obj[0] - 2 * R * math.cos(phi), obj[1] + 2 * R * math.sin(phi))  # touching
    res = spin_reference_simulate(
        table(ball_friction=0.0, e_ball=1.0), [cue, obj], [(1.0, 0.0), (0.0, 0.0)]
    )
    assert res.events[0][1:] == ("ball", 0, 1)
    (p1, v1, _), (p2, v2, _) = res.after[0]
    with mp.workdps(50):
        n = (p2[0] - p1[0], p2[1] - p1[1])
        assert abs(ph.dot(v1, n)) < mpf("1e-45")  # cue ball: tangent line
        assert abs(v2[0] * n[1] - v2[1] * n[0]) < mpf("1e-45")  # object ball: along n


def test_spinning_ball_stops_in_place() -> None:
    wz = 25.0
    res = spin_reference_simulate(table(), [(3.0, 4.0)], [(0.0, 0.0)], [(0.0, 0.0, wz)])
    assert [k for _, k, _, _ in res.events] == ["spin_stop"]
    with mp.workdps(50):
        assert close(res.events[0][0], mpf(wz) / mpf(2.5 * 0.444 * G))
    assert res.positions[0] == (mpf(3.0), mpf(4.0))
    assert res.states == [ph.STATIONARY]


def test_rolling_ball_with_long_side_spin_ends_spinning_then_stops() -> None:
    v0, wz = 0.2, 30.0  # rolls 2.04 s, spins 2.75 s
    res = spin_reference_simulate(table(), [(5.0, 5.0)], [(v0, 0.0)], [(0.0, v0 / R, wz)])
    kinds = [k for _, k, _, _ in res.events]
    assert kinds == ["roll_spin", "spin_stop"]
    with mp.workdps(50):
        decel = mpf(2.5 * 0.444 * G)
        assert close(res.events[1][0], mpf(wz) / decel)
        # Side spin does not bend a rolling ball's path: it stops v^2 / (2 mu_r g) away.
        assert close(res.positions[0][0], mpf(5) + mpf(v0) ** 2 / (2 * mpf(0.01) * mpf(G)))
        assert res.positions[0][1] == mpf(5)


@pytest.mark.parametrize("friction", ["alciatore", 0.0, 0.06])
@pytest.mark.parametrize("e_ball", [1.0, 0.9])
def test_ball_ball_conserves_momentum_and_never_gains_energy(friction, e_ball) -> None:
    tb = table(ball_friction=friction, e_ball=e_ball)
    res = spin_reference_simulate(
        tb,
        [(20.0, 20.0), (20.3, 20.02)],
        [(2.0, 0.1), (-0.3, 0.2)],
        [(5.0, -30.0, 40.0), (-10.0, 3.0, -7.0)],
    )
    k = next(n for n, e in enumerate(res.events) if e[1] == "ball")
    (_, va, wa), (_, vb, wb) = res.before[k]
    (_, va2, wa2), (_, vb2, wb2) = res.after[k]
    with mp.workdps(50):
        for axis in (0, 1):
            assert close(va[axis] + vb[axis], va2[axis] + vb2[axis], mpf("1e-45"))
        before = energy(va, wa) + energy(vb, wb)
        after = energy(va2, wa2) + energy(vb2, wb2)
        if friction == 0.0 and e_ball == 1.0:
            assert close(after, before, mpf("1e-45"))
        else:
            assert after < before


def test_ball_ball_unequal_masses_conserve_momentum() -> None:
    res = spin_reference_simulate(
        table(), [(20.0, 20.0), (20.4, 20.01)], [(1.5, 0.0), (0.0, 0.0)], masses=[0.17, 0.25]
    )
    k = next(n for n, e in enumerate(res.events) if e[1] == "ball")
    (_, va, _), (_, vb, _) = res.before[k]
    (_, va2, _), (_, vb2, _) = res.after[k]
    with mp.workdps(50):
        for axis in (0, 1):
            before = mpf(0.17) * va[axis] + mpf(0.25) * vb[axis]
            assert close(before, mpf(0.17) * va2[axis] + mpf(0.25) * vb2[axis], mpf("1e-45"))


def test_cushion_frictionless_square_hit_reflects_with_e() -> None:
    """Han 2005 with no cushion friction and no spin: the normal speed turns by -e cos^2."""
    tb = table(length=2.54, width=1.27, cushion_friction=0.0)
    res = spin_reference_simulate(tb, [(2.0, 0.6)], [(1.0, 0.0)], [(0.0, 1.0 / R, 0.0)])
    k = next(n for n, e in enumerate(res.events) if e[1] == "cushion")
    assert res.events[k][3] == 1
    _, v, _ = res.before[k][0]
    _, v2, w2 = res.after[k][0]
    with mp.workdps(50):
        sin_t = mpf(0.635 * 2 * R) / mpf(R) - 1
        # The impulse acts along the tilted contact normal: only its horizontal part counts.
        assert close(v2[0], v[0] - (1 + mpf(0.85)) * v[0] * (1 - sin_t**2))
        assert v2[1] == 0
        assert energy(v2, w2) < energy(v, (0, 1 / mpf(R) * v[0], 0))


def test_cushion_never_gains_energy_and_keeps_the_ball_in() -> None:
    tb = table(length=2.54, width=1.27)
    for k, (vx, vy, wz) in enumerate([(1.0, 2.0, 40.0), (-3.0, 0.5, -60.0), (0.3, -2.0, 0.0)]):
        res = spin_reference_simulate(tb, [(1.2, 0.6)], [(vx, vy)], [(0.0, 0.0, wz)])
        for n, (_, kind, _, _) in enumerate(res.events):
            if kind == "cushion":
                (_, v, w), (_, v2, w2) = res.before[n][0], res.after[n][0]
                assert energy(v2, w2) < energy(v, w), k
        x, y = res.positions[0]
        assert R <= x <= 2.54 - R and R <= y <= 1.27 - R


@pytest.mark.parametrize(("a", "deg"), [(0.3, 1.2), (0.5, 1.9), (0.7, 2.2)])
def test_squirt_angle_figures(a: float, deg: float) -> None:
    with mp.workdps(50):
        ang = ph.squirt_angle(mpf(a), mpf(M), mpf(M) / 30)
    assert abs(math.degrees(float(ang)) - deg) < 0.05


def test_strike_rolls_at_once_at_two_fifths_above_centre() -> None:
    tb = table()
    with mp.workdps(50):
        from pool_env.testing.spin_reference import params_from

        prm = params_from(tb)
        tip = mpf("0.4") * (1 + prm["cue_tip_radius"] / prm["R"])  # contact at 0.4 R
        v, w = ph.cue_strike(mpf(2), mpf("0.3"), (mpf(0), tip), mpf(0), prm, mpf(M))
        assert ph.norm(ph.slip(v, w, prm["R"])) < mpf("1e-45")
        assert close(ph.norm(v), mpf(2))
        # Right english turns the ball left (squirt) and spins it anticlockwise.
        v2, w2 = ph.cue_strike(mpf(2), mpf(0), (mpf("0.5"), mpf(0)), mpf(0), prm, mpf(M))
        assert v2[1] > 0 and w2[2] > 0


def _mul(p: list[mpf], q: list[mpf]) -> list[mpf]:
    out = [mpf(0)] * (len(p) + len(q) - 1)
    for i, a in enumerate(p):
        for j, b in enumerate(q):
            out[i + j] += a * b
    return out


def test_quartic_roots_of_known_polynomial() -> None:
    """Real roots of (x - 0.1)(x - 0.25)(x - 3.5)(x - r4) and of a quartic with a complex pair."""
    with mp.workdps(50):
        roots = [mpf("0.1"), mpf("0.25"), mpf("3.5")]
        cubic = [mpf(1)]
        for r in roots:
            cubic = _mul(cubic, [-r, mpf(1)])  # ascending coefficients
        four = _mul(cubic, [mpf("-7.25"), mpf(1)])
        got = _real_roots(four)
        assert len(got) == 4
        assert all(
            close(g, r, mpf("1e-45")) for g, r in zip(got, [*roots, mpf("7.25")], strict=True)
        )
        # (x^2 + 1) contributes no real root; a double root (grazing) is found once or twice.
        got = _real_roots(_mul(_mul([-roots[0], mpf(1)], [-roots[1], mpf(1)]), [1, 0, 1]))
        assert len(got) == 2 and close(got[0], roots[0], mpf("1e-45"))
        got = _real_roots(_mul(_mul([-roots[2], mpf(1)], [-roots[2], mpf(1)]), [1, 0, 1]))
        assert got and all(close(g, roots[2], mpf("1e-30")) for g in got)


def test_sliding_balls_collide_at_contact_distance() -> None:
    """Two curving (sliding, spinning) balls meet at exactly 2R: the quartic's root."""
    res = spin_reference_simulate(
        table(),
        [(20.0, 20.0), (20.5, 20.3)],
        [(1.6, 0.4), (-0.4, -0.5)],
        [(-20.0, 40.0, 5.0), (30.0, 10.0, 0.0)],
    )
    k = next(n for n, e in enumerate(res.events) if e[1] == "ball")
    assert res.before[k][0] != res.after[k][0]
    (p1, _, _), (p2, _, _) = res.before[k]
    with mp.workdps(50):
        assert close(ph.norm((p2[0] - p1[0], p2[1] - p1[1])), 2 * mpf(R), mpf("1e-40"))
        assert all(e[1] != "ball" for e in res.events[:k]) and k >= 1  # curved when they met


def test_bad_input_raises() -> None:
    with pytest.raises(ValueError, match="outside"):
        spin_reference_simulate(table(length=1.0), [(2.0, 0.5)], [(0.0, 0.0)])
    with pytest.raises(ValueError, match="overlaps"):
        spin_reference_simulate(table(), [(2.0, 2.0), (2.01, 2.0)], [(0.0, 0.0), (0.0, 0.0)])
    with pytest.raises(ValueError, match="shape"):
        spin_reference_simulate(table(), [(2.0, 2.0)], [(0.0, 0.0, 1.0)])
    with pytest.raises(SpinReferenceError):
        spin_reference_simulate(
            table(length=2.54, width=1.27), [(1.2, 0.6)], [(3.0, 1.0)], max_events=2
        )


def test_side_spin_that_dies_first_ends_in_a_plain_stop() -> None:
    """Vertical spin decays to zero and stays there: the roll then ends at rest."""
    v0, wz = 0.2, -5.0  # spin gone after 0.46 s, roll lasts 2.04 s
    res = spin_reference_simulate(table(), [(5.0, 5.0)], [(v0, 0.0)], [(0.0, v0 / R, wz)])
    assert [k for _, k, _, _ in res.events] == ["stop"]
    assert res.angular_velocities[0] == (0, 0, 0)
    assert res.states == [ph.STATIONARY]


def test_slip_shrinks_linearly_along_a_fixed_direction() -> None:
    """While sliding, u(t) = u0 (1 - 7 mu_s g t / (2 |u0|)), seen at a mid-slide impact."""
    v0, w0 = (1.2, 0.3), (20.0, -60.0, 15.0)
    res = spin_reference_simulate(
        table(), [(20.0, 20.0), (20.25, 20.06)], [v0, (0.0, 0.0)], [w0, (0.0, 0.0, 0.0)]
    )
    assert res.events[0][1] == "ball"
    t = res.events[0][0]
    (_, v, w), _ = res.before[0]
    with mp.workdps(50):
        u0 = ph.slip((mpf(v0[0]), mpf(v0[1])), tuple(mpf(x) for x in w0), mpf(R))
        shrink = 1 - 7 * mpf(0.2) * mpf(G) * t / (2 * ph.norm(u0))
        assert 0 < shrink < 1
        u = ph.slip(v, w, mpf(R))
        assert close(u[0], u0[0] * shrink) and close(u[1], u0[1] * shrink)
        assert close(w[2], mpf(w0[2]) - mpf(2.5 * 0.444 * G) * t)


def _contact_slip(before_after: list) -> tuple[mpf, ...]:
    (p1, v1, w1), (p2, v2, w2) = before_after
    d = (p2[0] - p1[0], p2[1] - p1[1])
    dn = ph.norm(d)
    n = (d[0] / dn, d[1] / dn, mpf(0))
    r = mpf(R)
    c1 = ph.cross(w1, tuple(r * x for x in n))
    c2 = ph.cross(w2, tuple(-r * x for x in n))
    rel = [v1[0] - v2[0] + c1[0] - c2[0], v1[1] - v2[1] + c1[1] - c2[1], c1[2] - c2[2]]
    along = rel[0] * n[0] + rel[1] * n[1]
    return (rel[0] - along * n[0], rel[1] - along * n[1], rel[2])


@pytest.mark.parametrize("throw", ["coulomb", "pooltool"])
@pytest.mark.parametrize("mu", [0.01, 1.0])
def test_throw_impulse_capped_at_no_slip(mu: float, throw: str) -> None:
    """The contact slip s falls by 7 k s, k = mu J / (m |s|), at most 1/7 (no slip).

    Per unit mass, J is the normal impulse (1 + e) du / 2 (Coulomb) or pooltool 0.6.0's
    separation speed e du.

    Of the 7, 2 come from the velocities and 5 from the spins; the dropped vertical
    velocity change undoes the 2 on the vertical component, which falls by 5 k only.
    """
    e = 0.95
    res = spin_reference_simulate(
        table(ball_friction=mu, e_ball=e),
        [(20.0, 20.0), (20.2, 20.04)],
        [(1.5, 0.0), (0.0, 0.0)],
        [(0.0, 0.0, 30.0), (0.0, 0.0, 0.0)],
        throw=throw,
    )
    k = next(n for n, ev in enumerate(res.events) if ev[1] == "ball")
    with mp.workdps(50):
        s0, s1 = _contact_slip(res.before[k]), _contact_slip(res.after[k])
        (p1, v1, _), (p2, v2, _) = res.before[k]
        d = (p2[0] - p1[0], p2[1] - p1[1])
        du = ((v1[0] - v2[0]) * d[0] + (v1[1] - v2[1]) * d[1]) / ph.norm(d)
        per_mass = (1 + mpf(e)) / 2 * du if throw == "coulomb" else mpf(e) * du
        frac = min(mpf(mu) * per_mass / ph.norm(s0), mpf(1) / 7)
        assert (frac == mpf(1) / 7) == (mu == 1.0)  # the cap binds only at high friction
        for axis in (0, 1):
            assert close(s1[axis], s0[axis] * (1 - 7 * frac), mpf("1e-40"))
        assert close(s1[2], s0[2] * (1 - 5 * frac), mpf("1e-40"))
