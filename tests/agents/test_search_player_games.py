"""The search player off 9-ball: 10-ball and 8-ball through the rules' legal balls and calls.

And 9-ball unchanged: the actions of fixed racks, recorded on the code before 10-ball and
8-ball were added (``git show c9bd6fb``), are played again.
"""

from __future__ import annotations

import math
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest

from agents.learned.game_model import GameModel
from agents.learned.layout_value import (
    LAYOUT_FEATURES,
    LayoutValue,
    ball_on,
    design,
    layout_features,
)
from agents.learned.leaf_value import SetLeaf, next_targets
from agents.learned.legal_sets import observed_row, shooter_racks, target_sets
from agents.learned.next_shots import next_shot_table
from agents.learned.player_file import load_search_player
from agents.learned.search_player import SearchPlayer, SearchSettings
from agents.learned.set_value import SetValue
from pool_env import shot_constraints
from pool_env.game.codec import encode_ball, encode_pocket
from pool_env.game.games.wpa import EIGHT, rack_row
from pool_env.game.games.wpa.judge import KEEPS
from pool_env.game.games.wpa.rack_state import FOULS_0, FOULS_1, GROUP_0, GROUP_1, SOLIDS, STRIPES
from pool_env.game.geometry import pocket_mouths

ROOT = Path(__file__).resolve().parents[2]
FASTFIZ = (0.0021817, 0.075, 0.0175)
TINY = SearchSettings(budget=1e-6, samples=2, finalists=2, round_samples=2, next_samples=1,
                      min_rounds=1, hand_spots=2, hand_samples=1)  # fmt: skip
#: SearchPlayer's actions on two 9-ball racks (seeds 11, 12; four shots each), with TINY
#: settings and seed 3 at FastFiz noise, recorded on main before this change.
NINE_ACTIONS = {
    "runout": [
        [0.0, 1.0, 1.0, 0.0, 0.0, -1.0, 0.0, 0.0],
        [
            -0.5004816651344299,
            -0.10811056196689606,
            0.0,
            0.0,
            -0.8333333134651184,
            -1.0,
            -0.5144957304000854,
            0.8574929237365723,
        ],
        [0.2675003707408905, 0.15611092746257782, 0.0, 0.0, -0.8333333134651184, -1.0, 0.0, -0.5],
        [
            -0.9053215384483337,
            -0.4554440379142761,
            0.0,
            0.0,
            0.1666666716337204,
            -1.0,
            0.6000000238418579,
            0.0,
        ],
        [0.0, 1.0, 1.0, 0.0, 0.0, -1.0, 0.0, 0.0],
        [
            0.6671287417411804,
            0.9413994550704956,
            0.0,
            0.0,
            -0.8333333134651184,
            -1.0,
            0.6000000238418579,
            0.5,
        ],
        [0.11641190946102142, -0.3345896303653717, 0.0, 0.0, 0.5, -1.0, 0.0, -1.0],
        [-0.9336035847663879, -0.11412637680768967, 0.0, 0.0, 0.8333333134651184, -1.0, 0.0, 0.5],
    ],
    "duel": [
        [0.0, 1.0, 1.0, 0.0, 0.0, -1.0, 0.0, 0.0],
        [0.8500000238418579, -0.7777777910232544, 0.0, 0.0, 0.0, -1.0, 0.0, 0.0],
        [-0.6000000238418579, -0.7777777910232544, 0.0, 0.0, 0.0, -1.0, 0.0, 0.0],
        [0.6000000238418579, -0.7777777910232544, 0.0, 0.0, 0.0, -1.0, 0.0, 0.0],
        [0.0, 1.0, 1.0, 0.0, 0.0, -1.0, 0.0, 0.0],
        [-0.30000001192092896, -0.5802469253540039, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0],
        [-0.6000000238418579, -0.7777777910232544, 0.0, 0.0, 0.0, -1.0, 0.0, 0.0],
        [0.8500000238418579, -0.08641975373029709, 0.0, 0.0, 0.0, -1.0, 0.0, 0.0],
    ],
}


def _value() -> LayoutValue:
    """A logistic worth more the easier the best pot (as the search player's tests build it)."""
    w = np.zeros(design(np.zeros((1, len(LAYOUT_FEATURES)))).shape[1])
    w[0], w[1 + LAYOUT_FEATURES.index("p_best")] = -2.0, 4.0
    return LayoutValue(w)


@pytest.mark.parametrize(
    ("objective", "players", "path"),
    [("runout", 1, "runout_value.npz"), ("duel", 2, "duel_value.npz")],
)
def test_nine_ball_plays_the_actions_it_played_before(objective, players, path) -> None:
    env = gym.make("pool_env/NineBallGame-v2", noise=FASTFIZ)
    value = LayoutValue.load(ROOT / "models" / path)
    player = SearchPlayer(env, value, objective, TINY, seed=3, players=players)
    played = []
    for seed in (11, 12):
        obs, _ = env.reset(seed=seed)
        for _ in range(4):
            action = player.act(obs[None])[0]
            played.append(action)
            obs, _, terminated, truncated, _ = env.step(action)
            if terminated or truncated:
                break
    np.testing.assert_allclose(np.array(played), np.array(NINE_ACTIONS[objective]), atol=1e-6)


def _random_racks(rng: np.random.Generator, b: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``b`` random 8-ball rack rows (groups, shooter) and ball flags, some groups cleared."""
    on = rng.random((b, 16)) < 0.5
    on[:, 0] = on[:, 8] = True
    cleared = rng.random(b) < 0.3
    on[cleared, 1:8] = False  # solids cleared
    rows = np.stack([rack_row({}) for _ in range(b)])
    mine = rng.integers(0, 3, size=b)  # open, solids, stripes
    rows[:, GROUP_0] = mine
    rows[:, GROUP_1] = np.where(mine == 0, 0, SOLIDS + STRIPES - mine)
    viewers = rng.integers(0, 2, size=b)
    return rows, on, viewers


def test_eight_ball_legal_balls_batched_are_the_observations_and_follow_the_groups() -> None:
    env = gym.make("pool_env/EightBallGame-v1")
    config = env.unwrapped.config
    rows, on, viewers = _random_racks(np.random.default_rng(4), 200)
    legal = config.ruleset.legal_first_balls(rows, on, viewers)
    state = config.new_state(1)
    for k in range(len(rows)):
        state.rack[0], state.on_table[0] = rows[k], on[k]
        obs = config.ruleset.observe(config, state, np.array([viewers[k]]))[0]
        assert tuple(np.flatnonzero(legal[k])) == shot_constraints(config, obs).first_balls
        group = rows[k, GROUP_0 + viewers[k]]
        solids = [j for j in range(1, 8) if on[k, j]]
        stripes = [j for j in range(9, 16) if on[k, j]]
        # The rules by hand: open table, a group, the 8 once the group is cleared.
        want = {0: solids + stripes, SOLIDS: solids or [8], STRIPES: stripes or [8]}[group]
        assert np.flatnonzero(legal[k]).tolist() == sorted(want)
        # And back: the rack row the legal balls imply gives the same legal balls.
        sets = target_sets(legal[k : k + 1])
        again = shooter_racks("eight", on[k : k + 1], sets, (0, 0))
        assert (config.ruleset.legal_first_balls(again, on[k : k + 1], np.zeros(1, int))
                == legal[k]).all()  # fmt: skip
    assert legal[:, 8].any() and (legal[:, 1:8].any(1) & legal[:, 9:].any(1)).any()


@pytest.mark.parametrize(
    ("groups", "cleared", "mine"),
    [(("open", "open"), False, 0), (("stripes", "solids"), False, STRIPES),
     (("solids", "stripes"), True, SOLIDS), (("stripes", "solids"), True, STRIPES)],
)  # fmt: skip
def test_the_model_shoots_from_the_observed_group(groups, cleared, mine) -> None:
    env = gym.make("pool_env/EightBallGame-v1")
    balls = {0: (0.6, 0.5), 8: (1.9, 0.64), 3: (2.0, 0.3), 12: (1.0, 1.0), 9: (1.5, 0.4)}
    if cleared:  # the shooter's group is gone: the 8 is its only legal ball
        balls = {j: p for j, p in balls.items() if j in (0, 8) or (j < 8) != (mine == SOLIDS)}
    positions, on = _eight_layout(balls)
    rules = {"break": False, "ball_in_hand": False, "groups": list(groups), "fouls": [1, 2]}
    obs, _ = env.reset(options={"positions": positions, "on_table": on, "rules": rules})
    row = observed_row(obs, env.unwrapped.config)
    assert (row[GROUP_0], row[GROUP_1]) == (mine, 0 if mine == 0 else SOLIDS + STRIPES - mine)
    assert (row[FOULS_0], row[FOULS_1]) == (1, 2)


def test_the_batched_view_refuses_bad_shapes_and_seats() -> None:
    on = np.ones((2, 16), dtype=bool)
    with pytest.raises(ValueError, match="rack must be"):
        EIGHT.legal_first_balls(np.zeros((2, 3), np.int64), on)
    with pytest.raises(ValueError, match="viewers must be 0 or 1"):
        EIGHT.legal_first_balls(np.stack([rack_row({})] * 2), on, np.array([0, 2]))


def test_the_default_view_is_every_object_ball_on() -> None:
    ruleset = gym.make("pool_env/Pool-v1").unwrapped.config.ruleset
    on = np.array([[True, False, True, True]])
    legal = ruleset.legal_first_balls(np.zeros((1, 0), np.int64), on)
    assert legal.tolist() == [[False, False, True, True]] and on[0, 0]  # a copy, cue off


def _eight_layout(balls: dict[int, tuple[float, float]]) -> tuple[np.ndarray, np.ndarray]:
    positions = np.tile([0.1, 0.05], (16, 1))
    on = np.zeros(16, dtype=bool)
    for j, point in balls.items():
        positions[j], on[j] = point, True
    return positions, on


def test_layout_features_read_the_legal_balls() -> None:
    config = gym.make("pool_env/EightBallGame-v1").unwrapped.config
    table, mouths = config.table, pocket_mouths(config.table)
    # The 3 hangs in the far corner; the 12 lies mid-table; the 8 on the foot spot.
    positions, on = _eight_layout({0: (0.6, 0.5), 3: (2.45, 1.17), 12: (1.4, 0.3),
                                   8: (1.905, 0.635), 5: (0.3, 0.2)})  # fmt: skip
    pos, flags = np.stack([positions] * 4), np.stack([on] * 4)
    targets = np.array([[3, 5, 12], [12, -1, -1], [8, -1, -1], [3, 5, -1]])
    feats = layout_features(table, mouths, pos, flags, np.zeros(4, bool),
                            np.zeros((4, 2), int), 0.003, targets, "eight")  # fmt: skip
    p_best, last, left = (LAYOUT_FEATURES.index(k) for k in ("p_best", "last_ball",
                                                             "balls_left_over_9"))  # fmt: skip
    assert feats[0, p_best] == feats[3, p_best] > feats[1, p_best]  # the 3 is the easy pot
    assert feats[:, last].tolist() == [0.0, 0.0, 1.0, 0.0]  # only the 8 left: the money ball
    # Open table: the smaller group (one stripe) and the 8; stripes: 1 + 8; the 8; solids 2 + 8.
    assert (feats[:, left] * 9).round().tolist() == [2.0, 2.0, 1.0, 3.0]
    with pytest.raises(ValueError, match="8-ball layouts need targets"):
        layout_features(table, mouths, pos, flags, np.zeros(4, bool), np.zeros((4, 2), int),
                        0.003, None, "eight")  # fmt: skip


def test_nine_ball_features_are_the_same_with_the_ball_on_as_targets() -> None:
    config = gym.make("pool_env/NineBallGame-v2").unwrapped.config
    rng = np.random.default_rng(2)
    pos = rng.uniform([0.1, 0.1], [2.4, 1.17], size=(50, 10, 2))
    on = rng.random((50, 10)) < 0.6
    on[:, 0] = on[:, 9] = True
    hand, fouls = rng.random(50) < 0.5, rng.integers(0, 3, (50, 2))
    args = (config.table, pocket_mouths(config.table), pos, on, hand, fouls, 0.003)
    plain = layout_features(*args)
    given = layout_features(*args, ball_on(on)[:, None], "nine")
    assert np.array_equal(plain, given)


def test_next_shots_call_the_ball_on_and_its_pocket_in_ten_ball_and_the_pocket_in_eight() -> None:
    for env_id, balls, legal in (
        ("pool_env/TenBallGame-v1", 11, [[2, -1]]),
        ("pool_env/EightBallGame-v1", 16, [[3, 12]]),
    ):
        config = gym.make(env_id).unwrapped.config
        positions = np.tile([0.1, 0.05], (balls, 1))
        on = np.zeros(balls, dtype=bool)
        for j, point in {0: (0.6, 0.5), 2: (2.2, 1.0), 3: (2.2, 1.0), 12: (1.4, 0.3)}.items():
            if j < balls and (j != 3 or balls == 16) and (j != 2 or balls == 11):
                positions[j], on[j] = point, True
        if balls == 11:
            on[10], positions[10] = True, (1.9, 0.64)
        else:
            on[8], positions[8] = True, (1.9, 0.64)
        shots = next_shot_table(config, pocket_mouths(config.table), positions[None], on[None],
                                np.array(legal))  # fmt: skip
        ok = shots.ok[0]
        assert ok.any()
        played = shots.balls[0, ok]
        assert set(played.tolist()) <= {b for b in legal[0] if b >= 0}
        codes = [encode_pocket(config, k) for k in shots.pockets[0, ok]]
        assert np.allclose(shots.actions[0, ok, 4], codes)  # the pocket each one plays
        if config.ruleset.calls_ball:
            column = config.ruleset.ball_column
            assert np.allclose(shots.actions[0, ok, column], encode_ball(config, 2))


def test_a_pot_on_an_open_table_gives_the_shooter_its_group_in_the_model() -> None:
    config = gym.make("pool_env/EightBallGame-v1").unwrapped.config
    table = config.table
    u = np.array([table.length, table.width]) / math.hypot(table.length, table.width)
    three = np.array([table.length, table.width]) - u * 0.5
    positions, on = _eight_layout({0: tuple(three - u * 0.45), 3: tuple(three),
                                   8: (1.905, 0.635), 12: (1.2, 0.3), 5: (0.4, 1.0)})  # fmt: skip
    shots = next_shot_table(config, pocket_mouths(table), positions[None], on[None],
                            np.array([[3, 5, 12]]))  # fmt: skip
    centre = (shots.offsets == 0.0) & (shots.arrivals == 0.9)  # the mouth's middle, medium
    pick = int(np.flatnonzero(shots.ok[0] & (shots.balls[0] == 3) & centre)[0])
    result, _, left, racks = GameModel(config).play_racks(
        positions[None], on[None], rack_row({})[None], shots.actions[0, pick][None], 1
    )
    assert not left[0, 3] and result.hits[0, KEEPS]
    assert racks[0, GROUP_0] == SOLIDS and racks[0, GROUP_1] == STRIPES
    kept = np.array([True])
    assert next_targets(config.ruleset, racks, left, kept)[0].tolist() == [5]
    assert next_targets(config.ruleset, racks, left, ~kept)[0].tolist() == [12]


def _play(env_id: str, seed: int, shots: int, noise=None) -> list[tuple[dict, dict, np.ndarray]]:
    env = gym.make(env_id, noise=noise)
    config = env.unwrapped.config
    settings = SearchSettings(
        budget=0.05, samples=2, finalists=2, round_samples=2, next_samples=1, min_rounds=1,
        hand_spots=4, hand_samples=1,
    )  # fmt: skip
    player = SearchPlayer(env, _value(), "runout", settings, seed=1)
    obs, _ = env.reset(seed=seed)
    out = []
    for _ in range(shots):
        rules = shot_constraints(config, obs)
        action = player.act(obs[None])[0]
        obs, _, terminated, truncated, info = env.step(action)
        out.append(({"first": rules.first_balls, **player.last_plan}, info, action))
        if terminated or truncated:
            break
    return out


def test_ten_ball_rack_calls_the_ball_on_and_the_planned_pocket() -> None:
    config = gym.make("pool_env/TenBallGame-v1").unwrapped.config
    shots = _play("pool_env/TenBallGame-v1", 3, 8)
    planned = 0
    for plan, info, action in shots[1:]:  # the break calls nothing that counts
        assert action[config.ruleset.ball_column] == pytest.approx(
            encode_ball(config, min(plan["first"])), abs=1e-6
        )  # the ball on, every shot
        if plan.get("shot") in ("pot", "ghost") and plan.get("pocket", -1) >= 0:
            planned += 1
            assert action[4] == pytest.approx(encode_pocket(config, plan["pocket"]), abs=1e-6)
            assert info["foul"] != "wrong_ball_first"
    assert planned >= 2


def test_eight_ball_rack_plays_its_group_and_calls_the_eight() -> None:
    config = gym.make("pool_env/EightBallGame-v1").unwrapped.config
    shots = _play("pool_env/EightBallGame-v1", 1, 40)
    assert shots[0][0]["kind"] == "break" and shots[0][1]["foul"] is None  # a legal break
    potted_planned = 0
    for plan, info, action in shots[1:]:
        assert info.get("loss") is None  # never the 8 early or in an uncalled pocket
        if plan.get("shot") in ("pot", "ghost") and plan.get("pocket", -1) >= 0:
            assert action[4] == pytest.approx(encode_pocket(config, plan["pocket"]), abs=1e-6)
            assert info["foul"] != "wrong_ball_first"
            potted_planned += bool(set(info["potted"]) & set(plan["first"]))
    assert potted_planned >= 3
    assert shots[-1][1]["winner"] == 0  # noiseless: the rack is run out, the 8 called


def test_the_break_aims_at_the_apex_ball() -> None:
    env = gym.make("pool_env/EightBallGame-v1")
    player = SearchPlayer(env, _value(), settings=SearchSettings(break_y=0.1))
    obs, _ = env.reset(seed=7)
    apex = int(np.argmin(np.hypot(*(env.unwrapped.positions[1:] - [1.905, 0.635]).T))) + 1
    action = player.act(obs[None])[0]
    *_, info = env.step(action)
    assert player.last_plan["kind"] == "break" and info["first_contact"] == apex


def test_the_set_network_is_refused_off_nine_ball(tmp_path) -> None:
    env = gym.make("pool_env/TenBallGame-v1")
    config = env.unwrapped.config
    net = SetValue.load(ROOT / "models" / "set_value.npz")
    leaf = SetLeaf(net, config.table, pocket_mouths(config.table), 0.003)
    with pytest.raises(ValueError, match="9-ball layouts only"):
        SearchPlayer(env, _value(), leaf=leaf)
    positions, on = np.zeros((1, 11, 2)), np.ones((1, 11), dtype=bool)
    with pytest.raises(ValueError, match="9-ball layouts only"):
        leaf(positions, on, np.zeros(1, bool), np.zeros((1, 2), int), np.array([[1]]))
    bad = tmp_path / "p.yaml"
    bad.write_text(f"kind: search\ngame: ten\nlayout_value: {ROOT}/models/runout_value.npz\n"
                   f"set_value: {ROOT}/models/set_value.npz\n")  # fmt: skip
    with pytest.raises(ValueError, match="set_value is 9-ball's"):
        load_search_player(bad, env)


@pytest.mark.parametrize(
    ("file", "env_id", "game"),
    [
        ("search_player_ten.yaml", "pool_env/TenBallGame-v1", "ten"),
        ("search_player_eight.yaml", "pool_env/EightBallGame-v1", "eight"),
    ],
)
def test_the_player_files_load_for_their_game_and_refuse_another(file, env_id, game) -> None:
    path = ROOT / "models" / file
    for players in (1, 2):
        player = load_search_player(path, gym.make(env_id), players=players)
        assert player.config.game == game
    with pytest.raises(ValueError, match=f"game '{game}'.*cannot play game='nine'"):
        load_search_player(path, gym.make("pool_env/NineBallGame-v2"))
    with pytest.raises(ValueError, match="cannot play game="):  # 9-ball's file, another game
        load_search_player(ROOT / "models" / "search_player.yaml", gym.make(env_id))
    # Not a WPA game at all: the message names the games the player plays, not a file.
    with pytest.raises(ValueError, match=r"cannot play pool_env/Pool-v1: the search player plays"):
        load_search_player(path, gym.make("pool_env/Pool-v1"))


def test_a_player_file_refuses_an_unknown_game(tmp_path) -> None:
    bad = tmp_path / "p.yaml"
    bad.write_text(f"kind: search\ngame: snooker\nlayout_value: {ROOT}/models/runout_value.npz\n")
    with pytest.raises(ValueError, match="game must be one of nine, ten, eight, got 'snooker'"):
        load_search_player(bad, gym.make("pool_env/NineBallGame-v2"))


def test_the_rack_network_player_stays_on_nine_ball() -> None:
    from agents.learned.rack_net import RackNetPlayer

    with pytest.raises(
        ValueError, match=r"RackNetPlayer plays .*NineBallGame-v2\), got game='ten'"
    ):
        RackNetPlayer(
            gym.make("pool_env/TenBallGame-v1"), ROOT / "models" / "search_player_net.yaml"
        )


def test_collect_records_eight_ball_layouts_over_the_legal_balls() -> None:
    from agents.training.fit_layout_value import collect

    data = collect("ghost", "ghost", 6, 910000, True, FASTFIZ, "pool_env/EightBallGame-v1")
    assert str(data["env"]) == "pool_env/EightBallGame-v1" and data["won"].size > 0
    config = gym.make("pool_env/EightBallGame-v1").unwrapped.config
    targets, on = data["targets"], data["on_table"]
    legal = targets >= 0
    assert on[np.arange(len(on))[:, None], np.maximum(targets, 0)][legal].all()
    eight = (targets == 8).any(axis=1)
    assert (legal.sum(axis=1)[eight] == 1).all()  # the 8 is legal alone, never with a group
    features = layout_features(
        config.table, pocket_mouths(config.table), data["positions"], on, data["in_hand"],
        data["fouls"], float(data["sigma"]), targets, "eight",
    )  # fmt: skip
    assert np.array_equal(features, data["features"])
