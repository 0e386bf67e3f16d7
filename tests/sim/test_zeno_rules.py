"""The Zeno and sticking rules, pinned by closed forms (docs/physics.md, "Zeno rules").

The rules: an impact that repeats within a microsecond at a normal approach speed below
``ZENO_SPEED`` is perfectly inelastic; an isolated slow impact keeps ``e``; an inelastic
impact that leaves a pair pressed together (two balls moving the same way at one speed
are) makes the pair and every ball touching it leave as one lump at its centre-of-mass
velocity.

The scenes are rows of touching balls struck at t = 0 on a table whose radius and
positions are exact binary fractions, so every contact of the cascade is exact and all its
impacts fall on the same instant, taken in the documented order (the lowest pair first).
:func:`cascade` applies those rules to a row, independently of the kernels; the first
case is also worked out by hand.
"""

from __future__ import annotations

import numpy as np
import pytest

from pool_env import Table, simulate

#: The documented inelastic threshold (m/s), written from the rule, not read from the code.
ZENO_SPEED = 1e-6
#: Impacts of one pair in a row after which it sticks whatever its speed.
ZENO_REPEATS = 16
R = 1.0 / 32.0  # m: 2R = 1/16, exact


def _table(e: float) -> Table:
    return Table(ball_radius=R, e_ball=e, pockets="none")


def _row(n: int) -> np.ndarray:
    return np.array([[0.5 + 2 * R * k, 0.625] for k in range(n)])


def cascade(speeds: list[float], e: float) -> tuple[list[float], list[int]]:
    """Speeds (along +x) of a touching row after one instant of sequential impacts.

    Equal masses. Returns the final speeds and the pairs hit (``k`` for balls ``k, k+1``).
    """
    v = list(speeds)
    repeats = [0] * (len(v) - 1)
    hits = []
    while True:
        approaching = [k for k in range(len(v) - 1) if v[k] - v[k + 1] > 1e-12 * v[k]]
        if not approaching:
            return v, hits
        k = approaching[0]
        hits.append(k)
        repeats[k] += 1
        approach = v[k] - v[k + 1]
        slow_repeat = approach < ZENO_SPEED and repeats[k] >= 2
        e_eff = 0.0 if slow_repeat else e
        mean = 0.5 * (v[k] + v[k + 1])
        v[k], v[k + 1] = mean - 0.5 * e_eff * approach, mean + 0.5 * e_eff * approach
        if e_eff == 0.0 or repeats[k] >= ZENO_REPEATS:
            # Inelastic: the pair moves on at one speed, pressed together, and sticks with
            # the whole touching row: one lump at the centre-of-mass speed.
            lump = sum(v) / len(v)
            return [lump] * len(v), hits


def _rest_x(table: Table, x0: np.ndarray, speeds: list[float]) -> np.ndarray:
    return x0 + np.array(speeds) ** 2 / (2 * table.deceleration)


def test_three_ball_cradle_by_hand() -> None:
    """Cue at 0.4 m/s, e = 0.95: (0,1), (1,2), then (0,1) again at 2.5e-4 m/s, elastic."""
    table = _table(0.95)
    result = simulate(table, _row(3), [[0.4, 0.0], [0.0, 0.0], [0.0, 0.0]])
    # (0,1): 0.4 -> 0.025 * 0.4 = 0.01 and 0.975 * 0.4 = 0.39.
    # (1,2): 0.39 -> 0.00975 and 0.38025.
    # (0,1): approach 0.01 - 0.00975 = 2.5e-4 m/s, above ZENO_SPEED: e = 0.95 again,
    #        mean 0.009875 -+ 0.475 * 2.5e-4 -> 0.00975625 and 0.00999375; then all separate.
    speeds = [0.00975625, 0.00999375, 0.38025]
    kinds = [(e.kind, e.i, e.j) for e in result.events]
    assert kinds == [("ball", 0, 1), ("ball", 1, 2), ("ball", 0, 1)] + [
        ("stop", k, -1) for k in (0, 1, 2)
    ]
    assert all(e.time == 0.0 for e in result.events[:3])
    np.testing.assert_allclose(
        result.positions[:, 0], _rest_x(table, _row(3)[:, 0], speeds), rtol=0, atol=1e-12
    )
    np.testing.assert_array_equal(result.positions[:, 1], 0.625)
    assert cascade([0.4, 0.0, 0.0], 0.95) == (pytest.approx(speeds, rel=1e-12), [0, 1, 0])


@pytest.mark.parametrize("e", [0.95, 0.5, 0.1, 0.0])
@pytest.mark.parametrize("n", [3, 4, 5])
def test_inelastic_cradle_final_positions(e: float, n: int) -> None:
    """The whole cascade, sticking included (e = 0.1 with 4 or 5 balls ends in a lump)."""
    table = _table(e)
    velocities = np.zeros((n, 2))
    velocities[0, 0] = 0.4
    result = simulate(table, _row(n), velocities)
    speeds, hits = cascade([0.4] + [0.0] * (n - 1), e)
    balls = [(ev.i, ev.j) for ev in result.events if ev.kind == "ball"]
    assert balls == [(k, k + 1) for k in hits]
    np.testing.assert_allclose(
        result.positions[:, 0], _rest_x(table, _row(n)[:, 0], speeds), rtol=0, atol=1e-12
    )


def test_the_cascades_cover_both_endings() -> None:
    """The table above holds cascades that end separating and ones that end stuck."""
    assert len(set(cascade([0.4, 0.0, 0.0, 0.0], 0.1)[0])) == 1  # a lump
    assert len(cascade([0.4, 0.0, 0.0, 0.0], 0.1)[1]) > ZENO_REPEATS  # after many impacts
    assert len(set(cascade([0.4, 0.0, 0.0], 0.95)[0])) == 3  # separating


@pytest.mark.parametrize("factor", [0.99, 1.01])
def test_repeated_slow_impact_below_and_above_the_threshold(factor: float) -> None:
    """The repeat of (0,1) comes at ((1 - e) / 2)^2 of the cue's speed: set it to 1e-6 -+ 1%.

    Just below the threshold it is inelastic and the row leaves as one lump (all three
    balls rest together, at a third of the cue's speed squared over 2a); just above it keeps
    e = 0.95 and the balls separate as in the hand-worked cradle.
    """
    e = 0.95
    table = _table(e)
    u = factor * ZENO_SPEED / ((1 - e) / 2) ** 2
    result = simulate(table, _row(3), [[u, 0.0], [0.0, 0.0], [0.0, 0.0]])
    if factor < 1:
        speeds = [u / 3] * 3
    else:
        v1 = (1 + e) / 2 * u
        first, second = (1 - e) / 2 * u, (1 - e) / 2 * v1
        mean, approach = 0.5 * (first + second), first - second
        speeds = [mean - 0.5 * e * approach, mean + 0.5 * e * approach, (1 + e) / 2 * v1]
    assert cascade([u, 0.0, 0.0], e)[0] == pytest.approx(speeds, rel=1e-9)
    np.testing.assert_allclose(
        result.positions[:, 0], _rest_x(table, _row(3)[:, 0], speeds), rtol=0, atol=1e-15
    )
    stops = [ev.time for ev in result.events if ev.kind == "stop"]
    assert (len(set(stops)) == 1) == (factor < 1)  # a lump stops as one


@pytest.mark.parametrize("approach", [5e-7, 2e-6])
def test_an_isolated_slow_impact_keeps_its_restitution(approach: float) -> None:
    """Two touching balls moving the same way, the rear one faster by less than 1e-6 m/s.

    One impact, no repeat: e applies at any approach speed, so the front ball leaves
    faster by ``e * approach`` (an inelastic impact would send them on together).
    """
    e = 0.95
    table = _table(e)
    v_front = 0.2
    v_rear = v_front + approach
    result = simulate(table, _row(2), [[v_rear, 0.0], [v_front, 0.0]])
    assert (result.events[0].kind, result.events[0].i, result.events[0].j) == ("ball", 0, 1)
    assert sum(ev.kind == "ball" for ev in result.events) == 1
    mean = 0.5 * (v_rear + v_front)
    speeds = [mean - 0.5 * e * approach, mean + 0.5 * e * approach]
    np.testing.assert_allclose(
        result.positions[:, 0], _rest_x(table, _row(2)[:, 0], speeds), rtol=0, atol=1e-12
    )
    # The separation is far above the tolerance: a lump would rest this much nearer.
    lump = _rest_x(table, _row(2)[:, 0], [mean, mean])
    assert result.positions[1, 0] - lump[1] > 100 * 1e-12


def test_a_lump_takes_only_the_balls_touching_it() -> None:
    """With e = 0 the struck row sticks as a lump; a ball 1/1024 m beyond joins on impact.

    At t = 0 the cue (0.6 m/s) and the touching balls 1, 2 leave as one lump at 0.2 m/s.
    Ball 3, 0.98 mm past ball 2, is not touching: the lump reaches it after rolling the gap,
    at ``w = sqrt(0.2^2 - 2 a g)``; that impact is inelastic too and the four leave at the
    centre-of-mass speed ``(3 w + 0) / 4``.
    """
    table = _table(0.0)
    gap = 1.0 / 1024.0
    positions = _row(4)
    positions[3, 0] += gap
    velocities = np.zeros((4, 2))
    velocities[0, 0] = 0.6
    result = simulate(table, positions, velocities)
    a = table.deceleration
    w = np.sqrt(0.2**2 - 2 * a * gap)
    travel = (0.75 * w) ** 2 / (2 * a)
    expected = positions[:, 0] + travel + np.array([gap, gap, gap, 0.0])
    np.testing.assert_allclose(result.positions[:, 0], expected, rtol=0, atol=1e-12)
    hits = [(ev.i, ev.j) for ev in result.events if ev.kind == "ball"]
    assert hits == [(0, 1), (2, 3)]
    assert result.events[1].time == pytest.approx((0.2 - w) / a, rel=1e-12)


@pytest.mark.parametrize(("vx", "pressed"), [(0.08, True), (0.4, False)])
def test_an_inelastic_glancing_pair_sticks_only_when_pressed_together(vx, pressed) -> None:
    """With e = 0, the cue moving (vx, 0.001) into a ball touching it along +x.

    The impact equalises the x speeds (vx / 2 each) and the cue keeps ``vy``. The cue then
    decelerates along its own direction ``u0`` and ball 1 along +x, so the squared gap
    curves as ``vy^2 - 2 a R (1 - u0x)`` (half of ``D''``, with ``d = 2R`` along x). Slow
    (vx = 0.08) that is negative: the pair is pressed together and sticks at once, one
    impact, the lump at the centre-of-mass velocity (vx / 2, vy / 2). Faster (0.4) it is
    positive and the two separate, each on its own.
    """
    vy = 0.001
    table = _table(0.0)
    a = table.deceleration
    u0x = (vx / 2) / np.hypot(vx / 2, vy)
    assert (vy**2 - 2 * a * R * (1 - u0x) < 0) == pressed
    result = simulate(table, _row(2), [[vx, vy], [0.0, 0.0]])
    lump, apart = [(vx / 2, vy / 2)] * 2, [(vx / 2, vy), (vx / 2, 0.0)]
    velocities = lump if pressed else apart
    expected = [
        p + np.array(v) * np.hypot(*v) / (2 * a) for p, v in zip(_row(2), velocities, strict=True)
    ]
    np.testing.assert_allclose(result.positions, expected, rtol=0, atol=1e-12)
    assert [ev.kind for ev in result.events] == ["ball", "stop", "stop"]
