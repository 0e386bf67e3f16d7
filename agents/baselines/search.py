"""SearchAgent: ghost-ball candidate shots, checked shot by shot on the simulator.

The oracle upper bound among the baselines (it was called ``GhostBallAgent`` before the
geometric heuristic of :mod:`agents.baselines.ghost_ball` took that name). For every legal
object ball and pocket it aims at a few points across the pocket's mouth
(:func:`agents.baselines.geometry.ghost_shots`), keeps the shots whose paths are clear, and
takes a few speeds from the known rolling deceleration
(:func:`agents.baselines.geometry.cue_speed`) so that the object ball arrives with a margin.
Each candidate is then played on :func:`pool_env.shoot` (a shot costs ~10-20 us): the ones
that pot without scratching are replayed with small aim and speed errors, and the most
forgiving one wins (ties: the softer and straighter shot). When no candidate pots
(a rack, a blocked ball), a random search over actions, also simulated, picks the best shot
it finds.

On a spin env (the action ends with the cue tip) every candidate is also tried with the tips
of :data:`SEARCH_TIPS` (stun, follow, draw, a little side), aimed and paced by the
closed-form contact of :func:`agents.baselines.spin_play.plan_contact` (throw and squirt
allowed for); the replays perturb the tip too, by the env's tip noise.

Simulating candidates is what a planner with a perfect model does; the environment's state
is fully observed. With execution noise on, the agent aims at the noiseless optimum, but
prefers shots that survive errors of the noise's size.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from agents.baselines.aiming import decode, shot_to_action
from agents.baselines.base import BaselineAgent, EnvSpec, LayoutSource, env_spec
from agents.baselines.geometry import (
    MAX_CUT,
    GhostShot,
    LegalTargets,
    any_object_ball,
    cue_speed,
    ghost_shots,
    pocket_mouths,
)
from agents.baselines.spin_play import plan_contact
from pool_env import ShotResult, onto_tip_circle, shoot
from pool_env.game.formulas import decode_tips

#: A planned candidate: ``(angle, speed, tip, difficulty, pocket)``.
Planned = tuple[float, float, tuple[float, float], float, int]

#: Speeds (m/s) at which the object ball should reach the pocket: softer shots keep the cue
#: ball under control, harder ones forgive more of the deceleration model.
ARRIVAL_SPEEDS = (0.3, 0.7, 1.2, 2.0)
#: Aim points across the mouth, as fractions of its half-width sideways from its middle.
AIM_OFFSETS = (0.0, -0.4, 0.4)
#: Tips tried on a spin env, as fractions of the tip limit ``(side, vertical)``.
SEARCH_TIPS = ((0.0, 0.0), (0.0, 0.6), (0.0, -0.6), (0.5, 0.0), (-0.5, 0.0))
#: Tip error (fraction of R) of the replays on a noiseless spin env.
ROBUST_TIP = 0.03


@dataclass
class Shot:
    """A candidate shot and what the simulator says it does.

    Attributes:
        action: The float32 action that plays it.
        angle: Executed direction (radians from +x).
        speed: Executed cue speed (m/s).
        tip: Executed tip ``(side, vertical)`` (fractions of R; zeros on a roll env).
        difficulty: Heuristic cost for ties (longer and thinner shots cost more).
        value: Outcome of the nominal shot: clean pots, minus scratches.
        robustness: How many perturbed replays also pot cleanly.
        pocket: The pocket the ghost-ball candidate aims at (-1: a random action).
    """

    action: NDArray[np.float32]
    angle: float
    speed: float
    tip: tuple[float, float]
    difficulty: float
    value: float = 0.0
    robustness: int = 0
    pocket: int = -1


class SearchAgent(BaselineAgent):
    """Ghost-ball candidates, verified with the simulator; SB3's ``predict`` signature.

    Args:
        env: The environment it plays (``gym.Env``, wrapped or not, or an SB3 ``VecEnv`` of
            ``PoolEnv``): the table and action decoding are read from it, and its exact layout
            when it matches the observation.
        seed: Seed for the fallback random search.
        n_search: Random actions tried when no ghost-ball shot pots.
        n_robust: Best ghost-ball shots replayed with errors to rank them.
        legal_targets: Which object balls may be aimed at (default: any on the table).
    """

    def __init__(
        self,
        env: Any,
        seed: int | None = 0,
        n_search: int = 128,
        n_robust: int = 12,
        legal_targets: LegalTargets = any_object_ball,
    ) -> None:
        self.spec: EnvSpec = env_spec(env)
        self.source = LayoutSource(env, self.spec.table, self.spec.n_balls)
        self.mouths = pocket_mouths(self.spec.table)
        self.legal_targets = legal_targets
        self.rng = np.random.default_rng(seed)
        self.n_search = n_search
        self.n_robust = n_robust
        self.last_plan: dict[str, Any] = {}
        #: Balls the aim mode refers to (the nearest legal ball on a rules id), or ``None``
        #: for every ball on the table.
        self.reference: NDArray[np.bool_] | None = None
        self._rows: NDArray[np.intp] = np.zeros(0, dtype=np.intp)

    def act(self, observations: NDArray[np.floating]) -> NDArray[np.float32]:
        """The planned action for each observation's layout."""
        return np.stack([self.plan(pos, on) for pos, on in self.source.layouts(observations)])

    # -- planning -------------------------------------------------------------------------

    def plan(self, positions: NDArray[np.float64], on_table: NDArray[np.bool_]) -> NDArray:
        """The action for one layout (``(N, 2)`` centres, cue first; ``(N,)`` on the table)."""
        rows = on_table.nonzero()[0]
        self._rows = rows
        sub = np.ascontiguousarray(positions[rows])
        shots = self._ghost_shots(positions, on_table, sub)
        for shot in shots:
            shot.value = self._outcome(sub, shot.angle, shot.speed, shot.tip)
        good = sorted((s for s in shots if s.value >= 1.0), key=self.order_key)
        if good:
            for shot in good[: self.n_robust]:
                shot.robustness = self._robustness(sub, shot)
            best = max(good[: self.n_robust], key=self.choice_key)
            self.last_plan = {"kind": "ghost", "candidates": len(shots), "shot": best}
            return best.action
        best = self._search(positions, on_table, sub)
        self.last_plan = {"kind": "search", "candidates": len(shots), "shot": best}
        return best.action

    def order_key(self, shot: Shot) -> tuple[float, ...]:
        """Which potting candidates are replayed first: more pots, then easier."""
        return (-shot.value, shot.difficulty)

    def choice_key(self, shot: Shot) -> tuple[float, ...]:
        """The replayed candidate played (the largest): pots, robustness, ease."""
        return (shot.value, shot.robustness, -shot.difficulty)

    def _ghost_shots(
        self, positions: NDArray[np.float64], on_table: NDArray[np.bool_], sub: NDArray
    ) -> list[Shot]:
        """Every clear ghost-ball shot (ball, pocket, aim point, arrival speed)."""
        table = self.spec.table
        targets = self.legal_targets(positions, on_table)
        planned: list[Planned] = []
        for offset in AIM_OFFSETS:
            for shot in ghost_shots(
                table, self.mouths, positions, on_table, targets, offset, MAX_CUT
            ):
                if not shot.clear:
                    continue
                cos_cut = math.cos(shot.cut)
                difficulty = (shot.cue_distance + shot.ball_distance) / cos_cut
                if self.spec.spin:
                    planned += self._spin_candidates(shot, positions, difficulty)
                    continue
                for v_arrive in ARRIVAL_SPEEDS:
                    speed = cue_speed(table, shot, v_arrive)
                    cost = difficulty + 0.01 * v_arrive
                    planned.append((shot.angle, speed, (0.0, 0.0), cost, shot.pocket))
        return self._to_shots(planned, positions, self._aim_on(on_table))

    def _aim_on(self, on_table: NDArray[np.bool_]) -> NDArray[np.bool_]:
        """The balls the aim mode refers to (:attr:`reference`, default ``on_table``)."""
        return on_table if self.reference is None else self.reference

    def _spin_candidates(
        self, shot: GhostShot, positions: NDArray[np.float64], difficulty: float
    ) -> list[Planned]:
        """The strikes that pot ``shot`` with each tip of :data:`SEARCH_TIPS` (closed form)."""
        limit = self.spec.tip_limit or 0.0
        out: list[Planned] = []
        for side, vertical in SEARCH_TIPS:
            tip = (side * limit, vertical * limit)
            for v_arrive in ARRIVAL_SPEEDS:
                contact = plan_contact(self.spec.table, self.mouths, shot, positions, tip, v_arrive)
                if contact is not None:
                    cost = difficulty + 0.01 * v_arrive + 0.01 * math.hypot(side, vertical)
                    out.append((contact.aim, contact.speed, tip, cost, shot.pocket))
        return out

    def _to_shots(
        self,
        planned: list[Planned],
        positions: NDArray[np.float64],
        on_table: NDArray[np.bool_],
    ) -> list[Shot]:
        """Representable shots, with the direction, speed and tip the env will execute."""
        kept, actions = [], []
        for angle, speed, tip, difficulty, pocket in planned:
            action = shot_to_action(angle, speed, positions, on_table, self.spec, tip)
            if action is not None:
                kept.append((difficulty, pocket))
                actions.append(action)
        if not actions:
            return []
        acts = np.stack(actions)
        angles, speeds = decode(acts[:, :2], positions, on_table, self.spec)
        tips = self._tips(acts)
        return [
            Shot(
                acts[k], float(angles[k]), float(speeds[k]), tips[k], kept[k][0], pocket=kept[k][1]
            )
            for k in range(len(kept))
        ]

    def _tips(self, acts: NDArray[np.float32]) -> list[tuple[float, float]]:
        """The executed tips of ``(B, 4)`` actions (zeros on a roll env).

        Each component times the tip limit, scaled back onto the miscue circle.
        """
        limit = self.spec.tip_limit
        if limit is None:
            return [(0.0, 0.0)] * acts.shape[0]
        return [(a, b) for a, b in decode_tips(acts, 2, limit).tolist()]  # the env's decoder

    def _outcome(
        self, sub: NDArray, angle: float, speed: float, tip: tuple[float, float] = (0.0, 0.0)
    ) -> float:
        """The shot's value on the simulator (:meth:`value`)."""
        return self.value(shoot(self.spec.table, sub, angle, speed, tip=tip))

    def value(self, result: ShotResult) -> float:
        """Clean pots of a shot (0 if it scratches, -1 if it scratches without a pot).

        ``result`` is of the balls on the table only (``self._rows`` maps them back);
        a rules game overrides this with its own judge.
        """
        pocketed = result.pocketed
        pots = int(np.count_nonzero(pocketed[1:] >= 0))
        if pocketed[0] >= 0:
            return -1.0 if pots == 0 else 0.0
        return float(pots)

    def rank(self, result: ShotResult) -> float:
        """The first key of a random action in :meth:`_search`: pots, 0 if it scratches."""
        pocketed = result.pocketed
        return 0.0 if pocketed[0] >= 0 else float(np.count_nonzero(pocketed[1:] >= 0))

    def _robustness(self, sub: NDArray, shot: Shot) -> int:
        """How many of a few perturbed replays (aim, speed) still pot cleanly."""
        noise = self.spec.noise
        d_angle = max(noise[0], 5e-4) if noise else 1.5e-3
        speeds = (
            (shot.speed - noise[1], shot.speed + noise[1])
            if noise and noise[1] > 0.0
            else (0.9 * shot.speed, 1.1 * shot.speed)
        )
        tip = shot.tip
        trials = [(shot.angle + k * d_angle, shot.speed, tip) for k in (-2, -1, 1, 2)]
        trials += [(shot.angle, max(s, 0.0), tip) for s in speeds]
        if self.spec.spin:
            d_tip = noise[2] if noise and len(noise) > 2 and noise[2] > 0.0 else ROBUST_TIP
            trials += [(shot.angle, shot.speed, t) for t in self._near_tips(tip, d_tip)]
        return sum(self._outcome(sub, a, s, t) >= 1.0 for a, s, t in trials)

    def _near_tips(self, tip: tuple[float, float], d: float) -> list[tuple[float, float]]:
        """``tip`` moved by ``d`` each way along both axes, kept within the miscue circle."""
        limit = self.spec.tip_limit or 0.0
        moves = ((d, 0.0), (-d, 0.0), (0.0, d), (0.0, -d))
        return [onto_tip_circle(tip[0] + da, tip[1] + db, limit) for da, db in moves]

    def _search(
        self, positions: NDArray[np.float64], on_table: NDArray[np.bool_], sub: NDArray
    ) -> Shot:
        """The best of ``n_search`` random actions: pots first, then no scratch, then soft."""
        width = 4 if self.spec.spin else 2
        acts = self.rng.uniform(-1.0, 1.0, size=(self.n_search, width)).astype(np.float32)
        angles, speeds = decode(acts[:, :2], positions, self._aim_on(on_table), self.spec)
        tips = self._tips(acts)
        best, best_key = None, None
        for k in range(self.n_search):
            result = shoot(self.spec.table, sub, float(angles[k]), float(speeds[k]), tip=tips[k])
            pocketed = result.pocketed
            pots = int(np.count_nonzero(pocketed[1:] >= 0))
            scratch = bool(pocketed[0] >= 0)
            contact = result.first_contact is not None
            key = (self.rank(result), pots, not scratch, contact, -float(speeds[k]))
            if best_key is None or key > best_key:
                best_key = key
                best = Shot(
                    acts[k], float(angles[k]), float(speeds[k]), tips[k], 0.0, float(key[0])
                )
        assert best is not None
        return best
