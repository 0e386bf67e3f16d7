"""Observation wrappers that add what a player looks at: pockets, cut angles, distances.

``PocketFeatures`` appends the pockets as seen along the aim line; ``GhostBallFeatures``
appends, per pocket, the ghost-ball shot on the env's reference ball (the aim action that
plays it, its cut, distances, approach, whether the paths are clear, the speed action the
geometric model asks for), batched over observations (:func:`ghost_feature_batch`); its SB3
``VecEnv`` counterpart for training is :class:`agents.training.vec_features.GhostFeaturesVecEnv`.
This module needs no stable-baselines3: a saved model's evaluation applies these wrappers.
With them PPO and SAC learn to aim on OneBallRoll-v1 (results/agents.md); without, PPO plays the
best constant.

PocketFeatures: the raw observation plus the pockets as seen along the aim line.

The environment's default action aims relative to the line from the cue ball to the nearest
object ball (its ``cut`` offset). The raw observation gives absolute coordinates, so a
policy must learn rotations and ``atan2`` before it can relate the line to a pocket. This
wrapper appends, in the frame of that line, where each pocket lies from the object ball
(``cos``, ``sin`` of its bearing and its distance), sorted from the straightest pocket to
the thinnest cut, plus the cue-to-ball distance: what a player looks at. Sorting makes
"cut towards the first pocket" a smooth function of the observation, where a fixed pocket
order asks the network to learn an argmax. It computes nothing the observation does not
determine, and it does not solve the shot: which pocket, how thin and how hard are still
learned. Measured on OneBallRoll-v1 (results/agents.md): PPO with it ends on the same plateau
as without (the constant full hit), at 300k and at 1M steps.
"""

from __future__ import annotations

import math

import gymnasium as gym
import numpy as np
from numpy.typing import NDArray

from agents.baselines.base import EnvSpec, env_spec
from pool_env import nearest_object_ball
from pool_env.game.codec import decode_observations
from pool_env.game.shot_features import SHOT_FEATURES, shot_feature_batch, table_mouths


class PocketFeatures(gym.ObservationWrapper):
    """Append ``1 + 3 K`` features (``K`` pockets) to a ``PoolEnv`` observation.

    Features, all in ``[-1, 1]``: the cue-to-reference-ball distance over the table
    diagonal, then per pocket ``cos`` and ``sin`` of the bearing from the reference ball to
    the pocket, measured from the cue-to-ball direction, and that distance over the diagonal,
    pockets sorted by decreasing ``cos`` (straightest first).
    The reference ball is the env's aim reference, the nearest object ball; with none left
    the features are 0.

    Args:
        env: A (wrapped) ``PoolEnv``.
    """

    def __init__(self, env: gym.Env) -> None:
        super().__init__(env)
        table = env.unwrapped.config.table
        self._pockets = np.asarray(table.pockets[:, :2], dtype=np.float64)
        self._diagonal = math.hypot(table.length, table.width)
        raw = env.observation_space.shape[0]
        n = raw + 1 + 3 * self._pockets.shape[0]
        self.observation_space = gym.spaces.Box(-1.0, 1.0, (n,), np.float32)

    def observation(self, observation: NDArray[np.float32]) -> NDArray[np.float32]:
        """The raw observation followed by the pocket features."""
        env = self.env.unwrapped
        return np.concatenate([observation, self.features(env.positions, env.on_table)])

    def features(self, positions: NDArray[np.float64], on_table: NDArray[np.bool_]) -> NDArray:
        """The appended features for one layout (cue first)."""
        out = np.zeros(1 + 3 * self._pockets.shape[0], dtype=np.float32)
        j, dist, base = nearest_object_ball(positions, on_table, 0)
        if j < 0:
            return out
        out[0] = dist / self._diagonal
        w = self._pockets - positions[j]
        bearing = np.arctan2(w[:, 1], w[:, 0]) - base
        order = np.argsort(-np.cos(bearing), kind="stable")  # straightest pocket first
        out[1::3] = np.cos(bearing[order])
        out[2::3] = np.sin(bearing[order])
        out[3::3] = np.hypot(w[order, 0], w[order, 1]) / self._diagonal
        return np.clip(out, -1.0, 1.0)


class GhostShotFeatures:
    """The ghost-ball features of one layout: one row per direct shot on the reference ball.

    The reference ball is the one the action aims relative to (the nearest object ball;
    :func:`pool_env.nearest_object_ball`). For each direct shot of
    :func:`pool_env.game.geometry.ghost_shots` on it (a cut under 85 degrees, the mouth open to
    the ball's path, the ghost-ball point on the table) that the aim mode can play, easiest
    first (largest aim tolerance), :data:`PER_SHOT` features:

    ``valid`` (1), ``clear`` (1 when no ball is in either path), the aim action that sends
    the cue ball at the ghost-ball point (action[0]; in the default ``cut`` aim it is
    ``-sin(cut)``, the cut offset in ball diameters), ``cos(cut)``, the cue-to-ghost-point
    distance and the ghost-point-to-pocket distance over the table diagonal, the cosine of
    the approach to the mouth, and the speed action (action[1]) of the speed the geometric
    model asks for (:func:`pool_env.game.geometry.cue_speeds` at the ghost-ball agent's arrival
    speed; clipped to ``[-1, 1]``). Pockets without a playable shot give zero rows at the
    end. Everything comes from the layout and the table's public geometry; no simulation.

    Args:
        spec: The environment's table, aim mode and ranges (:func:`agents.baselines.base.env_spec`).
    """

    #: Features per shot (see above).
    PER_SHOT = len(SHOT_FEATURES)

    def __init__(self, spec: EnvSpec) -> None:
        self.spec = spec
        self.mouths = table_mouths(spec.table)
        self._diagonal = math.hypot(spec.table.length, spec.table.width)

    @property
    def size(self) -> int:
        """Number of features (``PER_SHOT`` per pocket)."""
        return self.PER_SHOT * self.mouths.n

    def __call__(self, positions: NDArray[np.float64], on_table: NDArray[np.bool_]) -> NDArray:
        """The ``(size,)`` float32 features of one layout (``(N, 2)`` centres, cue first)."""
        return ghost_feature_batch(self.spec, positions[None], on_table[None])[0]

    def of_observations(self, observations: NDArray[np.floating]) -> NDArray[np.float32]:
        """``(B, size)`` features of ``(B, D)`` observations, each decoded to its layout.

        Decoding the observation (float32, ~0.1 um) rather than reading the env's state
        makes the features a function of the observation alone: the same for a training
        step, a terminal observation and an evaluation env. Touching balls are not pushed
        apart as :func:`agents.baselines.base.decode_observation` does for the simulator: the
        geometry here does not need a valid layout.
        """
        balls = np.asarray(observations)[:, : 3 * self.spec.n_balls]
        positions, on_table = decode_observations(self.spec.table, balls)
        return ghost_feature_batch(self.spec, positions, on_table)


class GhostBallFeatures(gym.ObservationWrapper):
    """A ``PoolEnv`` observation followed by its :class:`GhostShotFeatures`.

    Args:
        env: A (wrapped) ``PoolEnv``.
    """

    #: Features per shot (see :class:`GhostShotFeatures`).
    PER_SHOT = GhostShotFeatures.PER_SHOT

    def __init__(self, env: gym.Env) -> None:
        super().__init__(env)
        self.ghost_features = GhostShotFeatures(env_spec(env))
        n = env.observation_space.shape[0] + self.ghost_features.size
        self.observation_space = gym.spaces.Box(-1.0, 1.0, (n,), np.float32)

    def observation(self, observation: NDArray[np.float32]) -> NDArray[np.float32]:
        """The raw observation followed by the ghost-ball features."""
        extra = self.ghost_features.of_observations(observation[None])[0]
        return np.concatenate([observation, extra])


def ghost_feature_batch(
    spec: EnvSpec,
    positions: NDArray[np.float64],
    on_table: NDArray[np.bool_],
) -> NDArray[np.float32]:
    """:class:`GhostShotFeatures` of ``B`` layouts at once, ``(B, K * PER_SHOT)`` float32.

    The env's ``"shots"`` observation features
    (:func:`pool_env.game.shot_features.shot_feature_batch`), on the nearest ball: compiled
    calls, each once for the batch, which is what lets the native vector env train on them.

    Args:
        spec: The environment's table and config (aim mode and ranges).
        positions: ``(B, N, 2)`` ball centres, cue (ball 0) first.
        on_table: ``(B, N)`` which balls are on the table.
    """
    config = spec.config
    return shot_feature_batch(
        spec.table, config.params, config.aim_range, config.speed_range, positions,
        on_table, on_table,
    )  # fmt: skip
