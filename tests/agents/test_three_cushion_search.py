"""The three-cushion search player: its point test, its shots, its budget, its refusals."""

from __future__ import annotations

import math
import time
from dataclasses import replace

import gymnasium as gym
import numpy as np
import pytest

from agents.baselines.carom import near_scores, noisy_rows, point_of_events, points_of_rows
from agents.baselines.random_agent import RandomAgent
from agents.baselines.three_cushion_agent import ThreeCushionSearchAgent
from agents.baselines.three_cushion_search import ThreeCushionSearch
from agents.evaluation.three_cushion import ENV_ID, main, play_innings, random_layout
from pool_env import Event, Table, shoot
from pool_env.game.checks import default_tip_limit
from pool_env.game.games.three_cushion.layout import starting_layout
from pool_env.game.noise import fastfiz_sigmas
from pool_env.sim import rollout

TABLE = Table.preset("carom")


def _random_rows(rng: np.random.Generator, n: int) -> np.ndarray:
    rows = np.zeros((n, 5))
    rows[:, 0] = rng.uniform(0.0, 2.0 * math.pi, n)
    rows[:, 1] = rng.uniform(1.0, 6.0, n)
    rows[:, 2:4] = rng.uniform(-0.45, 0.45, (n, 2))
    return rows


@pytest.mark.parametrize("cue", [0, 1])
def test_the_rows_point_equals_the_event_log_recount(cue: int) -> None:
    """The rollout rows' point equals the recount over each shot's event log.

    From random layouts: the search grid's points, its near misses (both balls met after
    fewer cushions) and random shots, compared shot by shot.
    """
    rng = np.random.default_rng(cue)
    grid = ThreeCushionSearch(TABLE, budget=0.5)._grid
    kinds = np.zeros(3, dtype=np.int64)  # points, near misses, others compared
    for _ in range(4):
        pos = random_layout(TABLE, rng)
        out = rollout(TABLE, pos, grid, cue=cue)
        near = near_scores(out, cue)
        picked = [rng.permutation(np.flatnonzero(near == v))[:40] for v in (3.0, 2.0, 1.0)]
        rows = np.concatenate([grid[np.concatenate(picked)], _random_rows(rng, 40)])
        fast = points_of_rows(rollout(TABLE, pos, rows, cue=cue), cue)
        slow = [
            point_of_events(shoot(TABLE, pos, r[0], r[1], cue=cue, tip=(r[2], r[3])).events, cue)
            for r in rows
        ]
        assert fast.tolist() == slow
        kinds += [int(fast.sum()), sum(len(p) for p in picked[1:]), 40]
    assert kinds[0] >= 20  # the comparison saw points, not only misses
    assert kinds[1] >= 20  # and carom shots one or two cushions short


def _event(time: float, kind: str, i: int, j: int) -> Event:
    return Event(time=time, kind=kind, i=i, j=j)  # type: ignore[arg-type]


def test_the_event_log_point_counts_cushions_up_to_the_second_ball() -> None:
    """Three cushions before the second ball score; one after it does not count.

    A cushion at the very time of the second contact counts (pooltool's ``time <=``); the
    same ball met twice is one ball.
    """
    c = [_event(0.1 * k, "cushion", 0, k % 4) for k in range(1, 4)]
    first, second = _event(0.05, "ball", 0, 2), _event(0.35, "ball", 0, 1)
    assert point_of_events([first, *c, second], 0)
    assert not point_of_events([first, *c[:2], second, replace(c[2], time=0.4)], 0)
    assert point_of_events([first, *c[:2], second, replace(c[2], time=0.35)], 0)
    again = _event(0.35, "ball", 0, 2)
    assert not point_of_events([first, *c, again], 0)
    # The other cue ball's cushions and contacts are not the striker's.
    assert not point_of_events([first, *(replace(e, i=1) for e in c), second], 0)
    assert point_of_events([_event(0.05, "ball", 1, 2), *(replace(e, i=1) for e in c),
                            _event(0.35, "ball", 0, 1)], 1)  # fmt: skip


def test_the_player_scores_from_the_break_without_noise() -> None:
    """From the UMB break (the red first) the chosen shot scores when played exactly.

    Played on the recorded simulator: a point the event log confirms.
    """
    player = ThreeCushionSearch(TABLE, noise=None, budget=2.0, seed=0)
    pos = starting_layout(TABLE)
    plan = player.plan(pos, cue=0, first_ball=2)
    assert plan.kind == "point"
    result = shoot(TABLE, pos, plan.angle, plan.speed, cue=0, tip=plan.tip)
    assert point_of_events(result.events, 0)
    assert int(result.first_hit[0]) == 2


def test_the_player_scores_under_noise_from_an_easy_layout() -> None:
    """Yellow's cue ball, an open layout, FastFiz x1: the chosen shot mostly scores.

    In most of 64 noisy replays judged on the event log (its own estimate says so too).
    """
    sigmas = fastfiz_sigmas(TABLE, 1.0)
    pos = np.array([[2.2, 1.0], [0.6, 0.4], [1.5, 0.9]])
    plan = ThreeCushionSearch(TABLE, noise=sigmas, budget=2.0, seed=1).plan(pos, cue=1)
    assert plan.kind == "point"
    assert plan.success >= 0.6
    draws = np.random.default_rng(5).standard_normal((64, 4))
    rows = noisy_rows(plan.row[None], draws, sigmas, default_tip_limit(TABLE))
    scored = [
        point_of_events(shoot(TABLE, pos, r[0], r[1], cue=1, tip=(r[2], r[3])).events, 1)
        for r in rows
    ]
    assert np.mean(scored) >= 0.5


def test_the_budget_is_kept_loosely() -> None:
    """A 0.3 s budget ends well within a generous bound (speed is the bench's business)."""
    player = ThreeCushionSearch(TABLE, noise=fastfiz_sigmas(TABLE, 5.0), budget=0.3, seed=2)
    pos = random_layout(TABLE, np.random.default_rng(3))
    start = time.perf_counter()
    plan = player.plan(pos, cue=0)
    assert time.perf_counter() - start < 3.0
    assert plan.seconds < 3.0
    assert plan.stages[0] == "grid"


@pytest.mark.parametrize("aim", ["absolute", "cut"])
def test_the_agent_scores_through_the_env(aim: str) -> None:
    """Through the env's action, without noise, the planned point is the env's point.

    From the break (the red first) under absolute aim, and from an open layout under the
    id's cut aim (only the cone at the nearest ball can be expressed).
    """
    env = gym.make(ENV_ID, noise=("fastfiz", 0), aim=aim)
    options = None
    if aim == "cut":
        options = {"positions": [[2.2, 1.0], [0.6, 0.4], [1.5, 0.9]]}
    obs, _ = env.reset(seed=0, options=options)
    agent = ThreeCushionSearchAgent(env, budget=1.0, seed=0)
    action, _ = agent.predict(obs)
    assert agent.last_plan["kind"] == "point"
    _, reward, _, _, info = env.step(action)
    assert info["point"]
    assert info["foul"] == ""
    assert reward == 1.0


def test_an_inning_counts_the_env_points_and_ends() -> None:
    """Random actions from the break: each inning ends, its points its shots less the last.

    An inning runs until its first miss (the truncation at 100 shots is not reached).
    """
    env = gym.make(ENV_ID, noise=("fastfiz", 1), aim="absolute")
    logs = play_innings(env, RandomAgent(env, seed=0), "break", 5, seed=0)
    assert len(logs) == 5
    for log in logs:
        assert log.shots >= 1
        assert log.points == log.shots - 1  # an inning runs until its first miss
        assert not log.truncated
        assert not log.target
    with pytest.raises(ValueError, match="layout"):
        play_innings(env, RandomAgent(env, seed=0), "rack", 1, seed=0)


def test_the_agent_refuses_another_game() -> None:
    env = gym.make("pool_env/OneBall-v1")
    with pytest.raises(ValueError, match="three_cushion"):
        ThreeCushionSearchAgent(env)


@pytest.mark.parametrize(
    ("kwargs", "words"),
    [
        ({"table": Table(model="roll")}, "spin"),
        ({"budget": 0.0}, "budget"),
        ({"budget": math.inf}, "budget"),
        ({"threads": 0}, "threads"),
        ({"threads": True}, "threads"),
        ({"speed_range": (3.0, 2.0)}, "speed_range"),
        ({"tip_limit": 1.5}, "tip_limit"),
        ({"noise": (0.1, 0.1)}, "noise"),
        ({"noise": (0.1, -0.1, 0.0)}, "noise"),
    ],
)
def test_bad_settings_are_refused(kwargs: dict, words: str) -> None:
    with pytest.raises(ValueError, match=words):
        ThreeCushionSearch(**kwargs)


@pytest.mark.parametrize(
    ("args", "words"),
    [
        ((np.zeros((2, 2)), 0, None), "positions"),
        ((None, 2, None), "cue"),
        ((None, True, None), "cue"),
        ((None, 0, 0), "first_ball"),
        ((None, 0, 5), "first_ball"),
        ((None, 0, None, (1.0, 0.5)), "aim_window"),
        ((None, 0, None, (0.0, 7.0)), "aim_window"),
    ],
)
def test_bad_plans_are_refused(args: tuple, words: str) -> None:
    player = ThreeCushionSearch(TABLE, budget=0.1)
    pos = starting_layout(TABLE) if args[0] is None else args[0]
    with pytest.raises(ValueError, match=words):
        player.plan(pos, *args[1:])


def test_the_command_refuses_bad_flags(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit):
        main(["--innings", "0"])
    assert "--innings must be one count >= 1" in capsys.readouterr().err
