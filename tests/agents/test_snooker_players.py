"""The snooker players: the ghost-ball player's pots and nominations, legal actions, usage.

Both players' actions on both levels, the search's reading of the frame, the D, and the
evaluation command's refusals.
"""

from __future__ import annotations

from typing import Any

import gymnasium as gym
import numpy as np
import pytest

import pool_env  # noqa: F401  (registers the ids)
from agents.baselines.snooker_play import COLOURS, SnookerGhostBallAgent, TheD, phase_of
from agents.baselines.snooker_search import SnookerSearchAgent
from pool_env import decode_action, shot_constraints
from tests.repo.test_usage_errors import assert_usage_error, run

BREAK_IDS = ("pool_env/SnookerBreak-v1", "pool_env/SnookerBreakRoll-v1")
N = 22
BLACK, PINK, YELLOW = 21, 20, 16


def _spots(env: Any) -> np.ndarray:
    """The frame's layout (colours on their spots), read from the game's own scene."""
    env.reset(seed=0)
    return env.unwrapped.positions


def _reset(env: Any, balls: dict[int, tuple[float, float]], rules: dict[str, Any]) -> Any:
    """Reset to the colours on their spots, the balls of ``balls`` moved, the others off."""
    positions = _spots(env)
    on = np.zeros(N, dtype=bool)
    on[[0, *COLOURS]] = True
    for j, point in balls.items():
        positions[j] = point
        on[j] = True
    obs, _ = env.reset(seed=0, options={"positions": positions, "on_table": on, "rules": rules})
    return obs


def _along(env: Any, pocket: int, *distances: float) -> list[tuple[float, float]]:
    """Points on the line from ``pocket``'s centre into the table towards its centre."""
    table = env.unwrapped.config.table
    p = table.pockets[pocket, :2]
    u = np.array([table.length / 2.0, table.width / 2.0]) - p
    u /= np.hypot(*u)
    return [tuple(p + s * u) for s in distances]


def _corner(env: Any) -> int:
    """The top corner pocket at ``y`` low (the far end from the D)."""
    t = env.unwrapped.config.table
    return int(np.argmin(np.hypot(t.pockets[:, 0] - t.length, t.pockets[:, 1])))


@pytest.mark.parametrize("env_id", BREAK_IDS)
def test_ghost_pots_a_straight_red_at_no_noise(env_id: str) -> None:
    env = gym.make(env_id)
    red, cue = _along(env, _corner(env), 0.35, 0.85)
    obs = _reset(env, {0: cue, 1: red}, {"ball_in_hand": False})
    agent = SnookerGhostBallAgent(env)
    action, _ = agent.predict(obs)
    *_, info = env.step(action)
    assert agent.last_plan["kind"] == "ghost" and agent.last_plan["shot"].ball == 1
    assert info["potted"] == (1,) and info["foul"] is None and info["points"] == 1
    assert env.unwrapped.rack["phase"] == "colour"  # the visit goes on, a colour on


def _colour_case(env: Any) -> Any:
    """A colour on; the black boxed in by reds, the yellow nearer and easier than the pink.

    From the cue ball, the pink is straight into the top corner pocket at ``y = 0`` half a
    metre away, the yellow straight into the other top corner pocket 15 cm away (a shorter
    cue-ball path: the more forgiving pot; both within the cut aim's reach of the nearest
    colour); six reds touch the black all round (no pot).
    """
    table = env.unwrapped.config.table
    r = table.ball_radius
    cue = np.array([2.4, 0.6]) * table.length / 3.569
    balls = {0: tuple(cue)}
    for ball, corner, distance in ((PINK, (table.length, 0.0), 0.5),
                                   (YELLOW, (table.length, table.width), 0.15)):  # fmt: skip
        u = np.array(corner) - cue
        balls[ball] = tuple(cue + distance * u / np.hypot(*u))
    black = (table.length - 0.324, table.width / 2.0)
    balls[BLACK] = black
    for k in range(6):
        a = k * np.pi / 3.0
        balls[1 + k] = (black[0] + 2.02 * r * np.cos(a), black[1] + 2.02 * r * np.sin(a))
    return _reset(env, balls, {"phase": "colour", "ball_in_hand": False})


def test_ghost_nominates_the_highest_colour_it_can_pot() -> None:
    # absolute aim: the ids' cut aim strikes only the nearest colour (the yellow here)
    env = gym.make("pool_env/SnookerBreakRoll-v1", aim="absolute")
    obs = _colour_case(env)
    agent = SnookerGhostBallAgent(env)
    on = env.unwrapped.on_table
    rules = shot_constraints(env.unwrapped.config, obs)
    _, reference = agent.balls_on(rules, "colour", on)
    positions = env.unwrapped.positions
    # the yellow is the easier pot, the black none: value x chance picks the pink
    assert agent.best_pot(positions, on, reference, BLACK) == 0.0
    assert agent.best_pot(positions, on, reference, YELLOW) > 0.99
    assert 0.0 < agent.best_pot(positions, on, reference, PINK) < 1.0
    action, _ = agent.predict(obs)
    assert agent.last_plan["colour"] == PINK
    shot = decode_action(env.unwrapped.config, action, positions, on, env.unwrapped.rack)
    assert shot.ball == PINK
    *_, info = env.step(action)
    assert info["nominated"] == PINK and info["potted"] == (PINK,) and info["points"] == 6


def _assert_legal(env: Any, agent: Any, visits: int) -> int:
    """Play ``visits`` visits; every action in the space, every nomination a colour on."""
    config = env.unwrapped.config
    shots = 0
    for seed in range(visits):
        obs, _ = env.reset(seed=seed)
        done = False
        while not done:
            action, _ = agent.predict(obs)
            assert env.action_space.contains(action), action
            if phase_of(config, obs) == "colour":
                u = env.unwrapped
                shot = decode_action(config, action, u.positions, u.on_table, u.rack)
                assert shot.ball in COLOURS and u.on_table[shot.ball], shot
            obs, _, terminated, truncated, _ = env.step(action)
            shots += 1
            done = terminated or truncated
    return shots


@pytest.mark.parametrize("env_id", BREAK_IDS)
def test_both_players_act_legally(env_id: str) -> None:
    env = gym.make(env_id, noise=("fastfiz", 1.0))
    assert _assert_legal(env, SnookerGhostBallAgent(env), 4) >= 4
    search = SnookerSearchAgent(env, budget=0.2, samples=4)
    assert _assert_legal(env, search, 3) >= 3


def test_search_pots_the_straight_red_and_reads_the_frame_from_the_observation() -> None:
    env = gym.make("pool_env/SnookerBreak-v1")
    red, cue = _along(env, _corner(env), 0.35, 0.85)
    obs = _reset(env, {0: cue, 1: red}, {"ball_in_hand": False, "break": 12, "score_0": 30})
    search = SnookerSearchAgent(env)
    row = search.rack_row(obs)
    assert env.unwrapped.config.ruleset.state_dict(row) == {**env.unwrapped.rack}
    action, _ = search.predict(obs)
    *_, info = env.step(action)
    assert info["potted"] == (1,) and info["break"] == 13
    assert search.last_plan["rounds"] == 1  # no noise: one exact play of each candidate


def test_the_d_points_lie_in_the_d() -> None:
    env = gym.make("pool_env/SnookerBreakRoll-v1")
    obs, _ = env.reset(seed=3)
    d = TheD.of(shot_constraints(env.unwrapped.config, obs))
    points = d.grid()
    assert points and all(d.contains(p) for p in points)
    assert not d.contains(np.array([d.baulk_x + 0.01, d.centre_y]))
    assert not d.contains(np.array([d.baulk_x - 0.5 * d.radius, d.centre_y + d.radius]))


def test_players_refuse_other_games_and_bad_settings() -> None:
    env = gym.make("pool_env/NineBallGameRoll-v2")
    with pytest.raises(ValueError, match=r"game='snooker'.*'nine'"):
        SnookerGhostBallAgent(env)
    snooker = gym.make("pool_env/SnookerBreakRoll-v1")
    with pytest.raises(ValueError, match=r"budget.*-1"):
        SnookerSearchAgent(snooker, budget=-1.0)
    with pytest.raises(ValueError, match=r"samples.*2\.5"):
        SnookerSearchAgent(snooker, samples=2.5)  # type: ignore[arg-type]


@pytest.mark.parametrize(
    ("args", "words"),
    [
        (["--visits", "0"], ["--visits", "0"]),
        (["--players", "ghost", "champion"], ["--players", "champion", "search"]),
        (["--noise", "fastfiz:x"], ["--noise", "fastfiz:x"]),
        (["--env", "pool_env/NineBallGame-v2"], ["--env", "NineBallGame"]),
        (["--budget", "0"], ["--budget", "0"]),
        (["--visitz", "3"], ["unrecognized", "--visitz"]),
    ],
)
def test_the_evaluation_refuses_bad_usage(args: list[str], words: list[str]) -> None:
    assert_usage_error(run(["-m", "agents.evaluation.snooker", *args]), *words)


def test_under_the_cut_aim_the_ghost_nominates_the_nearest_colour() -> None:
    env = gym.make("pool_env/SnookerBreakRoll-v1")  # cut aim: the pink cannot be struck
    obs = _colour_case(env)
    agent = SnookerGhostBallAgent(env)
    action, _ = agent.predict(obs)
    assert agent.last_plan["colour"] == YELLOW
    *_, info = env.step(action)
    assert info["nominated"] == YELLOW and info["potted"] == (YELLOW,) and info["points"] == 2
