"""The rules option ``push_out``: 9-ball with it (``-v2``) and without it (``-v1``)."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

from pool_env import default_config, obs_layout
from pool_env.game.config import make_config


@pytest.mark.parametrize(
    ("overrides", "message"),
    [
        ({"game": "eight", "push_out": True}, "push_out=True: game='eight' has no push-out"),
        ({"game": "ten", "push_out": False}, "only 9-ball is played without the push-out"),
        ({"game": "nine", "push_out": "no"}, "push_out"),
    ],
)
def test_a_push_out_the_game_cannot_play_is_refused(overrides: dict, message: str) -> None:
    scene = {"nine": "nine_ball", "ten": "ten_ball", "eight": "eight_ball"}[overrides["game"]]
    with pytest.raises(ValueError, match=message):
        make_config(default_config(scene=scene, **overrides))


@pytest.mark.parametrize(("game", "expected"), [("nine", True), ("ten", True), ("eight", False)])
def test_the_default_is_the_games_rule(game: str, expected: bool) -> None:
    config = make_config(default_config(scene=f"{game}_ball", game=game))
    assert config.rules.push_out is expected


def test_without_the_push_out_the_action_and_observation_lose_the_option() -> None:
    with_it = make_config(default_config(scene="nine_ball", game="nine"))
    without = make_config(default_config(scene="nine_ball", game="nine", push_out=False))
    assert without.action_size == with_it.action_size - 1
    assert without.observation_size == with_it.observation_size - 2
    assert {"push_out", "option"} <= set(obs_layout(with_it))
    assert not {"push_out", "option"} & set(obs_layout(without))
    assert "push_out" not in without.ruleset.info_keys


@pytest.mark.parametrize(("env_id", "offered"), [
    ("pool_env/NineBallGameRoll-v2", True), ("pool_env/NineBallGameRoll-v1", False),
])  # fmt: skip
def test_after_a_legal_break_only_v2_offers_the_push_out(env_id: str, offered: bool) -> None:
    env = gym.make(env_id, aim="absolute").unwrapped
    for seed in range(40):  # random breaks until one is legal and keeps the table
        env.reset(seed=seed)
        action = np.zeros(env.action_space.shape, dtype=np.float32)
        action[1] = 1.0  # the hardest break, straight up the table at the 1
        _, _, terminated, _, info = env.step(action)
        if not info["foul"] and not terminated and env.rack["shooter"] == 0:
            break
    else:
        pytest.fail("no legal break in 40 seeds")
    assert env.rack["push_out"] is offered
    assert ("push_out" in info) is offered
