"""PoolEnv behaviour: shots, rewards, episode ends, determinism, bad input, pickling, workers."""

from __future__ import annotations

import math
import pickle

import gymnasium as gym
import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import pool_env
from pool_env import PoolEnv, Table, check_layout
from pool_env.envs.registration import ENV_IDS, GAME_IDS
from pool_env.game.config import DEFAULT_SPEED_RANGE
from pool_env.sim.layouts import head_spot
from tests.profiles import examples

TABLE = Table()
R = TABLE.ball_radius
HEAD = head_spot(TABLE)

# Object ball 0.42 m from the bottom-left corner pocket, cue ball behind it on the diagonal.
STRAIGHT_POT = np.array([[0.6, 0.6], [0.3, 0.3]])
TO_CORNER = -0.75  # absolute aim: action -0.75 is -135 degrees, down the diagonal


def _speed_action(
    speed: float, low: float = DEFAULT_SPEED_RANGE[0], high: float = DEFAULT_SPEED_RANGE[1]
) -> float:
    return 2.0 * (speed - low) / (high - low) - 1.0


FIRM = _speed_action(1.45)  # the speed action of 1.45 m/s


def _env(**kwargs: object) -> PoolEnv:
    """A PoolEnv on the roll table (``TABLE``'s), unless told otherwise.

    The shots and figures below are worked out on it, the cheap model for the env's logic.
    """
    return PoolEnv(**{"model": "roll", **kwargs})  # type: ignore[arg-type]


@pytest.mark.parametrize("aim", ["relative", "cut", "absolute"])
def test_a_straight_pot_scores_one_and_clears_the_table(aim: str) -> None:
    env = _env(scene=STRAIGHT_POT, aim=aim)
    obs, info = env.reset(seed=0)
    assert info == {}
    assert obs[5] == 1.0
    aim_action = TO_CORNER if aim == "absolute" else 0.0  # relative and cut: a full hit
    obs, reward, terminated, truncated, info = env.step(np.array([aim_action, FIRM]))
    assert reward == 1.0
    assert obs[3:].tolist() == [0.0, 0.0, 0.0]  # ball 1 potted: flag 0, position zeroed
    assert terminated
    assert not truncated
    assert info["potted"] == (1,)
    assert info["first_contact"] == 1
    assert info["is_success"]
    assert not info["scratch"]
    assert info["angle"] == pytest.approx(-0.75 * math.pi)
    assert info["speed"] == pytest.approx(1.45)
    assert not env.on_table[1]
    assert env.on_table[0]


def test_a_scratch_costs_one_and_returns_the_cue_ball_to_the_head_spot() -> None:
    env = _env(scene=np.array([[0.3, 0.3], [2.0, 1.0]]), aim="absolute")
    env.reset(seed=0)
    obs, reward, terminated, _, info = env.step(np.array([TO_CORNER, FIRM]))
    assert reward == -1.0
    assert info["scratch"]
    assert info["potted"] == ()
    assert info["first_contact"] == -1
    assert not terminated
    np.testing.assert_array_equal(env.positions[0], HEAD)
    np.testing.assert_allclose(obs[:3], [-0.5, 0.0, 1.0])
    np.testing.assert_array_equal(env.positions[1], [2.0, 1.0])  # untouched


def test_a_scratch_with_the_head_spot_taken_uses_the_nearest_free_point() -> None:
    env = _env(scene=np.array([[0.3, 0.3], HEAD]), aim="absolute")
    env.reset(seed=0)
    _, reward, _, _, info = env.step(np.array([TO_CORNER, FIRM]))
    assert info["scratch"]
    assert reward == -1.0
    cue = env.positions[0]
    assert np.hypot(*(cue - HEAD)) == pytest.approx(2 * R, abs=1e-6)
    check_layout(TABLE, env.positions)


def test_a_pot_and_a_scratch_in_one_shot_add_up() -> None:
    # A slight cut at 6 m/s: the object ball drops, the deflected cue ball finds a pocket too.
    # The scene was laid out for the capture-circle table and the old speed range.
    env = _env(
        scene=np.array([[0.6, 0.6], [0.3, 0.3], [2.2, 1.0]]),
        aim="absolute",
        table={"pockets": "circles", "e_cushion": 0.85},
        speed_range=(0.5, 10.0),
    )
    env.reset(seed=0)
    _, reward, terminated, _, info = env.step(np.array([-0.745, _speed_action(6.0, 0.5, 10.0)]))
    assert info["potted"] == (1,)
    assert info["scratch"]
    assert reward == 0.0
    assert not terminated


def test_aim_zero_hits_the_nearest_object_ball_full() -> None:
    layout = np.array([[1.0, 0.6], [1.6, 0.9], [1.3, 0.5], [0.5, 0.2]])  # ball 2 is nearest
    for aim in ("relative", "cut"):
        env = _env(scene=layout, aim=aim)
        env.reset(seed=0)
        *_, info = env.step(np.array([0.0, -0.9]))
        assert info["first_contact"] == 2
        assert info["angle"] == pytest.approx(math.atan2(-0.1, 0.3))


def test_end_on_miss_ends_the_episode_on_a_shot_that_pots_nothing() -> None:
    layout = np.array([[1.0, 0.6], [1.6, 0.9]])
    for end_on_miss in (False, True):
        env = _env(scene=layout, aim="absolute", end_on_miss=end_on_miss)
        env.reset(seed=0)
        _, reward, terminated, _, info = env.step(np.array([0.5, -0.95]))  # straight up, soft
        assert reward == 0.0
        assert info["potted"] == ()
        assert terminated is end_on_miss


def test_max_shots_truncates_the_raw_env() -> None:
    env = _env(table={"pockets": "none"}, max_shots=3)  # nothing can drop: never terminates
    env.reset(seed=0)
    ends = [env.step(np.array([0.0, 0.0]))[2:4] for _ in range(3)]
    assert ends == [(False, False), (False, False), (False, True)]
    env.reset()
    assert env.shots == 0
    assert env.step(np.array([0.0, 0.0]))[3] is False


def test_time_limit_truncates_through_make() -> None:
    env = gym.make("pool_env/PoolRoll-v1", table={"pockets": "none"}, max_episode_steps=4)
    env.reset(seed=1)
    truncated = [env.step(env.action_space.sample())[3] for _ in range(4)]
    assert truncated == [False, False, False, True]
    assert (
        gym.make("pool_env/PoolRoll-v1").spec.max_episode_steps
        == ENV_IDS["pool_env/PoolRoll-v1"][1]
    )


def test_reward_options_no_contact_and_shaping() -> None:
    layout = np.array([[1.0, 0.6], [1.6, 0.9]])
    env = _env(scene=layout, aim="absolute", reward_no_contact=-0.5, reward_shaping=1.0)
    env.reset(seed=0)
    _, reward, *_ = env.step(np.array([0.5, -0.95]))  # misses ball 1, which stays put
    assert reward == -0.5
    # A straight pot gains the ball's distance to its nearest pocket over the diagonal.
    env = _env(scene=STRAIGHT_POT, aim="absolute", reward_shaping=1.0)
    env.reset(seed=0)
    _, reward, *_ = env.step(np.array([TO_CORNER, FIRM]))
    gain = math.hypot(0.3, 0.3) / math.hypot(TABLE.length, TABLE.width)
    assert reward == pytest.approx(1.0 + gain)


def test_noise_perturbs_the_shot_reproducibly() -> None:
    clean, noisy = _env(aim="absolute"), _env(aim="absolute", noise=(0.02, 0.01))
    angles = []
    for env in (clean, noisy, _env(aim="absolute", noise=(0.02, 0.01))):
        env.reset(seed=5)
        angles.append(env.step(np.array([0.2, 0.0]))[4]["angle"])
    assert angles[0] == pytest.approx(0.2 * math.pi)
    assert angles[1] != angles[0]
    assert angles[1] == angles[2]
    assert abs(angles[1] - angles[0]) < 0.1


def test_nan_action_raises_and_changes_nothing() -> None:
    env = _env(scene="nine_ball", noise=(0.01, 0.1))
    env.reset(seed=3)
    env.step(np.array([0.0, 0.5]))
    before = pickle.dumps(env)
    positions, on_table, shots = env.positions, env.on_table, env.shots
    rng_state = env.np_random.bit_generator.state
    for bad in ([np.nan, 0.0], [0.3, np.nan], np.array([np.nan, np.nan], np.float32)):
        with pytest.raises(ValueError, match="NaN"):
            env.step(bad)
    np.testing.assert_array_equal(env.positions, positions)
    np.testing.assert_array_equal(env.on_table, on_table)
    assert env.shots == shots
    assert env.np_random.bit_generator.state == rng_state
    after = pickle.loads(before)  # and the env still plays exactly as an untouched copy
    assert _same(env.step([0.1, 0.1]), after.step([0.1, 0.1]))


def test_out_of_range_actions_are_clipped() -> None:
    results = []
    for action in ([1.0, -1.0], [5.0, -7.0], [np.inf, -np.inf]):
        env = _env(scene="random", n_balls=4)
        env.reset(seed=11)
        results.append(env.step(np.array(action)))
    assert _same(results[0], results[1])
    assert _same(results[0], results[2])


def test_bad_action_shape_raises() -> None:
    env = _env()
    env.reset(seed=0)
    with pytest.raises(ValueError, match="shape"):
        env.step(np.zeros(3))
    with pytest.raises(RuntimeError, match="reset"):
        _env().step(np.zeros(2))


@pytest.mark.parametrize(
    ("kwargs", "name"),
    [
        ({"aim": "sideways"}, "aim"),
        ({"aim_range": (1.0, -1.0)}, "aim_range"),
        ({"speed_range": (-1.0, 2.0)}, "speed_range"),
        ({"speed_range": (1.0,)}, "speed_range"),
        ({"noise": (-0.1, 0.0)}, "noise"),
        ({"noise": (0.1,)}, "noise"),
        ({"end_on_miss": "yes"}, "end_on_miss"),
        ({"max_shots": 0}, "max_shots"),
        ({"reward_pot": "a lot"}, "reward_pot"),
        ({"reward_scratch": math.nan}, "reward_scratch"),
        ({"render_mode": "ascii"}, "render_mode"),
        ({"render_width": -5}, "render_width"),
        ({"render_width": 10}, "render_width"),
        ({"table": "big"}, "table"),
        ({"table": {"lenght": 3.0}}, "table"),
        ({"scene": "snooker"}, "scene"),
        ({"scene": "nine_ball", "n_balls": 4}, "n_balls"),
        ({"n_balls": 40}, "n_balls"),
    ],
)
def test_bad_arguments_raise_value_errors_naming_them(kwargs: dict, name: str) -> None:
    with pytest.raises(ValueError, match=name):
        _env(**kwargs)


def test_an_impossible_scene_fails_at_make_with_a_clear_error() -> None:
    tiny = {"length": 0.2, "width": 0.2, "pockets": "none"}
    with pytest.raises(
        ValueError, match=r"scene='random', n_balls=15: cannot lay out.*fewer balls"
    ):
        gym.make("pool_env/PoolRoll-v1", table=tiny, n_balls=15)


def test_reset_options_start_from_a_given_layout() -> None:
    env = _env(n_balls=2)
    layout = np.array([[0.5, 0.5], [1.0, 0.5], [2.0, 0.8]])
    obs, _ = env.reset(seed=0, options={"positions": layout, "on_table": [True, False, True]})
    np.testing.assert_array_equal(env.positions, layout)
    assert obs[5] == 0.0
    assert obs[8] == 1.0
    bad_options = [
        {"positions": layout[:2]},
        {"positions": layout, "on_table": [False, True, True]},
        {"positions": [[0.5, 0.5], [0.51, 0.5], [2.0, 0.8]]},
        {"on_table": [True, True, True]},
        {"layout": layout},
    ]
    for options in bad_options:
        with pytest.raises(ValueError, match=r"options|overlap"):
            env.reset(options=options)


def _same(a: tuple, b: tuple) -> bool:
    """Exact equality of two step (or reset) results."""
    if len(a) != len(b):
        return False
    for x, y in zip(a, b, strict=True):
        if isinstance(x, np.ndarray):
            if not np.array_equal(x, y):
                return False
        elif x != y:
            return False
    return True


def _rollout(env: gym.Env, seed: int, steps: int) -> list[tuple]:
    out: list[tuple] = [env.reset(seed=seed)]
    env.action_space.seed(seed)
    for _ in range(steps):
        result = env.step(env.action_space.sample())
        out.append(result)
        if result[2] or result[3]:
            out.append(env.reset())
    return out


@pytest.mark.parametrize("env_id", list(ENV_IDS))
def test_same_seed_same_rollout_exactly(env_id: str) -> None:
    kwargs = {"noise": (0.01, 0.05)}
    a = _rollout(gym.make(env_id, **kwargs), 42, 60)
    b = _rollout(gym.make(env_id, **kwargs), 42, 60)
    c = _rollout(gym.make(env_id, **kwargs), 43, 60)
    assert all(_same(x, y) for x, y in zip(a, b, strict=True))
    assert not all(_same(x, y) for x, y in zip(a, c, strict=False))


@settings(max_examples=examples(25), deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    seed=st.integers(0, 2**31 - 1),
    env_id=st.sampled_from([i for i in ENV_IDS if i not in GAME_IDS]),  # solitaire rewards
    aim=st.sampled_from(["relative", "cut", "absolute"]),
)
def test_long_random_rollouts_stay_in_the_observation_space(
    seed: int, env_id: str, aim: str
) -> None:
    env = gym.make(env_id, aim=aim)
    raw = env.unwrapped
    obs, _ = env.reset(seed=seed)
    rng = np.random.default_rng(seed)
    for _ in range(300):
        action = rng.uniform(-1.5, 1.5, env.action_space.shape)  # out of range too: clipped
        obs, reward, terminated, truncated, info = env.step(action)
        assert obs.dtype == np.float32
        assert env.observation_space.contains(obs)
        on = raw.on_table
        np.testing.assert_array_equal(obs[2::3], on)
        assert not obs.reshape(-1, 3)[~on].any()  # potted balls read all zeros
        assert on[0]  # the cue ball is always back on the table
        assert reward == len(info["potted"]) - info["scratch"]
        assert info["is_success"] == (not on[1:].any())
        # legal: inside, apart, not potted
        pool_env.shoot(raw.config.table, raw.positions[on], 0.0, 0.0)
        if terminated or truncated:
            obs, _ = env.reset()
            assert env.observation_space.contains(obs)


@pytest.mark.parametrize("render_mode", [None, "rgb_array"])
def test_pickling_mid_episode_resumes_identically(render_mode: str | None) -> None:
    env = gym.make("pool_env/NineBallRoll-v1", noise=(0.01, 0.1), render_mode=render_mode)
    env.reset(seed=9)
    for action in ([0.0, 0.8], [0.3, -0.5], [-0.2, -0.2]):
        env.step(np.array(action))
    if render_mode:
        env.render()
    clone = pickle.loads(pickle.dumps(env))
    rng = np.random.default_rng(0)
    for _ in range(20):
        action = rng.uniform(-1, 1, 2)
        assert _same(env.step(action), clone.step(action))
    if render_mode:
        np.testing.assert_array_equal(env.render(), clone.render())


def test_unwrapped_exposes_what_agents_need() -> None:
    env = gym.make("pool_env/OneBallRoll-v1")
    env.reset(seed=0)
    raw = env.unwrapped
    assert isinstance(raw, PoolEnv)
    assert isinstance(raw.config.table, Table)
    assert raw.config.aim == "cut"
    assert raw.config.aim_range == (-1.0, 1.0)
    assert raw.config.speed_range == (0.45, 4.5)
    assert raw.config.n_object_balls == 1
    assert raw.positions.shape == (2, 2)
    raw.positions[0] = 0.0  # a copy: the state cannot be changed through it
    assert raw.positions[0, 0] != 0.0


def test_subproc_vec_env_with_two_workers_matches_dummy_vec_env() -> None:
    from stable_baselines3.common.env_util import make_vec_env
    from stable_baselines3.common.vec_env import DummyVecEnv, SubprocVecEnv

    # "module:id" makes each worker import pool_env, whatever its start method.
    env_id = "pool_env:pool_env/NineBallRoll-v1"
    sub = make_vec_env(env_id, n_envs=2, seed=3, vec_env_cls=SubprocVecEnv)
    dummy = make_vec_env(env_id, n_envs=2, seed=3, vec_env_cls=DummyVecEnv)
    try:
        np.testing.assert_array_equal(sub.reset(), dummy.reset())
        rng = np.random.default_rng(1)
        for _ in range(30):
            actions = rng.uniform(-1, 1, (2, 2)).astype(np.float32)
            s, d = sub.step(actions), dummy.step(actions)
            for x, y in zip(s[:3], d[:3], strict=True):
                np.testing.assert_array_equal(x, y)
    finally:
        sub.close()
        dummy.close()


def test_package_exports() -> None:
    assert pool_env.PoolEnv is PoolEnv
    assert "PoolEnv" in pool_env.__all__


def test_the_state_never_aliases_what_callers_were_given() -> None:
    # Issue 11 (3): editing last_shot.positions used to change the environment.
    layout = np.array([[0.5, 0.5], [1.0, 0.5], [2.0, 0.8]])
    env = _env(n_balls=2)
    env.reset(seed=0, options={"positions": layout})
    layout[:] = np.nan  # the caller's layout was copied
    obs, *_ = env.step(np.array([0.2, -0.5]))
    before = env.positions
    env.last_shot.positions[:] = np.nan
    env.last_shot.pocketed[:] = 0
    obs[:] = 7.0
    np.testing.assert_array_equal(env.positions, before)
    assert np.isfinite(env.step(np.array([0.1, -0.5]))[0]).all()  # plays on as before


@pytest.mark.parametrize("dtype", [np.float16, np.float32, np.longdouble, ">f8", "<f4", np.int8])
def test_every_real_action_dtype_plays_as_its_float64_value(dtype: object) -> None:
    # Issue 11 (7): float16, long double and big-endian actions raised numba's TypingError.
    action = np.array([0.25, -0.5], dtype=dtype) if dtype != np.int8 else np.array([1, -1], dtype)
    results = []
    for played in (action, action.astype(np.float64)):
        env = _env(scene="random", n_balls=4)
        env.reset(seed=4)
        results.append(env.step(played))
    assert _same(*results)


@pytest.mark.parametrize(
    ("action", "message"),
    [
        (np.array([0.3 + 0.5j, 0.1]), "real numbers"),
        ([0.3j, 0.0], "real numbers"),
        (np.array(["a", "b"]), "real numbers"),
        ([object(), 1.0], "real numbers"),
    ],
)
def test_complex_and_other_non_real_actions_are_refused(action: object, message: str) -> None:
    env = _env()
    env.reset(seed=0)
    before = env.positions
    with pytest.raises(ValueError, match=message):
        env.step(action)
    np.testing.assert_array_equal(env.positions, before)


def test_a_reset_layout_without_object_balls_says_so() -> None:
    env = _env(n_balls=2)
    layout = [[0.5, 0.5], [1.0, 0.5], [2.0, 0.8]]
    with pytest.raises(ValueError, match="no object ball"):
        env.reset(options={"positions": layout, "on_table": [True, False, False]})
