"""PoolVectorEnv: the same trajectories as a SyncVectorEnv of PoolEnvs, autoreset, spaces."""

from __future__ import annotations

import pickle
import warnings

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import data_equivalence
from gymnasium.vector import AutoresetMode
from gymnasium.vector.utils import batch_space

import pool_env
from pool_env import ENV_IDS, PoolEnv, PoolVectorEnv, Table
from pool_env.game.config import make_config
from pool_env.game.kernels.actions import executed_shots
from pool_env.game.kernels.layout import sample_layouts
from pool_env.game.kernels.params import N_PARAMS, RESTARTS, TRIES, X_HIGH, Y_HIGH
from pool_env.game.state import generator_addresses
from pool_env.sim.batch import simulate_batch, simulate_batch_threads
from pool_env.sim.layouts import head_spot

NEXT, SAME, DISABLED = AutoresetMode.NEXT_STEP, AutoresetMode.SAME_STEP, AutoresetMode.DISABLED
HEAD = head_spot(Table())
SCRATCH_LAYOUT = np.array([[0.3, 0.3], [2.0, 1.0]])  # the cue ball rolls into a corner
SCRATCH_SHOT = [-0.75, -0.8]  # absolute aim: down the diagonal at 1.45 m/s


def _pair(env_id: str, n: int, mode: AutoresetMode, **kwargs: object) -> tuple:
    sync = gym.make_vec(
        env_id, n, vectorization_mode="sync", vector_kwargs={"autoreset_mode": mode}, **kwargs
    )
    native = gym.make_vec(
        env_id, n, vectorization_mode="vector_entry_point", autoreset_mode=mode, **kwargs
    )
    return sync, native


def _assert_same(a: object, b: object, what: str) -> None:
    for x, y, name in zip(a, b, ("obs", "reward", "terminated", "truncated", "info"), strict=False):
        assert data_equivalence(x, y, exact=True), f"{what}: {name} differs\n{x}\n{y}"


def _compare(sync: gym.vector.VectorEnv, native: PoolVectorEnv, steps: int, seed: int) -> int:
    """Step both with the same random actions; return how many episodes ended."""
    _assert_same(sync.reset(seed=seed), native.reset(seed=seed), "reset")
    rng = np.random.default_rng(seed)
    ended = 0
    for t in range(steps):
        # Out-of-range actions too: both clip them alike.
        actions = rng.uniform(-1.1, 1.1, native.action_space.shape).astype(np.float32)
        a, b = sync.step(actions), native.step(actions)
        _assert_same(a, b, f"step {t}")
        ended += int(np.sum(b[2] | b[3]))
    return ended


@pytest.mark.parametrize("mode", [NEXT, SAME])
@pytest.mark.parametrize("env_id", list(ENV_IDS))
def test_equals_a_sync_vector_env_of_pool_envs(env_id: str, mode: AutoresetMode) -> None:
    steps = 120 if env_id == "pool_env/OneBallRoll-v1" else 60
    if env_id == "pool_env/EightBall-v1":  # no table clears 15 balls in 60 shots: truncation
        steps = 85
    # a snooker frame of random strokes lasts hundreds: its shot limit ends the episodes
    extra = {"max_shots": 20} if "SnookerFrame" in env_id else {}
    ended = _compare(*_pair(env_id, 5, mode, **extra), steps=steps, seed=11)
    assert ended > 0  # the autoreset paths ran


@pytest.mark.parametrize(
    "kwargs",
    [
        {"noise": (0.05, 0.4), "reward_shaping": 0.5, "reward_no_contact": -0.2},
        {"aim": "relative", "n_balls": 6, "max_shots": 3, "end_on_miss": True},
        {"aim": "absolute", "n_balls": 1, "speed_range": (0.2, 4.0)},
        {"scene": SCRATCH_LAYOUT, "aim": "absolute", "noise": (0.3, 0.0)},
        {"scene": lambda table, rng: [[0.5, 0.6], rng.uniform([1.0, 0.3], [1.5, 0.9]), [2, 1]]},
        {"scene": "nine_ball", "table": {"pockets": "none"}, "aim": "relative"},
    ],
    ids=["noise-shaping", "relative-max-shots", "absolute", "fixed-layout", "callable", "carom"],
)
def test_equals_sync_under_every_option(kwargs: dict) -> None:
    for mode in (NEXT, SAME):
        _compare(*_pair("pool_env/PoolRoll-v1", 4, mode, **kwargs), steps=40, seed=5)


def test_disabled_autoreset_waits_for_a_masked_reset_and_equals_sync() -> None:
    sync, native = _pair("pool_env/OneBallRoll-v1", 4, DISABLED)
    _assert_same(sync.reset(seed=2), native.reset(seed=2), "reset")
    rng = np.random.default_rng(2)
    for _ in range(10):
        actions = rng.uniform(-1, 1, (4, 2)).astype(np.float32)
        a, b = sync.step(actions), native.step(actions)
        _assert_same(a, b, "step")
        done = b[2] | b[3]
        assert done.any()  # OneBall: every shot ends the episode
        with pytest.raises(RuntimeError, match="reset_mask"):
            native.step(actions)
        _assert_same(
            sync.reset(options={"reset_mask": done.copy()}),
            native.reset(options={"reset_mask": done.copy()}),
            "masked reset",
        )
    with pytest.raises(ValueError, match="reset_mask"):
        native.reset(options={"reset_mask": np.zeros(4, dtype=bool)})


def test_next_step_autoreset_ignores_the_action_of_a_finished_table() -> None:
    env = PoolVectorEnv(3, scene="one_ball", end_on_miss=True, autoreset_mode=NEXT, model="roll")
    env.reset(seed=0)
    _, _, terminated, _, info = env.step(np.zeros((3, 2)))
    assert terminated.all() and info["_potted"].all()
    # The next step resets every table: the actions, even NaN, are not used.
    obs, rewards, terminated, truncated, info = env.step(np.full((3, 2), np.nan))
    assert info == {}
    assert not (rewards.any() or terminated.any() or truncated.any())
    assert (obs[:, 2::3] == 1.0).all()  # fresh layouts: every ball on the table
    assert env.shots.tolist() == [0, 0, 0]


def test_same_step_autoreset_reports_final_observation_and_info() -> None:
    env = PoolVectorEnv(2, scene=SCRATCH_LAYOUT, aim="absolute", autoreset_mode=SAME, model="roll")
    env.reset(seed=0)
    obs, reward, terminated, truncated, info = env.step([SCRATCH_SHOT, SCRATCH_SHOT])
    assert reward.tolist() == [-1.0, -1.0] and not terminated.any()
    np.testing.assert_allclose(obs[:, :3], [[-0.5, 0.0, 1.0]] * 2)  # back on the head spot
    env = PoolVectorEnv(
        2,
        max_episode_steps=1,
        scene=SCRATCH_LAYOUT,
        aim="absolute",
        autoreset_mode=SAME,
        model="roll",
    )
    env.reset(seed=0)
    obs, reward, terminated, truncated, info = env.step([SCRATCH_SHOT, SCRATCH_SHOT])
    assert truncated.all() and not terminated.any()
    assert set(info) == {"final_obs", "_final_obs", "final_info", "_final_info"}
    np.testing.assert_allclose(info["final_obs"][0][:3], [-0.5, 0.0, 1.0])
    assert info["final_info"]["scratch"].tolist() == [True, True]
    np.testing.assert_array_equal(env.positions, np.repeat(SCRATCH_LAYOUT[None], 2, axis=0))


def test_a_scratch_with_the_head_spot_taken_matches_pool_env() -> None:
    layout = np.array([SCRATCH_LAYOUT[0], HEAD])
    single = PoolEnv(scene=layout, aim="absolute", model="roll")
    single.reset(seed=0)
    expected = single.step(np.array(SCRATCH_SHOT))
    env = PoolVectorEnv(2, scene=layout, aim="absolute", model="roll")
    env.reset(seed=0)
    obs, _, _, _, info = env.step([SCRATCH_SHOT, SCRATCH_SHOT])
    assert info["scratch"].all()
    np.testing.assert_array_equal(obs[1], expected[0])
    np.testing.assert_array_equal(env.positions[1], single.positions)
    assert np.hypot(*(env.positions[1, 0] - HEAD)) > 2 * single.config.table.ball_radius


@pytest.mark.parametrize("env_id", list(ENV_IDS))
def test_make_vec_builds_it_with_the_ids_spaces_and_limit(env_id: str) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # make_vec warns about missing autoreset metadata
        # (an earlier version's "out of date" is meant: tests/envs/test_id_versions.py)
        warnings.filterwarnings("ignore", ".*is out of date", DeprecationWarning)
        env = gym.make_vec(env_id, num_envs=3)
    single = gym.make(env_id)
    assert isinstance(env, PoolVectorEnv)
    assert env.metadata["autoreset_mode"] is NEXT
    assert env.max_episode_steps == ENV_IDS[env_id][1]
    assert env.single_observation_space == single.observation_space
    assert env.single_action_space == single.action_space
    assert env.observation_space == batch_space(single.observation_space, 3)
    assert env.action_space == batch_space(single.action_space, 3)
    obs, info = env.reset(seed=1)
    assert info == {} and obs in env.observation_space
    obs, rewards, terminated, truncated, info = env.step(env.action_space.sample())
    assert obs in env.observation_space and obs.dtype == np.float32
    assert rewards.dtype == np.float64 and rewards.shape == (3,)
    assert terminated.dtype == truncated.dtype == np.bool_
    assert info["potted"].dtype == object and info["_potted"].all()


def test_seeding_per_table_and_reproducibility() -> None:
    env = PoolVectorEnv(3, scene="one_ball")
    first, _ = env.reset(seed=7)
    assert env.np_random_seed == (7, 8, 9)
    again, _ = env.reset(seed=7)
    np.testing.assert_array_equal(first, again)
    listed, _ = env.reset(seed=[9, 8, 7])
    np.testing.assert_array_equal(listed, first[::-1])
    single = PoolEnv(scene="one_ball")
    np.testing.assert_array_equal(single.reset(seed=8)[0], first[1])
    # Without a seed each table goes on with its own stream, as PoolEnv does.
    np.testing.assert_array_equal(single.reset()[0], env.reset()[0][1])
    with pytest.raises(ValueError, match="seed"):
        env.reset(seed=[1, 2])


def test_bad_input_raises_and_changes_nothing() -> None:
    with pytest.raises(ValueError, match="num_envs"):
        PoolVectorEnv(0, model="roll")
    with pytest.raises(ValueError, match="render_mode"):
        PoolVectorEnv(2, render_mode="human", model="roll")
    with pytest.raises(ValueError, match="aim"):
        PoolVectorEnv(2, aim="sideways", model="roll")  # PoolEnv's own checks
    env = PoolVectorEnv(2, model="roll")
    with pytest.raises(RuntimeError, match="reset"):
        env.step(np.zeros((2, 2)))
    env.reset(seed=0, options={"reset_mask": np.array([True, False])})
    with pytest.raises(RuntimeError, match=r"tables \[1\] were never reset"):
        env.step(np.zeros((2, 2)))
    env.reset(seed=0)
    before = env.positions
    with pytest.raises(ValueError, match="table 1 contains NaN"):
        env.step([[0.0, 0.0], [np.nan, 0.0]])
    with pytest.raises(ValueError, match="shape"):
        env.step(np.zeros((3, 2)))
    np.testing.assert_array_equal(env.positions, before)
    assert env.shots.tolist() == [0, 0]
    with pytest.raises(ValueError, match="overlap"):
        env.reset(options={"positions": [[0.5, 0.5], [0.51, 0.5], [1, 1], [2, 1]]})
    with pytest.raises(ValueError, match="unknown reset options"):
        env.reset(options={"layout": None})


def test_reset_options_lay_out_each_table() -> None:
    env = PoolVectorEnv(2, n_balls=2)
    layouts = np.array([[[0.5, 0.5], [1.0, 0.5], [2, 1]], [[1.5, 0.5], [2.0, 0.7], [1, 1]]])
    obs, _ = env.reset(options={"positions": layouts, "on_table": [True, False, True]})
    np.testing.assert_array_equal(env.positions, layouts)
    assert obs[:, 5].tolist() == [0.0, 0.0] and obs[:, 8].tolist() == [1.0, 1.0]
    obs, _ = env.reset(options={"positions": layouts[1]})  # one layout for every table
    np.testing.assert_array_equal(obs[0], obs[1])
    assert env.on_table.all()


def test_returned_arrays_are_not_the_state_and_pickling_resumes_identically() -> None:
    env = PoolVectorEnv(4, scene="nine_ball", noise=(0.01, 0.1), model="roll")
    obs, _ = env.reset(seed=3)
    obs[:] = 0.0
    assert env.step(np.zeros((4, 2)))[0].any()
    clone = pickle.loads(pickle.dumps(env))
    actions = np.random.default_rng(0).uniform(-1, 1, (5, 4, 2))
    for a in actions:
        _assert_same(env.step(a), clone.step(a), "pickled")


def test_gymnasium_vector_wrappers_work_on_top() -> None:
    from gymnasium.wrappers.vector import (
        DictInfoToList,
        NormalizeObservation,
        RecordEpisodeStatistics,
    )

    env = DictInfoToList(RecordEpisodeStatistics(NormalizeObservation(gym.make_vec(
        "pool_env/OneBallRoll-v1", num_envs=4
    ))))  # fmt: skip
    env.reset(seed=0)
    episodes = 0
    for _ in range(6):
        *_, infos = env.step(env.action_space.sample())
        episodes += sum("episode" in info for info in infos)
    assert episodes > 0
    assert all(set(info) >= {"potted", "scratch"} for info in infos if info)


def test_rgb_array_render_gives_one_frame_per_table() -> None:
    env = PoolVectorEnv(2, render_mode="rgb_array", render_width=200)
    env.reset(seed=0)
    frames = env.render()
    single = PoolEnv(render_mode="rgb_array", render_width=200)
    single.reset(seed=0)
    assert len(frames) == 2
    np.testing.assert_array_equal(frames[0], single.render())  # no shot yet: no trails
    assert not np.array_equal(frames[0], frames[1])
    with pytest.warns(UserWarning, match="render_mode"):
        assert PoolVectorEnv(1).render() is None


@pytest.mark.parametrize("bits", [np.random.PCG64, np.random.MT19937, np.random.Philox])
def test_compiled_draws_equal_numpys(bits: type) -> None:
    ours, theirs = np.random.Generator(bits(3)), np.random.Generator(bits(3))
    table = np.array([generator_addresses(ours)], dtype=np.uintp)
    one, zero_action = np.zeros(1, np.intp), np.zeros((1, 2))
    noise = (1.0, 2.0)
    params = make_config(
        scene="one_ball", aim="absolute", aim_range=(0.0, 0.0), speed_range=(5.0, 5.0),
        noise=noise, model="roll"
    ).params  # fmt: skip
    at_rest, on = np.zeros((1, 2, 2)), np.ones((1, 2), np.bool_)
    angles, speeds = np.zeros(20_000), np.zeros(20_000)
    for k in range(20_000):  # noise of one table, drawn 20,000 times: tails included
        # Absolute aim with a zero-width range: the shot is angle 0 at 5 m/s, plus noise.
        shots, _ = executed_shots(params, zero_action, one, at_rest, on, table)
        angles[k], speeds[k] = shots[0]
    normals = theirs.standard_normal(40_000)
    aims = normals[0::2]  # the reported direction: in [-pi, pi), wrapped when beyond it
    inside = (aims >= -np.pi) & (aims < np.pi)
    np.testing.assert_array_equal(
        angles, np.where(inside, aims, (aims + np.pi) % (2 * np.pi) - np.pi)
    )
    assert not inside.all()  # sigma 1 rad: some draws turn beyond pi
    np.testing.assert_array_equal(speeds, np.maximum(0.0, 5.0 + 2.0 * normals[1::2]))
    positions, unit_box, no_pockets = (
        np.zeros((1, 2, 2)),
        np.array([0, 1, 0, 1.0]),
        np.zeros((0, 3)),
    )
    nothing_placed = np.zeros((0, 2))
    unit = np.zeros(N_PARAMS)
    unit[[X_HIGH, Y_HIGH, TRIES, RESTARTS]] = 1.0, 1.0, 9, 1  # a 1 m square, no pockets
    sample_layouts(
        unit, no_pockets, one, positions, table, nothing_placed, unit_box, np.zeros((2, 2))
    )
    np.testing.assert_array_equal(positions[0].ravel(), theirs.random(8)[:4])


def test_threaded_batch_equals_serial_and_names_the_table() -> None:
    table = Table()
    env = PoolVectorEnv(50, scene="one_ball")
    env.reset(seed=1)
    pos, on = env.positions, env.on_table
    rng = np.random.default_rng(0)
    angle, speed = rng.uniform(-3, 3, 50), rng.uniform(0, 10, 50)
    vel = np.zeros((50, 2, 2))
    vel[:, 0] = np.stack([speed * np.cos(angle), speed * np.sin(angle)], axis=1)
    serial = simulate_batch(table, pos, vel, active=on, parallel=False)
    for threads in (2, 3):
        split = simulate_batch_threads(table, pos, vel, on, threads)
        for field in serial.__slots__:
            np.testing.assert_array_equal(getattr(split, field), getattr(serial, field))
    pos[40, 1] = pos[40, 0]
    with pytest.raises(ValueError, match="table 40: balls 0 and 1 overlap"):
        simulate_batch_threads(table, pos, vel, on, 2)


@pytest.mark.parametrize("dtype", [np.float16, np.longdouble, ">f8", np.float32])
def test_action_dtypes_play_as_in_pool_env(dtype: object) -> None:
    actions = np.array([[0.25, -0.5], [-0.7, 0.3]], dtype=dtype)
    env = PoolVectorEnv(2, scene="random", n_balls=4, model="roll")
    env.reset(seed=4)
    obs, rewards, *_ = env.step(actions)
    for i in range(2):
        single = PoolEnv(scene="random", n_balls=4, model="roll")
        single.reset(seed=4 + i)
        expected = single.step(actions[i])
        np.testing.assert_array_equal(obs[i], expected[0])
        assert rewards[i] == expected[1]


def test_bad_actions_seeds_and_layouts_get_the_same_messages_as_pool_env() -> None:
    env, single = PoolVectorEnv(2, n_balls=2), PoolEnv(n_balls=2)
    env.reset(seed=0)
    single.reset(seed=0)
    for bad in (np.array([0.3 + 0.5j, 0.1]), np.array(["a", "b"])):
        with pytest.raises(ValueError, match="real numbers") as vector_error:
            env.step(np.stack([bad, bad]))
        with pytest.raises(ValueError, match="real numbers") as single_error:
            single.step(bad)
        assert str(vector_error.value).split("got")[-1] == str(single_error.value).split("got")[-1]
    for seed in (1.5, "7", [1, 2.5], [-1, 2], True):
        with pytest.raises(ValueError, match="seed"):
            env.reset(seed=seed)  # type: ignore[arg-type]
    for seed in (1.5, "7", -1, True):
        with pytest.raises(ValueError, match="seed"):
            single.reset(seed=seed)  # type: ignore[arg-type]
    layout = [[0.5, 0.5], [1.0, 0.5], [2.0, 0.8]]
    for target in (env, single):
        with pytest.raises(ValueError, match="leaves no object ball on the table"):
            target.reset(options={"positions": layout, "on_table": [True, False, False]})


def test_a_crowded_scene_never_fails_in_an_autoreset() -> None:
    # Issue 11 (5): the autoreset inside step() raised "cannot lay out the scene".
    env = PoolVectorEnv(
        16, table={"length": 0.4, "width": 0.2}, n_balls=11, autoreset_mode=SAME, model="roll"
    )
    env.reset(seed=0)
    rng = np.random.default_rng(0)
    for _ in range(30):
        env.step(rng.uniform(-1, 1, (16, 2)))
        for positions, on in zip(env.positions, env.on_table, strict=True):
            pool_env.check_layout(env.config.table, positions[on])
