"""GhostBallAgent: the classic aiming heuristic, checked shot by shot with the simulator.

For every object ball and pocket the agent aims the object ball at a few points of the
pocket's capture circle, puts the cue ball where it must be at contact (the *ghost ball*,
``2R`` behind the object ball on that line), checks that both paths are clear, and picks a
speed from the known rolling deceleration so that the object ball arrives with a margin.
Each candidate is then played on :func:`pool_env.shoot` (a shot costs ~10-20 us): the ones
that pot without scratching are replayed with small aim and speed errors, and the most
forgiving one wins (ties: the softer and straighter shot). When no candidate pots (a rack, a
blocked ball), a random search over actions, also simulated, picks the best shot it finds.

Simulating candidates is legitimate for a planner: it is what a player does in their head,
and the environment's state is fully observed. With execution noise on, the agent aims at
the noiseless optimum, but prefers shots that survive errors of the noise's size.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from agents.aiming import decode, shot_to_action
from agents.base import BaselineAgent, EnvSpec, LayoutSource, env_spec
from pool_env import shoot

#: Speeds (m/s) at which the object ball should reach the capture circle: softer shots keep
#: the cue ball under control, harder ones forgive more of the deceleration model.
ARRIVAL_SPEEDS = (0.3, 0.7, 1.2, 2.0)
#: Aim points across the capture circle, as fractions of its radius sideways from the centre.
AIM_OFFSETS = (0.0, -0.4, 0.4)
#: Cuts beyond this need more speed than a cue ball keeps control of (and thin contact).
MAX_CUT = math.radians(85.0)


@dataclass
class Shot:
    """A candidate shot and what the simulator says it does.

    Attributes:
        action: The float32 action that plays it.
        angle: Executed direction (radians from +x).
        speed: Executed cue speed (m/s).
        difficulty: Heuristic cost for ties (longer and thinner shots cost more).
        value: Outcome of the nominal shot: clean pots, minus scratches.
        robustness: How many perturbed replays also pot cleanly.
    """

    action: NDArray[np.float32]
    angle: float
    speed: float
    difficulty: float
    value: float = 0.0
    robustness: int = 0


class GhostBallAgent(BaselineAgent):
    """Ghost-ball aiming, verified with the simulator; SB3's ``predict`` signature.

    Args:
        env: The environment it plays (``gym.Env``, wrapped or not, or an SB3 ``VecEnv`` of
            ``PoolEnv``): the table and action decoding are read from it, and its exact layout
            when it matches the observation.
        seed: Seed for the fallback random search.
        n_search: Random actions tried when no ghost-ball shot pots.
        n_robust: Best ghost-ball shots replayed with errors to rank them.
    """

    def __init__(
        self, env: Any, seed: int | None = 0, n_search: int = 128, n_robust: int = 12
    ) -> None:
        self.spec: EnvSpec = env_spec(env)
        self.source = LayoutSource(env, self.spec.table)
        self.rng = np.random.default_rng(seed)
        self.n_search = n_search
        self.n_robust = n_robust
        self.last_plan: dict[str, Any] = {}

    def act(self, observations: NDArray[np.floating]) -> NDArray[np.float32]:
        """The planned action for each observation's layout."""
        return np.stack([self.plan(pos, on) for pos, on in self.source.layouts(observations)])

    # -- planning -------------------------------------------------------------------------

    def plan(self, positions: NDArray[np.float64], on_table: NDArray[np.bool_]) -> NDArray:
        """The action for one layout (``(N, 2)`` centres, cue first; ``(N,)`` on the table)."""
        rows = on_table.nonzero()[0]
        sub = np.ascontiguousarray(positions[rows])
        shots = self._ghost_shots(positions, on_table, sub)
        for shot in shots:
            shot.value = self._outcome(sub, shot.angle, shot.speed)
        good = sorted((s for s in shots if s.value >= 1.0), key=lambda s: (-s.value, s.difficulty))
        if good:
            for shot in good[: self.n_robust]:
                shot.robustness = self._robustness(sub, shot)
            best = max(good[: self.n_robust], key=lambda s: (s.value, s.robustness, -s.difficulty))
            self.last_plan = {"kind": "ghost", "candidates": len(shots), "shot": best}
            return best.action
        best = self._search(positions, on_table, sub)
        self.last_plan = {"kind": "search", "candidates": len(shots), "shot": best}
        return best.action

    def _ghost_shots(
        self, positions: NDArray[np.float64], on_table: NDArray[np.bool_], sub: NDArray
    ) -> list[Shot]:
        """Every ghost-ball shot (ball, pocket, aim point, speed) with clear paths."""
        table = self.spec.table
        r, decel, e = table.ball_radius, table.deceleration, table.e_ball
        cue = sub[0]
        planned: list[tuple[float, float, float]] = []  # (angle, speed, difficulty)
        for b in range(1, sub.shape[0]):
            ball = sub[b]
            others_ob = np.delete(sub, [0, b], axis=0)  # what the object ball must miss
            for px, py, pr in table.pockets.tolist():
                to_pocket = np.array([px, py]) - ball
                side = np.array([-to_pocket[1], to_pocket[0]]) / np.hypot(*to_pocket)
                for frac in AIM_OFFSETS:
                    target = np.array([px, py]) + frac * pr * side
                    u = target - ball
                    d_ob = float(np.hypot(*u))
                    u /= d_ob
                    ghost = ball - 2.0 * r * u
                    v = ghost - cue
                    d_cue = float(np.hypot(*v))
                    d = u if d_cue < 1e-12 else v / d_cue
                    cos_cut = float(d @ u)
                    if cos_cut < math.cos(MAX_CUT):
                        continue
                    if not (_clear(cue, ghost, others_ob, 2.0 * r)):
                        continue
                    if not _clear(ball, target, others_ob, 2.0 * r):
                        continue
                    angle = math.atan2(d[1], d[0])
                    travel = max(d_ob - pr, 0.0)
                    difficulty = (d_cue + d_ob) / cos_cut
                    for v_arrive in ARRIVAL_SPEEDS:
                        v_ball = math.sqrt(v_arrive**2 + 2.0 * decel * travel)
                        v_contact = v_ball / ((1.0 + e) / 2.0 * cos_cut)
                        speed = math.sqrt(v_contact**2 + 2.0 * decel * d_cue)
                        planned.append((angle, speed, difficulty + 0.01 * v_arrive))
        return self._to_shots(planned, positions, on_table)

    def _to_shots(
        self,
        planned: list[tuple[float, float, float]],
        positions: NDArray[np.float64],
        on_table: NDArray[np.bool_],
    ) -> list[Shot]:
        """Representable shots, with the direction and speed the env will really execute."""
        kept, actions = [], []
        for angle, speed, difficulty in planned:
            action = shot_to_action(angle, speed, positions, on_table, self.spec)
            if action is not None:
                kept.append(difficulty)
                actions.append(action)
        if not actions:
            return []
        acts = np.stack(actions)
        angles, speeds = decode(acts, positions, on_table, self.spec)
        return [
            Shot(acts[k], float(angles[k]), float(speeds[k]), kept[k]) for k in range(len(kept))
        ]

    def _outcome(self, sub: NDArray, angle: float, speed: float) -> float:
        """Clean pots of the shot (0 if it scratches, -1 if it scratches without a pot)."""
        pocketed = shoot(self.spec.table, sub, angle, speed).pocketed
        pots = int(np.count_nonzero(pocketed[1:] >= 0))
        if pocketed[0] >= 0:
            return -1.0 if pots == 0 else 0.0
        return float(pots)

    def _robustness(self, sub: NDArray, shot: Shot) -> int:
        """How many of a few perturbed replays (aim, speed) still pot cleanly."""
        noise = self.spec.noise
        d_angle = max(noise[0], 5e-4) if noise else 1.5e-3
        speeds = (
            (shot.speed - noise[1], shot.speed + noise[1])
            if noise and noise[1] > 0.0
            else (0.9 * shot.speed, 1.1 * shot.speed)
        )
        trials = [(shot.angle + k * d_angle, shot.speed) for k in (-2, -1, 1, 2)]
        trials += [(shot.angle, max(s, 0.0)) for s in speeds]
        return sum(self._outcome(sub, a, s) >= 1.0 for a, s in trials)

    def _search(
        self, positions: NDArray[np.float64], on_table: NDArray[np.bool_], sub: NDArray
    ) -> Shot:
        """The best of ``n_search`` random actions: pots first, then no scratch, then soft."""
        acts = self.rng.uniform(-1.0, 1.0, size=(self.n_search, 2)).astype(np.float32)
        angles, speeds = decode(acts, positions, on_table, self.spec)
        best, best_key = None, None
        for k in range(self.n_search):
            result = shoot(self.spec.table, sub, float(angles[k]), float(speeds[k]))
            pocketed = result.pocketed
            pots = int(np.count_nonzero(pocketed[1:] >= 0))
            scratch = bool(pocketed[0] >= 0)
            contact = result.first_contact is not None
            key = (0 if scratch else pots, pots, not scratch, contact, -float(speeds[k]))
            if best_key is None or key > best_key:
                best_key = key
                best = Shot(acts[k], float(angles[k]), float(speeds[k]), 0.0, float(key[0]))
        assert best is not None
        return best


def _clear(start: NDArray, end: NDArray, balls: NDArray, reach: float) -> bool:
    """Whether a ball moving from ``start`` to ``end`` stays ``reach`` from every ball."""
    if balls.shape[0] == 0:
        return True
    seg = end - start
    length2 = float(seg @ seg)
    rel = balls - start
    t = np.clip(rel @ seg / length2, 0.0, 1.0) if length2 > 0.0 else np.zeros(len(balls))
    closest = start + t[:, None] * seg
    gap = np.hypot(*(balls - closest).T)
    return bool(np.all(gap > reach))
