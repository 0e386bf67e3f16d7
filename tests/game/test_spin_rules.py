"""Ball-ball closed forms of the spin level with frictionless balls, to 1e-9 m.

The 90- and 30-degree rules, and draw and follow after a full hit (angles to 1e-12 rad).

With frictionless balls an impact exchanges only the normal velocity components and leaves
every spin as it was; the cloth then turns the cue ball's slip into roll. Over a slide
the velocity changes by ``-(2/7) u0`` (``u0`` the slip at its start), so the final rolling
velocity is ``v' - (2/7) u0``.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from pool_env import Table, simulate

TOL = 1e-9


def _table(e_ball: float) -> Table:
    return Table(
        length=300.0, width=300.0, model="spin", pockets="none", ball_friction=0.0, e_ball=e_ball
    )


def _rest_after_slide(table: Table, v, w):
    """Displacement of a free ball from velocity ``v`` and spin ``w_xy`` to rest."""
    r, g = table.ball_radius, table.g
    v = np.asarray(v, float)
    u = np.array([v[0] - r * w[1], v[1] + r * w[0]])
    slip = np.hypot(*u)
    mu = table.mu_slide
    t_s = 2.0 * slip / (7.0 * mu * g)
    disp = v * t_s - 0.5 * mu * g * t_s * t_s * (u / slip if slip > 0 else 0.0)
    v1 = v - mu * g * t_s * (u / slip if slip > 0 else 0.0)
    s1 = np.hypot(*v1)
    return disp + v1 * s1 / (2.0 * table.mu_roll * g)


@pytest.mark.parametrize("cut_deg", [10.0, 30.0, 45.0, 60.0, 80.0])
@pytest.mark.parametrize("v0", [0.5, 3.0])
def test_ninety_degree_rule(cut_deg: float, v0: float) -> None:
    """A stun cue ball (no spin at contact) leaves along the tangent line."""
    t = _table(1.0)
    r = t.ball_radius
    phi = math.radians(cut_deg)
    n = np.array([math.cos(phi), math.sin(phi)])
    cue = np.array([150.0, 150.0])
    obj = cue + 2.0 * r * n
    res = simulate(t, [cue, obj], [[v0, 0.0], [0.0, 0.0]])  # touching (to rounding)
    assert res.events[0].kind == "ball" and res.events[0].time <= 1e-13
    assert [e.kind for e in res.events].count("ball") == 1
    tangent = np.array([math.sin(phi), -math.cos(phi)])
    v_cue = v0 * math.sin(phi) * tangent
    v_obj = v0 * math.cos(phi) * n
    np.testing.assert_allclose(
        res.positions[0], cue + _rest_after_slide(t, v_cue, (0, 0)), rtol=0, atol=TOL
    )
    np.testing.assert_allclose(
        res.positions[1], obj + _rest_after_slide(t, v_obj, (0, 0)), rtol=0, atol=TOL
    )
    # 90 degrees between the two paths.
    d_cue, d_obj = res.positions[0] - cue, res.positions[1] - obj
    assert abs(d_cue @ d_obj) <= 1e-9 * np.hypot(*d_cue) * np.hypot(*d_obj)


@pytest.mark.parametrize("cut_deg", [5.0, 14.4775, 28.0, 30.0, 48.59, 70.0])
@pytest.mark.parametrize("v0", [0.8, 4.0])
def test_thirty_degree_rule(cut_deg: float, v0: float) -> None:
    """A rolling cue ball ends deflected by ``atan[sin cos / (sin^2 + 2/5)]``."""
    t = _table(1.0)
    r = t.ball_radius
    phi = math.radians(cut_deg)
    cue = np.array([100.0, 150.0])
    obj = np.array([100.4, 150.0 + 2.0 * r * math.sin(phi)])
    res = simulate(
        t, [cue, obj], [[v0, 0.0], [0.0, 0.0]], angular_velocities=[[0, v0 / r, 0], [0, 0, 0]]
    )
    kinds = [(e.kind, e.i) for e in res.events]
    assert kinds[0] == ("ball", 0)
    ball, _, state, _ = res.segments
    rows = np.flatnonzero(ball == 0)
    # The cue ball's rows: start (rolling), after the impact (sliding), after slide_roll.
    assert res.events[1:].__len__() >= 2 and ("slide_roll", 0) in kinds
    final = state[rows[2], 2:4]
    deflection = -math.atan2(final[1], final[0])
    expected = math.atan(math.sin(phi) * math.cos(phi) / (math.sin(phi) ** 2 + 0.4))
    assert deflection == pytest.approx(expected, abs=1e-12)


def test_thirty_degree_rule_maximum() -> None:
    """The closed form peaks at 33.7 degrees near a 28-degree cut (TP B-13)."""
    phis = np.radians(np.linspace(1, 89, 8801))
    theta = np.degrees(np.arctan(np.sin(phis) * np.cos(phis) / (np.sin(phis) ** 2 + 0.4)))
    assert theta.max() == pytest.approx(33.7, abs=0.05)
    assert np.degrees(phis[theta.argmax()]) == pytest.approx(28.0, abs=0.5)


@pytest.mark.parametrize("k", [-2.0, -0.5, 0.0, 1.0, 1.5])
@pytest.mark.parametrize("e", [0.9, 0.95])
def test_draw_and_follow_after_full_hit(k: float, e: float) -> None:
    """Full hit with spin ``wy = k v / R``: the cue ball keeps its spin through the impact.

    After it ``v' = v (1 - e) / 2``, slip ``u0 = v' - k v``, slide time
    ``2 |u0| / (7 mu_s g)``, slide distance ``v' t_s - mu_s g sign(u0) t_s^2 / 2`` and a
    roll at ``v' - (2/7) u0 = (5 v' + 2 k v) / 7`` for ``v_f^2 / (2 mu_r g)`` along its sign:
    draw (back) for ``k < -(1 - e) 5 / 4``, follow beyond.
    """
    t = _table(e)
    r = t.ball_radius
    v = 2.0
    cue = np.array([150.0, 150.0])
    obj = cue + [2.0 * r, 0.0]
    res = simulate(
        t, [cue, obj], [[v, 0.0], [0.0, 0.0]], angular_velocities=[[0, k * v / r, 0], [0, 0, 0]]
    )
    assert [e_.kind for e_ in res.events].count("ball") == 1
    vp = v * (1.0 - e) / 2.0
    u0 = vp - k * v
    mu, g = t.mu_slide, t.g
    t_s = 2.0 * abs(u0) / (7.0 * mu * g)
    x_slide = vp * t_s - 0.5 * mu * g * math.copysign(1.0, u0) * t_s * t_s
    v_f = (5.0 * vp + 2.0 * k * v) / 7.0
    x_roll = math.copysign(v_f * v_f / (2.0 * t.mu_roll * g), v_f)
    np.testing.assert_allclose(res.positions[0], cue + [x_slide + x_roll, 0.0], rtol=0, atol=TOL)
    # The object ball: stun at v (1 + e) / 2.
    vo = v * (1.0 + e) / 2.0
    np.testing.assert_allclose(
        res.positions[1], obj + _rest_after_slide(t, (vo, 0.0), (0, 0)), rtol=0, atol=TOL
    )
