"""The rules' choices of the game agents: the action's columns, calls, option, push-out."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

import pool_env
from agents.baselines.game_agents import GameGhostBallAgent
from agents.baselines.rule_play import TAKE_CHANCE, push_value, rule_action, take_table
from agents.evaluation.duels import play_duels
from agents.evaluation.players import make_agent
from agents.policy import last_plan
from pool_env.envs.multiagent import AGENTS, PoolDuelEnv
from pool_env.envs.registration import spin_id

NOISE = (0.003, 0.05, 0.05)
SPIN_IDS = ("NineBallGame-v2", "TenBallGame-v1", "EightBallGame-v1")
ROLL_IDS = ("NineBallGameRoll-v2", "TenBallGameRoll-v1", "EightBallGameRoll-v1")


def _ball_on(on_table: np.ndarray) -> int:
    return int(np.flatnonzero(on_table[1:])[0]) + 1


@pytest.mark.parametrize("env_id", SPIN_IDS + ROLL_IDS)
def test_rule_action_lays_out_the_calls_and_the_tip_where_the_game_reads_them(env_id: str) -> None:
    env = gym.make(f"pool_env/{env_id}")
    config = env.unwrapped.config
    env.reset(seed=3)
    u = env.unwrapped
    strike = [0.1, -0.2, 0.3, -0.4] if config.spin else [0.1, -0.2]
    rack = {**u.rack, "break": False}
    shot = pool_env.decode_action(
        config, rule_action(config, strike, pocket=4, ball=2), u.positions, u.on_table, rack
    )
    assert shot.pocket == 4
    assert shot.ball == (2 if config.game == "ten" else None)
    assert not shot.push_out and not shot.pass_back
    if config.game == "ten":
        with pytest.raises(ValueError, match="calls a ball"):
            rule_action(config, strike)
    if config.spin:  # the tip is read from the game's own tip columns, whatever its width
        centre = pool_env.decode_action(
            config, rule_action(config, strike[:2] + [0.0, 0.0], ball=2), u.positions,
            u.on_table, rack,
        )  # fmt: skip
        assert shot.tip != centre.tip and centre.tip == (0.0, 0.0)
    if config.ruleset.has_option:  # the option column declares a push-out where offered
        pushed = pool_env.decode_action(
            config, rule_action(config, strike, ball=2, option=True), u.positions, u.on_table,
            {**rack, "push_out": True},
        )  # fmt: skip
        assert pushed.push_out


@pytest.mark.parametrize("env_id", SPIN_IDS + ROLL_IDS)
def test_every_game_agent_plays_racks_the_env_accepts(env_id: str) -> None:
    """Every game agent plays racks the env takes; 10-ball's shots call the ball on.

    Ghost-ball and the search, and on the spin ids the centre-ball ghost (and on the
    rotation ones the rack planner).
    """
    spin = env_id in SPIN_IDS
    env = gym.make(f"pool_env/{env_id}", noise=NOISE if spin else NOISE[:2])
    config = env.unwrapped.config
    names = ["ghost", "search"] + (["ghost-centre"] if spin else [])
    if spin and config.game != "eight":
        names.append("rack-planner")
    for name in names:
        agent = make_agent(name, env)
        obs, _ = env.reset(seed=20_000)
        for _ in range(6):
            u = env.unwrapped
            rack, positions, on = dict(u.rack), u.positions.copy(), u.on_table.copy()
            action, _ = agent.predict(obs)
            assert action.shape == (config.action_size,) and np.all(np.abs(action) <= 1.0)
            if config.game == "ten" and not rack["break"]:
                shot = pool_env.decode_action(config, action, positions, on, rack)
                assert shot.ball == _ball_on(on), (name, shot)
            obs, _, terminated, truncated, info = env.step(action)
            # One player: a push-out would end a run or be a free placement (rule_play).
            assert not info.get("push_out") and not info.get("handed_back")
            if terminated or truncated:
                break


def _scatter(rng: np.random.Generator, config, balls: list[int]) -> tuple[np.ndarray, np.ndarray]:
    """A layout of the cue ball and ``balls`` at random points, apart and off the pockets."""
    table = config.table
    n, r = config.n_balls, table.ball_radius
    positions = np.zeros((n, 2))
    on = np.zeros(n, dtype=bool)
    placed: list[np.ndarray] = []
    for j in [0, *balls]:
        while True:
            p = rng.uniform([4 * r, 4 * r], [table.length - 4 * r, table.width - 4 * r])
            if all(np.hypot(*(p - q)) > 3 * r for q in placed):
                break
        placed.append(p)
        positions[j], on[j] = p, True
    for j in np.flatnonzero(~on):  # off the table: anywhere free (not read)
        positions[j] = (r * (1 + 2 * j), r)
    return positions, on


def test_the_ten_ball_ghost_agent_makes_most_of_its_pots_as_called() -> None:
    """Of its legal pots of the ball on, at least 90% keep the table: the call was made.

    One shot on each of 60 seeded layouts (the 1, 2 and 10, or the 3, 6 and 10): a legal
    shot that pots the ball on keeps the table exactly when it dropped in the called pocket.
    """
    env = gym.make("pool_env/TenBallGame-v1", noise=NOISE)
    config = env.unwrapped.config
    agent = GameGhostBallAgent(env)
    rng = np.random.default_rng(34)
    rules = {"break": False, "ball_in_hand": False}
    made = potted = 0
    for k in range(60):
        balls = [1, 2, 10] if k % 2 else [3, 6, 10]
        positions, on = _scatter(rng, config, balls)
        obs, _ = env.reset(options={"positions": positions, "on_table": on, "rules": rules})
        u = env.unwrapped
        action, _ = agent.predict(obs)
        shot = pool_env.decode_action(config, action, u.positions, u.on_table, u.rack)
        assert shot.ball == balls[0]
        if last_plan(agent).get("kind") == "ghost":
            assert shot.pocket == last_plan(agent)["pocket"]
        *_, info = env.step(action)
        if info["foul"] is None and balls[0] in info["potted"]:
            potted += 1
            made += not info["turn_over"]
    assert potted >= 20, potted
    assert made >= 0.9 * potted, (made, potted)


def test_the_push_value_is_the_chooser_s_option() -> None:
    assert take_table(TAKE_CHANCE) and not take_table(TAKE_CHANCE - 1e-9)
    # Left a hard shot, the opponent hands it back; left an easy one, it takes it.
    assert push_value(0.2) == pytest.approx(0.2)
    assert push_value(0.9) == pytest.approx(0.1)
    assert max(push_value(c) for c in np.linspace(0, 1, 101)) <= 0.5


def _blocked_layout(config) -> tuple[np.ndarray, np.ndarray]:
    """The cue ball hidden from the 1 behind a wall of three balls: no clear pot.

    A soft roll up or down the table opens one.
    """
    n, r = config.n_balls, config.table.ball_radius
    mid = config.table.width / 2.0
    positions = np.array([(r * (1 + 2 * j), r) for j in range(n)], dtype=float)
    on = np.zeros(n, dtype=bool)
    positions[0], positions[1] = (0.6, mid), (1.9, mid)
    for j, dy in zip((2, 3, 4), (-2.1, 0.0, 2.1), strict=True):
        positions[j] = (1.2, mid + dy * r)
    positions[config.ruleset.money_ball] = (2.2, 0.25)
    on[[0, 1, 2, 3, 4, config.ruleset.money_ball]] = True
    return positions, on


def _duel(game: str) -> tuple[PoolDuelEnv, dict[str, GameGhostBallAgent]]:
    duel = PoolDuelEnv(game=game, model="spin", noise=NOISE)
    env = gym.make(spin_id("NineBallGame" if game == "nine" else "TenBallGame"), noise=NOISE)
    return duel, {seat: GameGhostBallAgent(env, players=2) for seat in AGENTS}


def _duel_step(duel: PoolDuelEnv, agents: dict[str, GameGhostBallAgent]) -> tuple[str, dict]:
    seat = duel.agent_selection
    action, _ = agents[seat].predict(duel.observe(seat))
    duel.step(np.asarray(action, dtype=np.float32))
    return seat, duel.infos[seat]


@pytest.mark.parametrize("game", ["nine", "ten"])
def test_a_two_player_agent_pushes_out_and_the_opponent_takes_or_hands_back(game: str) -> None:
    """Hidden from the ball on, the shooter pushes out; the opponent's choice goes through."""
    duel, agents = _duel(game)
    positions, on = _blocked_layout(duel.config)
    rules = {"break": False, "push_out": True}
    duel.reset(options={"positions": positions, "on_table": on, "rules": rules})
    seat, info = _duel_step(duel, agents)
    plan = last_plan(agents[seat])
    assert seat == AGENTS[0] and plan["kind"] == "push out", plan
    assert plan["chance"] == 0.0 and 0.0 < plan["value"] <= TAKE_CHANCE
    assert info["push_out"] and info["foul"] is None and info["potted"] == ()
    # The opponent has the option: it hands back exactly when its best chance is poor.
    chooser = duel.agent_selection
    assert chooser == AGENTS[1]
    chance = agents[chooser].best_chance(*_layout_of(duel, chooser, agents[chooser]))
    seat, info = _duel_step(duel, agents)
    assert info["handed_back"] == (not take_table(chance))
    assert last_plan(agents[chooser])["kind"] == ("hand back" if info["handed_back"] else "ghost")
    if info["handed_back"]:
        assert duel.agent_selection == AGENTS[0]  # the pusher shoots what it left


def _layout_of(duel: PoolDuelEnv, seat: str, agent: GameGhostBallAgent):
    """``(positions, on, reference)`` as the agent reads the seat's observation."""
    obs = duel.observe(seat)
    balls = pool_env.obs_layout(duel.config)["balls"]
    positions, on = agent.ghost.source.layouts(obs[None, balls])[0]
    legal = list(pool_env.shot_constraints(duel.config, obs).first_balls)
    agent._targets = legal
    reference = np.zeros_like(on)
    reference[0] = on[0]
    reference[legal] = on[legal]
    return positions, on, reference


@pytest.mark.parametrize("game", ["nine", "ten"])
def test_with_a_clear_shot_the_agent_neither_pushes_nor_hands_back(game: str) -> None:
    duel, agents = _duel(game)
    table = duel.config.table
    positions, on = _blocked_layout(duel.config)
    on[[2, 3, 4]] = False  # the wall gone: a straight-in shot on the 1 into the far corner
    corner = table.pockets[5, :2]
    u = (corner - positions[0]) / np.hypot(*(corner - positions[0]))
    positions[1] = corner - 0.35 * u
    positions[0] = positions[1] - 0.3 * u
    for rules in ({"break": False, "push_out": True}, {"break": False, "option": True}):
        duel.reset(options={"positions": positions, "on_table": on, "rules": rules})
        seat, info = _duel_step(duel, agents)
        assert not info["push_out"] and not info["handed_back"]
        assert last_plan(agents[seat])["kind"] == "ghost"


def test_with_the_option_on_a_hopeless_layout_the_agent_hands_back() -> None:
    duel, agents = _duel("nine")
    positions, on = _blocked_layout(duel.config)
    duel.reset(options={"positions": positions, "on_table": on,
                        "rules": {"break": False, "option": True}})  # fmt: skip
    seat, info = _duel_step(duel, agents)
    assert seat == AGENTS[0]
    assert info["handed_back"] and last_plan(agents[seat])["kind"] == "hand back"
    assert duel.agent_selection == AGENTS[1]  # the table goes back as it lies


def test_the_duels_play_ten_ball_racks_with_two_player_agents() -> None:
    out = play_duels("ghost", "ghost", racks=2, seed=20_000, env_id="pool_env/TenBallGame-v1")
    assert out["wins"] + out["losses"] + out["draws"] == 2
    shots = out["agent"]["shots"] + out["opponent"]["shots"]
    assert out["agent"]["breaks"] == out["opponent"]["breaks"] == 1 and shots >= 4
