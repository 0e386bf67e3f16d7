"""The set value: a network over the balls on the table, its inputs, its fit and its files."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest
import torch
import yaml

from agents.learned.layout_value import LAYOUT_FEATURES, design, layout_features
from agents.learned.set_value import (
    CONTEXT_FEATURES,
    ROW_FEATURES,
    SetInputs,
    SetValue,
    set_inputs,
)
from agents.training.fit_layout_value import collect
from agents.training.fit_set_value import (
    _net,
    fit_set_value,
    initial_value,
    load_records,
    log_loss,
    main,
)
from pool_env.game.geometry import pocket_mouths

ENV_ID = "pool_env/NineBallGame-v2"
SIGMA = 0.0021817


@pytest.fixture(scope="module")
def table():
    return gym.make(ENV_ID).unwrapped.config.table


def _layouts(table, count: int, seed: int) -> dict[str, np.ndarray]:
    """``count`` random 9-ball layouts: the cue ball, the 9 and a random subset of 1..8."""
    rng = np.random.default_rng(seed)
    r = table.ball_radius
    low, high = np.array([r, r]), np.array([table.length - r, table.width - r])
    positions = rng.uniform(low, high, (count, 10, 2))
    on = rng.random((count, 10)) < 0.5
    on[:, 0] = on[:, 9] = True
    return {
        "positions": positions,
        "on_table": on,
        "in_hand": rng.random(count) < 0.2,
        "fouls": rng.integers(0, 3, (count, 2)),
    }


def _random_value(seed: int, hidden: int = 16, scale: float = 1.0) -> SetValue:
    rng = np.random.default_rng(seed)
    model = initial_value(hidden, rng.normal(size=13), seed, SIGMA)
    weights = {k: v + scale * rng.normal(size=v.shape) for k, v in model.weights.items()}
    return SetValue(weights, sigma=SIGMA)


def _value(model: SetValue, table, layouts: dict[str, np.ndarray]) -> np.ndarray:
    return model.value(table, pocket_mouths(table), **layouts, sigma=SIGMA)


def test_the_network_does_not_depend_on_the_order_of_its_rows(table) -> None:
    inputs = set_inputs(table, pocket_mouths(table), **_layouts(table, 50, 0), sigma=SIGMA)
    model = _random_value(1)
    rng = np.random.default_rng(2)
    for _ in range(5):
        order = rng.permutation(inputs.rows.shape[1])
        shuffled = SetInputs(inputs.rows[:, order], inputs.mask[:, order], inputs.context)
        np.testing.assert_allclose(model.logits(shuffled), model.logits(inputs), rtol=1e-12)
    # What the empty slots hold does not count either.
    noisy = inputs.rows + rng.normal(size=inputs.rows.shape) * ~inputs.mask[..., None]
    same = model.logits(SetInputs(noisy, inputs.mask, inputs.context))
    np.testing.assert_allclose(same, model.logits(inputs), rtol=1e-12)


def test_a_layout_renumbered_in_the_same_order_is_worth_the_same(table) -> None:
    """Balls 1, 2, 3 and 9 read as 4, 6, 7 and 9: the same ball on, ranks, pots, rows."""
    layouts = _layouts(table, 30, 3)
    layouts["on_table"][:, 1:9] = False
    layouts["on_table"][:, 1:4] = True
    moved = {k: v.copy() for k, v in layouts.items()}
    moved["on_table"][:, 1:9] = False
    moved["on_table"][:, [4, 6, 7]] = True
    moved["positions"][:, [4, 6, 7]] = layouts["positions"][:, [1, 2, 3]]
    moved["positions"][:, [1, 2, 3]] = layouts["positions"][:, [5, 8, 4]]  # off the table
    model = _random_value(4)
    np.testing.assert_allclose(_value(model, table, moved), _value(model, table, layouts),
                               rtol=1e-12)  # fmt: skip


def test_the_inputs_read_the_rules_and_the_logistics_features(table) -> None:
    layouts = _layouts(table, 40, 5)
    mouths = pocket_mouths(table)
    inputs = set_inputs(table, mouths, **layouts, sigma=SIGMA)
    on = layouts["on_table"][:, 1:]
    assert inputs.rows.shape == (40, 9, len(ROW_FEATURES))
    assert inputs.context.shape == (40, len(CONTEXT_FEATURES))
    np.testing.assert_array_equal(inputs.mask, on)
    np.testing.assert_array_equal(
        inputs.context[:, : len(LAYOUT_FEATURES)],
        layout_features(table, mouths, **layouts, sigma=SIGMA),
    )
    rows = {name: inputs.rows[..., k] for k, name in enumerate(ROW_FEATURES)}
    assert (rows["ball_on"].sum(axis=1) == 1).all()
    assert (rows["last_ball"][:, 8] == 1).all()  # the 9 is always on in these layouts
    assert np.all(rows["rank"][rows["ball_on"] == 1] == 0)
    np.testing.assert_allclose(rows["rank"][:, 8], (on.sum(axis=1) - 1) / 8)
    # The ball on's best pot chance is the logistic's p_best, unless the cue ball is in hand.
    seen = ~layouts["in_hand"]
    best_on = (rows["p_best"] * rows["ball_on"]).sum(axis=1)
    p_best = inputs.context[:, LAYOUT_FEATURES.index("p_best")]
    np.testing.assert_allclose(best_on[seen], p_best[seen], rtol=1e-12)
    assert np.all(rows["p_best"][~seen] == 0) and np.all(rows["cue_x"][~seen] == 0)
    assert np.all((rows["p_second"] <= rows["p_best"]) & (rows["p_best"] <= 1.0))
    assert np.all(inputs.rows[~inputs.mask] == 0)


def test_chances_are_strictly_between_0_and_1(table) -> None:
    layouts = _layouts(table, 200, 6)
    for scale in (0.1, 3.0, 30.0):  # up to weights far larger than any fit leaves
        p = _value(_random_value(7, scale=scale), table, layouts)
        assert p.shape == (200,) and p.dtype == np.float64
        assert np.all((p > 0.0) & (p < 1.0))
    empty = {k: v[:0] for k, v in layouts.items()}
    assert _value(_random_value(7), table, empty).shape == (0,)


@pytest.mark.parametrize(
    ("change", "message"),
    [
        (lambda d: d.update(positions=d["positions"][:, :9]), "positions must be"),
        (lambda d: d["positions"].__setitem__((0, 3, 0), np.nan), "positions must be"),
        (lambda d: d.update(on_table=d["on_table"][0]), "on_table must be"),
        (lambda d: d.update(in_hand=d["in_hand"][:3]), "in_hand must be"),
        (lambda d: d.update(fouls=d["fouls"][:, :1]), "fouls"),
        (lambda d: d["fouls"].__setitem__((1, 0), 3), "fouls must be"),
        (lambda d: d["on_table"].__setitem__((2, slice(1, None)), False), "no object ball"),
        (lambda d: d.update(sigma=0.0), "sigma must be"),
    ],
)
def test_bad_layouts_are_refused(table, change, message) -> None:
    layouts = {**_layouts(table, 5, 8), "sigma": SIGMA}
    change(layouts)
    with pytest.raises(ValueError, match=message):
        _random_value(0).value(table, pocket_mouths(table), **layouts)


def test_bad_weights_are_refused() -> None:
    weights = dict(_random_value(0).weights)
    with pytest.raises(ValueError, match="lack"):
        SetValue({k: v for k, v in weights.items() if k != "skip"})
    with pytest.raises(ValueError, match="phi1_w must be"):
        SetValue({**weights, "phi1_w": weights["phi1_w"][:, :3]})
    with pytest.raises(ValueError, match="skip must be"):
        SetValue({**weights, "skip": np.full(13, np.inf)})


def test_a_saved_value_loads_the_same(tmp_path, table) -> None:
    model = _random_value(9)
    model.save(tmp_path / "v.npz")
    again = SetValue.load(tmp_path / "v.npz")
    assert again.sigma == SIGMA and again.hidden == model.hidden
    layouts = _layouts(table, 20, 10)
    np.testing.assert_array_equal(_value(again, table, layouts), _value(model, table, layouts))
    # A file of other features is refused, not misread.
    with np.load(tmp_path / "v.npz") as data:
        arrays = dict(data)
    arrays["row_features"] = np.array(ROW_FEATURES[::-1])
    np.savez(tmp_path / "w.npz", **arrays)
    with pytest.raises(ValueError, match="row_features"):
        SetValue.load(tmp_path / "w.npz")


def _synthetic(table, count: int, seed: int) -> dict[str, np.ndarray]:
    """Layouts labelled by a rule of the set that the logistic's features cannot see.

    Run out when the ball after the ball on lies in the table's left half (10% of labels
    flipped): a function of two rows, not of the ball on's pot chances or the counts.
    """
    layouts = _layouts(table, count, seed)
    on = layouts["on_table"]
    order = np.argsort(~on[:, 1:], axis=1, kind="stable") + 1  # balls on the table, lowest first
    second = np.where(on[:, 1:].sum(axis=1) > 1, order[:, 1], 9)
    x = layouts["positions"][np.arange(count), second, 0]
    flip = np.random.default_rng(seed + 1).random(count) < 0.1
    label = (x < table.length / 2) ^ flip
    return {**layouts, "label": label, "rack": np.arange(count) // 2, "sigma": np.float64(SIGMA)}


def test_the_fit_learns_a_rule_of_the_set_the_logistic_cannot(table) -> None:
    records = _synthetic(table, 3000, 11)
    model, report = fit_set_value(records, seed=0, hidden=16, epochs=60, patience=15, lr=5e-3)
    held = report["held_out"]
    assert held["base_rate"] > 0.68  # the labels are half and half
    assert held["logistic"] > 0.65  # it sees nothing of the rule
    assert held["net"] < 0.6 * held["base_rate"], report
    assert report["layouts"]["held_out"] == pytest.approx(600, abs=2)  # 20% of the racks
    # The torch module the fit trains computes the numpy network's logits.
    inputs = set_inputs(table, pocket_mouths(table), **{k: records[k][:50] for k in
                        ("positions", "on_table", "in_hand", "fouls")}, sigma=SIGMA)  # fmt: skip
    with torch.no_grad():
        args = (
            inputs.rows,
            inputs.mask,
            inputs.context,
            design(inputs.context[:, : len(LAYOUT_FEATURES)]),
        )
        z = _net(model)(*(torch.tensor(a, dtype=torch.float32) for a in args)).numpy()
    np.testing.assert_allclose(z, model.logits(inputs), atol=1e-4)


def test_records_of_several_files_keep_their_racks_apart(tmp_path, table) -> None:
    a, b = _synthetic(table, 10, 12), _synthetic(table, 6, 13)
    np.savez(tmp_path / "a.npz", **a)
    np.savez(tmp_path / "b.npz", **b)
    records = load_records([tmp_path / "a.npz", tmp_path / "b.npz"])
    assert records["label"].shape == (16,) and records["positions"].shape == (16, 10, 2)
    np.testing.assert_array_equal(records["rack"], np.r_[np.arange(10) // 2, 5 + np.arange(6) // 2])
    assert float(records["sigma"]) == SIGMA
    np.savez(tmp_path / "c.npz", **{**b, "sigma": np.float64(0.003)})
    with pytest.raises(ValueError, match="different aim errors"):
        load_records([tmp_path / "a.npz", tmp_path / "c.npz"])
    np.savez(tmp_path / "d.npz", features=np.zeros((2, 7)), won=np.zeros(2, bool))
    with pytest.raises(ValueError, match="no raw layouts"):
        load_records([tmp_path / "d.npz"])


def test_the_command_line_fit_writes_the_model_and_its_figures(tmp_path, table) -> None:
    np.savez(tmp_path / "d.npz", **_synthetic(table, 400, 14))
    out = tmp_path / "m.npz"
    assert (
        main(["fit", str(tmp_path / "d.npz"), "--out", str(out), "--seed", "3", "--hidden", "8"])
        == 0
    )
    config = yaml.safe_load(out.with_name("m_config.yaml").read_text())
    assert config["kind"] == "set_value" and config["hidden"] == 8
    assert config["row_features"] == list(ROW_FEATURES) and config["sigma"] == SIGMA
    assert set(config["fit"]["held_out"]) == {"net", "logistic", "base_rate"}
    assert SetValue.load(out).n_parameters == config["parameters"]


@pytest.mark.parametrize("runout", [True, False])
def test_the_collector_keeps_the_raw_layouts_beside_their_features(runout: bool) -> None:
    noise = (SIGMA, 0.075, 0.0175)
    data = collect("ghost", "ghost", 3, 90_000, runout=runout, noise=noise)
    m = data["label"].size
    assert m >= 1 and float(data["sigma"]) == SIGMA
    assert data["positions"].shape == (m, 10, 2) and data["on_table"].shape == (m, 10)
    assert data["fouls"].shape == (m, 2) and data["in_hand"].shape == (m,)
    assert set(data["rack"].tolist()) <= {90_000, 90_001, 90_002}
    np.testing.assert_array_equal(data["label"], data["won"])
    table = gym.make(ENV_ID).unwrapped.config.table
    again = layout_features(table, pocket_mouths(table), data["positions"], data["on_table"],
                            data["in_hand"], data["fouls"], SIGMA)  # fmt: skip
    np.testing.assert_array_equal(again, data["features"])
    assert log_loss(np.full(m, 0.5), data["label"]) == pytest.approx(np.log(2.0))


def test_the_chain_chance_is_the_pot_from_where_the_ball_before_lies(table) -> None:
    """Ball 5's chain chance: the cue ball put on ball 2 (the one before it), 2 and below off."""
    mouths = pocket_mouths(table)
    positions = np.tile([[0.1, 0.05]], (10, 1)) + np.arange(10)[:, None] * [0.06, 0.0]
    on = np.zeros(10, dtype=bool)
    for ball, point in {0: (0.5, 0.4), 2: (1.0, 0.6), 5: (1.8, 0.9), 9: (2.2, 0.3)}.items():
        positions[ball], on[ball] = point, True
    layouts = {"positions": positions[None], "on_table": on[None], "in_hand": np.array([False]),
               "fouls": np.zeros((1, 2), int)}  # fmt: skip
    rows = set_inputs(table, mouths, **layouts, sigma=SIGMA).rows[0]
    chain = ROW_FEATURES.index("p_chain")
    moved, left = positions.copy(), on.copy()
    moved[0], left[2] = positions[2], False
    features = layout_features(table, mouths, moved[None], left[None], np.array([False]),
                               np.zeros((1, 2), int), SIGMA)  # fmt: skip
    expected = features[0, LAYOUT_FEATURES.index("p_best")]  # ball 5 is on there
    assert expected > 0.0
    assert rows[5 - 1, chain] == pytest.approx(expected, rel=1e-12)
    # The ball on's chain chance is its pot from the cue ball.
    assert rows[2 - 1, chain] == rows[2 - 1, ROW_FEATURES.index("p_best")]
    np.testing.assert_allclose(rows[5 - 1, ROW_FEATURES.index("chain_distance")],
                               np.hypot(0.8, 0.3) / table.length)  # fmt: skip
