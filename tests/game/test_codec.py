"""The action codec: it decodes as a step executes, and encoding inverts it."""

from __future__ import annotations

import math

import gymnasium as gym
import numpy as np
import pytest

import pool_env
from pool_env import PoolEnv, Shot, decode_action, encode_action

IDS = [
    "pool_env/OneBallRoll-v1",
    "pool_env/OneBall-v1",
    "pool_env/Pool-v1",
    "pool_env/NineBallGameRoll-v2",
    "pool_env/NineBallGame-v2",
    "pool_env/EightBallGame-v1",
]


def _before(env: PoolEnv) -> tuple:
    rack = env.rack if env.config.ruleset.has_rack else None
    return env.positions, env.on_table, rack


@pytest.mark.parametrize("aim", ["cut", "relative", "absolute"])
@pytest.mark.parametrize("env_id", IDS)
def test_decode_is_what_the_step_executes(env_id: str, aim: str) -> None:
    env = gym.make(env_id, aim=aim).unwrapped
    env.reset(seed=1)
    rng = np.random.default_rng(1)
    for _ in range(12):
        action = rng.uniform(-1.1, 1.1, env.action_space.shape)
        positions, on_table, rack = _before(env)
        shot = decode_action(env.config, action, positions, on_table, rack)
        _, _, terminated, truncated, info = env.step(action)
        assert (shot.angle, shot.speed) == (info["angle"], info["speed"])  # bit for bit
        assert shot.tip == info.get("tip", (0.0, 0.0)) == env.last_strike[2:]
        if terminated or truncated:
            env.reset()


@pytest.mark.parametrize("aim", ["cut", "relative", "absolute"])
@pytest.mark.parametrize("env_id", IDS)
def test_encode_inverts_decode(env_id: str, aim: str) -> None:
    env = gym.make(env_id, aim=aim).unwrapped
    env.reset(seed=2)
    config = env.config
    rng = np.random.default_rng(2)
    for _ in range(40):
        action = rng.uniform(-1.0, 1.0, env.action_space.shape)
        if config.spin:  # inside the miscue circle: the corners are clipped onto it
            action[-2:] *= 0.7
        positions, on_table, rack = _before(env)
        shot = decode_action(config, action, positions, on_table, rack)
        again = encode_action(config, shot, positions, on_table, rack)
        twice = decode_action(config, again, positions, on_table, rack)
        assert twice.angle == pytest.approx(shot.angle, abs=1e-9)
        assert twice.speed == pytest.approx(shot.speed, abs=1e-12)
        np.testing.assert_allclose(twice.tip, shot.tip, atol=1e-15)
        assert twice.pocket == shot.pocket and (twice.cue is None) == (shot.cue is None)
        calls = (shot.ball, shot.push_out, shot.pass_back)
        assert (twice.ball, twice.push_out, twice.pass_back) == calls
        if shot.cue is not None:
            np.testing.assert_allclose(twice.cue, shot.cue, rtol=0, atol=1e-12)
        keep = np.ones(action.shape, dtype=bool)
        if config.ruleset.has_rack:
            # a pocket's and a ball's bins, encoded as their middles; the option's sign
            keep[4 : config.ruleset.action_width] = False
            keep[2:4] = False  # a covered point moves to a free one: compared as shot.cue
        np.testing.assert_allclose(again[keep], action[keep], atol=1e-9)


def test_encode_plays_a_chosen_draw_shot() -> None:
    env = PoolEnv(scene="one_ball", end_on_miss=True, model="spin", aim="cut")
    env.reset(seed=0)
    cue, ball = env.positions
    angle = math.atan2(*(ball - cue)[::-1])  # straight at the ball: a full hit
    limit = env.config.tip_limit
    shot = Shot(angle=angle, speed=2.0, tip=(0.0, -limit))
    action = encode_action(env.config, shot, env.positions, env.on_table)
    np.testing.assert_allclose(
        action, [0.0, 2 * (2.0 - 0.45) / (4.5 - 0.45) - 1, 0, -1], atol=1e-12
    )
    env.step(action)
    assert env.last_strike == pytest.approx((angle, 2.0, 0.0, -limit), abs=1e-12)


def test_encode_refuses_what_the_action_cannot_play() -> None:
    spin = PoolEnv(scene=np.array([[0.5, 0.6], [1.0, 0.6]]), model="spin")
    spin.reset(seed=0)
    args = (spin.config, spin.positions[None][0], spin.on_table)
    limit = spin.config.tip_limit
    with pytest.raises(ValueError, match="tip limit"):
        encode_action(spin.config, Shot(0.0, 1.0, tip=(limit, 0.1)), *args[1:])
    clipped = encode_action(spin.config, Shot(0.0, 1.0, tip=(limit, limit)), *args[1:], clip=True)
    np.testing.assert_allclose(clipped[2:], [1 / math.sqrt(2)] * 2)
    with pytest.raises(ValueError, match="90 degrees"):
        encode_action(spin.config, Shot(math.pi, 1.0), *args[1:])  # away from the ball
    with pytest.raises(ValueError, match="speed"):
        encode_action(spin.config, Shot(0.0, 9.0), *args[1:])
    roll = PoolEnv(scene="one_ball", model="roll")
    roll.reset(seed=0)
    with pytest.raises(ValueError, match="needs a spin table"):
        encode_action(roll.config, Shot(0.0, 1.0, tip=(0.1, 0.0)), roll.positions)
    game = PoolEnv(scene="nine_ball", game="nine", model="roll")
    game.reset(seed=0)
    with pytest.raises(ValueError, match="pocket"):
        encode_action(game.config, Shot(0.0, 9.0, pocket=6), game.positions, rack=game.rack)
    with pytest.raises(ValueError, match="rack is for the rules"):
        encode_action(roll.config, Shot(0.0, 1.0), roll.positions, rack=game.rack)


@pytest.mark.parametrize("clip", [False, True])
@pytest.mark.parametrize(
    "shot",
    [
        Shot(0.0, 1.0, tip=(math.nan, 0.0)),
        Shot(0.0, 1.0, tip=(math.inf, 0.0)),
        Shot(0.0, 1.0, tip=(0.0, -math.inf)),
        Shot(0.0, math.nan),
        Shot(0.0, math.inf),
        Shot(math.nan, 1.0),
        Shot(0.0, 1.0, cue=(math.nan, 0.5)),
    ],
)
def test_encode_refuses_a_part_that_is_not_finite(shot: Shot, clip: bool) -> None:
    """NaN and infinities raise, with or without clip (clipping NaN gave a NaN action)."""
    game = PoolEnv(scene="nine_ball", game="nine", model="spin")
    game.reset(seed=0)
    with pytest.raises(ValueError, match="not a finite number"):
        encode_action(game.config, shot, game.positions, rack=game.rack, clip=clip)


def test_the_codec_is_public() -> None:
    assert {"Shot", "decode_action", "encode_action"} <= set(pool_env.__all__)
