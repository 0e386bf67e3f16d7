"""The ``"shots"`` observation: per pocket, the ghost-ball shot on the aim's reference ball.

What a player reads off a layout before choosing a shot, in the action's own units. The
environment's default observation is ball positions; a learner must then learn rotations
and ``atan2`` before it can relate a ball to a pocket, and on the one-ball tasks PPO on the
env's own action plays near the best constant action. With ``observation="shots"`` every
front appends, for each pocket, the direct (ghost-ball) shot of the *reference ball* (the
ball that cut and relative aim refer to: the nearest object ball, under rules the nearest
ball the viewer may hit first) into it, easiest first (largest aim tolerance), as
:data:`SHOT_FEATURES`:

* ``valid``: 1 for a shot the geometry allows (a cut under 85 degrees, the mouth open to the
  ball's path, the ghost-ball point on the cloth) and the aim mode can play; a pocket
  without one gives a row of zeros at the end.
* ``clear``: 1 when no other ball is within ``2R`` of either path.
* ``aim``: the aim action (``action[0]``) that sends the cue ball at the ghost-ball point; in
  the default cut aim, ``-sin(cut)``, the cut offset in ball diameters.
* ``cos_cut``: the cut's cosine.
* ``cue_distance``, ``ball_distance``: cue centre to the ghost-ball point, and the object
  ball's centre to its drop, over the table's diagonal.
* ``approach``: the cosine of the ball's path against the mouth's normal.
* ``speed``: the speed action (``action[1]``) at which the roll model's ball arrives at
  :data:`ARRIVAL_SPEED` (:func:`pool_env.game.geometry.cue_speeds`), clipped to ``[-1, 1]``.

It is geometry, not simulation: the spin table's throw, squirt and swerve, the speed's
effect on the cue ball's path and position play are still the learner's. The same function
builds the agents' ``ghost_features`` wrapper (:mod:`agents.learned.features`), which computes
these features from a decoded observation instead of the state.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
from numpy.typing import NDArray

from pool_env.game import geometry as geo
from pool_env.game.kernels import params as kp
from pool_env.game.kernels.encode import encode_shots as kernel_encode_shots
from pool_env.game.kernels.encode import reference_balls
from pool_env.game.pockets import PocketMouths, pocket_mouths
from pool_env.sim.table import Table

__all__ = [
    "ARRIVAL_SPEED",
    "OBSERVATIONS",
    "SHOT_FEATURES",
    "shot_feature_batch",
    "shot_features_width",
    "table_mouths",
]

#: The observation kinds (``observation=``): the balls (and the rules' state) only, or
#: with the ghost-ball shots appended.
OBSERVATIONS: tuple[str, ...] = ("balls", "shots")

#: The features of one pocket's row, in order (the module docstring says what each is).
SHOT_FEATURES: tuple[str, ...] = (
    "valid", "clear", "aim", "cos_cut", "cue_distance", "ball_distance", "approach", "speed",
)  # fmt: skip

#: Speed (m/s) at which the ``speed`` feature's object ball drops: enough to forgive a small
#: error of the deceleration model, soft enough that the jaws take it and the cue ball stays
#: out of the pockets (the ghost-ball agent's, ``agents.baselines.ghost_ball``).
ARRIVAL_SPEED = 0.3


@lru_cache(maxsize=32)
def table_mouths(table: Table) -> PocketMouths:
    """The table's pockets as mouths, built once per table (tables hash by identity)."""
    return pocket_mouths(table)


def shot_features_width(table: Table) -> int:
    """Entries the ``"shots"`` observation appends: ``len(SHOT_FEATURES)`` per pocket."""
    return len(SHOT_FEATURES) * table_mouths(table).n


def shot_feature_batch(
    table: Table,
    params: NDArray[np.float64],
    aim_range: tuple[float, float],
    speed_range: tuple[float, float],
    positions: NDArray[np.float64],
    on_table: NDArray[np.bool_],
    refer: NDArray[np.bool_],
) -> NDArray[np.float32]:
    """The ``(B, K * 8)`` float32 shot features of ``B`` layouts (``K`` pockets).

    Compiled calls, each once for the batch: the reference ball of each layout, the
    ghost-ball shots on it (:func:`pool_env.game.geometry.ghost_shots`, offset 0), their
    speeds and their actions in the config's aim mode and ranges; rows ordered by
    tolerance, the invalid ones zeroed and last.

    Args:
        table: The table.
        params: The config's kernel numbers (aim mode, ball radius).
        aim_range: What ``action[0] = -1`` and ``+1`` map to.
        speed_range: Cue speeds (m/s) of ``action[1] = -1`` and ``+1``.
        positions: ``(B, N, 2)`` ball centres, cue (ball 0) first.
        on_table: ``(B, N)`` the balls on the table (every one of them may block a path).
        refer: ``(B, N)`` the balls the aim may refer to (on the table; under rules the
            viewer's legal first balls).
    """
    mouths = table_mouths(table)
    pos = np.ascontiguousarray(positions, dtype=np.float64)
    on = np.ascontiguousarray(on_table, dtype=np.bool_)
    ref = np.ascontiguousarray(refer, dtype=np.bool_)
    nb = pos.shape[0]
    target = reference_balls(pos, ref)
    shots = geo.ghost_shots(table, mouths, pos, on, target[:, None])[:, 0]
    speed = geo.cue_speeds(table, shots, ARRIVAL_SPEED)
    actions, playable = kernel_encode_shots(
        int(params[kp.AIM_MODE]), *aim_range, *speed_range, float(params[kp.RADIUS]), 0.0,
        pos, ref, shots[..., geo.ANGLE], speed, np.zeros((*speed.shape, 2)),
    )  # fmt: skip
    valid = (shots[..., geo.VALID] > 0.0) & playable
    action = actions.astype(np.float32).astype(np.float64)  # the env's action dtype
    diagonal = math.hypot(table.length, table.width)
    per_shot = np.stack(
        [
            np.ones(valid.shape),
            shots[..., geo.CLEAR_PATH],
            action[..., 0],
            shots[..., geo.COS_CUT],
            shots[..., geo.CUE_DIST] / diagonal,
            (shots[..., geo.BALL_DIST] + 2.0 * table.ball_radius) / diagonal,
            shots[..., geo.APPROACH],
            action[..., 1],
        ],
        axis=-1,
    )  # (B, K, len(SHOT_FEATURES))
    order = np.argsort(np.where(valid, -shots[..., geo.TOLERANCE], np.inf), axis=1, kind="stable")
    per_shot = np.where(valid[..., None], per_shot, 0.0)
    out = np.take_along_axis(per_shot, order[..., None], axis=1)
    return np.clip(out, -1.0, 1.0).reshape(nb, -1).astype(np.float32)
