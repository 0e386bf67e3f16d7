"""Baselines under the rules: the ghost-ball agent on the game ids, and the evaluation's counts."""

from __future__ import annotations

from typing import Any

import gymnasium as gym
import numpy as np
import pytest

import pool_env  # noqa: F401  (registers the ids)
from agents.baselines.game_agents import GameGhostBallAgent
from agents.baselines.ghost_ball import GhostBallAgent
from agents.evaluation.evaluate import run_episodes
from agents.evaluation.players import make_agent
from agents.evaluation.table import format_table
from pool_env.envs.registration import roll_id
from tests.game.test_games import KWARGS, layout, parked, straight_in

CUT = {k: v for k, v in KWARGS.items() if k != "aim"}  # the default cut aim


def _shoot(game: str, balls: dict, rules: dict | None = None) -> tuple[Any, dict, Any]:
    env = gym.make(roll_id("NineBallGame" if game == "nine" else "EightBallGame"), **CUT)
    obs, _ = env.reset(seed=0, options={**layout(game, balls), "rules": rules or {}})
    agent = GameGhostBallAgent(env)
    action, _ = agent.predict(obs)
    *_, info = env.step(action)
    return agent, info, action


def test_ghost_plays_the_ball_on_not_the_nearest_ball() -> None:
    # the 2 is nearer the cue ball and straight in too; the 1 is the ball on
    balls = {**straight_in(2, 0.45, 0.3), 1: (1.0, 0.6), 9: parked(1)}
    agent, info, _ = _shoot("nine", balls)
    assert agent.last_plan["kind"] == "ghost" and agent.last_plan["shot"].ball == 1
    assert info["first_contact"] == 1 and info["foul"] is None


def test_ghost_places_the_cue_ball_in_hand_for_a_pot() -> None:
    balls = {0: (0.3, 0.3), 1: (1.5, 0.9), 9: parked(1)}
    agent, info, action = _shoot("nine", balls, {"ball_in_hand": True})
    assert agent.last_plan["in_hand"] and agent.last_plan["kind"] == "ghost"
    assert info["foul"] is None and info["potted"] == (1,)
    assert np.any(action[2:4] != 0.0)


def test_ghost_calls_the_pocket_of_its_shot_on_the_eight() -> None:
    balls = {**straight_in(8), 11: parked(1)}
    agent, info, action = _shoot("eight", balls, {"groups": ("solids", "stripes")})
    shot = agent.last_plan["shot"]
    assert shot.ball == 8 and int((action[4] + 1) / 2 * 6) == shot.pocket
    assert info["winner"] == 0 and info["potted"] == (8,)


def test_evaluate_makes_the_rules_agent_for_a_game_id() -> None:
    env = gym.make("pool_env/NineBallGameRoll-v2")
    assert isinstance(make_agent("ghost", env), GameGhostBallAgent)
    assert type(make_agent("ghost", gym.make("pool_env/NineBallRoll-v1"))) is GhostBallAgent
    with pytest.raises(ValueError, match="game ids"):
        GameGhostBallAgent(gym.make("pool_env/NineBallRoll-v1"))


class _Scripted(gym.Env):
    """Plays back fixed step results (one rack per list), to check the counting."""

    observation_space = gym.spaces.Box(-1, 1, (1,), np.float32)
    action_space = gym.spaces.Box(-1, 1, (5,), np.float32)

    def __init__(self, racks: list[list[tuple[dict, bool]]]) -> None:
        self.racks, self.rack, self.t = racks, -1, 0

    def reset(self, *, seed: int | None = None, options: dict | None = None):
        self.rack, self.t = self.rack + 1, 0
        return np.zeros(1, np.float32), {}

    def step(self, action: Any):
        info, done = self.racks[self.rack][self.t]
        self.t += 1
        full = {"potted": (), "scratch": False, "is_success": False, "turn_over": False,
                "foul": None, **info}  # fmt: skip
        return np.zeros(1, np.float32), 0.0, done, False, full


class _Idle:
    def predict(self, obs: Any, deterministic: bool = True) -> tuple[Any, None]:
        return np.zeros(5, np.float32), None


def test_run_episodes_counts_fouls_racks_won_and_run_outs() -> None:
    pot = {"potted": (1,)}
    racks = [
        # a run-out: every shot keeps the table, the last wins
        [(pot, False), ({"potted": (9,), "is_success": True}, True)],
        # a foul, then the win: won, not a run-out
        [({"foul": "scratch", "scratch": True, "turn_over": True}, False),
         ({"potted": (9,), "is_success": True}, True)],
        # a legal miss then a lost rack (three fouls): not won
        [({"turn_over": True}, False),
         ({"foul": "no_contact", "turn_over": True, "winner": 1}, True)],
    ]  # fmt: skip
    log = run_episodes(_Idle(), _Scripted(racks), 3, seed=0)
    assert log.fouls == [0, 1, 1]
    assert log.cleared == [True, True, False] and log.run_out == [True, False, False]
    assert log.turns == [1, 2, 2]
    stats = log.summary()
    assert stats["fouls_per_shot"].value == 2 / 6
    assert "fouls/shot" in format_table({"idle": stats}, 3)
