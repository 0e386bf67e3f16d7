"""Observation wrappers that add what a player looks at: pockets, cut angles, distances.

``PocketFeatures`` appends the pockets as seen along the aim line; ``GhostBallFeatures``
appends, per pocket, the ghost-ball shot on the env's reference ball (the aim action that
plays it, its cut, distances, approach, whether the paths are clear, the speed action the
geometric model asks for), batched over observations (:func:`ghost_feature_batch`); its SB3
``VecEnv`` counterpart for training is :class:`agents.training.vec_features.GhostFeaturesVecEnv`.
This module needs no stable-baselines3: a saved model's evaluation applies these wrappers.
With them PPO and SAC learn to aim on OneBall-v0 (results/agents.md); without, PPO plays the
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
learned. Measured on OneBall-v0 (results/agents.md): PPO with it ends on the same plateau
as without (the constant full hit), at 300k and at 1M steps.
"""

from __future__ import annotations

import math

import gymnasium as gym
import numpy as np
from numpy.typing import NDArray

from agents.baselines.base import EnvSpec, env_spec
from agents.baselines.geometry import MAX_CUT, MIN_APPROACH_COS, PocketMouths, pocket_mouths
from agents.baselines.ghost_ball import ARRIVAL_SPEED
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


class GhostShotFeatures:
    """The ghost-ball features of one layout: one row per direct shot on the reference ball.

    The reference ball is the one the action aims relative to (the nearest object ball;
    :func:`pool_env.nearest_object_ball`). For each direct shot of
    :func:`agents.baselines.geometry.ghost_shots` on it (a cut under 85 degrees, the mouth open to
    the ball's path, the ghost-ball point on the table) that the aim mode can play, easiest
    first (largest aim tolerance), :data:`PER_SHOT` features:

    ``valid`` (1), ``clear`` (1 when no ball is in either path), the aim action that sends
    the cue ball at the ghost-ball point (action[0]; in the default ``cut`` aim it is
    ``-sin(cut)``, the cut offset in ball diameters), ``cos(cut)``, the cue-to-ghost-point
    distance and the ghost-point-to-pocket distance over the table diagonal, the cosine of
    the approach to the mouth, and the speed action (action[1]) of the speed the geometric
    model asks for (:func:`agents.baselines.geometry.cue_speed` at the ghost-ball agent's arrival
    speed; clipped to ``[-1, 1]``). Pockets without a playable shot give zero rows at the
    end. Everything comes from the layout and the table's public geometry; no simulation.

    Args:
        spec: The environment's table, aim mode and ranges (:func:`agents.baselines.base.env_spec`).
    """

    #: Features per shot (see above).
    PER_SHOT = 8

    def __init__(self, spec: EnvSpec) -> None:
        self.spec = spec
        self.mouths = pocket_mouths(spec.table)
        self._diagonal = math.hypot(spec.table.length, spec.table.width)

    @property
    def size(self) -> int:
        """Number of features (``PER_SHOT`` per pocket)."""
        return self.PER_SHOT * self.mouths.n

    def __call__(self, positions: NDArray[np.float64], on_table: NDArray[np.bool_]) -> NDArray:
        """The ``(size,)`` float32 features of one layout (``(N, 2)`` centres, cue first)."""
        return ghost_feature_batch(self.spec, self.mouths, positions[None], on_table[None])[0]

    def of_observations(self, observations: NDArray[np.floating]) -> NDArray[np.float32]:
        """``(B, size)`` features of ``(B, D)`` observations, each decoded to its layout.

        Decoding the observation (float32, ~0.1 um) rather than reading the env's state
        makes the features a function of the observation alone: the same for a training
        step, a terminal observation and an evaluation env. Touching balls are not pushed
        apart as :func:`agents.baselines.base.decode_observation` does for the simulator: the
        geometry here does not need a valid layout.
        """
        table = self.spec.table
        per_ball = np.asarray(observations, dtype=np.float64).reshape(len(observations), -1, 3)
        r = table.ball_radius
        positions = np.empty(per_ball.shape[:2] + (2,))
        positions[..., 0] = np.clip(
            (per_ball[..., 0] + 1.0) * table.length / 2.0, r, table.length - r
        )
        positions[..., 1] = np.clip(
            (per_ball[..., 1] + 1.0) * table.width / 2.0, r, table.width - r
        )
        return ghost_feature_batch(self.spec, self.mouths, positions, per_ball[..., 2] > 0.5)


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
    mouths: PocketMouths,
    positions: NDArray[np.float64],
    on_table: NDArray[np.bool_],
) -> NDArray[np.float32]:
    """:class:`GhostShotFeatures` of ``B`` layouts at once, ``(B, K * PER_SHOT)`` float32.

    The same shots as :func:`agents.baselines.geometry.ghost_shots` on each layout's nearest object
    ball (offset 0), the same tolerance order, speed (:func:`agents.baselines.geometry.cue_speed`)
    and action (:func:`agents.baselines.aiming.shot_to_action`), computed for every layout and
    pocket in array operations: about 40 times faster than a loop over the layouts, which
    is what lets the native vector env train on them. ``tests/test_features.py`` checks it
    against those functions on random layouts of both pocket models.

    Args:
        spec: The environment's table, aim mode and ranges.
        mouths: The table's pockets (:func:`agents.baselines.geometry.pocket_mouths`).
        positions: ``(B, N, 2)`` ball centres, cue (ball 0) first.
        on_table: ``(B, N)`` which balls are on the table.
    """
    table = spec.table
    r = table.ball_radius
    pos = np.asarray(positions, dtype=np.float64)
    on = np.asarray(on_table, dtype=bool)
    nb = on.shape[0]
    rows = np.arange(nb)
    cue = pos[:, 0]
    # The reference ball: the nearest object ball on the table, ties to the lower index.
    rel = pos - cue[:, None]
    d2 = np.where(on, rel[..., 0] ** 2 + rel[..., 1] ** 2, np.inf)
    d2[:, 0] = np.inf
    j = np.argmin(d2, axis=1)
    has_ball = np.isfinite(d2[rows, j])
    ball = pos[rows, j]  # (B, 2)
    ref = ball - cue
    ref_dist = np.hypot(ref[:, 0], ref[:, 1])
    base = np.arctan2(ref[:, 1], ref[:, 0])

    to_target = mouths.targets[None] - ball[:, None]  # (B, K, 2)
    d_ball = np.hypot(to_target[..., 0], to_target[..., 1])
    u = to_target / d_ball[..., None]
    has_normal = np.any(mouths.inward != 0.0, axis=1)  # (K,)
    cos_a = np.where(has_normal, np.einsum("bkc,kc->bk", u, mouths.inward), 1.0)
    half = np.where(
        cos_a < MIN_APPROACH_COS,
        0.0,
        np.maximum(mouths.widths / 2.0 * cos_a - mouths.clearance, 0.0),
    )
    ghost = ball[:, None] - 2.0 * r * u
    lo, hi = r - 1e-12, np.array([table.length - r, table.width - r]) + 1e-12
    on_cloth = np.all((ghost >= lo) & (ghost <= hi), axis=-1)
    v = ghost - cue[:, None]
    d_cue = np.hypot(v[..., 0], v[..., 1])
    tiny = d_cue < 1e-12
    d = np.where(tiny[..., None], u, v / np.where(tiny, 1.0, d_cue)[..., None])
    cos_cut = np.clip(np.sum(d * u, axis=-1), -1.0, 1.0)
    cut = np.arctan2(d[..., 0] * u[..., 1] - d[..., 1] * u[..., 0], cos_cut)
    travel = _travel(mouths, ball, u)
    valid = (
        has_ball[:, None]
        & (half > 0.0)
        & on_cloth
        & (cos_cut >= math.cos(MAX_CUT))
        & np.isfinite(travel)
    )
    # Clear paths: cue to ghost point and ball to target, 2R from every other ball.
    others = on.copy()
    others[:, 0] = False
    others[rows, j] = False
    reach = 2.0 * r
    clear = _path_clear(cue[:, None], ghost, pos, others, reach) & _path_clear(
        ball[:, None], mouths.targets[None], pos, others, reach
    )
    tolerance = 2.0 * r * cos_cut * half / (np.maximum(d_cue, 2.0 * r) * d_ball)
    # The speed of cue_speed and the action of shot_to_action.
    a, e = table.deceleration, table.e_ball
    v_ball = np.sqrt(ARRIVAL_SPEED**2 + 2.0 * a * np.where(valid, travel, 0.0))
    v_contact = v_ball / ((1.0 + e) / 2.0 * np.cos(cut))
    speed = np.sqrt(v_contact**2 + 2.0 * a * d_cue)
    angle = np.arctan2(d[..., 1], d[..., 0])
    param, representable = _aim_parameter(spec, angle, base[:, None], ref_dist[:, None])
    valid &= representable
    aim_lo, aim_hi = spec.aim_range
    speed_lo, speed_hi = spec.speed_range
    a0 = 2.0 * (param - aim_lo) / (aim_hi - aim_lo) - 1.0
    a1 = 2.0 * (np.clip(speed, speed_lo, speed_hi) - speed_lo) / (speed_hi - speed_lo) - 1.0
    if speed_hi <= speed_lo:
        a1 = np.zeros_like(a1)
    action = np.clip(np.stack([a0, a1], axis=-1).astype(np.float32), -1.0, 1.0)
    diagonal = math.hypot(table.length, table.width)
    per_shot = np.stack(
        [
            np.ones_like(cos_cut),
            clear.astype(np.float64),
            action[..., 0].astype(np.float64),
            cos_cut,
            d_cue / diagonal,
            (d_ball + 2.0 * r) / diagonal,
            np.where(has_normal, cos_a, 1.0),
            action[..., 1].astype(np.float64),
        ],
        axis=-1,
    )  # (B, K, PER_SHOT)
    order = np.argsort(np.where(valid, -tolerance, np.inf), axis=1, kind="stable")
    per_shot = np.where(valid[..., None], per_shot, 0.0)
    out = np.take_along_axis(per_shot, order[..., None], axis=1)
    return np.clip(out, -1.0, 1.0).reshape(nb, -1).astype(np.float32)


def _travel(mouths: PocketMouths, start: NDArray, u: NDArray) -> NDArray[np.float64]:
    """:meth:`PocketMouths.travel` for ``(B, 2)`` starts and ``(B, K, 2)`` directions."""
    if mouths.model == "jaws":
        normal = mouths.drop_normals[None]  # (1, K, 2)
        closing = -np.sum(u * normal, axis=-1)
        height = np.sum((start[:, None] - mouths.drop_points[None]) * normal, axis=-1)
        ok = (closing > 0.0) & (height >= 0.0)
        return np.where(ok, height / np.where(ok, closing, 1.0), np.inf)
    w = start[:, None] - mouths.capture[None, :, :2]
    b = np.sum(w * u, axis=-1)
    c = np.sum(w * w, axis=-1) - mouths.capture[None, :, 2] ** 2
    disc = b * b - c
    root = np.sqrt(np.maximum(disc, 0.0))
    miss = (disc < 0.0) | (-b + root < 0.0)
    return np.where(miss, np.inf, np.maximum(-b - root, 0.0))


def _path_clear(
    start: NDArray, end: NDArray, pos: NDArray, others: NDArray[np.bool_], reach: float
) -> NDArray[np.bool_]:
    """``agents.baselines.geometry.path_clear`` for ``(B, K, 2)`` segments, ``(B, N)`` balls."""
    start, end = np.broadcast_arrays(start, end)
    seg = end - start  # (B, K, 2)
    length2 = np.sum(seg * seg, axis=-1)
    rel = pos[:, None] - start[:, :, None]  # (B, K, N, 2)
    proj = np.einsum("bknc,bkc->bkn", rel, seg)
    safe = np.where(length2 > 0.0, length2, 1.0)[..., None]
    t = np.where(length2[..., None] > 0.0, np.clip(proj / safe, 0.0, 1.0), 0.0)
    closest = start[:, :, None] + t[..., None] * seg[:, :, None]
    gap = np.hypot(*np.moveaxis(pos[:, None] - closest, -1, 0))
    return np.all((gap > reach) | ~others[:, None], axis=-1)


def _aim_parameter(
    spec: EnvSpec, angle: NDArray, base: NDArray, dist: NDArray
) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
    """``agents.baselines.aiming.aim_parameter`` for arrays of directions: ``(param, ok)``."""
    lo, hi = spec.aim_range
    tol = 1e-9
    if spec.aim == "absolute":
        wrapped = np.remainder(angle + np.pi, 2.0 * np.pi) - np.pi
        param = np.full(angle.shape, np.nan)
        for k in (2.0, -2.0, 1.0, -1.0, 0.0):  # the first representative in range wins
            p = wrapped + 2.0 * np.pi * k
            param = np.where((p >= lo - tol) & (p <= hi + tol), p, param)
        return param, np.isfinite(param)
    delta = np.remainder(angle - base + np.pi, 2.0 * np.pi) - np.pi
    if spec.aim == "relative":
        param = delta
        ok = np.ones(delta.shape, bool)
    else:
        ok = np.abs(delta) <= np.pi / 2.0
        param = np.sin(delta) * dist / (2.0 * spec.table.ball_radius)
    ok &= (param >= lo - tol) & (param <= hi + tol)
    return param, ok
