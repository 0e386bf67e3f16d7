"""What the codec and the shot views take, and what they report.

Configs in every form, observations of the config's game, integer calls, and the executed
direction in [-pi, pi).
"""

from __future__ import annotations

import math
from typing import Any

import gymnasium as gym
import numpy as np
import pytest

from pool_env import (
    PoolEnv,
    PoolVectorEnv,
    Shot,
    decode_action,
    default_config,
    encode_action,
    obs_layout,
    shot_constraints,
)
from pool_env.game.codec import encode_ball, encode_placement, encode_pocket
from pool_env.game.config import make_config

NINE = "pool_env/NineBallGame-v2"


# --- obs_layout and shot_constraints take a config in every form, or refuse -----------------


def test_obs_layout_and_shot_constraints_take_a_config_in_every_form() -> None:
    env = gym.make(NINE)
    obs, _ = env.reset(seed=0)
    config = env.unwrapped.config
    vector = gym.make_vec(NINE, num_envs=2, vectorization_mode="vector_entry_point")
    forms = [config, env, env.unwrapped, vector, default_config(game="nine", scene="nine_ball",
             model="spin")]  # fmt: skip
    want_layout, want_rules = obs_layout(config), shot_constraints(config, obs)
    assert want_rules.breaking and want_rules.ball_in_hand and want_rules.first_balls == (1,)
    for form in forms:
        assert obs_layout(form) == want_layout
        assert shot_constraints(form, obs) == want_rules
    solitaire = default_config(scene="one_ball")
    assert obs_layout(solitaire) == {"balls": slice(0, 6)}


@pytest.mark.parametrize("given", [None, {"game": "nine"}, "nine", 3, PoolEnv])
def test_obs_layout_and_shot_constraints_refuse_anything_else_saying_what_they_take(
    given: Any,
) -> None:
    with pytest.raises(ValueError, match=r"obs_layout takes a GameConfig .* PoolConfig"):
        obs_layout(given)
    with pytest.raises(ValueError, match=r"shot_constraints takes a GameConfig .* env"):
        shot_constraints(given, np.zeros(48))


def test_shot_constraints_refuses_an_observation_of_another_game_of_the_same_size() -> None:
    nine = gym.make(NINE)
    nine_obs, _ = nine.reset(seed=0)
    solitaire = gym.make("pool_env/EightBall-v1")  # 15 balls: 48 entries, as 9-ball's
    for seed in range(5):
        fifteen, _ = solitaire.reset(seed=seed)
        assert fifteen.shape == nine_obs.shape
        with pytest.raises(ValueError, match="not an observation of this env"):
            shot_constraints(nine, fifteen)
    # And the other way: 9-ball's flags sit where 15-ball solitaire has balls.
    with pytest.raises(ValueError, match=r"no ball 10 of game='solitaire'"):
        shot_constraints(solitaire, nine_obs)


def test_shot_constraints_names_the_entry_that_no_observation_of_the_game_holds() -> None:
    env = gym.make(NINE)
    obs, _ = env.reset(seed=0)
    layout = obs_layout(env)
    cases = {
        layout["balls"].start: (1.5, r"observation\[0\] = 1.5 lies outside \[-1, 1\]"),
        layout["balls"].start + 5: (0.5, "no ball 1"),  # on_table of ball 1: a flag
        layout["legal"].start + 1: (0.5, "ball 2 may be hit first"),
        layout["fouls"].start: (0.25, "fouls"),
        layout["open_table"].start: (1.0, "open_table: 8-ball's"),
    }
    for index, (value, message) in cases.items():
        bad = obs.copy()
        bad[index] = value
        with pytest.raises(ValueError, match=message):
            shot_constraints(env, bad)
    pushing = obs.copy()  # the push-out offered to a viewer who does not shoot
    pushing[layout["push_out"].start], pushing[layout["to_shoot"].start] = 1.0, 0.0
    with pytest.raises(ValueError, match="push_out: only for the viewer to shoot"):
        shot_constraints(env, pushing)
    potted = obs.copy()  # a ball off the table reads (0, 0, 0): here flagged legal
    potted[3:6] = 0.0
    with pytest.raises(ValueError, match="ball 1 may be hit first"):
        shot_constraints(env, potted)


# --- Shot's integer calls and flags ----------------------------------------------------------


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"pocket": 2.5}, r"Shot.pocket must be an integer >= 0, got 2.5"),
        ({"pocket": True}, r"Shot.pocket must be an integer >= 0, got True"),
        ({"pocket": np.bool_(True)}, r"Shot.pocket must be an integer"),
        ({"pocket": -1}, r"Shot.pocket must be an integer >= 0, got -1"),
        ({"pocket": "2"}, r"Shot.pocket must be an integer"),
        ({"ball": 3.0}, r"Shot.ball must be an integer >= 1, got 3.0"),
        ({"ball": True}, r"Shot.ball must be an integer >= 1, got True"),
        ({"ball": 0}, r"Shot.ball must be an integer >= 1, got 0"),
        ({"push_out": 1}, r"Shot.push_out must be True or False, got 1"),
        ({"pass_back": "yes"}, r"Shot.pass_back must be True or False"),
    ],
)
def test_a_shot_refuses_calls_that_are_no_integers_or_flags(
    kwargs: dict[str, Any], message: str
) -> None:
    with pytest.raises(ValueError, match=message):
        Shot(0.0, 1.0, **kwargs)


def test_a_shot_takes_numpy_integers_as_python_ints() -> None:
    shot = Shot(0.0, 1.0, pocket=np.int64(2), ball=np.int32(3), push_out=np.bool_(True))
    assert (shot.pocket, shot.ball, shot.push_out) == (2, 3, True)
    assert type(shot.pocket) is int and type(shot.ball) is int and type(shot.push_out) is bool


def test_encoding_refuses_a_call_out_of_range_or_not_an_integer() -> None:
    ten = gym.make("pool_env/TenBallGameRoll-v1").unwrapped
    ten.reset(seed=0)
    args = (ten.positions, ten.on_table, ten.rack)
    with pytest.raises(ValueError, match=r"pocket must be an integer in 0\.\.5, got 6"):
        encode_action(ten.config, Shot(0.0, 9.0, pocket=6), *args)
    with pytest.raises(ValueError, match=r"the called ball must be an integer in 1\.\.10"):
        encode_action(ten.config, Shot(0.0, 9.0, ball=11), *args)
    for bad in (2.5, True, np.bool_(False)):
        with pytest.raises(ValueError, match=r"pocket must be an integer in 0\.\.5"):
            encode_pocket(ten.config, bad)  # type: ignore[arg-type]
        with pytest.raises(ValueError, match=r"the called ball must be an integer in 1\.\.10"):
            encode_ball(ten.config, bad)  # type: ignore[arg-type]
    assert encode_pocket(ten.config, np.int64(5)) == pytest.approx(5.0 / 6.0)


# --- the executed direction, in [-pi, pi) ---------------------------------------------------

#: The cue ball right of ball 1 on one line: the direction to it is pi, and a cut to its
#: counter-clockwise side turns beyond pi.
LEFTWARD = np.array([[1.5, 0.6], [1.0, 0.6]])


def _in_range(angle: float) -> bool:
    return -math.pi <= angle < math.pi


@pytest.mark.parametrize("noise", [None, (0.01, 0.0)])
def test_the_reported_angle_is_in_minus_pi_to_pi_on_the_single_and_the_vector_env(
    noise: Any,
) -> None:
    env = PoolEnv(scene="one_ball", noise=noise, model="roll")
    envs = PoolVectorEnv(3, scene="one_ball", noise=noise, model="roll")
    for seed in range(3):
        env.reset(seed=seed, options={"positions": LEFTWARD})
        envs.reset(seed=[seed, seed, seed], options={"positions": LEFTWARD})
        action = np.array([0.8, 0.0])  # a cut of 0.8 ball diameters, counter-clockwise
        shot = decode_action(env.config, action, LEFTWARD)
        info = env.step(action)[4]
        angle = info["angle"]
        cut = math.asin(0.8 * 2.0 * env.config.table.ball_radius / 0.5)
        assert _in_range(angle) and angle == pytest.approx(cut - math.pi, abs=0.05)
        assert env.last_strike[0] == angle  # the one direction, wherever it is read
        if noise is None:
            assert shot.angle == angle
        vector_info = envs.step(np.tile(action, (3, 1)))[4]
        assert vector_info["angle"].tolist() == [angle] * 3  # each table as the single env


def test_absolute_aim_at_plus_pi_is_reported_as_minus_pi() -> None:
    env = PoolEnv(scene="one_ball", aim="absolute", model="roll")
    env.reset(seed=0, options={"positions": LEFTWARD})
    info = env.step(np.array([1.0, 0.0]))[4]  # +1 maps to +pi: the same direction as -pi
    assert info["angle"] == -math.pi


def test_every_codec_function_takes_the_config_in_every_form() -> None:
    """encode_action, decode_action and the encoders read what obs_layout reads."""
    from pool_env.envs.multiagent import VersusPolicyEnv

    source = default_config(game="eight", scene="eight_ball", model="roll")
    parsed = make_config(source)
    positions = np.array([[0.5 + 0.1 * i, 0.3 + 0.05 * (i % 5)] for i in range(16)])
    shot = Shot(0.1, 2.0, pocket=3)
    want = encode_action(parsed, shot, positions)
    for form in (source, gym.make("pool_env/EightBallGameRoll-v1"), PoolEnv(config=source)):
        np.testing.assert_array_equal(encode_action(form, shot, positions), want)
        assert decode_action(form, want, positions).pocket == 3
        assert encode_pocket(form, 3) == encode_pocket(parsed, 3)
        assert encode_placement(form, (0.4, 0.5)) == encode_placement(parsed, (0.4, 0.5))
    versus = VersusPolicyEnv(game="eight", model="roll")
    assert obs_layout(versus) == obs_layout(versus.duel.config)
    sync = gym.make_vec("pool_env/NineBallGameRoll-v2", 2, vectorization_mode="sync")
    assert obs_layout(sync) == obs_layout(sync.envs[0].unwrapped.config)
    with pytest.raises(ValueError, match="encode_action takes a GameConfig"):
        encode_action({"game": "eight"}, shot, positions)
