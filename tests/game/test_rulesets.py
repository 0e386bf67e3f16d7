"""The games as rulesets: each config value picks one strategy, and the step has one path.

The behaviour of each game is pinned elsewhere (tests/game/test_games.py, tests/game/test_wpa.py,
tests/game/test_game_reference.py); here: the registry names the built-in games and the
WPA codes, the spaces are each ruleset's closed forms, ball in hand is the WPA games' alone,
a new ruleset registered by its name alone is what the step, the reward and the ``info``
run, and each step's reward terms sum to its reward.
"""

from __future__ import annotations

from typing import Any

import gymnasium as gym
import numpy as np
import pytest
from numpy.typing import NDArray

from pool_env import PoolEnv
from pool_env.envs.registration import CURRENT_IDS, ENV_IDS
from pool_env.game import registry
from pool_env.game.config import GAMES, make_config
from pool_env.game.games.solitaire import Solitaire
from pool_env.game.games.wpa import params as wp
from pool_env.game.games.wpa import rack_state as wpa
from pool_env.game.info import info_keys
from pool_env.game.kernels import params as kp
from pool_env.game.registry import game_names, register_game, ruleset_for
from pool_env.game.ruleset import Judged, Outcome, Turn
from pool_env.game.state import GameState, new_state
from pool_env.sim.table import Table

# (id, object balls, observation size, action size): 3 N for solitaire; the WPA games add
# N - 1 legal-ball flags and 7 rule features; actions 2 / 5, and 2 tip components on spin.
SPACES = [
    ("pool_env/OneBallRoll-v1", 1, 6, 2),
    ("pool_env/EightBall-v1", 15, 48, 4),
    ("pool_env/NineBallGameRoll-v2", 9, 30 + 9 + 9, 6),
    ("pool_env/NineBallGame-v2", 9, 30 + 9 + 9, 8),
    ("pool_env/TenBallGameRoll-v1", 10, 33 + 10 + 9, 7),
    ("pool_env/TenBallGame-v1", 10, 33 + 10 + 9, 9),
    ("pool_env/EightBallGameRoll-v1", 15, 48 + 15 + 7, 5),
]


def test_the_registry_names_the_built_in_games_and_the_wpa_codes() -> None:
    assert tuple(registry.BUILTIN) == GAMES
    assert GAMES == ("solitaire", "nine", "eight", "ten", "three_cushion", "snooker")
    # Then any game registered since (tests/user_game).
    assert game_names()[: len(GAMES)] == GAMES
    codes = {"nine": wpa.NINE, "eight": wpa.EIGHT, "ten": wpa.TEN}
    for name in GAMES:
        ruleset = ruleset_for(name)
        assert ruleset.name == name
        assert ruleset_for(name) is ruleset
        assert ruleset.has_rack == (name != "solitaire")
        if name in codes:
            assert ruleset.code == codes[name]  # type: ignore[attr-defined]


@pytest.mark.parametrize("game", ["ten_ball", "", None, 1, "Solitaire"])
def test_an_unknown_game_is_refused_naming_the_games(game: object) -> None:
    names = r"\['solitaire', 'nine', 'eight', 'ten'"  # and the games registered since
    with pytest.raises(ValueError, match=rf"game must be one of {names}"):
        make_config(game=game)  # type: ignore[arg-type]


@pytest.mark.parametrize(("env_id", "n_objects", "obs", "act"), SPACES)
def test_spaces_are_the_rulesets_closed_forms(
    env_id: str, n_objects: int, obs: int, act: int
) -> None:
    env = gym.make(env_id).unwrapped
    config = env.config
    assert config.n_object_balls == n_objects
    assert env.observation_space.shape == (obs,)
    assert env.action_space.shape == (act,)
    assert config.ruleset.observation_width(n_objects + 1) == obs
    _, info = env.reset(seed=3)
    _, _, _, _, info = env.step(env.action_space.sample())
    spin = config.spin
    assert set(info) == set(info_keys(config.ruleset, spin))
    assert env.observation_space.contains(env.unwrapped._observation())


def _one_table(n_balls: int, rack: NDArray[np.int64] | None = None) -> GameState:
    state = new_state(1, n_balls, wpa.N_RACK)
    table = Table()
    # The object balls on the foot half, the cue ball past the head string.
    state.positions[0] = np.linspace((0.6, 0.3), (0.9, 0.7), n_balls) * table.length
    state.positions[0, 0] = (table.length * 0.5, table.width * 0.5)
    state.on_table[0] = True
    if rack is not None:
        state.rack[0] = rack
    return state


@pytest.mark.parametrize("game", ["nine", "eight"])
def test_ball_in_hand_is_placed_by_the_wpa_rulesets_alone(game: str) -> None:
    scene = "nine_ball" if game == "nine" else "eight_ball"
    config = make_config(scene=scene, game=game)
    n = config.n_balls
    rack = np.zeros(wpa.N_RACK, dtype=np.int64)
    rack[wpa.IN_HAND], rack[wpa.BEHIND] = 1, 1
    state = _one_table(n, rack)
    # Placement (+1, 0): the head string's far end of the kitchen, mid-table.
    action = np.array([[0.0, 0.0, 1.0, 0.0, 0.0]])
    config.ruleset.shoot(Turn(config, state, np.zeros(1, np.intp)), action)
    p = config.params
    x = p[kp.X_LOW] + 1.0 * (p[wp.HEAD_X] - p[kp.X_LOW])
    y = p[kp.Y_LOW] + 0.5 * (p[kp.Y_HIGH] - p[kp.Y_LOW])
    assert state.positions[0, 0].tolist() == [x, y]
    assert x == pytest.approx(config.table.length / 4.0)
    # Solitaire has no ball in hand: the same shot leaves the cue ball where it was.
    solitaire = make_config(scene=scene)
    state = _one_table(n, rack)
    before = state.positions.copy()
    solitaire.ruleset.shoot(Turn(solitaire, state, np.zeros(1, np.intp)), action[:, :2])
    np.testing.assert_array_equal(state.positions, before)


class _DoubleRewards(Solitaire):
    """Solitaire paying twice its reward: a new game written as a ruleset subclass."""

    name = "double"

    def judge(self, *args: Any) -> Judged:
        values, flags, hits = super().judge(*args)
        return Judged(2.0 * values, flags, hits)


class _Recorder(_DoubleRewards):
    """And which records the outcomes it judged (the step hands the ruleset the shots)."""

    name = "recorded"

    def __init__(self) -> None:
        self.seen: list[Outcome] = []

    def judge(self, *args: Any) -> Judged:
        self.seen.append(args[1])
        return super().judge(*args)


def test_a_new_ruleset_is_a_subclass_and_a_name(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(registry, "_games", dict(registry._games))  # undone after the test
    register_game(_DoubleRewards())
    recorder = register_game(_Recorder())
    kwargs = {"scene": "nine_ball", "reward_pot": 1.0, "reward_scratch": -1.0}
    envs = {g: PoolEnv(game=g, **kwargs, model="roll") for g in ("solitaire", "double", "recorded")}
    for env in envs.values():
        env.reset(seed=5)
    rng = np.random.default_rng(5)
    rewards: dict[str, list[float]] = {g: [] for g in envs}
    for _ in range(20):
        action = rng.uniform(-1.0, 1.0, 2)
        for game, env in envs.items():
            _, reward, _, _, info = env.step(action)
            rewards[game].append(reward)
            assert set(info) == set(info_keys(env.config.ruleset, False))
            assert reward == sum(info[f"reward_{t}"] for t in env.config.ruleset.reward_terms)
    assert any(r != 0.0 for r in rewards["solitaire"])  # the test can tell double from single
    assert rewards["double"] == [2.0 * r for r in rewards["solitaire"]]
    assert rewards["recorded"] == rewards["double"]
    assert len(recorder.seen) == 20
    np.testing.assert_array_equal(envs["double"].positions, envs["solitaire"].positions)


@pytest.mark.parametrize("env_id", [i for i in CURRENT_IDS if "Roll-" not in i])
def test_every_steps_reward_terms_sum_to_its_reward(env_id: str) -> None:
    """Each term reported (``info["reward_<term>"]``) and their sum is the reward, exactly."""
    game = ENV_IDS[env_id][0].get("game")
    # A scale that random play makes non-zero: solitaire's shaping; three-cushion's point
    # is rare at random, its foul (the break not on the red) is not.
    scales = {None: {"reward_shaping": 0.5}, "three_cushion": {"reward_foul": -1.0}}
    # A term the id sets to 0 (SnookerBreak's foul) is given a scale, so that it shows.
    zeroed = {k: -1.0 for k, v in ENV_IDS[env_id][0].items() if k.startswith("reward_") and v == 0}
    env = gym.make(env_id, noise=(0.01, 0.05), **{**scales.get(game, {}), **zeroed})
    terms = [f"reward_{t}" for t in env.unwrapped.config.ruleset.reward_terms]
    env.reset(seed=7)
    seen = set()
    for _ in range(40):
        _, reward, terminated, truncated, info = env.step(env.action_space.sample())
        parts = [info[key] for key in terms]
        assert reward == sum(parts), (reward, dict(zip(terms, parts, strict=True)))
        seen.update(key for key, part in zip(terms, parts, strict=True) if part != 0.0)
        if terminated or truncated:
            env.reset()
    assert seen, "no term was ever non-zero: the test could not tell a wrong term"


def test_reward_scales_are_the_games_terms_wherever_they_are_given() -> None:
    """``reward_foul=``, ``rewards={"foul": ...}`` and the old ``rules={"reward_foul": ...}``."""
    for kwargs in ({"reward_foul": -2.0}, {"rewards": {"foul": -2.0}},
                   {"rules": {"reward_foul": -2.0, "end_on_foul": True}}):  # fmt: skip
        config = make_config(scene="nine_ball", game="nine", **kwargs)
        assert config.rewards == {"pot": 1.0, "foul": -2.0, "win": 1.0}, kwargs
        assert config.params[wp.W_FOUL] == -2.0
    with pytest.raises(ValueError, match=r"game='nine' has no reward term 'scratch'"):
        make_config(scene="nine_ball", game="nine", reward_scratch=-1.0)
    with pytest.raises(ValueError, match="reward_pot must be finite, got nan"):
        make_config(scene="one_ball", reward_pot=float("nan"))
