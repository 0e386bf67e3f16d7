"""The rows a carom reads: each ball's second distinct contact and its cushions up to it.

``second_hit`` and ``cushions_at_second`` are tallied in the event loop; here they are
recounted from the recorded event log, as pooltool's three-cushion rules count (the
cushion events of the ball with ``time <= t`` of its second distinct ball contact), on
random shots of both levels and of a pocketless and a jaw table, and the batch and the
rollout carry the very same rows. The tie (a cushion impact at the instant of the second
contact, taken after it in the event order) is checked on the tally itself.
"""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from pool_env import ShotResult, Table, shoot
from pool_env.sim import rollout, simulate_batch
from pool_env.sim.kernels.kinds import BALL, CUSHION, CUSHION_KINDS, JAW, POINT
from pool_env.sim.kernels.packing import (
    BALL_CUSHIONS_AT_SECOND,
    BALL_FIRST_HIT,
    BALL_SECOND_HIT,
    N_BALL_ROWS,
)
from pool_env.sim.kernels.roots import INF
from pool_env.sim.kernels.sequence import close_tally, tally
from pool_env.testing.scenes_random import random_layout
from tests.profiles import examples

TABLES = {
    "carom": Table.preset("carom"),
    "jaws": Table(model="spin"),
    "roll": Table(model="roll", pockets="none"),
}


def recount(shot: ShotResult) -> tuple[list[int], list[int]]:
    """Each ball's second distinct ball and its cushion events up to it, from the log."""
    n = shot.n_balls
    seconds, counts = [-1] * n, [-1] * n
    for ball in range(n):
        touched: list[int] = []
        t_second = None
        for e in shot.events:
            if e.kind == "ball" and ball in (e.i, e.j):
                other = e.j if e.i == ball else e.i
                if other not in touched:
                    touched.append(other)
                    if len(touched) == 2:
                        seconds[ball], t_second = other, e.time
                        break
        if t_second is not None:
            counts[ball] = sum(
                e.kind in CUSHION_KINDS and e.i == ball and e.time <= t_second for e in shot.events
            )
    return seconds, counts


@settings(max_examples=examples(150))
@given(
    name=st.sampled_from(sorted(TABLES)),
    seed=st.integers(0, 2**32 - 1),
    n_balls=st.integers(2, 5),
    angle=st.floats(-math.pi, math.pi),
    speed=st.floats(0.5, 6.0),
    tip=st.tuples(st.floats(-0.5, 0.5), st.floats(-0.5, 0.5)),
)
def test_rows_equal_an_event_log_recount(
    name: str, seed: int, n_balls: int, angle: float, speed: float, tip: tuple[float, float]
) -> None:
    """Random layouts and shots: the rows are the recount of the recorded events."""
    table = TABLES[name]
    layout = random_layout(table, n_balls, np.random.default_rng(seed))
    spin = table.model == "spin"
    shot = shoot(table, layout, angle, speed, tip=tip if spin else (0.0, 0.0), record=True)
    seconds, counts = recount(shot)
    assert shot.second_hit.tolist() == seconds
    assert shot.cushions_at_second.tolist() == counts
    unrecorded = shoot(table, layout, angle, speed, tip=tip if spin else (0.0, 0.0))
    assert unrecorded.second_hit.tolist() == seconds
    assert unrecorded.cushions_at_second.tolist() == counts


def test_seeded_caroms_reach_the_counted_cases() -> None:
    """A seeded sweep on the carom table: points (3+ cushions), fewer, and no second ball."""
    table = TABLES["carom"]
    rng = np.random.default_rng(45)
    layout = random_layout(table, 3, rng, min_gap=0.05)
    rows = np.column_stack(
        [
            rng.uniform(-math.pi, math.pi, 400),
            rng.uniform(1.0, 6.0, 400),
            rng.uniform(-0.5, 0.5, (400, 2)),
            np.zeros(400),
        ]
    )
    out = rollout(table, layout, rows)
    seen = set()
    for s, (angle, speed, a, b, _) in enumerate(rows):
        shot = shoot(table, layout, angle, speed, tip=(a, b), record=True)
        seconds, counts = recount(shot)
        assert out.second_hit[s].tolist() == seconds, s
        assert out.cushions_at_second[s].tolist() == counts, s
        c = counts[0]
        seen.add("none" if c < 0 else "point" if c >= 3 else "short")
    assert seen == {"none", "point", "short"}


def test_batch_rows_equal_single_shots_with_an_inactive_ball() -> None:
    """The batch maps the second ball to table columns, an inactive ball keeps -1."""
    table = TABLES["carom"]
    rng = np.random.default_rng(7)
    layouts = np.stack([random_layout(table, 4, rng) for _ in range(30)])
    velocities = np.zeros((30, 4, 2))
    angles = rng.uniform(-math.pi, math.pi, 30)
    velocities[:, 0] = 4.0 * np.column_stack([np.cos(angles), np.sin(angles)])
    active = np.ones((30, 4), bool)
    active[:, 1] = False
    out = simulate_batch(table, layouts, velocities, active=active)
    assert np.all(out.second_hit[:, 1] == -1) and np.all(out.cushions_at_second[:, 1] == -1)
    on = np.array([0, 2, 3])
    for b in range(30):
        shot = shoot(table, layouts[b, on], float(angles[b]), 4.0, record=True)
        seconds, counts = recount(shot)
        want = [int(on[s]) if s >= 0 else -1 for s in seconds]
        assert out.second_hit[b, on].tolist() == want, b
        assert out.cushions_at_second[b, on].tolist() == counts, b


def _run(events: list[tuple[float, int, int, int]], n: int = 3) -> np.ndarray:
    """The rows the tally leaves after ``(t, kind, i, j)`` events (in the loop's order)."""
    balls = np.full((N_BALL_ROWS, n), -1, dtype=np.int64)
    balls[BALL_CUSHIONS_AT_SECOND] = 0
    t_second = np.full(n, INF)
    first_i = first_j = -1
    for t, kind, i, j in events:
        first_i, first_j = tally(kind, i, j, t, balls, t_second, first_i, first_j)
    close_tally(balls)
    return balls


def test_a_cushion_at_the_instant_of_the_second_contact_counts() -> None:
    """Ball-ball before cushion at one instant in the event order, yet ``time <= t``."""
    events = [
        (0.5, CUSHION, 0, 1),
        (1.0, BALL, 0, 1),
        (1.5, JAW, 0, 2),
        (2.0, BALL, 0, 2),
        (2.0, CUSHION, 0, 3),  # the same instant as the second contact: counted
        (2.5, POINT, 0, 3),  # after it: not counted
    ]
    balls = _run(events)
    assert balls[BALL_FIRST_HIT].tolist() == [1, 0, 0]
    assert balls[BALL_SECOND_HIT].tolist() == [2, -1, -1]
    assert balls[BALL_CUSHIONS_AT_SECOND].tolist() == [3, -1, -1]
    assert _run(events[:4] + events[5:])[BALL_CUSHIONS_AT_SECOND, 0] == 2


def test_repeated_contacts_with_the_first_ball_are_not_a_second() -> None:
    """A ball touching its first ball again (a kiss, a Zeno run) has no second ball yet."""
    balls = _run([(1.0, BALL, 0, 1), (1.2, CUSHION, 0, 0), (1.4, BALL, 0, 1)])
    assert balls[BALL_SECOND_HIT].tolist() == [-1, -1, -1]
    assert balls[BALL_CUSHIONS_AT_SECOND].tolist() == [-1, -1, -1]
    balls = _run([(1.0, BALL, 0, 1), (1.4, BALL, 1, 2), (1.6, CUSHION, 1, 0)])
    assert balls[BALL_SECOND_HIT].tolist() == [-1, 2, -1]  # ball 1: 0, then 2
    assert balls[BALL_CUSHIONS_AT_SECOND].tolist() == [-1, 0, -1]
