"""A layout decoded from an observation is one the simulator accepts, a ball in a throat too."""

from __future__ import annotations

import gymnasium as gym
import numpy as np

from agents.baselines.base import decode_observation
from agents.learned.game_model import GameModel
from pool_env import encode_observations
from pool_env.game.games.wpa import rack_row


def test_a_ball_in_a_corner_throat_with_one_frozen_to_it_decodes_to_a_valid_layout() -> None:
    """The layout of the duel that crashed the search (issue 46).

    The 3 rests in the top-right corner's throat, past the rail line, the cue ball frozen to
    it from below. Decoding brings the 3 back onto the rail line, onto the cue ball; pushing
    the two apart must not put either past the rail line, where the corner's jaw is (the
    simulator refused the layout: 'ball 0 ... is inside a jaw (facing or point) of pocket 5').
    """
    env = gym.make("pool_env/NineBallGame-v2", noise="fastfiz")
    config = env.unwrapped.config
    table = config.table
    r = table.ball_radius
    positions = np.tile([0.5, 0.5], (10, 1))
    on = np.zeros(10, dtype=bool)
    positions[3] = (2.4645, 1.2440)  # in the throat: 2.6 mm past the rail line
    positions[0] = (2.4645, 1.2440 - 2 * r - 1e-6)
    on[[0, 3]] = True
    obs = encode_observations(positions[None], on[None], table.length, table.width)[0]
    decoded, flags = decode_observation(obs, table)
    assert np.array_equal(flags, on)
    assert np.hypot(*(decoded[0] - decoded[3])) >= 2 * r
    assert (decoded[flags] >= r).all()
    assert (decoded[flags] <= [table.length - r, table.width - r]).all()
    # The simulator takes it: a shot is played from it (a refused layout is a ValueError).
    action = np.zeros((1, config.action_size))
    action[0, 1] = -0.5
    result, _, _ = GameModel(config).play(decoded, flags, rack_row({}), action, 1)
    assert result.hits.shape[0] == 1
