"""The baselines on the spin ids: position play with the tip, tip search, tip noise, the rules.

The ghost-ball agent must pot on ``OneBall-v1`` without calling the simulator, choose draw
when the next ball lies behind the cue ball, and give its tip in the action's last two
components; the search agent pots every seeded layout; the evaluation takes a tip noise;
the rules' next legal ball is the one the game names.
"""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

import pool_env  # noqa: F401  (registers the ids)
from agents import GhostBallAgent, SearchAgent, run_episodes
from agents.baselines.game_agents import GameGhostBallAgent, GameSearchAgent
from agents.evaluation.evaluate import main, rack_ends
from agents.evaluation.noise_flag import parse_noise
from agents.evaluation.players import make_agent
from pool_env.envs.registration import spin_id
from pool_env.sim.kernels import loop

ONE = "pool_env/OneBall-v1"
R = 0.028575


def _forbidden(*args: object, **kwargs: object) -> None:
    raise AssertionError("the geometric agent called the simulator")


def test_ghost_pots_on_oneball_v1_without_the_simulator(monkeypatch: pytest.MonkeyPatch) -> None:
    env = gym.make(ONE)
    agent = GhostBallAgent(env)
    pots = 0
    for k in range(40):
        obs, _ = env.reset(seed=10_000 + k)
        with monkeypatch.context() as m:
            m.setattr(loop, "packed_shot", _forbidden)
            m.setattr(loop, "packed_strike", _forbidden)
            action, _ = agent.predict(obs)
        assert action.shape == (4,) and np.all(np.abs(action) <= 1.0)
        *_, info = env.step(action)
        pots += info["potted"] == (1,) and not info["scratch"]
    assert pots >= 37  # >= 92.5% clean pots on 40 seeded layouts (95% is the 1000-episode target)


def test_ghost_draws_back_for_a_ball_behind_the_cue_ball() -> None:
    """Straight into the bottom side pocket, the next ball up behind the cue ball: draw."""
    env = gym.make("pool_env/Pool-v1", n_balls=2) if _has("pool_env/Pool-v1") else None
    if env is None:
        env = gym.make("pool_env/PoolRoll-v1", n_balls=2, model="spin")
    positions = np.array([[1.27, 0.55], [1.27, 0.30], [1.45, 1.05]])
    obs, _ = env.reset(seed=0, options={"positions": positions})
    agent = GhostBallAgent(env)
    action, _ = agent.predict(obs)
    assert agent.last_plan["shot"].ball == 1 and agent.last_plan["shot"].pocket == 1
    assert action[3] < 0.0  # draw
    *_, info = env.step(action)
    assert info["potted"] == (1,)
    rest = env.unwrapped.positions[0]
    assert rest[1] > 0.55  # it came back towards the next ball
    predicted = agent.last_contact.path.rest
    assert np.hypot(*(predicted - rest)) < 0.01  # and where the closed form said


def _has(env_id: str) -> bool:
    return env_id in gym.registry


def test_centre_agent_never_uses_the_tip() -> None:
    env = gym.make(ONE)
    agent = make_agent("ghost-centre", env)
    for k in range(5):
        obs, _ = env.reset(seed=10_000 + k)
        action, _ = agent.predict(obs)
        assert np.all(action[2:] == 0.0)


def test_search_pots_every_seeded_oneball_v1_layout() -> None:
    env = gym.make(ONE)
    stats = run_episodes(SearchAgent(env, seed=0), env, 20, 10_000).summary()
    assert stats["clean_pot_rate"].value == 1.0


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("0.003,0.05", (0.003, 0.05)),
        ("0.003,0.05,0.05", (0.003, 0.05, 0.05)),
        ("fastfiz", "fastfiz"),  # FastFiz's model, the championships' (pool_env.game.noise)
        ("fastfiz:5", ("fastfiz", 5.0)),
        ("fastfiz:0", ("fastfiz", 0.0)),
    ],
)
def test_noise_option_parses_sigmas_or_the_model(text: str, expected: object) -> None:
    assert parse_noise(text) == expected


@pytest.mark.parametrize(
    "text",
    ["0.003", "0.003,0.05,0.05,1", "a,b", "-1,0", "0,inf", "fastfizz", "fastfiz:x",
     "fastfiz:-1", "fastfiz:", "fastfiz,5"],
)  # fmt: skip
def test_bad_noise_is_a_clear_error(text: str) -> None:
    with pytest.raises(ValueError, match="--noise"):
        parse_noise(text)


def test_tip_noise_moves_the_executed_tip_by_its_sigma() -> None:
    """The evaluation's third sigma reaches the env: executed tips scatter around the chosen."""
    env = gym.make(ONE, noise=(0.0, 0.0, 0.05))
    agent = GhostBallAgent(env)
    errors = []
    for k in range(60):
        obs, _ = env.reset(seed=10_000 + k)
        action, _ = agent.predict(obs)
        env.step(action)
        limit = env.unwrapped.config.tip_limit
        executed = np.array(env.unwrapped.last_strike[2:])
        errors.append(executed - action[2:].astype(np.float64) * limit)
    spread = np.std(np.concatenate(errors))
    assert 0.035 < spread < 0.065
    assert agent.spec.noise == (0.0, 0.0, 0.05)


def test_the_commands_take_the_model_by_name(capsys: pytest.CaptureFixture[str]) -> None:
    """``--noise fastfiz:5`` reaches the env of agents.evaluate and agents.duels alike."""
    from agents.evaluation import duels

    assert main(["--env", ONE, "--agent", "random", "--episodes", "2", "--noise", "fastfiz:5"]) == 0
    assert f"{ONE}, noise fastfiz:5 (FastFiz x5), seeds" in capsys.readouterr().out
    argv = ["--env", "pool_env/NineBallGameRoll-v2", "--agent", "random", "--opponent",
            "random", "--racks", "1", "--noise", "fastfiz"]  # fmt: skip
    assert duels.main(argv) == 0
    assert "noise fastfiz (FastFiz x1, the field's)," in capsys.readouterr().out
    with pytest.raises(SystemExit):
        duels.main([*argv[:-1], "fastfiz:-1"])
    assert "k must be >= 0" in capsys.readouterr().err


def test_evaluate_runs_a_spin_id_with_tip_noise(capsys: pytest.CaptureFixture[str]) -> None:
    assert (
        main(["--env", ONE, "--agent", "ghost", "--episodes", "3", "--noise", "0.003,0.05,0.05"])
        == 0
    )
    assert "noise" in capsys.readouterr().out


@pytest.mark.parametrize(
    ("game", "left", "potted", "expected"),
    [
        ("nine", [3, 5, 9], 2, [3]),
        ("nine", [9], 8, [9]),
        ("eight", [2, 5, 8, 11], 1, [2, 5]),  # solids left
        ("eight", [8, 11], 3, [8]),  # the group is cleared: the 8
        ("eight", [2, 8, 12], 10, [12]),  # a stripe potted: stripes
        ("eight", [2, 12], 8, []),  # the 8 ends the rack
    ],
)
def test_next_legal_ball_by_the_rules(game: str, left: list, potted: int, expected: list) -> None:
    env = gym.make(spin_id("NineBallGame" if game == "nine" else "EightBallGame"))
    agent = GameGhostBallAgent(env)
    n = env.unwrapped.config.n_balls
    after = np.zeros(n, dtype=bool)
    after[[0, *left]] = True
    assert agent._next_legal(np.zeros((n, 2)), after, potted) == expected


@pytest.mark.parametrize(
    "name", ["pool_env/NineBallGame-v2", "pool_env/TenBallGame-v1", "pool_env/EightBallGame-v1"]
)
def test_both_agents_play_the_rules_ids_with_the_tip(name: str) -> None:
    env = gym.make(name, noise=(0.003, 0.05, 0.05))
    config = env.unwrapped.config
    tips = []
    for agent in (make_agent("ghost", env), make_agent("search", env)):
        assert isinstance(agent, GameGhostBallAgent | GameSearchAgent)
        obs, _ = env.reset(seed=10_000)
        for _ in range(3):
            action, _ = agent.predict(obs)
            assert action.shape == (config.action_size,) and np.all(np.abs(action) <= 1.0)
            tips.append(action[list(config.tip_columns)])
            obs, _, terminated, truncated, info = env.step(action)
            assert not info.get("push_out") and not info.get("handed_back")  # one player
            if terminated or truncated:
                break
    assert np.isfinite(tips).all()


def test_rack_ends_count_every_rack_and_agree_with_the_run_outs() -> None:
    env = gym.make("pool_env/NineBallGame-v2", noise=(0.003, 0.05, 0.05), end_on_foul=True)
    ends = rack_ends(make_agent("ghost", env), env, 12, 10_000)
    assert sum(ends.values()) == 12
    won = sum(count for (_, outcome), count in ends.items() if outcome == "won")
    stats = run_episodes(make_agent("ghost", env), env, 12, 10_000).summary()
    assert won == round(stats["run_out_rate"].value * 12)
