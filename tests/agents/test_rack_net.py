"""The rack network (agents.learned.rack_net), its distillation (agents.training.distill_rack)."""

from __future__ import annotations

from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest
import yaml

from agents.evaluation.players import make_agent
from agents.learned.next_shots import OFFSETS, next_shot_actions, next_shot_table
from agents.learned.rack_net import FEATURES, TILTS, RackNetPlayer, eligible, load_rack_net
from agents.learned.rack_play import ValueNet
from agents.training import distill_rack
from pool_env.game.codec import encode_shots
from pool_env.game.games.wpa import rack_row
from pool_env.game.games.wpa.judge import FOUL, KEEPS, WINNER
from pool_env.game.geometry import ANGLE

ENV_ID = "pool_env/NineBallGame-v2"
ROOT = Path(__file__).resolve().parents[2]
PLAYER = ROOT / "models" / "search_player_net.yaml"
COL = {name: k for k, name in enumerate(FEATURES)}


def _net(seed: int = 0, hidden: int = 8) -> ValueNet:
    rng = np.random.default_rng(seed)
    f = len(FEATURES)
    return ValueNet({
        "mean": rng.normal(size=f), "scale": rng.uniform(0.5, 2.0, size=f),
        "W0": rng.normal(size=(f, hidden)), "b0": rng.normal(size=hidden),
        "W1": rng.normal(size=(hidden, 1)), "b1": rng.normal(size=1),
    }, n_features=f)  # fmt: skip


def _mid_rack(env, seed: int = 949003):
    """An observation after the break with the cue ball where it lies (no ball in hand)."""
    for k in range(20):
        obs, _ = env.reset(seed=seed + k)
        breaker = make_agent(str(PLAYER), env)
        obs, _, terminated, _, info = env.step(breaker.predict(obs)[0])
        if not terminated and info["foul"] is None:
            return obs
    raise AssertionError("no racks kept after the break")


def test_the_forward_pass_is_the_hand_computed_mlp() -> None:
    weights = {
        "mean": np.array([1.0, -1.0]), "scale": np.array([2.0, 0.5]),
        "W0": np.array([[1.0, -1.0], [0.5, 2.0]]), "b0": np.array([0.0, -1.0]),
        "W1": np.array([[3.0], [1.0]]), "b1": np.array([0.5]),
    }  # fmt: skip
    net = ValueNet(weights, n_features=2)
    x = np.array([[3.0, 0.0], [1.0, -1.0]])
    # Row 0: z = ((3-1)/2, (0+1)/0.5) = (1, 2); h = relu(1*1 + 2*0.5, -1 + 2*2 - 1) = (2, 2);
    # out = 3*2 + 1*2 + 0.5 = 8.5. Row 1: z = (0, 0); h = relu(0, -1) = (0, 0); out = 0.5.
    np.testing.assert_allclose(net(x), [8.5, 0.5])
    with pytest.raises(ValueError, match="3 candidate features"):
        ValueNet(weights, n_features=3)


def test_next_shot_table_is_next_shot_actions_with_its_description() -> None:
    env = gym.make(ENV_ID)
    player = RackNetPlayer(env, PLAYER)
    obs = _mid_rack(env)
    positions, on, _ = player.observe(obs)
    actions, ok = next_shot_actions(player.config, player.mouths, positions[None], on[None])
    table = next_shot_table(player.config, player.mouths, positions[None], on[None])
    np.testing.assert_array_equal(table.actions, actions)
    np.testing.assert_array_equal(table.ok, ok)
    m = actions.shape[1]
    assert table.offsets.shape == (m,) and set(table.offsets) == set(OFFSETS)
    assert table.offsets[0] == OFFSETS[0] and table.offsets[-1] == OFFSETS[-1]


def test_the_player_plays_in_space_actions_and_the_argmax_of_its_net() -> None:
    env = gym.make(ENV_ID, noise="fastfiz", end_on_foul=True)
    player = RackNetPlayer(env, PLAYER, _net())
    played = 0
    for k in range(3):
        obs, _ = env.reset(seed=949000 + k)
        done, shot = False, 0
        while not done:
            action, _ = player.predict(obs, deterministic=True)
            assert env.action_space.contains(action), action
            if shot and player.last_plan.get("kind") == "rack_net":
                found, pick = player.last_candidates
                scores = player.scores(found.features)
                assert pick == int(np.argmax(scores))
                # Among the candidates whose exact play keeps the table when there is one.
                keeps = found.features[:, COL["keeps"]] > 0.5
                assert keeps[pick] or not keeps.any()
                net = player.net(found.features)
                np.testing.assert_array_equal(scores[keeps], net[keeps])
                # The strike played is the picked candidate's (aim, speed, tip).
                strike = found.actions[pick, [0, 1, *player.config.tip_columns]]
                np.testing.assert_allclose(
                    action[[0, 1, *player.config.tip_columns]], strike, atol=1e-6
                )
                played += 1
            obs, _, terminated, truncated, _ = env.step(action)
            done, shot = terminated or truncated, shot + 1
    assert played > 0


def test_the_fan_columns_read_the_neighbouring_aims_exact_plays() -> None:
    env = gym.make(ENV_ID)
    player = RackNetPlayer(env, PLAYER)
    checked = 0
    for seed in range(949000, 949010):
        obs, _ = env.reset(seed=seed)
        obs, _, terminated, _, info = env.step(make_agent(str(PLAYER), env).predict(obs)[0])
        if terminated or info["foul"] is not None:
            continue
        found = player.candidate_table(*player.observe(obs))
        f = found.features[found.kinds == "pot"]
        keys = [tuple(r) for r in f[:, [COL["pocket_rank"], COL["arrival_m_s"],
                                        COL["tip_vertical"]]]]  # fmt: skip
        for key in set(keys):
            group = f[[k == key for k in keys]]
            if len(group) != len(OFFSETS):
                continue  # an aim of the fan not playable: its neighbours read 0
            group = group[np.argsort(group[:, COL["mouth_offset"]])]
            keeps = group[:, COL["keeps"]]
            np.testing.assert_allclose(group[:, COL["fan_keeps"]], keeps.mean())
            np.testing.assert_array_equal(group[1:, COL["fan_left"]], keeps[:-1])
            np.testing.assert_array_equal(group[:-1, COL["fan_right"]], keeps[1:])
            assert group[0, COL["fan_left"]] == 0 and group[-1, COL["fan_right"]] == 0
            checked += 1
    assert checked > 0


def test_a_saved_network_loads_and_scores_the_same(tmp_path) -> None:
    net = _net(1)
    path = tmp_path / "net.npz"
    np.savez(path, **net.weights())
    player_rel = Path(__import__("os").path.relpath(PLAYER, tmp_path))
    (tmp_path / "net_config.yaml").write_text(
        yaml.safe_dump({"kind": "rack_net", "player": str(player_rel)})
    )
    env = gym.make(ENV_ID)
    loaded = load_rack_net(path, env)
    x = np.random.default_rng(2).normal(size=(5, len(FEATURES)))
    np.testing.assert_array_equal(loaded.net(x), net(x))
    via_players = make_agent(str(path), env)
    assert isinstance(via_players, RackNetPlayer)
    np.testing.assert_array_equal(via_players.net(x), net(x))
    (tmp_path / "net_config.yaml").write_text(yaml.safe_dump({"kind": "rack_net"}))
    with pytest.raises(ValueError, match="player"):
        load_rack_net(path, env)
    swapped = [FEATURES[1], FEATURES[0], *FEATURES[2:]]  # same width, another order
    (tmp_path / "net_config.yaml").write_text(yaml.safe_dump(
        {"kind": "rack_net", "player": str(player_rel), "features": swapped}
    ))  # fmt: skip
    with pytest.raises(ValueError, match="other features"):
        load_rack_net(path, env)


def test_collect_records_the_drivers_own_action(monkeypatch) -> None:
    given: list[np.ndarray] = []

    class Recording:
        def __init__(self, inner):
            self.inner = inner

        def predict(self, obs, deterministic=True):
            action, state = self.inner.predict(obs, deterministic=deterministic)
            given.append(np.array(action, dtype=np.float64))
            return action, state

    real = distill_rack.make_agent
    monkeypatch.setattr(distill_rack, "make_agent",
                        lambda name, env, seed: Recording(real(name, env, seed)))  # fmt: skip
    data = distill_rack.collect("ghost", racks=2, seed=949000, practice=False, samples=2,
                                log_every=0)  # fmt: skip
    d = data["rack"].size
    assert d > 0 and data["starts"].size == d + 1
    assert data["values"].size == data["features"].shape[0] == data["starts"][-1]
    # Every recorded action is one the driver returned, in order, the breaks left out.
    j = 0
    for row in data["driver_action"]:
        while j < len(given) and not np.array_equal(given[j], row):
            j += 1
        assert j < len(given), "a recorded action the driver never played"
        j += 1
    assert not any(np.array_equal(given[0], row) for row in data["driver_action"])
    assert ((data["driver_value"] >= 0) & (data["driver_value"] <= 1)).all()


def test_soft_targets_sum_to_one_and_sharpen_with_tau() -> None:
    v = np.array([0.1, 0.3, 0.2])
    for tau in (0.0, 0.01, 1.0):
        assert distill_rack.soft_targets(v, tau).sum() == pytest.approx(1.0)
    np.testing.assert_array_equal(distill_rack.soft_targets(v, 0.0), [0, 1, 0])
    assert distill_rack.soft_targets(v, 0.01)[1] > distill_rack.soft_targets(v, 1.0)[1]


def test_only_candidates_that_keep_the_table_are_eligible_unless_none_does() -> None:
    f = np.zeros((3, len(FEATURES)))
    f[1, COL["keeps"]] = 1.0
    np.testing.assert_array_equal(eligible(f), [False, True, False])
    np.testing.assert_array_equal(eligible(np.zeros((2, len(FEATURES)))), [True, True])


def test_the_tilted_aims_are_exact_plays_of_the_pot_turned_by_the_noise() -> None:
    env = gym.make(ENV_ID, noise="fastfiz")
    player = RackNetPlayer(env, PLAYER)
    obs = _mid_rack(env)
    positions, on, reference = player.observe(obs)
    found = player.candidate_table(positions, on, reference)
    pots = np.flatnonzero(found.kinds == "pot")
    assert pots.size
    f = found.features
    tilt = f[pots, COL["tilt_keeps"]]
    assert set(np.round(tilt * len(TILTS))) <= set(range(len(TILTS) + 1))
    # Both inner (or outer) tilts keeping the table count in the share.
    assert (tilt[f[pots, COL["tilt_inner"]] > 0.5] >= 2 / len(TILTS)).all()
    # A grid hit is not tilted: its tilt columns are its own outcome.
    grid = np.flatnonzero(found.kinds == "grid")
    np.testing.assert_array_equal(f[grid, COL["tilt_keeps"]], f[grid, COL["keeps"]])
    # Replay one pot with its aim turned by +2 sigma: the column says what the step does.
    table = next_shot_table(player.config, player.mouths, positions[None], on[None])
    ok = np.flatnonzero(table.ok[0])
    k = ok[0]
    parts, playable = encode_shots(
        player.config, positions[None], reference[None],
        table.rows[0, [k], ANGLE][None] + TILTS[-1] * player.sigma,
        table.speeds[:, [k]], table.tips[:, [k]],
    )  # fmt: skip
    action = table.actions[0, k].copy()
    action[0:2] = parts[0, 0, 0:2]
    action[list(player.config.tip_columns)] = parts[0, 0, 2:4]
    result, _, _ = player.exact.play(positions, on, rack_row({}), action[None], 1)
    h = result.hits[0]
    kept = playable[0, 0] and h[FOUL] == 0 and (h[KEEPS] != 0 or h[WINNER] == 0)
    inner = f[pots[0], COL["tilt_inner"]]
    outer = f[pots[0], COL["tilt_outer"]]
    share = f[pots[0], COL["tilt_keeps"]]
    # kept at +2 sigma: the outer pair may keep; not kept: it cannot, and the share is < 1.
    if not kept:
        assert outer == 0 and share < 1
    else:
        assert share >= 1 / len(TILTS)
    assert inner in (0.0, 1.0)
