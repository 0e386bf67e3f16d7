"""Snooker's codec reads the ball on from the layout, as the env's reset does."""

from __future__ import annotations

import numpy as np
import pytest

from pool_env import PoolEnv, decode_action
from pool_env.game.games.snooker.markings import frame_layout


@pytest.fixture(scope="module")
def colours_only() -> tuple[PoolEnv, np.ndarray, np.ndarray]:
    """A cut-aim env on the colours alone (no red), the cue ball at (1.5, 0.5)."""
    env = PoolEnv(game="snooker", scene="snooker", aim="cut")
    pos = frame_layout(env.config.table)
    on = np.zeros(22, dtype=bool)
    on[0], on[16:] = True, True
    pos[0] = (1.5, 0.5)
    return env, pos, on


def test_decode_without_a_rack_aims_at_the_colour_on(colours_only: tuple) -> None:
    """No reds: the colours in order, the yellow on; the decoded cut is the one executed."""
    env, pos, on = colours_only
    env.reset(seed=0, options={"positions": pos, "on_table": on})
    action = np.zeros(env.action_space.shape, dtype=np.float32)
    shot = decode_action(env.config, action, env.positions, env.on_table)
    info = env.step(action)[4]
    assert info["ball_on"] == 16
    assert shot.angle == pytest.approx(info["angle"], abs=1e-12)
    assert shot.speed == pytest.approx(info["speed"], abs=1e-12)


def test_a_red_on_without_reds_is_refused_as_reset_refuses_it(colours_only: tuple) -> None:
    env, pos, on = colours_only
    action = np.zeros(env.action_space.shape, dtype=np.float32)
    with pytest.raises(ValueError, match="'red' needs a red on the table"):
        decode_action(env.config, action, pos, on, rack={"phase": "red"})
    with pytest.raises(ValueError, match="'red' needs a red on the table"):
        env.reset(seed=0, options={"positions": pos, "on_table": on, "rules": {"phase": "red"}})
