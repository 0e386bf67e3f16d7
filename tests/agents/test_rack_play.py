"""The learned rack agent: its candidates encode their strikes, its value, its break, its model."""

from __future__ import annotations

import math
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest

import pool_env
from agents.baselines.rule_play import rule_action
from agents.evaluation.duels import play_duels
from agents.evaluation.evaluate import main as evaluate_main
from agents.evaluation.players import make_agent
from agents.learned.rack_play import BREAK_ARMS, FEATURES, RackAgent, ValueNet, load_rack_agent
from agents.training.racks import GAMMA, WIN_BONUS, fit, shot_reward

MODEL = Path(__file__).resolve().parents[2] / "models" / "rack_value.npz"
ENV_ID = "pool_env/NineBallGame-v2"


def _after_break(seed: int, **kwargs) -> tuple[gym.Env, RackAgent, np.ndarray]:
    """A noiseless rack after a break that kept the table (the next seed otherwise)."""
    env = gym.make(ENV_ID, **kwargs)
    agent = RackAgent(env)
    for s in range(seed, seed + 20):
        obs, _ = env.reset(seed=s)
        action, _ = agent.predict(obs)
        obs, _, terminated, truncated, info = env.step(action)
        if not (terminated or truncated or info["turn_over"]):
            return env, agent, obs
    raise AssertionError("no break kept the table in 20 racks")


def test_each_candidate_action_decodes_to_its_planned_strike_on_the_ball_on() -> None:
    for seed in (3, 40):
        env, agent, obs = _after_break(seed)
        agent.predict(obs)
        u = env.unwrapped
        ball_on = int(np.flatnonzero(u.on_table[1:])[0]) + 1
        assert len(agent.last_found) > 10
        for c in agent.last_found:
            action = rule_action(u.config, c.action)  # the tip where the game's action has it
            shot = pool_env.decode_action(u.config, action, u.positions, u.on_table, u.rack)
            turn = (shot.angle - c.aim + math.pi) % (2 * math.pi) - math.pi
            assert abs(turn) < 2e-6, (c, shot)
            assert shot.speed == pytest.approx(c.speed, rel=1e-5)
            assert shot.tip == pytest.approx(c.tip, abs=1e-5)
            assert c.ball == ball_on
            assert 0.0 < c.features[FEATURES.index("p_now")] <= 1.0


def test_the_planned_shots_hit_the_ball_on_first_without_noise() -> None:
    firsts = []
    for seed in (3, 40, 77, 120):
        env, agent, obs = _after_break(seed)
        ball_on = int(np.flatnonzero(env.unwrapped.on_table[1:])[0]) + 1
        action, _ = agent.predict(obs)
        *_, info = env.step(action)
        if agent.last_candidates is not None:
            firsts.append((info["first_contact"] == ball_on, info["foul"] is None))
    assert firsts and all(a and b for a, b in firsts)


def _linear(weights: np.ndarray, bias: float = 0.0) -> ValueNet:
    """A one-layer ValueNet ``x @ weights + bias`` (inputs not rescaled)."""
    f = len(FEATURES)
    return ValueNet({
        "mean": np.zeros(f), "scale": np.ones(f),
        "W0": np.asarray(weights, float)[:, None], "b0": np.array([bias]),
    })  # fmt: skip


def test_value_net_is_the_mlp_it_holds() -> None:
    f = len(FEATURES)
    rng = np.random.default_rng(0)
    w0, b0, w1, b1 = rng.normal(size=(f, 4)), rng.normal(size=4), rng.normal(size=(4, 1)), [0.5]
    mean, scale = rng.normal(size=f), rng.uniform(1, 2, f)
    net = ValueNet({"mean": mean, "scale": scale, "W0": w0, "b0": b0, "W1": w1, "b1": b1})
    x = rng.normal(size=(5, f))
    expected = np.maximum((x - mean) / scale @ w0 + b0, 0.0) @ w1[:, 0] + 0.5
    np.testing.assert_allclose(net(x), expected, rtol=1e-12)
    with pytest.raises(ValueError, match="candidate features"):
        ValueNet({"mean": np.zeros(3), "scale": np.ones(3), "W0": np.ones((3, 1)), "b0": [0]})


def test_the_agent_plays_the_candidate_of_the_highest_value() -> None:
    _, agent, obs = _after_break(3)
    p_now = FEATURES.index("p_now")
    agent.value = _linear(-np.eye(len(FEATURES))[p_now])  # the least likely pot
    action, _ = agent.predict(obs)
    features, pick = agent.last_candidates
    assert pick == int(np.argmin(features[:, p_now]))
    strike = action[[0, 1, *agent.config.tip_columns]]  # aim, speed and the tip (last two)
    np.testing.assert_array_equal(strike, agent.last_found[pick].action[[0, 1, 2, 3]])
    score = features[:, FEATURES.index("planner_score")]
    agent.top_k = 3  # the least likely pot among the planner's three best
    agent.predict(obs)
    top = np.argsort(-score, kind="stable")[:3]
    assert agent.last_candidates[1] == top[np.argmin(features[top, p_now])]
    agent.value = None  # the trivial policy: the planner's own score
    agent.predict(obs)
    features, pick = agent.last_candidates
    assert pick == int(np.argmax(features[:, FEATURES.index("planner_score")]))


@pytest.mark.parametrize("arm", [0, 7, len(BREAK_ARMS) - 1])
def test_a_break_arm_plays_its_speed_and_tip(arm: int) -> None:
    env = gym.make(ENV_ID)
    agent = RackAgent(env, break_arm=arm)
    obs, _ = env.reset(seed=5)
    action, _ = agent.predict(obs)
    *_, info = env.step(action)
    speed, vertical = BREAK_ARMS[arm]
    lo, hi = env.unwrapped.config.rules.break_speed_range
    assert info["speed"] == pytest.approx(lo + (speed + 1) / 2 * (hi - lo), rel=1e-5)
    limit = env.unwrapped.config.tip_limit
    assert info["tip"] == pytest.approx((0.0, vertical * limit), abs=1e-5)
    with pytest.raises(ValueError, match="break_arm"):
        RackAgent(env, break_arm=len(BREAK_ARMS))
    with pytest.raises(ValueError, match="spin rotation"):
        RackAgent(gym.make("pool_env/NineBallGameRoll-v2"))
    with pytest.raises(ValueError, match="spin rotation"):
        RackAgent(gym.make("pool_env/EightBallGame-v1"))


@pytest.mark.parametrize(
    ("info", "reward"),
    [
        ({"legal": True, "foul": None, "potted": (2,), "winner": -1}, 1.0),
        ({"legal": True, "foul": None, "potted": (), "winner": -1}, 0.0),
        ({"legal": True, "foul": None, "potted": (3, 9), "winner": 0}, 2.0 + WIN_BONUS),
        ({"legal": False, "foul": "scratch", "potted": (1,), "winner": -1}, 0.0),
        ({"legal": False, "foul": "wrong_ball_first", "potted": (), "winner": -1}, 0.0),
    ],
)
def test_shot_reward_counts_legal_pots_and_the_win(info: dict, reward: float) -> None:
    assert shot_reward(info) == reward


def test_fitted_q_iteration_recovers_the_discounted_return_of_a_chain() -> None:
    # Racks of two shots, one candidate each: the first (x = 0) pots and the rack goes on,
    # the second (x = 1) pots and ends it: Q = 1 + gamma and Q = 1.
    f, n = len(FEATURES), 60
    rows = np.zeros((2 * n, f))
    rows[1::2, 0] = 1.0
    data = {
        "features": rows, "offsets": np.arange(2 * n + 1), "picks": np.zeros(2 * n, int),
        "rewards": np.ones(2 * n), "dones": np.tile([False, True], n),
        "rack": np.repeat(np.arange(n), 2),
    }  # fmt: skip
    net, _, _ = fit(data, GAMMA, rounds=6, hidden=8, seed=0)
    q = net(rows[:2])
    assert q[0] == pytest.approx(1.0 + GAMMA, abs=0.05) and q[1] == pytest.approx(1.0, abs=0.05)


def test_the_committed_model_loads_and_plays(capsys) -> None:
    env = gym.make(ENV_ID, end_on_foul=True, noise=(0.003, 0.05, 0.05))
    agent = load_rack_agent(MODEL, env)
    assert agent.value is not None and agent.break_arm is not None
    assert isinstance(make_agent(str(MODEL), env), RackAgent)
    obs, _ = env.reset(seed=10000)
    action, _ = agent.predict(obs)
    assert action[1] == BREAK_ARMS[agent.break_arm][0]
    argv = ["--env", ENV_ID, "--agent", str(MODEL), "--episodes", "3", "--noise",
            "0.003,0.05,0.05", "--env-kwargs", "{end_on_foul: true}"]  # fmt: skip
    assert evaluate_main(argv) == 0
    assert "rack_value.npz" in capsys.readouterr().out


def test_a_model_without_its_config_is_refused(tmp_path) -> None:
    env = gym.make(ENV_ID)
    (tmp_path / "m.npz").write_bytes(MODEL.read_bytes())
    with pytest.raises(FileNotFoundError, match="config"):
        load_rack_agent(tmp_path / "m.npz", env)


def test_duels_alternate_the_break_and_count_every_rack() -> None:
    out = play_duels("ghost", "random", racks=2, seed=20000)
    assert out["wins"] + out["losses"] + out["draws"] == 2
    assert out["agent"]["breaks"] == 1 and out["opponent"]["breaks"] == 1
    assert 0.0 <= out["win_rate"].value <= 1.0
    with pytest.raises(ValueError, match="racks"):
        play_duels("ghost", "random", racks=0, seed=0)


def test_the_curve_reads_back_the_evaluation_table(tmp_path) -> None:
    from agents.evaluation.metrics import Estimate
    from agents.evaluation.table import format_table
    from agents.training.rack_curve import read_tables

    stats = {
        "fouls_per_shot": Estimate(0.141, 0.116, 0.166),
        "pots_per_shot": Estimate(0.873, 0.843, 0.904),
        "scratch_rate": Estimate(0.085, 0.064, 0.105),
        "clear_rate": Estimate(0.023, 0.011, 0.047),
        "run_out_rate": Estimate(0.023, 0.011, 0.047),
        "shots_per_episode": Estimate(2.79, 2.592, 2.988),
        "episode_reward": Estimate(1.767, 1.516, 2.018),
    }
    (tmp_path / "t.md").write_text(format_table({"ghost": stats}, 300))
    row = read_tables([str(tmp_path / "t.md")])["ghost"]
    assert row["run-outs"].value == pytest.approx(0.023) and row["run-outs"].high == 0.047
    assert row["pots/shot"].low == pytest.approx(0.843)
