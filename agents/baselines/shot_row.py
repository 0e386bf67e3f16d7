"""Plays the first row of the env's ``"shots"`` observation: the trivial policy of that view.

With ``observation="shots"`` the env offers, per pocket, the ghost-ball shot on the aim's
reference ball as actions (:mod:`pool_env.game.shot_features`), easiest first. Copying row
0's aim and speed (cue tip at the centre) is what a policy gets for reading its observation
and learning nothing else, so a learner on that observation must beat it. On the roll table
it pots about as often as the ghost-ball agent; on the spin table the geometry misses (the
cue ball slides before it rolls, and throw turns the object ball: the speed and aim are the
roll model's), which is what a learner there must learn.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from agents.baselines.base import BaselineAgent, env_spec
from pool_env import obs_layout
from pool_env.game.shot_features import SHOT_FEATURES

_VALID, _AIM, _SPEED = (SHOT_FEATURES.index(name) for name in ("valid", "aim", "speed"))


class ShotRowAgent(BaselineAgent):
    """Row 0 of the ``"shots"`` features as the action; a full hit, hardest, without one.

    Args:
        env: The environment (a ``PoolEnv`` made with ``observation="shots"``, wrapped or not).

    Raises:
        ValueError: If the env's observation has no shot features.
    """

    def __init__(self, env: Any) -> None:
        config = env_spec(env).config
        if config.observation != "shots":
            raise ValueError("the first-row agent reads observation='shots': make the env with it")
        self.shots = obs_layout(config)["shots"]
        self.width = int(config.action_size)

    def act(self, observations: NDArray[np.floating]) -> NDArray[np.float32]:
        """Row 0's ``(aim, speed)`` per observation, the other components 0 (centre ball)."""
        n = observations.shape[0]
        first = np.asarray(observations)[:, self.shots].reshape(n, -1, len(SHOT_FEATURES))[:, 0]
        out = np.zeros((n, self.width), dtype=np.float32)
        valid = first[:, _VALID] > 0.5
        out[:, 0] = np.where(valid, first[:, _AIM], 0.0)
        out[:, 1] = np.where(valid, first[:, _SPEED], 1.0)
        return out
