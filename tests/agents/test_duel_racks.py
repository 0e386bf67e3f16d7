"""Two-player rack collection: the outcome return on a table of cases, its bookkeeping."""

from __future__ import annotations

import numpy as np
import pytest

from agents.training.duel_racks import OUTCOMES, collect_duels, duel_rewards
from agents.training.racks import GAMMA, fit, merge


@pytest.mark.parametrize(
    ("decisions", "winner", "rewards", "dones"),
    [
        (3, "agent", [0.0, 0.0, 1.0], [False, False, True]),  # won on its third decision
        (1, "opponent", [-1.0], [True]),  # one miss, the opponent ran out
        (4, "opponent", [0.0, 0.0, 0.0, -1.0], [False, False, False, True]),
        (2, None, [0.0, 0.0], [False, True]),  # the shot limit: a draw pays nothing
        (0, "opponent", [], []),  # the opponent broke and ran out: no decision to pay
    ],
)
def test_duel_rewards_pay_the_outcome_on_the_last_decision(
    decisions: int, winner: str | None, rewards: list[float], dones: list[bool]
) -> None:
    r, d = duel_rewards(decisions, winner)
    np.testing.assert_array_equal(r, rewards)
    np.testing.assert_array_equal(d, dones)


def test_duel_rewards_reject_bad_input() -> None:
    with pytest.raises(ValueError, match="winner"):
        duel_rewards(2, "player_0")
    with pytest.raises(ValueError, match="decisions"):
        duel_rewards(-1, "agent")


def test_collected_racks_pay_each_outcome_once_and_fit_reads_them(tmp_path) -> None:
    data = collect_duels(racks=4, seed=50_000, explore=0.25, model=None)
    assert set(np.unique(data["outcome"])) <= set(OUTCOMES.values())
    # the agent breaks the even racks with an arm, the ghost agent the odd ones
    assert (data["arms"][1::2] == -1).all() and (data["arms"][0::2] >= 0).all()
    for k, outcome in enumerate(data["outcome"]):
        mine = data["rack"] == k
        paid = data["rewards"][mine].sum() + data["break_rewards"][k]
        assert paid == outcome  # the outcome, paid once: on the break or on a later shot
        ends = data["dones"][mine].sum() + (data["break_dones"][k] and data["arms"][k] >= 0)
        assert ends == (1 if mine.any() or data["arms"][k] >= 0 else 0)
        if mine.any():
            assert data["dones"][np.flatnonzero(mine)[-1]]  # only the last decision ends it
    off = data["offsets"]
    assert off[0] == 0 and off[-1] == data["features"].shape[0]
    assert ((data["picks"] < np.diff(off)) & (data["picks"] >= -1)).all()
    path = tmp_path / "d.npz"
    np.savez(path, **data)
    merged = merge([str(path), str(path)])
    assert merged["arms"].shape[0] == 8 and merged["rack"].max() == 7
    net, _, report = fit(merged, GAMMA, rounds=2, hidden=8, seed=0)
    # every target is a discounted outcome: within [-1, 1]
    assert abs(report["rounds"][-1]["target_mean"]) <= 1.0
    assert np.isfinite(net(merged["features"][:5])).all()
