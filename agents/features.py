"""Observation wrappers that add what a player looks at: pockets, cut angles, distances.

``PocketFeatures`` appends the pockets as seen along the aim line; ``GhostBallFeatures``
appends, per pocket, the ghost-ball shot on the env's reference ball (cut, distances,
approach, whether the paths are clear, the speed the geometric model asks for).

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
learned. Measured on OneBall-v0 (results/agents.md): PPO with it ends on the same plateau
as without (the constant full hit), at 300k and at 1M steps.
"""

from __future__ import annotations

import math

import gymnasium as gym
import numpy as np
from numpy.typing import NDArray

from agents.geometry import cue_speed, ghost_shots, pocket_mouths
from agents.ghost_ball import ARRIVAL_SPEED
from pool_env import nearest_object_ball


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
        table = env.unwrapped.table
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


class GhostBallFeatures(gym.ObservationWrapper):
    """Append the ghost-ball shot into each pocket on the env's reference ball.

    The reference ball is the one the action aims relative to (the nearest object ball;
    :func:`agents.aiming.nearest_object_ball`). For each direct shot of
    :func:`agents.geometry.ghost_shots` on it (a cut under 85 degrees, the mouth open to
    the ball's path, the ghost-ball point on the table), easiest first (largest aim
    tolerance), :data:`PER_SHOT` features:

    ``valid`` (1), ``clear`` (1 when no ball is in either path), ``sin(cut)`` (the cut
    offset in ball diameters: the ``cut`` aim's action before scaling), ``cos(cut)``, the
    cue-to-ghost-point distance and the ghost-point-to-pocket distance over the table
    diagonal, the cosine of the approach to the mouth, and the speed the geometric model
    asks for (:func:`agents.geometry.cue_speed` at the ghost-ball agent's arrival speed)
    on the env's speed action scale (clipped to ``[-1, 1]``). Pockets without a direct shot
    give zero rows at the end. Everything comes from the layout and the table's public
    geometry.

    Args:
        env: A (wrapped) ``PoolEnv``.
    """

    #: Features per shot (see above).
    PER_SHOT = 8

    def __init__(self, env: gym.Env) -> None:
        super().__init__(env)
        unwrapped = env.unwrapped
        self.table = unwrapped.table
        self.mouths = pocket_mouths(self.table)
        self.speed_range = tuple(float(v) for v in unwrapped.speed_range)
        self._diagonal = math.hypot(self.table.length, self.table.width)
        n = env.observation_space.shape[0] + self.PER_SHOT * self.mouths.n
        self.observation_space = gym.spaces.Box(-1.0, 1.0, (n,), np.float32)

    def observation(self, observation: NDArray[np.float32]) -> NDArray[np.float32]:
        """The raw observation followed by the ghost-ball features."""
        env = self.env.unwrapped
        return np.concatenate([observation, self.features(env.positions, env.on_table)])

    def features(self, positions: NDArray[np.float64], on_table: NDArray[np.bool_]) -> NDArray:
        """The appended features for one layout (cue first)."""
        out = np.zeros((self.mouths.n, self.PER_SHOT), dtype=np.float64)
        j = nearest_object_ball(positions, on_table, 0)[0]
        if j < 0:
            return out.ravel().astype(np.float32)
        shots = ghost_shots(self.table, self.mouths, positions, on_table, [j])
        lo, hi = self.speed_range
        r2 = 2.0 * self.table.ball_radius
        for row, shot in enumerate(sorted(shots, key=lambda s: -s.tolerance)):
            speed = cue_speed(self.table, shot, ARRIVAL_SPEED)
            out[row] = (
                1.0,
                float(shot.clear),
                math.sin(shot.cut),
                math.cos(shot.cut),
                shot.cue_distance / self._diagonal,
                (shot.ball_distance + r2) / self._diagonal,
                shot.approach_cos,
                2.0 * (speed - lo) / (hi - lo) - 1.0 if hi > lo else 0.0,
            )
        return np.clip(out, -1.0, 1.0).ravel().astype(np.float32)
