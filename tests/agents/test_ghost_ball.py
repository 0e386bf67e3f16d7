"""The geometric ghost-ball agent: aim and speed from geometry alone, checked on the simulator.

Constructed layouts (a straight-in shot, a 30-degree cut) name the pocket that must take the
ball; the speed model (distances, rolling resistance, ball restitution) is checked against
the simulator by playing just below and just above the speed at which the object ball
arrives at rest; and the agent must never call the simulator.
"""

from __future__ import annotations

import math

import gymnasium as gym
import numpy as np
import pytest

import pool_env
from agents import GhostBallAgent, RandomAgent, SearchAgent, run_episodes
from agents.baselines.geometry import cue_speed, pocket_mouths
from pool_env.sim.kernels import loop
from pool_env.sim.table import CORNER_MOUTH, SIDE_MOUTH, standard_pockets

ONE = "pool_env/OneBallRoll-v1"
R = 0.028575
L, W = 2.54, 1.27
#: Bottom-left corner (pocket 0) and bottom side (pocket 1) mouth midpoints, derived from
#: the capture circles in ball-centre coordinates (see ``pocket_mouths``).
CORNER_TARGET = np.array([(R + CORNER_MOUTH / math.sqrt(2)) / 2] * 2)
SIDE_TARGET = np.array([L / 2, R])
#: The capture-circle table, spelled out (the default table's pockets may change).
CIRCLES = pool_env.Table(pockets=standard_pockets(L, W, R))


def _one_ball_env(**kwargs: object) -> gym.Env:
    return gym.make("pool_env/PoolRoll-v1", n_balls=1, **kwargs)


def _cut_layout(ball: np.ndarray, target: np.ndarray, cut_deg: float, cue_dist: float):
    """Cue placed so that sending ``ball`` at ``target`` is a cut of ``cut_deg`` degrees."""
    u = (target - ball) / np.hypot(*(target - ball))
    ghost = ball - 2 * R * u
    c, s = math.cos(math.radians(-cut_deg)), math.sin(math.radians(-cut_deg))
    d = np.array([c * u[0] - s * u[1], s * u[0] + c * u[1]])  # u turned by -cut
    return np.array([ghost - cue_dist * d, ball])


def _play(env: gym.Env, positions: np.ndarray, agent: GhostBallAgent | None = None):
    obs, _ = env.reset(seed=0, options={"positions": positions})
    agent = agent or GhostBallAgent(env)
    action, _ = agent.predict(obs)
    _, _, _, _, info = env.step(action)
    return agent, info, env.unwrapped.last_shot


def test_mouths_from_capture_circles_match_hand_values() -> None:
    mouths = pocket_mouths(CIRCLES)
    assert np.allclose(mouths.targets[0], CORNER_TARGET, atol=1e-12)
    assert np.allclose(mouths.targets[1], SIDE_TARGET, atol=1e-12)
    # A corner circle cuts the rail lines at w / sqrt(2) from the corner; a side circle
    # cuts its rail line over the whole mouth width.
    assert mouths.widths[0] == pytest.approx(CORNER_MOUTH - math.sqrt(2) * R, abs=1e-12)
    assert mouths.widths[1] == pytest.approx(SIDE_MOUTH, abs=1e-12)
    assert np.allclose(mouths.inward[0], [-math.sqrt(0.5)] * 2)
    assert np.allclose(mouths.inward[1], [0.0, -1.0])


def test_straight_in_shot_drops_in_the_side_pocket(monkeypatch: pytest.MonkeyPatch) -> None:
    env = _one_ball_env()
    positions = np.array([[L / 2, 0.8], [L / 2, 0.4]])
    env.reset(seed=0, options={"positions": positions})
    agent = GhostBallAgent(env)
    with monkeypatch.context() as m:  # geometry only: the simulator must not be called
        m.setattr(loop, "packed_shot", _forbidden)
        m.setattr(loop, "packed_strike", _forbidden)
        action, _ = agent.predict(env.unwrapped._observation())
    shot = agent.last_plan["shot"]
    assert shot.pocket == 1 and shot.cut == pytest.approx(0.0, abs=1e-12)
    assert shot.cue_distance == pytest.approx(0.4 - 2 * R, abs=1e-12)
    _, _, _, _, info = env.step(action)
    assert info["potted"] == (1,) and not info["scratch"]
    assert env.unwrapped.last_shot.pocketed[1] == 1


def _forbidden(*args: object, **kwargs: object) -> None:
    raise AssertionError("the geometric agent called the simulator")


@pytest.mark.parametrize("cut_deg", [30.0, -30.0])
def test_thirty_degree_cut_drops_in_the_named_corner(cut_deg: float) -> None:
    positions = _cut_layout(np.array([0.6, 0.5]), CORNER_TARGET, cut_deg, 0.5)
    agent, info, result = _play(_one_ball_env(), positions)
    shot = agent.last_plan["shot"]
    assert shot.pocket == 0
    assert math.degrees(shot.cut) == pytest.approx(cut_deg, abs=1e-9)
    assert info["potted"] == (1,)
    assert result.pocketed[1] == 0  # the bottom-left corner


def test_speed_reaches_the_pocket_but_is_not_maximal() -> None:
    env = _one_ball_env()
    table = env.unwrapped.config.table
    positions = _cut_layout(np.array([0.6, 0.5]), CORNER_TARGET, 30.0, 0.5)
    agent, info, _ = _play(env, positions)
    shot, speed = agent.last_plan["shot"], agent.last_plan["speed"]
    # The closed form of the docstring, by hand: roll, collide, roll.
    a, e = table.deceleration, table.e_ball
    v_ball = math.sqrt(agent.arrival_speed**2 + 2 * a * shot.travel)
    v_contact = v_ball / ((1 + e) / 2 * math.cos(math.radians(30.0)))
    assert speed == pytest.approx(math.sqrt(v_contact**2 + 2 * a * shot.cue_distance), 1e-12)
    assert info["speed"] == pytest.approx(speed, rel=1e-6)
    assert info["potted"] == (1,)
    assert speed < 0.25 * env.unwrapped.config.speed_range[1]


@pytest.mark.parametrize("cut_deg", [0.0, 30.0])
def test_speed_model_matches_the_simulator(cut_deg: float) -> None:
    """The ball must just drop at 1.02x the zero-arrival speed and stop short at 0.98x."""
    table = pool_env.Table()
    positions = _cut_layout(np.array([1.0, 0.6]), CORNER_TARGET, cut_deg, 0.6)
    env = _one_ball_env()
    env.reset(seed=0, options={"positions": positions})
    agent = GhostBallAgent(env)
    shot, _, _ = agent.best_shot(positions, np.ones(2, dtype=bool))
    assert shot is not None and shot.pocket == 0
    v_rest = cue_speed(table, shot, 0.0)
    short = pool_env.shoot(table, positions, shot.angle, 0.98 * v_rest)
    long = pool_env.shoot(table, positions, shot.angle, 1.02 * v_rest)
    assert short.pocketed[1] == -1 and long.pocketed[1] == 0
    u = (short.positions[1] - positions[1]) / np.hypot(*(short.positions[1] - positions[1]))
    gap = agent.mouths.travel(0, short.positions[1], u)
    assert 0.0 < gap < 0.1 * shot.travel  # stopped just short of where it would drop


@pytest.mark.parametrize("aim", ["cut", "relative", "absolute"])
@pytest.mark.parametrize("noise", [None, (0.003, 0.05)])
def test_ghost_pots_in_every_aim_mode_with_and_without_noise(aim: str, noise) -> None:
    env = gym.make(ONE, aim=aim, noise=noise)
    ghost = run_episodes(GhostBallAgent(env), env, 100, seed=7).summary()
    rand = run_episodes(RandomAgent(env, seed=0), env, 100, seed=7).summary()
    # Noise of 0.17 degrees and 0.05 m/s costs a real player many pots: on the jaw table
    # about 40 points (measured 95% -> 55%), so the noisy floor is lower.
    floor = 0.9 if noise is None else 0.45
    assert ghost["pots_per_shot"].value >= floor
    assert ghost["clean_pot_rate"].value - rand["clean_pot_rate"].value >= 0.3


def test_search_beats_or_matches_ghost_on_a_seeded_sample() -> None:
    env = gym.make(ONE)
    ghost = run_episodes(GhostBallAgent(env), env, 150, seed=500).summary()
    search = run_episodes(SearchAgent(env), env, 150, seed=500).summary()
    for key in ("pots_per_shot", "clean_pot_rate", "episode_reward"):
        assert search[key].value >= ghost[key].value


@pytest.mark.parametrize(
    ("env_id", "episodes"),
    [
        ("pool_env/PoolRoll-v1", 20),
        ("pool_env/NineBallRoll-v1", 10),
        ("pool_env/EightBallRoll-v1", 5),
    ],
)
def test_ghost_outplays_random_on_every_rack_id(env_id: str, episodes: int) -> None:
    env = gym.make(env_id)
    ghost = run_episodes(GhostBallAgent(env), env, episodes, seed=3).summary()
    rand = run_episodes(RandomAgent(env, seed=0), env, episodes, seed=3).summary()
    assert ghost["pots_per_turn"].value > 1.5 * rand["pots_per_turn"].value
    assert ghost["shots_per_episode"].value < rand["shots_per_episode"].value


def test_legal_targets_is_the_one_rule_to_override() -> None:
    env = gym.make("pool_env/PoolRoll-v1", n_balls=2, aim="absolute")
    # Ball 1 lines up straight into the side pocket, ball 2 into the corner.
    positions = np.array([[1.27, 0.9], [1.27, 0.5], [0.4, 0.4]])
    env.reset(seed=0, options={"positions": positions})
    on = np.ones(3, dtype=bool)
    free = GhostBallAgent(env)
    free.plan(positions, on)
    assert free.last_plan["shot"].ball == 1
    only_two = GhostBallAgent(env, legal_targets=lambda pos, on: [2])
    only_two.plan(positions, on)
    assert only_two.last_plan["shot"].ball == 2
    none = GhostBallAgent(env, legal_targets=lambda pos, on: [])
    action = none.plan(positions, on)
    assert none.last_plan["kind"] == "fallback"
    assert action[1] == 1.0  # a full-speed hit on the nearest ball


def test_predict_batches_like_sb3() -> None:
    from stable_baselines3.common.env_util import make_vec_env

    vec = make_vec_env(ONE, n_envs=3, seed=0)
    obs = vec.reset()
    agent = GhostBallAgent(vec)
    batch, state = agent.predict(obs, deterministic=True)
    assert batch.shape == (3, 2) and batch.dtype == np.float32 and state is None
    layouts = zip(vec.get_attr("positions"), vec.get_attr("on_table"), strict=True)
    expected = np.stack([agent.plan(pos, on) for pos, on in layouts])
    assert np.array_equal(batch, expected)
    single, _ = agent.predict(obs[0])
    assert single.shape == (2,)


def test_bad_arrival_speed_is_a_clear_error() -> None:
    with pytest.raises(ValueError, match="arrival_speed"):
        GhostBallAgent(gym.make(ONE), arrival_speed=-1.0)


def test_ghost_ball_features_by_hand() -> None:
    from agents.learned.features import GhostBallFeatures

    env = GhostBallFeatures(_one_ball_env(table=CIRCLES))  # hand values for capture circles
    positions = np.array([[L / 2, 1.2], [L / 2, 0.8]])  # straight in, side pocket 1
    obs, _ = env.reset(seed=0, options={"positions": positions})
    assert env.observation_space.contains(obs)
    per = GhostBallFeatures.PER_SHOT
    rows = obs[6:].reshape(6, per)
    diag = math.hypot(L, W)
    table = env.unwrapped.config.table
    side_r = math.hypot(2 * R, SIDE_MOUTH / 2)
    travel = 0.8 - (side_r - R)  # down to the side circle centred R behind the rail
    a, e = table.deceleration, table.e_ball
    v_contact = math.sqrt(0.3**2 + 2 * a * travel) / ((1 + e) / 2)
    speed = math.sqrt(v_contact**2 + 2 * a * (0.4 - 2 * R))
    lo, hi = env.unwrapped.config.speed_range
    assert lo < speed < hi
    expected = [1, 1, 0, 1, (0.4 - 2 * R) / diag, (0.8 - R + 2 * R) / diag, 1,
                2 * (speed - lo) / (hi - lo) - 1]  # fmt: skip
    assert np.allclose(rows[0], expected, atol=1e-6)
    assert np.all(rows[1:, 0] <= 1) and np.all(rows[1:, 2] ** 2 + rows[1:, 3] ** 2 <= 1 + 1e-6)
    # The valid rows come first, the rest are zero; a 30-degree cut (the object ball leaving
    # counter-clockwise of the cue ball's path) is played with the cut action -sin(30) = -0.5.
    valid = rows[:, 0] == 1.0
    assert not np.any(rows[~valid]) and np.all(np.diff(valid.astype(int)) <= 0)
    cut = _cut_layout(np.array([0.6, 0.5]), CORNER_TARGET, 30.0, 0.5)
    obs, _ = env.reset(seed=0, options={"positions": cut})
    first = obs[6:].reshape(6, per)[0]
    assert first[2] == pytest.approx(-0.5, abs=1e-6)
    assert first[3] == pytest.approx(math.sqrt(3) / 2, abs=1e-6)


def test_cue_ball_trace_predicts_the_simulators_scratches() -> None:
    """Tangent line and cushions, cue ball alone: it must agree with the full simulation."""
    from agents.baselines.geometry import ghost_shots
    from agents.baselines.trace import cue_ball_scratches

    env = gym.make(ONE, table=CIRCLES)  # rails the whole length, as the trace assumes
    table = env.unwrapped.config.table
    mouths = pocket_mouths(table)
    agree = scratches = n = 0
    for seed in range(120):
        env.reset(seed=seed)
        positions, on = env.unwrapped.positions, env.unwrapped.on_table
        for shot in ghost_shots(table, mouths, positions, on, [1]):
            for arrival in (0.3, 1.5):
                speed = cue_speed(table, shot, arrival)
                real = pool_env.shoot(table, positions, shot.angle, speed).pocketed[0] >= 0
                agree += cue_ball_scratches(table, mouths, shot, speed) == real
                scratches += real
                n += 1
    assert n > 200 and scratches > 40
    assert agree / n >= 0.97


def test_mouths_of_a_jaw_table_by_hand() -> None:
    """The jaw branch reads ``table.jaws`` (points, rails, fall line), as the jaw table has it."""
    from types import SimpleNamespace

    s, shelf = SIDE_MOUTH / 2, 0.005
    side = SimpleNamespace(
        points=np.array([(L / 2 - s, 0.0), (L / 2 + s, 0.0)]),
        rails=(2, 2),
        fall_line=np.array([(L / 2 - s + 0.002, -shelf), (L / 2 + s - 0.002, -shelf)]),
        fall_normal=np.array([0.0, 1.0]),
    )
    table = SimpleNamespace(
        length=L, width=W, ball_radius=R, pocket_model="jaws", jaws=(side,),
        pockets=np.array([(L / 2, -R, 0.08)]),
    )  # fmt: skip
    mouths = pocket_mouths(table)
    assert mouths.model == "jaws"
    assert np.allclose(mouths.targets[0], (L / 2, R))
    assert np.allclose(mouths.openings[0], [(L / 2 - s, R), (L / 2 + s, R)])
    assert mouths.widths[0] == pytest.approx(SIDE_MOUTH)
    down, slant = np.array([0.0, -1.0]), np.array([math.sqrt(0.5), -math.sqrt(0.5)])
    assert mouths.half_tolerance(0, down) == pytest.approx(s - R)
    assert mouths.half_tolerance(0, slant) == pytest.approx(s * math.sqrt(0.5) - R)
    assert mouths.half_tolerance(0, np.array([math.sin(1.2), -math.cos(1.2)])) == 0.0  # 69 deg
    start = np.array([L / 2, 0.5])
    assert mouths.travel(0, start, down) == pytest.approx(0.5 + shelf)  # to the fall line
    assert mouths.entry(0, start, down) == pytest.approx(0.5 - R)  # into the opening
    assert mouths.entry(0, start + (s + 0.01, 0.0), down) == math.inf  # onto the rail
    assert mouths.travel(0, start, -down) == math.inf
