"""The compiled rules (rows from the simulator's tally) equal the plain-Python reference.

Random shots are random event lists of three balls (ball-ball contacts, cushion, jaw and
point impacts, ties included); the game's side reads the rows the simulator's own tally
makes of them, the reference reads the events (pooltool's way). Random rack states cover
the break, both strikers, the equalizing inning, the target and the inning limit.
``THREE_CUSHION_SWEEP=100000 python -m pytest tests/game/three_cushion -k sweep`` runs
the seeded sweep on 100,000 outcomes.
"""

from __future__ import annotations

import os

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from pool_env.game.games.three_cushion import section as sc
from pool_env.game.games.three_cushion.rules import judge_rows
from pool_env.sim.kernels.kinds import KIND_NAMES
from pool_env.sim.kernels.packing import (
    BALL_CUSHIONS_AT_SECOND,
    BALL_FIRST_HIT,
    BALL_SECOND_HIT,
    N_BALL_ROWS,
)
from pool_env.sim.kernels.roots import INF
from pool_env.sim.kernels.sequence import close_tally, tally
from pool_env.testing.reference.three_cushion_rules import judge_shot
from tests.profiles import examples

KIND = {name: code for code, name in enumerate(KIND_NAMES)}
PAIRS = ((0, 1), (0, 2), (1, 2))


def random_events(rng: np.random.Generator) -> list[tuple[float, str, int, int]]:
    """A shot's events in the loop's order: times on a coarse grid, so ties happen."""
    events = []
    for _ in range(int(rng.integers(0, 12))):
        t = float(rng.integers(0, 8)) * 0.25
        if rng.random() < 0.4:
            i, j = PAIRS[int(rng.integers(0, 3))]
            events.append((t, "ball", i, j))
        else:
            kind = ("cushion", "cushion", "jaw", "point")[int(rng.integers(0, 4))]
            events.append((t, kind, int(rng.integers(0, 3)), int(rng.integers(0, 4))))
    events.sort(key=lambda e: (e[0], KIND[e[1]], e[2], e[3]))  # (time, kind, i, j)
    return events


def rows_of(events: list[tuple[float, str, int, int]]) -> np.ndarray:
    """The per-ball rows the simulator's tally makes of ``events``."""
    balls = np.full((N_BALL_ROWS, 3), -1, dtype=np.int64)
    balls[BALL_CUSHIONS_AT_SECOND] = 0
    t_second = np.full(3, INF)
    fi = fj = -1
    for t, kind, i, j in events:
        fi, fj = tally(KIND[kind], i, j, t, balls, t_second, fi, fj)
    close_tally(balls)
    return balls


def random_state(rng: np.random.Generator, target: int, limit: int) -> dict:
    """A reachable-looking rack state (scores below the target, innings up to the limit)."""
    shooter = int(rng.integers(0, 2))
    innings0 = int(rng.integers(1, max(limit, 3) + 1))
    innings1 = innings0 if shooter == 1 else innings0 - 1
    return {
        "shooter": shooter,
        "score": [int(rng.integers(0, target)), int(rng.integers(0, target))],
        "innings": [innings0, innings1],
        "run": int(rng.integers(0, 3)),
        "breaking": bool(rng.random() < 0.2),
        "equalizing": bool(shooter == 1 and rng.random() < 0.3),
        "winner": -1,
    }


def row_of(state: dict) -> np.ndarray:
    return np.array(
        [state["shooter"], *state["score"], *state["innings"], state["run"],
         int(state["breaking"]), int(state["equalizing"]), state["winner"]],
        dtype=np.int64,
    )  # fmt: skip


def check(seed: int, n: int) -> None:
    """``n`` random outcomes in one vectorised call each side, compared row by row."""
    rng = np.random.default_rng(seed)
    target = int(rng.integers(1, 6))
    limit = int(rng.integers(0, 6))
    equalizing = bool(rng.random() < 0.5)
    players = int(rng.integers(1, 3))
    states = [random_state(rng, target, limit) for _ in range(n)]
    shots = [random_events(rng) for _ in range(n)]
    rack = np.stack([row_of(s) for s in states])
    first, second, cushions = np.empty(n, np.int64), np.empty(n, np.int64), np.empty(n, np.int64)
    for k, (state, events) in enumerate(zip(states, shots, strict=True)):
        rows = rows_of(events)
        cue = state["shooter"]
        first[k] = rows[BALL_FIRST_HIT, cue]
        second[k] = rows[BALL_SECOND_HIT, cue]
        cushions[k] = rows[BALL_CUSHIONS_AT_SECOND, cue]
    verdict = judge_rows(rack, first, second, cushions, target, limit, equalizing, players)
    for k, (state, events) in enumerate(zip(states, shots, strict=True)):
        want = judge_shot(state, events, target, limit, equalizing, players)
        context = (seed, k, state, events)
        assert rack[k].tolist() == row_of(want).tolist(), context
        assert bool(verdict.point[k]) == want["point"], context
        assert bool(verdict.foul[k]) == want["foul"], context
        assert bool(verdict.terminated[k]) == want["over"], context


@settings(max_examples=examples(100))
@given(seed=st.integers(0, 2**32 - 1))
def test_rules_equal_the_reference_on_random_outcomes(seed: int) -> None:
    """Hypothesis: each example a seed of 50 random outcomes under one set of options."""
    check(seed, 50)


def test_seeded_sweep_equals_the_reference() -> None:
    """A seeded sweep (``THREE_CUSHION_SWEEP`` outcomes, 2,000 by default)."""
    total = int(os.environ.get("THREE_CUSHION_SWEEP", "2000"))
    for seed in range(max(1, total // 1000)):
        check(10_000 + seed, min(1000, total))
    assert sc.N_RACK == 9
