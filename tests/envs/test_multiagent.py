"""The two-player AEC env: PettingZoo's API test, determinism, turns and wins by the rules."""

from __future__ import annotations

import math

import numpy as np
import pytest
from pettingzoo.test import api_test

from pool_env.envs.multiagent import PoolDuelEnv, VersusPolicyEnv

TOWARD_CORNER = -3 * math.pi / 4
# Tests that aim by direction (-pi .. pi from +x) pass aim="absolute": the default is the
# game ids' cut aim (tests/envs/test_front_defaults.py).


def _speed_action(env: PoolDuelEnv, speed: float) -> float:
    lo, hi = env.config.speed_range
    return 2.0 * (speed - lo) / (hi - lo) - 1.0


@pytest.mark.parametrize("game", ["nine", "eight"])
def test_pettingzoo_api(game: str) -> None:
    api_test(PoolDuelEnv(game, max_shots=40), num_cycles=100)


def _rollout(seed: int, shots: int = 12) -> list:
    env = PoolDuelEnv("nine", noise=(0.01, 0.05), max_shots=shots, model="roll")
    env.reset(seed=seed)
    rng = np.random.default_rng(seed)
    trace = []
    for agent in env.agent_iter():
        obs, reward, term, trunc, info = env.last()
        action = None if term or trunc else rng.uniform(-1, 1, 6).astype(np.float32)
        trace.append((agent, obs.tobytes(), reward, info.get("foul")))
        env.step(action)
    return trace


def test_same_seed_same_game() -> None:
    assert _rollout(3) == _rollout(3)
    assert _rollout(3) != _rollout(4)


def test_a_break_that_touches_nothing_gives_the_opponent_ball_in_hand() -> None:
    env = PoolDuelEnv("nine", aim="absolute", break_speed_range=(0.5, 10.0), model="roll")
    env.reset(seed=0)
    # Observation: 3 x 10 ball entries, 9 legal-ball flags, then ball in hand (39), behind
    # the head string (40), break (41), open table (42), own fouls (43), opponent's (44).
    assert env.agent_selection == "player_0" and env.observe("player_0")[39] == 1.0
    # Cue ball placed in the kitchen, shot softly into the head rail: it never reaches the rack.
    r = env.config.table.ball_radius
    ax = 2 * (0.3 - r) / (env.config.table.length / 4 - r) - 1  # the break's placement: the kitchen
    env.step(np.array([-1.0, -1.0, ax, 0.0, 0.0, 0.0], np.float32))
    assert env.infos["player_1"]["foul"] == "illegal_break"
    assert env.agent_selection == "player_1"
    obs = env.observe("player_1")
    assert obs[39] == 1.0 and obs[40] == 0.0  # ball in hand anywhere, not only the kitchen
    assert obs[44] == 0.5 and obs[43] == 0.0  # the opponent (player_0) has one foul in a row
    assert obs[45] == 1.0 and env.observe("player_0")[45] == 0.0  # player_1 shoots next


def test_the_nine_straight_in_wins_the_rack() -> None:
    env = PoolDuelEnv("nine", aim="absolute", model="roll")
    pos = np.array([[1.5, 0.6]] * 10)
    on = np.zeros(10, bool)
    on[[0, 9]] = True
    pos[0] = (0.45 / math.sqrt(2),) * 2
    pos[9] = (0.25 / math.sqrt(2),) * 2
    env.reset(seed=0, options={"positions": pos, "on_table": on})
    env.step(np.array([TOWARD_CORNER / math.pi, _speed_action(env, 1.5), 0, 0, 0, 0.0], np.float32))
    assert env.infos["player_0"]["winner"] == "player_0"
    assert env.rewards == {"player_0": 1.0, "player_1": -1.0}
    assert all(env.terminations.values())


def test_reset_refuses_an_invalid_layout() -> None:
    env = PoolDuelEnv("nine")
    pos = np.array([[1.0, 0.6]] * 10)
    with pytest.raises(ValueError, match="overlap"):
        env.reset(options={"positions": pos})
    with pytest.raises(ValueError, match="keep the cue"):
        env.reset(options={"positions": pos, "on_table": np.zeros(10, bool)})


def test_versus_policy_env_passes_the_checkers() -> None:
    from gymnasium.utils.env_checker import check_env
    from stable_baselines3.common.env_checker import check_env as sb3_check_env

    check_env(VersusPolicyEnv(game="nine", max_shots=30), skip_render_check=True)
    sb3_check_env(VersusPolicyEnv(game="eight", max_shots=30), warn=True)


def test_versus_policy_rack_ends_with_the_opponents_win_or_the_agents() -> None:
    """A rack against a random opponent: the agent's return is the rack's result."""
    env = VersusPolicyEnv(game="nine", max_shots=400, model="roll")
    env.reset(seed=1)
    total, done, rng = 0.0, False, np.random.default_rng(1)
    while not done:
        _, reward, term, trunc, _ = env.step(rng.uniform(-1, 1, 6).astype(np.float32))
        total += reward
        done = term or trunc
    winner = env.duel.rack["winner"]
    assert total == (0.0 if winner < 0 else (1.0 if winner == 0 else -1.0))
    with pytest.raises(ValueError, match="rack is over"):
        env.step(np.zeros(6, np.float32))


# --- issue 20: an opponent's failure, the shot limit, and the two-player front's edges ----


def _state_of(env: VersusPolicyEnv) -> tuple:
    duel = env.duel
    return (
        duel.positions.tobytes(), duel._state.on_table.tobytes(), duel.shots, duel.rack,
        duel.agent_selection, dict(duel.terminations), dict(duel.truncations),
        dict(duel.rewards), duel._state.generators[0].bit_generator.state,
        env.np_random.bit_generator.state,
    )  # fmt: skip


def _miss_then(policy):
    """An opponent that fails once (``policy``), then plays like the random one."""
    calls = {"n": 0}

    def opponent(obs: np.ndarray):
        calls["n"] += 1
        if calls["n"] == 1:
            return policy(obs)
        return np.zeros(6, np.float32)

    return opponent


def _boom(obs: np.ndarray):
    raise RuntimeError("boom")


@pytest.mark.parametrize(
    ("policy", "match"),
    [
        (_boom, r"opponent policy raised RuntimeError\('boom'\)"),
        (lambda obs: np.full(6, np.nan, np.float32), r"opponent policy returned an invalid.*NaN"),
        (lambda obs: np.zeros(3, np.float32), r"opponent policy returned an invalid.*shape"),
        (lambda obs: "aim left", r"opponent policy returned an invalid.*dtype"),
        (lambda obs: None, r"opponent policy returned an invalid"),
    ],
)
def test_an_opponent_failure_takes_the_agents_shot_back(policy, match: str) -> None:
    # The agent's break touches nothing (a foul): the opponent comes to the table and fails.
    # The step raises naming the opponent, and the game is as before the step: the agent is
    # still to break, the generators have not moved; the next step plays the agent's shot.
    env = VersusPolicyEnv(opponent=_miss_then(policy), game="nine", aim="absolute",
                          break_speed_range=(0.5, 10.0), model="roll")  # fmt: skip
    env.reset(seed=0)
    r = env.duel.config.table.ball_radius
    ax = 2 * (0.3 - r) / (env.duel.config.table.length / 4 - r) - 1
    soft = np.array([-1.0, -1.0, ax, 0.0, 0.0, 0.0], np.float32)  # into the head rail
    before = _state_of(env)
    with pytest.raises(ValueError, match=match):
        env.step(soft)
    assert _state_of(env) == before
    assert env.duel.agent_selection == "player_0" and env.duel.rack["break"]
    _, _, _, _, info = env.step(soft)  # the agent's shot again, then the opponent's
    assert info["foul"] == "illegal_break" and info["opponent_shots"] >= 1


def test_an_opponent_failure_on_reset_leaves_the_env_as_it_was() -> None:
    env = VersusPolicyEnv(opponent=_boom, game="nine")
    env.reset(seed=1)
    before = _state_of(env)
    pos = np.array([[0.3 + 0.1 * k, 0.3] for k in range(10)])
    with pytest.raises(ValueError, match="opponent policy raised"):
        env.reset(seed=2, options={"positions": pos, "rules": {"shooter": 1}})
    assert _state_of(env) == before


def test_a_bad_agent_action_changes_nothing() -> None:
    env = VersusPolicyEnv(game="nine")
    env.reset(seed=0)
    before = _state_of(env)
    for bad in (np.full(5, np.nan), np.zeros(2), "shoot"):
        with pytest.raises(ValueError, match="the action"):
            env.step(bad)
        assert _state_of(env) == before


def _straight_nine(env: PoolDuelEnv, **rules) -> None:
    pos = np.array([[1.5, 0.6]] * 10)
    pos[1:9] = [[1.2 + 0.07 * k, 1.1] for k in range(8)]
    on = np.zeros(10, bool)
    on[[0, 9]] = True
    pos[0] = (0.45 / math.sqrt(2),) * 2
    pos[9] = (0.25 / math.sqrt(2),) * 2
    env.reset(seed=0, options={"positions": pos, "on_table": on, "rules": rules})


@pytest.mark.parametrize("limit", [1, 2, 3])
def test_the_shot_limit_truncates_both_players(limit: int) -> None:
    # Every shot misses (a soft shot away from the 9): the turn passes each time, so the
    # last shot is player_0's (odd limits) or player_1's (even). Both are truncated at
    # once, whoever shot, and the AEC loop then only removes them: no shot past the limit.
    env = PoolDuelEnv("nine", max_shots=limit, aim="absolute", model="roll")
    _straight_nine(env)
    away = np.array([0.25, -0.9, 0.0, 0.0, 0.0, 0.0], np.float32)  # +pi/4: off the 9's line
    shooters = []
    for agent in env.agent_iter(max_iter=50):
        _, _, term, trunc, _ = env.last()
        if term or trunc:
            env.step(None)
            continue
        shooters.append(agent)
        env.step(away)
        if env.shots == limit:
            assert env.truncations == {"player_0": True, "player_1": True}
            assert not any(env.terminations.values())
    assert env.shots == limit and env.agents == []
    assert shooters == [("player_0", "player_1")[k % 2] for k in range(limit)]


def test_a_win_on_the_last_allowed_shot_terminates_rather_than_truncates() -> None:
    env = PoolDuelEnv("nine", max_shots=1, aim="absolute", model="roll")
    _straight_nine(env)
    env.step(np.array([TOWARD_CORNER / math.pi, _speed_action(env, 1.5), 0, 0, 0, 0.0], np.float32))
    assert env.terminations == {"player_0": True, "player_1": True}
    assert env.truncations == {"player_0": False, "player_1": False}
    assert env.rewards == {"player_0": 1.0, "player_1": -1.0}


def test_the_loser_sees_its_minus_one_and_the_rewards_sum_to_zero() -> None:
    # player_1 shoots the 9 in: player_0 (who did not shoot) gets -1 through last().
    env = PoolDuelEnv("nine", aim="absolute", model="roll")
    _straight_nine(env, shooter=1)
    assert env.agent_selection == "player_1"
    env.step(np.array([TOWARD_CORNER / math.pi, _speed_action(env, 1.5), 0, 0, 0, 0.0], np.float32))
    assert env.infos["player_0"]["winner"] == "player_1"
    seen = {}
    for agent in env.agent_iter(max_iter=4):
        _, reward, term, _, _ = env.last()
        seen[agent] = reward
        assert term
        env.step(None)
    assert seen == {"player_0": -1.0, "player_1": 1.0}


def test_versus_policy_truncates_at_the_shot_limit_inside_the_opponents_turn() -> None:
    # The agent's soft break fouls; a passive opponent then runs into the limit: the
    # agent's step reports the truncation, and a further step is refused.
    env = VersusPolicyEnv(opponent=lambda obs: np.array([0.5, -1, 0, 0, 0, 0.0], np.float32),
                          game="nine", max_shots=2, aim="absolute",
                          break_speed_range=(0.5, 10.0), model="roll")  # fmt: skip
    env.reset(seed=0)
    r = env.duel.config.table.ball_radius
    ax = 2 * (0.3 - r) / (env.duel.config.table.length / 4 - r) - 1
    _, reward, term, trunc, info = env.step(np.array([-1.0, -1.0, ax, 0, 0, 0.0], np.float32))
    assert info["opponent_shots"] == 1 and env.duel.shots == 2
    assert trunc and not term and reward == 0.0
    with pytest.raises(ValueError, match="rack is over"):
        env.step(np.zeros(6, np.float32))


def test_observations_and_infos_are_never_shared() -> None:
    env = PoolDuelEnv("nine", model="roll")
    env.reset(seed=0)
    a, b = env.observe("player_0"), env.observe("player_0")
    a[:] = 0.5
    assert not np.array_equal(a, b) and np.array_equal(b, env.observe("player_0"))
    env.step(np.zeros(6, np.float32))
    env.infos["player_0"]["foul"] = "changed"
    assert env.infos["player_1"]["foul"] != "changed"


@pytest.mark.parametrize("seed", [np.int64(5), np.uint8(5), 5])
def test_numpy_integer_seeds_play_as_python_ints(seed) -> None:
    runs = []
    for s in (seed, 5):
        env = VersusPolicyEnv(game="nine", model="roll")
        obs, _ = env.reset(seed=s)
        out = env.step(np.array([0.0, 0.5, 0.0, 0.0, 0.0, 0.0], np.float32))
        runs.append((obs.tobytes(), out[0].tobytes(), out[4]["opponent_shots"]))
        duel = PoolDuelEnv("nine", noise=(0.01, 0.05), model="roll")
        duel.reset(seed=s)
        duel.step(np.zeros(6, np.float32))
        runs.append(duel.positions.tobytes())
    assert runs[0] == runs[2] and runs[1] == runs[3]


def test_the_opponent_winning_in_its_turn_gives_the_agent_minus_one() -> None:
    # The agent misses everything (a foul); the opponent, with ball in hand, places the cue
    # ball on the 9's diagonal and pots it: the agent's step ends the episode with -1.
    def potter(obs: np.ndarray) -> np.ndarray:
        table = env.duel.config.table
        r = table.ball_radius
        x = y = 0.45 / math.sqrt(2)
        u = 2 * (x - r) / (table.length - 2 * r) - 1
        v = 2 * (y - r) / (table.width - 2 * r) - 1
        return np.array([TOWARD_CORNER / math.pi, speed, u, v, 0.0, 0.0], np.float32)

    env = VersusPolicyEnv(opponent=potter, game="nine", aim="absolute", model="roll")
    speed = _speed_action(env.duel, 1.5)
    pos = np.array([[1.5, 0.6]] * 10)
    on = np.zeros(10, bool)
    on[[0, 9]] = True
    pos[0], pos[9] = (1.0, 1.0), (0.25 / math.sqrt(2),) * 2
    env.reset(seed=0, options={"positions": pos, "on_table": on})
    _, reward, term, trunc, info = env.step(
        np.array([0.5, _speed_action(env.duel, 0.3), 0, 0, 0, 0.0], np.float32)  # up the table
    )
    assert info["foul"] == "no_contact" and info["opponent_shots"] == 1
    assert reward == -1.0 and term and not trunc
    assert env.duel.rack["winner"] == 1


def test_a_bad_action_in_the_duel_changes_nothing() -> None:
    env = PoolDuelEnv("nine")
    env.reset(seed=0)
    before = (env.positions.tobytes(), env.rack, env.shots, env.agent_selection,
              env._state.generators[0].bit_generator.state)  # fmt: skip
    for bad in (np.full(5, np.nan), np.zeros(4), "break"):
        with pytest.raises(ValueError, match="the action"):
            env.step(bad)
        after = (env.positions.tobytes(), env.rack, env.shots, env.agent_selection,
                 env._state.generators[0].bit_generator.state)  # fmt: skip
        assert after == before
