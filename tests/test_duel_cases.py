"""The two-player front's own decoding of ball in hand and the called pocket, by hand.

:class:`pool_env.multiagent.PoolDuelEnv` turns actions 2-3 into a placement request and
action 4 into the pocket called for the 8 (six equal slices of [-1, 1], pockets 0..5); the
rules (:func:`pool_env.game.wpa.judge`) and the placement
(:func:`pool_env.game.placement.nearest_free_point`) are pinned elsewhere. Here the
expected values come from the documented decoding and the WPA rules.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from pool_env.game.wpa import SOLIDS, STRIPES
from pool_env.multiagent import PoolDuelEnv

TOWARD_CORNER = -3 * math.pi / 4  # along the diagonal into pocket 0 at (0, 0)


def test_the_break_places_the_cue_ball_behind_the_head_string() -> None:
    """A request at the foot rail is moved to the head string ``x = L / 4`` (WPA 8-ball 3.3).

    With a zero speed range the shot leaves the cue ball where it was placed.
    """
    env = PoolDuelEnv("eight", speed_range=(0.0, 0.0))
    env.reset(seed=0)
    assert env.state_.ball_in_hand and env.state_.behind_head_string
    env.step(np.array([0.0, -1.0, 1.0, 0.0, 0.0], np.float32))  # x = L - R, y = W / 2
    np.testing.assert_allclose(
        env.positions[0], [env.table.length / 4, env.table.width / 2], rtol=0, atol=1e-15
    )


@pytest.mark.parametrize(("call", "wins"), [(-0.9, True), (-0.6, False), (0.9, False)])
def test_the_called_pocket_is_one_of_six_equal_slices(call: float, wins: bool) -> None:
    """On the 8, straight into pocket 0: called 0 (action in [-1, -2/3)) wins, else loses."""
    env = PoolDuelEnv("eight")
    pos = np.array([[1.5, 0.6]] * 16)
    on = np.zeros(16, bool)
    on[[0, 8, 11]] = True
    pos[0] = (0.45 / math.sqrt(2),) * 2
    pos[8] = (0.25 / math.sqrt(2),) * 2
    pos[11] = (1.9, 0.9)
    env.reset(seed=0, options={"positions": pos, "on_table": on})
    env.state_ = replace(env.state_, groups=(SOLIDS, STRIPES))  # solids cleared: on the 8
    assert env.state_.ball_on == 8
    lo, hi = env.speed_range
    power = 2 * (1.5 - lo) / (hi - lo) - 1
    env.step(np.array([TOWARD_CORNER / math.pi, power, 0.0, 0.0, call], np.float32))
    assert env.infos["player_0"]["potted"] == (8,)
    assert env.infos["player_0"]["winner"] == ("player_0" if wins else "player_1")
    assert env.rewards == (
        {"player_0": 1.0, "player_1": -1.0} if wins else {"player_0": -1.0, "player_1": 1.0}
    )
