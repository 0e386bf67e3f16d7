"""A snooker break-builder: candidate pots played under the env's noise, valued with the leave.

:class:`SnookerSearchAgent` plays every shot of a visit this way, within ``budget`` seconds:

1. **Placement** (cue ball in hand): the ghost-ball player's :attr:`places` best points
   of the D (:meth:`agents.baselines.snooker_play.SnookerGhostBallAgent.placements`),
   each with its own candidates below.
2. **Candidates**: the clear ghost-ball pots (:func:`pool_env.game.geometry.ghost_shots`)
   on the balls on: the reds, or after a red every colour (each nominated as itself), or
   the colour on in order; the two best pockets of each ball, then the :attr:`shots` best
   by ``value x pot chance``; each at :data:`ARRIVALS` object-ball speeds
   (:func:`pool_env.game.geometry.cue_speeds`) and, on a spin env, :data:`VERTICAL_TIPS`
   (stun, follow, draw), each aimed at the ghost-ball direction and :data:`AIM_OFFSETS`
   of the shot's tolerance either side; and the ghost-ball player's own shot. (The ids'
   cut aim can only strike the nearest ball on: the other balls' pots are not
   candidates there, and the leave counts that ball's pots only.)
3. **Rollouts**: all candidates are played side by side through the game's own step
   (:func:`pool_env.game.candidate_actions.rollout_actions`: the rules, the placement, the
   execution noise), in rounds: each round draws one noise sample, the same for every
   candidate (common random numbers). After :data:`PRUNE_AFTER` rounds the
   :attr:`finalists` best go on alone; rounds go on while the budget lasts, up to
   :attr:`samples` (one at no noise: the step is then exact).
4. **Value**: each outcome is worth the points it scored plus, when the visit goes on, the
   leave: the best next pot's ``chance x (value + FUTURE)``, the chance of its most
   forgiving clear ghost-ball pot under the env's aim noise, its value that of the ball
   (the colours after a red: the nominated colour's), ``FUTURE`` what keeping the table is
   worth beyond it (:data:`FUTURE`). The candidate of the best mean is played.
"""

from __future__ import annotations

import itertools
import math
import time
from typing import Any

import numpy as np
from numpy.typing import NDArray

from agents.baselines.base import BaselineAgent
from agents.baselines.snooker_play import (
    COLOURS,
    SnookerGhostBallAgent,
    ball_value,
    phase_of,
    snooker_action,
)
from pool_env import obs_layout, shot_constraints
from pool_env.game import geometry as geo
from pool_env.game.candidate_actions import rollout_actions
from pool_env.game.codec import encode_shots, reference_balls
from pool_env.game.state import GameState

#: Object-ball speeds (m/s) at the pocket the candidates are struck for: a dying pot to a
#: firm one (the cue ball's travel after the contact grows with it).
ARRIVALS = (0.3, 0.7, 1.3, 2.2)
#: Vertical tips (fractions of the tip limit) tried on a spin env: stun, follow, draw.
VERTICAL_TIPS = (0.0, 0.6, -0.6)
#: Aim offsets off the ghost-ball direction tried, in the shot's tolerances: the throw and
#: the cut-induced spin move the object ball's path by a fraction of the tolerance.
AIM_OFFSETS = (-0.5, 0.0, 0.5)
#: What keeping the table is worth beyond the next ball's value (points): a leave's pot
#: chance times this is its position's worth. About the break a kept table goes on to.
FUTURE = 5.0
#: Noise rounds played by every candidate before all but the finalists drop out.
PRUNE_AFTER = 4
#: Values of the observation's points features are scaled by the maximum break.
MAX_BREAK = 147.0


class SnookerSearchAgent(BaselineAgent):
    """Candidate pots rolled out under the env's noise, points plus the leave (module doc).

    Args:
        env: A snooker env (``gym.make("pool_env/SnookerBreak-v1")``, wrapped or not).
        budget: Wall-clock seconds per shot (rounds of rollouts stop once it is spent; the
            first round always runs).
        samples: Most noise samples (rounds) per shot.
        shots: Ghost-ball pots expanded into candidates (per point of the D tried).
        places: Points of the D tried with the cue ball in hand (the ghost-ball player's
            best by its estimate).
        finalists: Candidates kept after :data:`PRUNE_AFTER` rounds.
        seed: Seed of the rollouts' noise.

    Raises:
        ValueError: On an env of another game, or a budget, samples or shots out of range.
    """

    def __init__(
        self,
        env: Any,
        budget: float = 1.0,
        samples: int = 64,
        shots: int = 10,
        places: int = 6,
        finalists: int = 24,
        seed: int = 0,
    ) -> None:
        self.player = SnookerGhostBallAgent(env)
        if not (math.isfinite(budget) and budget > 0.0):
            raise ValueError(f"budget must be a finite number of seconds > 0, got {budget!r}")
        counts = {"samples": samples, "shots": shots, "places": places, "finalists": finalists}
        for name, value in counts.items():
            if isinstance(value, bool) or not isinstance(value, int) or value < 1:
                raise ValueError(f"{name} must be an integer >= 1, got {value!r}")
        self.config = self.player.config
        self.budget, self.samples, self.shots = float(budget), samples, shots
        self.places, self.finalists = places, finalists
        self.mouths = geo.pocket_mouths(self.config.table)
        self.rng = np.random.default_rng(seed)
        self.last_plan: dict[str, Any] = {}

    def act(self, observations: NDArray[np.floating]) -> NDArray[np.float32]:
        """The searched actions: ``(B, config.action_size)``."""
        balls = obs_layout(self.config)["balls"]
        source = self.player.ghost.source
        layouts = source.layouts(np.ascontiguousarray(observations[:, balls]))
        pairs = zip(observations, layouts, strict=True)
        return np.stack([self.plan(obs, pos, on) for obs, (pos, on) in pairs]).astype(np.float32)

    def rack_row(self, obs: NDArray[np.floating]) -> NDArray[np.int64]:
        """The frame state the observation shows, from the striker's seat (shooter 0)."""
        layout = obs_layout(self.config)

        def flag(name: str) -> bool:
            return bool(obs[layout[name]][0] > 0.5)

        def points(name: str) -> int:
            return round(float(obs[layout[name]][0]) * MAX_BREAK)

        given = {
            "phase": phase_of(self.config, obs),
            "ball_in_hand": flag("ball_in_hand"),
            "free_ball": flag("free_ball"),
            "respotted_black": flag("respotted_black"),
            "break": points("break"),
            "score_0": points("score"),
            "score_1": points("opponent_score"),
        }
        return self.config.ruleset.state_row(self.config, given)

    def plan(
        self, obs: NDArray[np.floating], positions: NDArray[np.float64], on: NDArray[np.bool_]
    ) -> NDArray[np.float64]:
        """The action for one observation and its layout."""
        start = time.perf_counter()
        config, player = self.config, self.player
        ghost_action = player.plan(obs, positions, on)
        rules = shot_constraints(config, obs)
        phase = phase_of(config, obs)
        targets, reference = player.balls_on(rules, phase, on)
        spots = [p for _, p in player.last_places[: self.places]] if rules.ball_in_hand else []
        blocks = [ghost_action[None]]
        for spot in spots or [None]:
            placed, comps = positions.copy(), np.zeros(2)
            if spot is not None:
                placed[0], comps = spot, player.place_components(spot)
            blocks.append(self.candidates(placed, on, reference, targets, phase, comps))
        actions = np.vstack(blocks)
        state = config.new_state(1)
        state.positions[0], state.on_table[0] = positions, on
        state.rack[0] = self.rack_row(obs)
        rounds = 1 if config.noise is None else self.samples
        alive = np.arange(actions.shape[0])
        sums, counts = np.zeros(actions.shape[0]), np.zeros(actions.shape[0])
        for done in range(rounds):
            if done and time.perf_counter() - start >= self.budget:
                break
            if done == PRUNE_AFTER and alive.size > self.finalists:
                means = sums[alive] / counts[alive]
                alive = alive[np.argsort(-means, kind="stable")[: self.finalists]]
            state.use_generator(0, np.random.default_rng(self.rng.integers(2**63)))
            result, after = rollout_actions(config, state, 0, actions[alive])
            sums[alive] += result.rewards + np.where(result.terminated, 0.0, self.leave(after))
            counts[alive] += 1
        means = sums[alive] / counts[alive]
        best = int(alive[np.argmax(means)])
        self.last_plan = {
            "kind": "search", "candidates": actions.shape[0], "rounds": int(counts[best]),
            "value": float(sums[best] / counts[best]), "ghost": best == 0,
        }  # fmt: skip
        return actions[best]

    def candidates(
        self,
        positions: NDArray[np.float64],
        on: NDArray[np.bool_],
        reference: NDArray[np.bool_],
        targets: list[int],
        phase: str,
        place: NDArray[np.float64],
    ) -> NDArray[np.float64]:
        """The candidate actions (module doc, step 2): ``(C, action_size)``, maybe ``C = 0``."""
        config, table = self.config, self.config.table
        rows = geo.ghost_shots(table, self.mouths, positions[None], on[None], [targets])[0]
        sigma = self.player.sigma
        kept: list[tuple[float, int, NDArray[np.float64]]] = []
        for t, ball in enumerate(targets):
            ok = [
                k
                for k in range(rows.shape[1])
                if rows[t, k, geo.VALID] and rows[t, k, geo.CLEAR_PATH]
            ]
            ok.sort(key=lambda k: -rows[t, k, geo.TOLERANCE])
            for k in ok[:2]:
                chance = math.erf(rows[t, k, geo.TOLERANCE] / (sigma * math.sqrt(2.0)))
                kept.append((ball_value(ball) * chance, ball, rows[t, k]))
        kept.sort(key=lambda item: -item[0])
        kept = kept[: self.shots]
        limit = config.tip_limit
        tips = [(0.0, 0.0)] if limit is None else [(0.0, v * limit) for v in VERTICAL_TIPS]
        angles, speeds, tip_rows, colours = [], [], [], []
        low, high = config.speed_range
        for _, ball, row in kept:
            for arrival in ARRIVALS:
                speed = float(geo.cue_speeds(table, row, arrival))
                if not low <= speed <= high:
                    continue
                for tip, offset in itertools.product(tips, AIM_OFFSETS):
                    angles.append(row[geo.ANGLE] + offset * row[geo.TOLERANCE])
                    speeds.append(speed)
                    tip_rows.append(tip)
                    colours.append(ball if phase == "colour" and ball >= COLOURS[0] else None)
        if not angles:
            return np.zeros((0, config.action_size))
        parts, playable = encode_shots(
            config, positions[None], reference[None], [angles], [speeds],
            None if limit is None else [tip_rows],
        )  # fmt: skip
        return np.array(
            [
                snooker_action(config, parts[0, m], place, colours[m])
                for m in range(len(angles))
                if playable[0, m]
            ]
        ).reshape(-1, config.action_size)

    def leave(self, after: GameState) -> NDArray[np.float64]:
        """``(K,)`` each table's best next pot: ``chance x (value + FUTURE)``, 0 for none."""
        config = self.config
        legal = config.ruleset.aim_references(after)
        if config.aim == "cut":  # the cut aim hits the nearest ball on, and only it
            nearest = reference_balls(after.positions, legal)
            legal = np.zeros_like(legal)
            legal[np.flatnonzero(nearest >= 0), nearest[nearest >= 0]] = True
        n = legal.shape[1]
        targets = np.full((legal.shape[0], n - 1), -1, dtype=np.int64)
        for b in range(legal.shape[0]):
            balls = np.flatnonzero(legal[b, 1:]) + 1
            targets[b, : balls.size] = balls
        rows = geo.ghost_shots(config.table, self.mouths, after.positions, after.on_table, targets)
        ok = (rows[..., geo.VALID] > 0.0) & (rows[..., geo.CLEAR_PATH] > 0.0)
        ok &= targets[:, :, None] >= 0
        tolerance = np.where(ok, rows[..., geo.TOLERANCE], 0.0)
        chance = _erf(tolerance / (self.player.sigma * math.sqrt(2.0))).astype(np.float64)
        values = np.where(targets >= 0, _VALUES[np.maximum(targets, 0)], 0.0)
        worth = chance * (values[:, :, None] + FUTURE)
        return worth.reshape(worth.shape[0], -1).max(axis=1, initial=0.0)


#: Each ball's value as floats (the cue ball 0), for the leave's arrays.
_VALUES = np.array([0.0] + [float(ball_value(j)) for j in range(1, COLOURS[-1] + 1)])
_erf = np.frompyfunc(math.erf, 1, 1)
