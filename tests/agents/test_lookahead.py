"""The lookahead 9-ball player: its layout value, its model of the game, and its choices."""

from __future__ import annotations

import math
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest

from agents.baselines.rule_play import rule_action
from agents.evaluation.duels import shot_outcome
from agents.evaluation.players import make_agent
from agents.learned.game_model import GameModel
from agents.learned.layout_value import (
    LAYOUT_FEATURES,
    PLACE_DISTANCE,
    LayoutValue,
    ball_on,
    design,
    fit_layout_value,
    layout_features,
)
from agents.learned.lookahead import LookaheadAgent
from agents.training.fit_layout_value import main as layout_value_main
from agents.training.fit_layout_value import observation_features
from pool_env.game.games.wpa import rack_row
from pool_env.game.geometry import (
    AIM_X,
    AIM_Y,
    CLEAR_PATH,
    CUT,
    GX,
    GY,
    TOLERANCE,
    VALID,
    ghost_shots,
    pocket_mouths,
)

ENV_ID = "pool_env/NineBallGame-v2"
P_BEST = LAYOUT_FEATURES.index("p_best")
SIGMA = 0.003


def _env(**kwargs):
    return gym.make(ENV_ID, **kwargs)


def _layout(balls: dict[int, tuple[float, float]]) -> tuple[np.ndarray, np.ndarray]:
    """Positions and flags of a 9-ball layout: the balls given, the others off the table."""
    positions = np.zeros((10, 2))
    on = np.zeros(10, dtype=bool)
    spare = 0.1
    for j in range(10):
        if j in balls:
            positions[j], on[j] = balls[j], True
        else:  # off the table: any finite point
            positions[j] = (spare, 0.05)
            spare += 0.06
    return positions, on


def _features(env, positions, on, hand=False, fouls=(0, 0)):
    config = env.unwrapped.config
    return layout_features(
        config.table, pocket_mouths(config.table), positions[None], on[None],
        np.array([hand]), np.array([fouls]), SIGMA,
    )[0]  # fmt: skip


@pytest.mark.parametrize(
    ("balls", "expected"),
    [((1, 2, 9), 1), ((3, 9), 3), ((9,), 9), ((2, 5, 6, 9), 2), ((8, 9), 8)],
)
def test_the_ball_on_is_the_lowest_ball_left(balls, expected) -> None:
    on = np.zeros((1, 10), dtype=bool)
    on[0, 0] = True
    on[0, list(balls)] = True
    assert ball_on(on)[0] == expected


def test_features_read_the_rules_ball_on_the_9_and_the_fouls() -> None:
    env = _env()
    length = env.unwrapped.config.table.length
    positions, on = _layout({0: (0.6, 0.5), 4: (1.2, 0.4), 9: (1.8, 0.7)})
    f = _features(env, positions, on, fouls=(2, 1))
    assert f[LAYOUT_FEATURES.index("last_ball")] == 0.0
    assert f[LAYOUT_FEATURES.index("balls_left_over_9")] == pytest.approx(2 / 9)
    assert f[LAYOUT_FEATURES.index("fouls_self_over_2")] == 1.0
    assert f[LAYOUT_FEATURES.index("fouls_opponent_over_2")] == 0.5
    positions, on = _layout({0: (0.6, 0.5), 9: (length - 0.4, 0.7)})
    f = _features(env, positions, on)
    assert f[LAYOUT_FEATURES.index("last_ball")] == 1.0
    assert 0.0 <= f[LAYOUT_FEATURES.index("p_second")] <= f[P_BEST] <= 1.0


def test_p_best_is_the_erf_of_the_most_forgiving_clear_shot_and_a_blocker_removes_it() -> None:
    env = _env()
    config = env.unwrapped.config
    table, mouths = config.table, pocket_mouths(config.table)
    positions, on = _layout({0: (0.7, 0.35), 1: (1.5, 0.62), 9: (2.2, 0.3)})
    rows = ghost_shots(table, mouths, positions[None], on[None], np.array([[1]]))[0, 0]
    clear = rows[(rows[:, VALID] > 0.5) & (rows[:, CLEAR_PATH] > 0.5)]
    best = float(np.max(clear[:, TOLERANCE]))
    expected = math.erf(best / (SIGMA * math.sqrt(2.0)))
    assert clear.shape[0] >= 1
    assert _features(env, positions, on)[P_BEST] == pytest.approx(expected, rel=1e-12)
    # A ball halfway along the cue's path to the ball on blocks every pocket's shot.
    mid = (positions[0] + positions[1]) / 2.0
    blocked, on_b = _layout({0: tuple(positions[0]), 1: tuple(positions[1]), 5: tuple(mid),
                             9: tuple(positions[9])})  # fmt: skip
    assert _features(env, blocked, on_b)[P_BEST] == 0.0


def test_ball_in_hand_takes_the_straight_in_placement_for_each_pocket() -> None:
    env = _env()
    config = env.unwrapped.config
    table, mouths = config.table, pocket_mouths(config.table)
    # The cue ball far away and a thin cut: in hand, the best pocket is played straight in.
    positions, on = _layout({0: (0.3, 1.0), 1: (1.9, 0.35), 9: (1.2, 0.9)})
    from_cue = _features(env, positions, on)[P_BEST]
    in_hand = _features(env, positions, on, hand=True)[P_BEST]
    assert in_hand > from_cue
    # The placement is straight in (cut 0) from PLACE_DISTANCE behind the ghost-ball point,
    # and its chance is the one the geometry gives with the cue ball put there.
    rows = ghost_shots(table, mouths, positions[None], on[None], np.array([[1]]))[0, 0]
    best = None
    for k in np.flatnonzero(rows[:, VALID] > 0.5):
        g = rows[k, [GX, GY]]
        away = g - rows[k, [AIM_X, AIM_Y]]
        cue = g + away / np.hypot(*away) * PLACE_DISTANCE
        moved = positions.copy()
        moved[0] = cue
        placed = ghost_shots(table, mouths, moved[None], on[None], np.array([[1]]))[0, 0, k]
        assert abs(placed[CUT]) < 1e-9
        if placed[VALID] > 0.5 and placed[CLEAR_PATH] > 0.5:
            chance = math.erf(placed[TOLERANCE] / (SIGMA * math.sqrt(2.0)))
            best = chance if best is None else max(best, chance)
    assert in_hand == pytest.approx(best, rel=1e-12)


def test_the_logistic_fit_recovers_the_weights_that_made_the_labels() -> None:
    rng = np.random.default_rng(0)
    n = 40_000
    f = np.column_stack([
        rng.random(n) < 0.3, rng.random(n), rng.random(n) * 0.5, rng.random(n) < 0.2,
        rng.integers(1, 10, n) / 9.0, rng.integers(0, 3, n) / 2.0, rng.integers(0, 3, n) / 2.0,
    ]).astype(float)  # fmt: skip
    true = np.array([-1.0, 0.5, 2.5, 0.3, 0.4, -0.6, -0.8, 0.2, -0.5, 1.0, 0.4, 0.3, 0.2])
    p = 1.0 / (1.0 + np.exp(-(design(f) @ true)))
    won = rng.random(n) < p
    model = fit_layout_value(f, won, l2=0.0)
    assert np.abs(model(f) - p).max() < 0.03
    assert model(f).mean() == pytest.approx(won.mean(), abs=1e-6)  # the MLE matches the rate


def test_layout_value_refuses_bad_weights_and_round_trips(tmp_path) -> None:
    width = design(np.zeros((1, len(LAYOUT_FEATURES)))).shape[1]
    with pytest.raises(ValueError, match="finite numbers"):
        LayoutValue(np.zeros(width - 1))
    with pytest.raises(ValueError, match="finite numbers"):
        LayoutValue(np.full(width, np.nan))
    with pytest.raises(ValueError, match="both outcomes"):
        fit_layout_value(np.zeros((5, len(LAYOUT_FEATURES))), np.ones(5, dtype=bool))
    model = LayoutValue(np.linspace(-1, 1, width))
    model.save(tmp_path / "v.npz")
    again = LayoutValue.load(tmp_path / "v.npz")
    x = np.random.default_rng(1).random((7, len(LAYOUT_FEATURES)))
    np.testing.assert_array_equal(again(x), model(x))


def _open_layout():
    return _layout({0: (0.6, 0.62), 1: (1.3, 0.45), 2: (1.9, 0.9), 9: (2.1, 0.3)})


def test_the_model_plays_as_the_env_steps_and_shares_noise_across_candidates() -> None:
    positions, on = _open_layout()
    rules = {"break": False, "ball_in_hand": False}
    rng = np.random.default_rng(5)
    env = _env()
    # (aim, speed, side, vertical) laid out in the game's action (the tip last).
    strikes = rng.uniform(-0.5, 0.5, (3, 4))
    actions = np.stack([rule_action(env.unwrapped.config, s) for s in strikes])
    # Noiseless: every sample is what the env itself does with the action.
    model = GameModel(env.unwrapped.config)
    result, after, left = model.play(positions, on, rack_row({}), actions, 2)
    for c in range(3):
        env.reset(options={"positions": positions, "on_table": on, "rules": rules})
        env.step(actions[c].astype(np.float32))
        for row in (2 * c, 2 * c + 1):
            np.testing.assert_array_equal(left[row], env.unwrapped.on_table)
            np.testing.assert_allclose(after[row][left[row]], env.unwrapped.positions[left[row]])
    # With noise: sample m of every candidate draws the same errors.
    noisy = GameModel(_env(noise=(0.003, 0.05, 0.05)).unwrapped.config, seed=3)
    same = np.repeat(actions[:1], 2, axis=0)
    result, after, _ = noisy.play(positions, on, rack_row({}), same, 4)
    np.testing.assert_array_equal(result.shots[:4], result.shots[4:])
    np.testing.assert_array_equal(after[:4], after[4:])
    assert np.unique(result.shots[:4, 0]).size == 4  # the samples differ from each other
    after[0, 0] = -1.0  # a copy: the model's own tables are untouched
    assert noisy.state.positions[0, 0, 0] != -1.0


def test_the_model_refuses_ball_in_hand_and_bad_actions() -> None:
    positions, on = _open_layout()
    config = _env().unwrapped.config
    model = GameModel(config)
    width = config.action_size
    with pytest.raises(ValueError, match="place the cue ball"):
        model.play(positions, on, rack_row({"ball_in_hand": True}), np.zeros((1, width)), 1)
    with pytest.raises(ValueError, match="actions must be"):
        model.play(positions, on, rack_row({}), np.zeros((1, width - 1)), 1)
    with pytest.raises(ValueError, match="samples"):
        model.play(positions, on, rack_row({}), np.zeros((1, width)), 0)


def _flat_value() -> LayoutValue:
    width = design(np.zeros((1, len(LAYOUT_FEATURES)))).shape[1]
    w = np.zeros(width)
    w[1 + P_BEST] = 4.0  # a layout is worth more the easier its ball on
    w[0] = -2.0
    return LayoutValue(w)


@pytest.mark.parametrize("objective", ["duel", "runout"])
def test_with_the_9_straight_in_it_pots_the_9_and_wins(objective) -> None:
    env = _env()
    length, width = env.unwrapped.config.table.length, env.unwrapped.config.table.width
    r = env.unwrapped.config.table.ball_radius
    # The 9 on the diagonal to the far corner pocket, the cue ball behind it on that line.
    u = np.array([length, width]) / np.hypot(length, width)
    nine = np.array([length, width]) - u * 0.5
    positions, on = _layout({0: tuple(nine - u * (0.4 + 2 * r)), 9: tuple(nine)})
    obs, _ = env.reset(options={"positions": positions, "on_table": on,
                                "rules": {"break": False, "ball_in_hand": False}})  # fmt: skip
    agent = LookaheadAgent(env, _flat_value(), objective=objective, samples=2, final_samples=2)
    action, _ = agent.predict(obs)
    *_, terminated, _, info = env.step(action)
    assert terminated and info["potted"] == (9,) and info["legal"]
    assert agent.last_values is not None and np.max(agent.last_values) == 1.0


def test_with_no_pot_open_it_plays_a_legal_shot_in_a_duel() -> None:
    env = _env()
    # The 1 frozen behind the 2 and 3 from the cue ball's side: no direct pot is clear.
    positions, on = _layout({0: (0.5, 0.635), 1: (2.3, 0.15), 2: (1.2, 0.5), 9: (2.0, 1.1)})
    obs, _ = env.reset(options={"positions": positions, "on_table": on,
                                "rules": {"break": False, "ball_in_hand": False}})  # fmt: skip
    agent = LookaheadAgent(env, _flat_value(), samples=2, final_samples=2)
    action, _ = agent.predict(obs)
    *_, info = env.step(action)
    assert info["foul"] is None, info


@pytest.mark.parametrize(
    ("info", "expected"),
    [
        ({"foul": None, "winner": None, "turn_over": False}, "pot"),
        ({"foul": None, "winner": None, "turn_over": True}, "miss"),
        ({"foul": None, "winner": "player_0", "turn_over": True}, "won"),
        ({"foul": "scratch", "winner": None, "turn_over": True}, "scratch"),
        ({"foul": "wrong_ball_first", "winner": "player_1", "turn_over": True}, "wrong_ball_first"),
    ],
)
def test_a_duel_shot_is_read_by_the_rules(info, expected) -> None:
    assert shot_outcome(info) == expected


def test_features_read_from_an_observation_are_the_tables_own() -> None:
    env = _env(noise=(0.003, 0.05, 0.05))
    config = env.unwrapped.config
    mouths = pocket_mouths(config.table)
    obs, _ = env.reset(seed=4)
    for _ in range(3):  # the break, then two random shots (ball in hand after a foul too)
        obs, *_ = env.step(env.action_space.sample())
        u = env.unwrapped
        rack = u.rack
        truth = layout_features(
            config.table, mouths, u.positions[None], u.on_table[None],
            np.array([rack["ball_in_hand"]]), np.array([rack["fouls"]]), SIGMA,
        )[0]  # fmt: skip
        seen = observation_features(config, mouths, obs)
        np.testing.assert_allclose(seen, truth, atol=2e-3)


def test_a_fitted_value_is_saved_with_a_config_that_plays_it(tmp_path) -> None:
    rng = np.random.default_rng(2)
    features = rng.random((200, len(LAYOUT_FEATURES)))
    won = rng.random(200) < features[:, P_BEST]
    data = tmp_path / "d.npz"
    np.savez(data, features=features, won=won)
    out = tmp_path / "value.npz"
    assert layout_value_main(["fit", str(data), "--out", str(out)]) == 0
    agent = make_agent(str(out), _env())
    assert isinstance(agent, LookaheadAgent)
    np.testing.assert_array_equal(
        agent.layout_value.weights, fit_layout_value(features, won).weights
    )


@pytest.mark.parametrize("name", ["duel_value", "runout_value"])
def test_a_committed_value_prizes_an_easier_ball_on(name) -> None:
    """Every other feature held, the shooter's chance grows with the ball on's pot chance.

    Where it decides the rack: the 9 on, or the cue ball in hand late in the rack. (Early in
    a duel the data shows no such dependence: with 4+ balls left and no ball in hand the
    shooter won 45-51% of racks in every p_best bin of the seed-0 training data.)
    """
    models = Path(__file__).resolve().parents[2] / "models"
    agent = make_agent(str(models / f"{name}.npz"), _env(noise=(0.003, 0.05, 0.05)))
    assert isinstance(agent, LookaheadAgent)
    assert agent.objective == name.removesuffix("_value")
    grid = np.linspace(0.0, 1.0, 11)
    for hand, last, left in ((1, 0, 3 / 9), (0, 1, 1 / 9), (1, 1, 1 / 9)):
        f = np.zeros((grid.size, len(LAYOUT_FEATURES)))
        f[:, 0], f[:, P_BEST], f[:, 3], f[:, 4] = hand, grid, last, left
        value = agent.layout_value(f)
        assert np.all((value > 0.0) & (value < 1.0))
        assert np.all(np.diff(value) > 0.0), (name, hand, last, value)


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"objective": "pots"}, "objective must be one of"),
        ({"pots": 0}, "must be >= 1"),
        ({"samples": 0}, "must be >= 1"),
        ({"final_samples": -1}, "final_samples >= 0"),
        ({"break_arm": 99}, "break_arm must index"),
    ],
)
def test_bad_settings_are_refused(kwargs, message) -> None:
    with pytest.raises(ValueError, match=message):
        LookaheadAgent(_env(), _flat_value(), **kwargs)


def test_the_agent_refuses_a_roll_table_id() -> None:
    with pytest.raises(ValueError, match="spin rotation"):
        LookaheadAgent(gym.make("pool_env/NineBallGameRoll-v2"), _flat_value())


def test_duel_collection_builds_both_sides_as_the_duels_do(monkeypatch) -> None:
    """Both sides know they play an opponent (players=2): a search player's duel objective."""
    import agents.training.fit_layout_value as fit

    seen = []

    def recording(name, env, seed=0, players=None):
        seen.append((name, players))
        return make_agent(name, env, seed=seed, players=players)

    monkeypatch.setattr(fit, "make_agent", recording)
    fit.collect("ghost", "ghost", racks=1, seed=70000)
    assert seen == [("ghost", 2), ("ghost", 2)]


@pytest.mark.parametrize(("name", "players"), [("duel_value.npz", 2), ("runout_value.npz", None)])
def test_a_lookahead_file_is_the_search_player_at_depth_1_shot_for_shot(name, players) -> None:
    """The lookahead is the search's cheap setting: the same shots as the lookahead class."""
    from agents.learned.lookahead import PLAY_SETTINGS
    from agents.learned.rack_play import rack_model_config
    from agents.learned.search_player import SearchPlayer

    path = Path(__file__).resolve().parents[2] / "models" / name
    config = rack_model_config(path)
    envs = [gym.make(ENV_ID, noise="fastfiz") for _ in range(2)]
    settings = {k: config[k] for k in PLAY_SETTINGS if k in config}
    own = LookaheadAgent(envs[0], LayoutValue.load(path), players=players, **settings)
    player = make_agent(str(path), envs[1], players=players)
    assert isinstance(player, SearchPlayer) and player.settings.depth == 1
    shots = 0
    for seed in (11, 12):
        obs = [env.reset(seed=seed)[0] for env in envs]
        for _ in range(4):
            actions = [agent.predict(o)[0] for agent, o in zip((own, player), obs, strict=True)]
            np.testing.assert_array_equal(actions[0], actions[1])
            assert player.last_plan["kind"] == own.last_plan["kind"]  # "lookahead", a break
            steps = [env.step(a) for env, a in zip(envs, actions, strict=True)]
            obs = [s[0] for s in steps]
            shots += 1
            if steps[0][2] or steps[0][3]:
                break
    assert shots >= 4
    with pytest.raises(ValueError, match=r"holds 9-ball layout values.*not game='eight'"):
        make_agent(str(path), gym.make("pool_env/EightBallGame-v1"), players=players)
