"""The 9-ball search player: its deeper ply, its outcome values, its break and ball in hand."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path
from types import SimpleNamespace

import gymnasium as gym
import numpy as np
import pytest

from agents.evaluation.players import make_agent
from agents.evaluation.runouts import ENDINGS, paired_difference
from agents.evaluation.runouts import main as runouts_main
from agents.learned.game_model import GameModel
from agents.learned.layout_value import LAYOUT_FEATURES, LayoutValue, design
from agents.learned.leaf_value import outcome_values
from agents.learned.next_shots import best_next_values, next_shot_actions
from agents.learned.player_file import load_search_player
from agents.learned.search_player import SearchPlayer, SearchSettings
from pool_env.game.codec import decode_observations, obs_layout
from pool_env.game.games.wpa import rack_row
from pool_env.game.games.wpa.judge import FOUL, KEEPS, WINNER
from pool_env.game.geometry import pocket_mouths

ENV_ID = "pool_env/NineBallGame-v2"
ROOT = Path(__file__).resolve().parents[2]


def _env(**kwargs):
    return gym.make(ENV_ID, **kwargs)


def _layout(balls: dict[int, tuple[float, float]]) -> tuple[np.ndarray, np.ndarray]:
    """Positions and flags of a 9-ball layout: the balls given, the others off the table."""
    positions = np.tile([0.1, 0.05], (10, 1))
    on = np.zeros(10, dtype=bool)
    for j, point in balls.items():
        positions[j], on[j] = point, True
    return positions, on


def _value() -> LayoutValue:
    """A logistic worth more the easier the ball on (as the lookahead's tests build it)."""
    w = np.zeros(design(np.zeros((1, len(LAYOUT_FEATURES)))).shape[1])
    w[0], w[1 + LAYOUT_FEATURES.index("p_best")] = -2.0, 4.0
    return LayoutValue(w)


def _nine_straight_in(env) -> tuple[np.ndarray, np.ndarray]:
    """The 9 on the diagonal to the far corner pocket, the cue ball 0.4 m behind it."""
    table = env.unwrapped.config.table
    u = np.array([table.length, table.width]) / np.hypot(table.length, table.width)
    nine = np.array([table.length, table.width]) - u * 0.5
    return _layout({0: tuple(nine - u * (0.4 + 2 * table.ball_radius)), 9: tuple(nine)})


def _constant_leaf(value: float):
    def leaf(positions, on_table, in_hand, fouls):
        return np.full(len(positions), value)

    return leaf


def test_the_next_ply_wins_a_straight_in_9_and_keeps_the_leaf_where_nothing_is_open() -> None:
    env = _env()
    config = env.unwrapped.config
    mouths = pocket_mouths(config.table)
    straight = _nine_straight_in(env)
    # The 1 frozen to the foot rail's middle, behind the 2 and 3: no clear pot at all.
    blocked = _layout({0: (0.5, 0.635), 1: (2.5, 0.635), 2: (2.3, 0.62), 3: (2.3, 0.68)})
    positions = np.stack([straight[0], blocked[0]])
    on = np.stack([straight[1], blocked[1]])
    _, ok = next_shot_actions(config, mouths, positions, on)
    assert ok[0].any() and not ok[1].any()
    values = best_next_values(
        GameModel(config), mouths, _constant_leaf(0.25), True, positions, on, (0, 0), 2
    )
    assert values[0] == 1.0  # noiseless: some candidate drops the 9 every time
    assert values[1] == 0.25  # nothing to play: the layout keeps its own leaf value


@pytest.mark.parametrize(
    ("hits", "runout", "expected"),
    [
        ((0, 1, 0), True, 1.0),  # the rack won (by the shooter, player 0)
        ((0, 1, 1), True, 0.0),  # lost
        ((0, 1, -1), True, 0.3),  # the table kept: the leaf value of the leave
        ((0, 0, -1), True, 0.0),  # a miss ends a run-out
        ((1, 0, -1), True, 0.0),  # a foul ends a run-out
        ((0, 1, -1), False, 0.3),  # a duel: kept, the shooter's chance
        ((0, 0, -1), False, 0.7),  # a duel miss: one minus the opponent's chance
        ((1, 0, -1), False, 0.7),  # a duel foul: the opponent's, with ball in hand
    ],
)
def test_outcomes_are_valued_by_the_rules(hits, runout, expected) -> None:
    row = np.zeros((1, max(FOUL, KEEPS, WINNER) + 1), dtype=np.int64)
    row[0, [FOUL, KEEPS, WINNER]] = hits
    seen = {}

    def leaf(positions, on_table, in_hand, fouls):
        seen["hand"], seen["fouls"] = bool(in_hand[0]), tuple(int(f) for f in fouls[0])
        return np.full(len(positions), 0.3)

    positions, on = _layout({0: (0.5, 0.5), 1: (1.5, 0.5)})
    value = outcome_values(
        leaf, runout, SimpleNamespace(hits=row), positions[None], on[None], (1, 2)
    )
    assert value[0] == pytest.approx(expected)
    if hits == (1, 0, -1) and not runout:  # the opponent shoots with ball in hand
        assert seen == {"hand": True, "fouls": (2, 2)}
    if hits == (0, 1, -1):  # the shooter again, its fouls cleared
        assert seen == {"hand": False, "fouls": (0, 2)}


def test_play_layouts_is_play_from_each_layout() -> None:
    config = _env(noise=(0.003, 0.05, 0.05)).unwrapped.config
    positions, on = _nine_straight_in(_env())
    rng = np.random.default_rng(1)
    actions = rng.uniform(-0.4, 0.4, (3, config.action_size))
    one = GameModel(config, seed=7).play(positions, on, rack_row({}), actions, 2)
    many = GameModel(config, seed=7).play_layouts(
        np.repeat(positions[None], 3, 0), np.repeat(on[None], 3, 0),
        np.repeat(rack_row({})[None], 3, 0), actions, 2,
    )  # fmt: skip
    np.testing.assert_array_equal(one[0].shots, many[0].shots)
    np.testing.assert_array_equal(one[1], many[1])
    with pytest.raises(ValueError, match="positions must be"):
        GameModel(config).play_layouts(positions[None], on[None], rack_row({})[None],
                                       actions, 1)  # fmt: skip


def test_with_the_9_straight_in_the_search_pots_it_and_wins() -> None:
    env = _env()
    positions, on = _nine_straight_in(env)
    obs, _ = env.reset(options={"positions": positions, "on_table": on,
                                "rules": {"break": False, "ball_in_hand": False}})  # fmt: skip
    settings = SearchSettings(budget=0.05, samples=2, finalists=2, round_samples=2)
    agent = SearchPlayer(env, _value(), settings=settings)
    action, _ = agent.predict(obs)
    *_, terminated, _, info = env.step(action)
    assert terminated and info["potted"] == (9,) and info["winner"] == 0
    assert agent.last_search["rounds"] >= settings.min_rounds


def test_with_ball_in_hand_it_places_the_cue_ball_where_the_9_drops() -> None:
    env = _env()
    table = env.unwrapped.config.table
    positions, on = _layout({0: (0.4, 0.3), 9: (1.9, 0.9)})
    obs, _ = env.reset(options={"positions": positions, "on_table": on,
                                "rules": {"break": False, "ball_in_hand": True}})  # fmt: skip
    settings = SearchSettings(budget=0.05, samples=2, finalists=2, round_samples=2)
    agent = SearchPlayer(env, _value(), settings=settings, seed=3)
    action, _ = agent.predict(obs)
    assert agent.last_search["hand_spots"] > 0
    *_, info = env.step(action)
    assert info["potted"] == (9,) and info["winner"] == 0
    assert env.unwrapped.on_table[0]  # the cue ball stayed up
    assert table.ball_radius < env.unwrapped.positions[0, 0] < table.length


def test_the_break_places_the_cue_ball_on_the_head_string_and_hits_the_1() -> None:
    env = _env()
    config = env.unwrapped.config
    settings = SearchSettings(break_y=0.2, break_speed=0.0, break_tip=(0.0, 0.5))
    agent = SearchPlayer(env, _value(), settings=settings)
    obs, _ = env.reset(seed=5)
    action, _ = agent.predict(obs)
    assert agent.last_plan["kind"] == "break"
    spot = agent.last_plan["spot"]
    assert spot == pytest.approx([config.table.length / 4, config.table.width / 2 + 0.2])
    *_, info = env.step(action)
    assert info["first_contact"] == 1
    assert info["speed"] == pytest.approx(np.mean(config.rules.break_speed_range))


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"budget": 0.0}, "budget must be a finite number > 0"),
        ({"budget": float("inf")}, "budget must be a finite number > 0"),
        ({"samples": 0}, r"samples must be an integer in \[1, 512\]"),
        ({"samples": 2.7}, r"samples must be an integer in \[1, 512\]"),  # failed on the 2nd shot
        ({"finalists": True}, "finalists must be an integer in \\[1, 16\\]"),
        ({"samples": 10**12}, r"samples must be an integer in \[1, 512\] \(first ply"),  # PiB
        ({"round_samples": 33}, r"round_samples must be an integer in \[1, 32\]"),
        ({"min_rounds": 101}, r"min_rounds must be an integer in \[0, 100\]"),
        ({"hand_spots": -1}, "hand_spots must be an integer in \\[0, 200\\]"),
        ({"prune_z": float("nan")}, "prune_z must be a finite number >= 0"),
        ({"break_cut": float("nan")}, "break_cut must be a finite number"),  # failed at the break
        ({"break_speed": 1.5}, "break_speed must be a finite number in"),
        ({"break_tip": (0.0, 2.0)}, "break_tip must be two finite numbers"),
        ({"break_tip": "ab"}, "break_tip must be two finite numbers"),
        ({"depth": 3}, r"depth must be an integer in \[1, 2\] \(1: the lookahead, 2: the search\)"),
        ({"break_arm": 20}, r"break_arm must be an integer in \[-1, 19\]"),
        ({"final_samples": -1}, r"final_samples must be an integer in \[0, 512\]"),
    ],
)
def test_bad_settings_are_refused(kwargs, message) -> None:
    with pytest.raises(ValueError, match=message):
        replace(SearchSettings(), **kwargs)


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"break_y": 5.0}, r"break_y must lie in \[-0.6064, 0.6064\] m"),  # off the table
        ({"break_cut": 0.5}, r"break_cut must lie in \[-0.0450, 0.0450\] rad"),  # misses the 1
    ],
)
def test_a_break_off_the_table_or_past_the_1_is_refused_by_the_player(kwargs, message) -> None:
    settings = SearchSettings(**kwargs)  # the table bounds them: the player checks them
    with pytest.raises(ValueError, match=message):
        SearchPlayer(_env(), _value(), settings=settings)


def test_the_player_refuses_other_games_and_bad_configs(tmp_path) -> None:
    with pytest.raises(ValueError, match="plays the spin WPA game ids"):
        SearchPlayer(gym.make("pool_env/SnookerFrame-v1"), _value())
    with pytest.raises(ValueError, match="got game='eight' on a roll table"):
        SearchPlayer(gym.make("pool_env/EightBallGameRoll-v1"), _value())
    bad = tmp_path / "bad.yaml"
    bad.write_text("kind: lookahead\n")
    with pytest.raises(ValueError, match="kind must be 'search'"):
        load_search_player(bad, _env())
    bad.write_text("kind: search\nlayout_value: x.npz\nsettings: {plies: 3}\n")
    with pytest.raises(ValueError, match=r"unknown key settings\.plies"):
        load_search_player(bad, _env())
    with pytest.raises(ValueError, match="not found"):  # tests/agents/test_player_files.py
        load_search_player(tmp_path / "missing.yaml", _env())


def test_the_committed_config_loads_for_one_player_and_for_a_duel() -> None:
    path = str(ROOT / "models" / "search_player.yaml")
    solo = make_agent(path, _env(noise="fastfiz"))
    duel = make_agent(path, _env(noise="fastfiz"), players=2)
    assert isinstance(solo, SearchPlayer) and isinstance(duel, SearchPlayer)
    assert (solo.objective, duel.objective) == ("runout", "duel")
    assert solo.settings.budget == 1.0


def test_rack_endings_are_counted_once_per_rack(tmp_path, capsys) -> None:
    out = tmp_path / "r.json"
    runouts_main(["--agents", "ghost", "--racks", "6", "--seed", "5", "--out", str(out)])
    import json

    result = json.loads(out.read_text())["results"][0]
    assert sum(result["endings"].values()) == 6 and set(result["endings"]) <= set(ENDINGS)
    assert len(result["per_rack"]) == 6
    assert "| ghost | 6 |" in capsys.readouterr().out


def test_the_break_reads_the_layout_from_the_observation() -> None:
    env = _env()
    obs, _ = env.reset(seed=11)
    config = env.unwrapped.config
    positions, on = decode_observations(config.table, obs[None, obs_layout(config)["balls"]])
    action = SearchPlayer(env, _value()).break_action(positions[0], on[0])
    assert action.shape == (config.action_size,)


def test_the_paired_difference_counts_only_discordant_racks() -> None:
    a = ["run-out", "run-out", "foul", "missed pot", "run-out"]
    b = ["run-out", "foul", "run-out", "missed pot", "foul"]
    diff, low, high = paired_difference(a, b)
    assert diff == pytest.approx(1 / 5)  # 2 racks only a ran out, 1 only b
    assert low < diff < high
    assert paired_difference(a, a) == (0.0, 0.0, 0.0)
    with pytest.raises(ValueError, match="paired racks"):
        paired_difference(a, b[:2])
    # A duel's racks: the winner of each (None: a draw); the agent's wins are the successes.
    won = ["agent", "opponent", None, "agent"]
    other = ["opponent", "opponent", "agent", "agent"]
    assert paired_difference(won, other, success="agent")[0] == pytest.approx(0.0)  # 1 - 1


def test_shots_made_after_the_break_exclude_the_shots_that_ended_a_rack() -> None:
    from agents.evaluation.runouts import made_after_break

    result = {"shots": 10, "endings": {"run-out": 1, "missed pot": 1, "foul": 1, "dry break": 2}}
    assert made_after_break(result).value == pytest.approx(0.8)  # 2 of 10 ended a rack
