"""A game from outside ``pool_env/``: ``tests/user_game/rotation.py`` (``docs/own_game.md``).

The folder registers its game and its id with one call each and touches nothing in
``pool_env/``; here it is played through every front the built-in games have: Gymnasium's
checker, its rules as a table of cases, its reward terms, its ``info``, the vector env.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import pool_env
from pool_env import PoolEnv, PoolVectorEnv, Shot, encode_action
from pool_env.game import registry
from pool_env.game.ruleset import Executed, Judged, Outcome, RulesSection, Turn
from tests.user_game import rotation

ROOT = Path(__file__).resolve().parents[2]
R = pool_env.Table().ball_radius


def _layout(first: int) -> np.ndarray:
    """The nine balls: ``first`` straight between the cue ball and the far corner pocket.

    The others lie in a row along the near long rail, out of the way.
    """
    pos = np.zeros((10, 2))
    pos[0] = (1.6, 0.6)
    direction = np.array([2.54, 1.27]) - pos[0]
    pos[first] = pos[0] + 0.4 * direction / np.linalg.norm(direction)
    others = [j for j in range(1, 10) if j != first]
    for k, j in enumerate(others):
        pos[j] = (0.15 + 0.09 * k, 0.1)
    return pos


def _angle_to(pos: np.ndarray, ball: int) -> float:
    dx, dy = pos[ball] - pos[0]
    return math.atan2(dy, dx)


def _shoot(env: PoolEnv, pos: np.ndarray, angle: float, speed: float) -> tuple:
    env.reset(seed=0, options={"positions": pos})
    action = encode_action(env.config, Shot(angle, speed), env.positions)
    return env.step(action)


def test_the_game_and_its_id_come_from_a_folder_outside_pool_env() -> None:
    assert rotation.Rotation.__module__ == "tests.user_game.rotation"
    assert "rotation" not in registry.BUILTIN
    assert registry.ruleset_for("rotation") is rotation.GAME
    assert "rotation" in registry.game_names()
    assert not any("user_game" in p.read_text() for p in (ROOT / "pool_env").rglob("*.py"))
    env = gym.make(rotation.ID)
    assert env.unwrapped.config.ruleset is rotation.GAME
    assert env.spec.max_episode_steps == 30


def test_gymnasiums_checker_passes_on_its_id() -> None:
    check_env(gym.make(rotation.ID).unwrapped, skip_render_check=True)


@pytest.mark.parametrize(
    ("first", "end_on_foul", "reward", "foul", "terminated"),
    [
        (1, True, 1.0, False, False),  # the 1 first and potted: clean, it scores
        (2, True, -1.0, True, True),  # the 2 first: a foul ends the rack
        (2, False, -1.0, True, False),  # ... or not, with end_on_foul=False
    ],
)
def test_the_rule_as_a_table_of_cases(
    first: int, end_on_foul: bool, reward: float, foul: bool, terminated: bool
) -> None:
    env = PoolEnv(game="rotation", scene="nine_ball", end_on_foul=end_on_foul)
    pos = _layout(first)
    _, got, done, _, info = _shoot(env, pos, _angle_to(pos, first), 2.0)
    assert info["first_contact"] == first and info["ball_on"] == 1
    assert (got, info["foul"], done) == (reward, foul, terminated)
    if not foul:
        assert info["potted"] == (1,) and not env.on_table[1]
    assert got == info["reward_pot"] + info["reward_foul"]


def test_a_miss_and_a_scratch_are_fouls_and_the_cue_ball_comes_back() -> None:
    env = PoolEnv(game="rotation", scene="nine_ball", aim="absolute")
    pos = _layout(1)
    _, reward, done, _, info = _shoot(env, pos, math.pi / 2, 0.5)  # up the table: no ball
    assert info["first_contact"] == -1 and info["foul"] and done and reward == -1.0
    corner = np.array([2.54, 0.0])  # the cue ball rolled into the near right corner
    _, reward, done, _, info = _shoot(env, pos, math.atan2(*(corner - pos[0])[::-1]), 3.0)
    assert info["scratch"] and info["foul"] and done
    assert env.on_table[0]  # back on the table, on the head spot or the free point nearest


def test_its_reward_terms_are_scaled_reported_and_refused_where_it_has_none() -> None:
    env = PoolEnv(game="rotation", scene="nine_ball", reward_pot=3.0, reward_foul=-0.5)
    pos = _layout(1)
    _, reward, *_, info = _shoot(env, pos, _angle_to(pos, 1), 2.0)
    assert (reward, info["reward_pot"], info["reward_foul"]) == (3.0, 3.0, 0.0)
    with pytest.raises(ValueError, match=r"no reward term 'scratch' \(its terms: reward_pot"):
        PoolEnv(game="rotation", scene="nine_ball", reward_scratch=-1.0)
    with pytest.raises(ValueError, match="end_on_foul must be a bool"):
        PoolEnv(game="rotation", scene="nine_ball", end_on_foul=1)
    with pytest.raises(ValueError, match="break_speed_range is a rule of game 'nine'"):
        PoolEnv(game="rotation", scene="nine_ball", rules={"break_speed_range": (1, 2)})


def test_the_vector_env_plays_it_as_the_single_env_does() -> None:
    vec = PoolVectorEnv(4, game="rotation", scene="nine_ball", model="spin")
    singles = [PoolEnv(game="rotation", scene="nine_ball", model="spin") for _ in range(4)]
    obs, _ = vec.reset(seed=[10, 11, 12, 13])
    actions = np.random.default_rng(3).uniform(-1, 1, (4, 4))
    obs, rewards, terminated, _, info = vec.step(actions)
    for k, env in enumerate(singles):
        env.reset(seed=10 + k)
        one, reward, done, _, one_info = env.step(actions[k])
        np.testing.assert_array_equal(obs[k], one)
        assert (reward, done) == (rewards[k], terminated[k])
        assert (one_info["foul"], one_info["ball_on"]) == (info["foul"][k], info["ball_on"][k])


def test_the_docs_page_shows_the_folders_module_as_it_is() -> None:
    page = (ROOT / "docs" / "own_game.md").read_text()
    source = (ROOT / "tests" / "user_game" / "rotation.py").read_text()
    assert f"```python\n{source}```" in page


class _Drill(rotation.Rotation):
    """Another game, for the registry's checks (never left registered)."""

    name = "drill"


@dataclass(frozen=True)
class _PrefixedRules(RulesSection):
    game: str = "drill"
    reward_bonus: float = 0.0


@pytest.mark.parametrize(
    ("game", "message"),
    [
        (object(), "a game is a pool_env.game.ruleset.Ruleset instance"),
        (type("Bad", (_Drill,), {"name": "two words"})(), "must be an identifier"),
        (type("Nine", (_Drill,), {"name": "nine"})(), "built-in game's"),
        (type("Terms", (_Drill,), {"reward_terms": {"pot": "one"}})(), "reward_terms must map"),
        (type("Width", (_Drill,), {"action_width": 1})(), "action_width must be an int >= 2"),
        (type("Keys", (_Drill,), {"info_keys": ()})(), "name them in its info_keys"),
        (
            type("Prefix", (_Drill,), {"section": _PrefixedRules})(),
            r"rules keys \['reward_bonus'\] take the reward_ prefix",
        ),
    ],
)
def test_register_game_refuses_what_is_no_game(
    game: object, message: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(registry, "_games", dict(registry._games))
    with pytest.raises(ValueError, match=message):
        registry.register_game(game)  # type: ignore[arg-type]


def test_a_name_is_taken_once_unless_replaced(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(registry, "_games", dict(registry._games))
    first = registry.register_game(_Drill())
    with pytest.raises(ValueError, match="registered already"):
        registry.register_game(_Drill())
    second = registry.register_game(_Drill(), replace=True)
    assert registry.ruleset_for("drill") is second is not first


def test_an_installed_package_joins_through_its_entry_point(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    class Point:  # what importlib.metadata gives for [project.entry-points."pool_env.games"]
        name = "drill"

        @staticmethod
        def load() -> object:
            return {"drill": _Drill()}

    seen: list[str] = []

    def points(group: str) -> list[Point]:
        seen.append(group)
        return [Point()]

    monkeypatch.setattr(registry, "_games", dict(registry._games))
    monkeypatch.setattr(registry, "_entry_points_loaded", False)
    monkeypatch.setattr(registry, "entry_points", points)
    assert isinstance(registry.ruleset_for("drill"), _Drill)
    assert seen == [registry.ENTRY_POINT_GROUP] and "drill" in registry.game_names()


def test_a_broken_package_is_named_in_a_warning_and_the_others_still_join(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    class Broken:
        name = "broken"

        @staticmethod
        def load() -> object:
            raise ImportError("no module named 'missing_dependency'")

    class Good:
        name = "drill"

        @staticmethod
        def load() -> object:
            return _Drill()

    monkeypatch.setattr(registry, "_games", dict(registry._games))
    monkeypatch.setattr(registry, "_entry_points_loaded", False)
    monkeypatch.setattr(registry, "entry_points", lambda group: [Broken(), Good()])
    with pytest.warns(RuntimeWarning, match="'broken'.*missing_dependency"):
        names = registry.game_names()
    assert "drill" in names and "broken" not in names


class _Wide(rotation.Rotation):
    """A column of its own before the tip, on the default shot; and a state of its own."""

    name = "wide"
    action_width = 3
    rack_width = 1

    def judge(self, turn: Turn, out: Outcome, executed: Executed) -> Judged:
        turn.state.rack[turn.tables, 0] += 1  # counts its shots in its own state
        return super().judge(turn, out, executed)


def test_the_default_shot_reads_the_tip_after_the_games_columns_and_state_starts_at_zero(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.setattr(registry, "_games", dict(registry._games))
    registry.register_game(_Wide())
    env = PoolEnv(game="wide", scene="nine_ball", model="spin")
    assert env.action_space.shape == (5,)
    env.reset(seed=0)
    limit = env.config.tip_limit
    _, _, _, _, info = env.step(np.array([0.0, 0.0, 0.9, 0.5, -0.25]))
    assert info["tip"] == pytest.approx((0.5 * limit, -0.25 * limit))
    assert env._state.rack[0, 0] == 1
    env.reset(seed=1)
    assert env._state.rack[0, 0] == 0  # the game's state starts from zeros


def test_its_own_scene_is_its_alone() -> None:
    env = gym.make(rotation.ID).unwrapped
    assert env.config.scene.spec is rotation.rotation_rack
    table = env.config.table
    rack = pool_env.sim.layouts.break_scene(table, "nine")[1:]
    cues = []
    for seed in range(5):
        env.reset(seed=seed)
        np.testing.assert_array_equal(env.positions[1:], rack)  # the rack as laid out
        cues.append(env.positions[0])
        assert env.positions[0, 0] <= table.length / 4  # the cue ball in the kitchen
    assert len({tuple(c) for c in cues}) == 5  # drawn by each reset
    with pytest.raises(ValueError, match="scene must be one of"):
        PoolEnv(scene="rotation_rack")  # solitaire has no such scene
