"""GhostBallAgent: the geometric ghost-ball heuristic of the pool literature; no simulation.

For every legal object ball and pocket it puts the cue ball on the ghost-ball point (``2R``
behind the object ball on the line to the pocket's mouth), keeps the shots whose paths are
clear of the other balls and whose pocket is open to the object ball's path, and plays the
easiest: the one that forgives the largest aim error (thin cuts, long distances and a mouth
seen at an angle all shrink it; :func:`agents.geometry.ghost_shots`) among those whose cue
ball, followed along the tangent line and off the cushions, stays out of the pockets
(:func:`agents.geometry.cue_ball_scratches`). The speed comes from
the distances, the rolling resistance and the ball-ball restitution
(:func:`agents.geometry.cue_speed`) so that the object ball drops at a gentle
:data:`ARRIVAL_SPEED`. When no direct shot exists (a rack, a ball in the way) it hits the
nearest legal ball full at the top speed: the break, or a shot that opens the table.

It never calls the simulator: everything it knows is the table's public geometry and
constants and the layout. Compare :class:`agents.search.SearchAgent`, which checks
candidate shots on the simulator (the oracle upper bound).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import NDArray

from agents.aiming import shot_to_action
from agents.base import BaselineAgent, EnvSpec, LayoutSource, env_spec
from agents.geometry import (
    GhostShot,
    LegalTargets,
    any_object_ball,
    cue_ball_scratches,
    cue_speed,
    ghost_shots,
    pocket_mouths,
)
from pool_env import nearest_object_ball

#: Speed (m/s) at which the object ball should reach the pocket: enough to forgive a small
#: error of the deceleration model, soft enough that the cue ball stays out of the pockets.
ARRIVAL_SPEED = 0.3


class GhostBallAgent(BaselineAgent):
    """Geometric ghost-ball aiming and speed from the distances; SB3's ``predict`` signature.

    Args:
        env: The environment it plays (``gym.Env``, wrapped or not, or an SB3 ``VecEnv`` of
            ``PoolEnv``): the table and the action decoding are read from it, and its exact
            layout when it matches the observation.
        arrival_speed: Speed (m/s) at which the object ball should drop.
        legal_targets: Which object balls may be aimed at (default: any on the table; a
            rules game passes its own).
    """

    def __init__(
        self,
        env: Any,
        arrival_speed: float = ARRIVAL_SPEED,
        legal_targets: LegalTargets = any_object_ball,
    ) -> None:
        if not (math.isfinite(arrival_speed) and arrival_speed >= 0.0):
            raise ValueError(f"arrival_speed must be a finite speed >= 0, got {arrival_speed!r}")
        self.spec: EnvSpec = env_spec(env)
        self.source = LayoutSource(env, self.spec.table)
        self.mouths = pocket_mouths(self.spec.table)
        self.arrival_speed = float(arrival_speed)
        self.legal_targets = legal_targets
        self.last_plan: dict[str, Any] = {}

    def act(self, observations: NDArray[np.floating]) -> NDArray[np.float32]:
        """The planned action for each observation's layout."""
        return np.stack([self.plan(pos, on) for pos, on in self.source.layouts(observations)])

    def plan(self, positions: NDArray[np.float64], on_table: NDArray[np.bool_]) -> NDArray:
        """The action for one layout (``(N, 2)`` centres, cue first; ``(N,)`` on the table)."""
        shot, speed, action = self.best_shot(positions, on_table)
        if action is not None:
            self.last_plan = {"kind": "ghost", "shot": shot, "speed": speed}
            return action
        self.last_plan = {"kind": "fallback", "shot": None, "speed": self.spec.speed_range[1]}
        return self._fallback(positions, on_table)

    def best_shot(
        self, positions: NDArray[np.float64], on_table: NDArray[np.bool_]
    ) -> tuple[GhostShot | None, float, NDArray[np.float32] | None]:
        """The most forgiving clear shot the action space can play: ``(shot, speed, action)``.

        A shot is skipped when it needs more than the top speed or when the aim mode cannot
        express its direction (``cut`` and ``relative`` aim relative to the nearest ball).
        ``(None, nan, None)`` when no shot is left.
        """
        table = self.spec.table
        top = self.spec.speed_range[1]
        targets = self.legal_targets(positions, on_table)
        shots = [
            s for s in ghost_shots(table, self.mouths, positions, on_table, targets) if s.clear
        ]
        playable = []
        for shot in sorted(shots, key=lambda s: -s.tolerance):
            speed = cue_speed(table, shot, self.arrival_speed)
            if speed > top:
                continue
            action = shot_to_action(shot.angle, speed, positions, on_table, self.spec)
            if action is not None:
                playable.append((shot, speed, action))
        # The easiest shot whose cue ball stays out of the pockets, else the easiest.
        for shot, speed, action in playable:
            played = max(speed, self.spec.speed_range[0])  # a softer shot is not available
            if not cue_ball_scratches(table, self.mouths, shot, played):
                return shot, speed, action
        return playable[0] if playable else (None, math.nan, None)

    def _fallback(self, positions: NDArray[np.float64], on_table: NDArray[np.bool_]) -> NDArray:
        """A full hit on the nearest legal ball at the top speed (the nearest ball if it fails)."""
        cue = positions[0]
        targets = self.legal_targets(positions, on_table)
        if targets:
            j = min(targets, key=lambda b: float(np.hypot(*(positions[b] - cue))))
        else:
            j = nearest_object_ball(positions, on_table, 0)[0]
        speed = self.spec.speed_range[1]
        if j >= 0:
            d = positions[j] - cue
            action = shot_to_action(math.atan2(d[1], d[0]), speed, positions, on_table, self.spec)
            if action is not None:
                return action
        # A legal ball that cut or relative aim cannot reach: a full hit on their reference
        # ball (the nearest), which action[0] = "aim parameter 0" is in both modes.
        aim_lo, aim_hi = self.spec.aim_range
        zero = (
            0.0
            if aim_hi == aim_lo
            else float(np.clip(-(aim_lo + aim_hi) / (aim_hi - aim_lo), -1, 1))
        )
        return np.array([zero, 1.0], dtype=np.float32)
