"""GhostBallAgent: the geometric ghost-ball heuristic of the pool literature; no simulation.

For every legal object ball and pocket it puts the cue ball on the ghost-ball point (``2R``
behind the object ball on the line to the pocket's mouth), keeps the shots whose paths are
clear of the other balls and whose pocket is open to the object ball's path, and plays the
easiest: the one that forgives the largest aim error (thin cuts, long distances and a mouth
seen at an angle all shrink it; :func:`agents.baselines.geometry.ghost_shots`) among those whose cue
ball, followed along the tangent line and off the cushions, stays out of the pockets
(:func:`agents.baselines.trace.cue_ball_scratches`). The speed comes from
the distances, the rolling resistance and the ball-ball restitution
(:func:`agents.baselines.geometry.cue_speed`) so that the object ball drops at a gentle
:data:`ARRIVAL_SPEED`. When no direct shot exists (a rack, a ball in the way) it hits the
nearest legal ball full at the top speed: the break, or a shot that opens the table.

On a spin env (the spin ids: the action ends with the cue tip's two components) it also
plays position (:mod:`agents.baselines.spin_play`): for the most forgiving few shots it
tries stun, follow and draw (:data:`~agents.baselines.spin_play.VERTICAL_TIPS`) at a few
object-ball arrival speeds, works out each strike in closed form (throw, squirt, the cue
ball's slide and roll, :mod:`agents.baselines.cue_path`), drops those whose cue ball
scratches, and keeps the one whose cue ball stops where the next shot is easiest
(:class:`~agents.baselines.spin_play.PositionScore`). ``spin=False`` restricts it to a
centre-ball strike (position by speed alone): the comparison that says what spin adds.

It never calls the simulator: everything it knows is the table's public geometry and
constants and the layout. Compare :class:`agents.baselines.search.SearchAgent`, which checks
candidate shots on the simulator (the oracle upper bound).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from agents.baselines.aiming import shot_to_action
from agents.baselines.base import BaselineAgent, EnvSpec, LayoutSource, env_spec
from agents.baselines.geometry import (
    GhostShot,
    LegalTargets,
    any_object_ball,
    cue_speed,
    ghost_shots,
    pocket_mouths,
)
from agents.baselines.spin_play import (
    ARRIVAL_SPEEDS,
    SIDE_TIPS,
    THROW_ROUNDS,
    VERTICAL_TIPS,
    Contact,
    NextTargets,
    PositionScore,
    TracedPot,
    plan_contact,
    pot_chance,
    traced_pots,
)
from agents.baselines.trace import cue_ball_scratches
from pool_env import nearest_object_ball, onto_tip_circle
from pool_env.game.formulas import to_unit
from pool_env.game.shot_features import ARRIVAL_SPEED  # the shot features' arrival speed

#: On a spin env: the most forgiving shots whose tips and speeds are tried for position.
POSITION_SHOTS = 6
#: The least aim error (rad) the position score assumes (a noiseless env still rewards
#: shots that forgive more).
MIN_SIGMA = 1e-3


@dataclass(frozen=True)
class PositionOption:
    """One strike the spin ghost-ball agent weighs (:meth:`GhostBallAgent.position_options`).

    Attributes:
        shot: The ghost-ball shot (object ball and pocket).
        contact: The strike that pots it and what the cue ball does after.
        arrival: The object ball's planned speed at the pocket (m/s).
        action: The env action that plays it.
        score: Its :class:`~agents.baselines.spin_play.PositionScore` less the small
            preference for soft and centre-ball strikes; ``None`` when the cue ball
            follows it into a pocket.
    """

    shot: GhostShot
    contact: Contact
    arrival: float
    action: NDArray[np.float32]
    score: float | None


def best_option(options: list[PositionOption]) -> PositionOption | None:
    """The option the agent plays: the first best score, else the first most forgiving scratch."""
    best: PositionOption | None = None
    scratch: PositionOption | None = None
    for option in options:
        if option.score is None:
            if scratch is None or option.shot.tolerance > scratch.shot.tolerance:
                scratch = option
        elif best is None or option.score > best.score:  # type: ignore[operator]
            best = option
    return best or scratch


class GhostBallAgent(BaselineAgent):
    """Geometric ghost-ball aiming and speed from the distances; SB3's ``predict`` signature.

    Args:
        env: The environment it plays (``gym.Env``, wrapped or not, or an SB3 ``VecEnv`` of
            ``PoolEnv``): the table and the action decoding are read from it, and its exact
            layout when it matches the observation.
        arrival_speed: Speed (m/s) at which the object ball should drop.
        legal_targets: Which object balls may be aimed at (default: any on the table; a
            rules game passes its own).
        spin: On a spin env, whether to use the tip (else centre ball, position by speed).
        next_targets: On a spin env, the legal balls once a ball drops (default:
            ``legal_targets`` of the layout without it).

    Examples:
        >>> import gymnasium as gym
        >>> import pool_env
        >>> from agents import GhostBallAgent
        >>> env = gym.make("pool_env/OneBallRoll-v1")
        >>> agent = GhostBallAgent(env)
        >>> obs, _ = env.reset(seed=10000)
        >>> action, _ = agent.predict(obs)  # cut offset and speed, both in [-1, 1]
        >>> obs, reward, terminated, truncated, info = env.step(action)
        >>> reward, info["potted"]
        (1.0, (1,))
    """

    def __init__(
        self,
        env: Any,
        arrival_speed: float = ARRIVAL_SPEED,
        legal_targets: LegalTargets = any_object_ball,
        spin: bool = True,
        next_targets: NextTargets | None = None,
    ) -> None:
        if not (math.isfinite(arrival_speed) and arrival_speed >= 0.0):
            raise ValueError(f"arrival_speed must be a finite speed >= 0, got {arrival_speed!r}")
        self.spec: EnvSpec = env_spec(env)
        self.source = LayoutSource(env, self.spec.table, self.spec.n_balls)
        self.mouths = pocket_mouths(self.spec.table)
        self.arrival_speed = float(arrival_speed)
        self.legal_targets = legal_targets
        self.last_plan: dict[str, Any] = {}
        self.last_contact: Contact | None = None
        self.last_traced: TracedPot | None = None
        limit = self.spec.tip_limit or 0.0
        fractions = [(a, b) for b in VERTICAL_TIPS for a in SIDE_TIPS] if spin else [(0.0, 0.0)]
        # What the env executes: a tip beyond the miscue circle is scaled back onto it.
        tips = [onto_tip_circle(a * limit, b * limit, limit) for a, b in fractions]
        self.tips = list(dict.fromkeys(tips))
        self.next_targets: NextTargets = next_targets or (
            lambda positions, on_table, ball: legal_targets(positions, on_table)
        )

    def act(self, observations: NDArray[np.floating]) -> NDArray[np.float32]:
        """The planned action for each observation's layout."""
        return np.stack([self.plan(pos, on) for pos, on in self.source.layouts(observations)])

    def plan(self, positions: NDArray[np.float64], on_table: NDArray[np.bool_]) -> NDArray:
        """The action for one layout (``(N, 2)`` centres, cue first; ``(N,)`` on the table)."""
        shot, speed, action = self.best_shot(positions, on_table)
        if action is not None:
            kind = "ghost" if shot is not None else "traced"  # a bank or carom (spin envs)
            self.last_plan = {"kind": kind, "shot": shot, "speed": speed}
            return action
        self.last_plan = {"kind": "fallback", "shot": None, "speed": self.spec.speed_range[1]}
        return self._fallback(positions, on_table)

    def best_shot(
        self,
        positions: NDArray[np.float64],
        on_table: NDArray[np.bool_],
        reference: NDArray[np.bool_] | None = None,
    ) -> tuple[GhostShot | None, float, NDArray[np.float32] | None]:
        """The most forgiving clear shot the action space can play: ``(shot, speed, action)``.

        A shot is skipped when it needs more than the top speed or when the aim mode cannot
        express its direction (``cut`` and ``relative`` aim relative to the nearest ball of
        ``reference``, default ``on_table``; the game ids aim at the nearest legal ball).
        ``(None, nan, None)`` when no shot is left.
        """
        if self.spec.spin:
            return self.position_shot(positions, on_table, reference)
        return self.easiest_shot(positions, on_table, reference)

    def easiest_shot(
        self,
        positions: NDArray[np.float64],
        on_table: NDArray[np.bool_],
        reference: NDArray[np.bool_] | None = None,
    ) -> tuple[GhostShot | None, float, NDArray[np.float32] | None]:
        """The roll level's choice: the most forgiving shot that does not scratch.

        On a spin env its action ends with a centre-ball tip (used to rank placements).
        """
        aim_on = on_table if reference is None else reference
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
            action = shot_to_action(shot.angle, speed, positions, aim_on, self.spec)
            if action is not None:
                playable.append((shot, speed, action))
        # The easiest shot whose cue ball stays out of the pockets, else the easiest.
        for shot, speed, action in playable:
            played = max(speed, self.spec.speed_range[0])  # a softer shot is not available
            if not cue_ball_scratches(table, self.mouths, shot, played):
                return shot, speed, action
        return playable[0] if playable else (None, math.nan, None)

    def forgiving_shots(
        self,
        positions: NDArray[np.float64],
        on_table: NDArray[np.bool_],
        targets: list[int],
        count: int,
    ) -> tuple[list[GhostShot], float, PositionScore]:
        """The ``count`` most forgiving clear shots on ``targets``, and how to score position.

        Returns:
            The shots (most forgiving first), the aim noise their pot chances assume (the
            env's, at least :data:`MIN_SIGMA`) and the :class:`PositionScore` of the next
            shot under that noise.
        """
        table, spec = self.spec.table, self.spec
        shots = sorted(
            (s for s in ghost_shots(table, self.mouths, positions, on_table, targets) if s.clear),
            key=lambda s: -s.tolerance,
        )[:count]
        sigma = max(spec.noise[0] if spec.noise else 0.0, MIN_SIGMA)
        return shots, sigma, PositionScore(table, self.mouths, sigma, self.next_targets)

    def position_options(
        self,
        positions: NDArray[np.float64],
        on_table: NDArray[np.bool_],
        reference: NDArray[np.bool_] | None = None,
    ) -> tuple[list[PositionOption], list[GhostShot], NDArray[np.bool_]]:
        """Every strike :meth:`position_shot` weighs, in the order it weighs them.

        Among the :data:`POSITION_SHOTS` most forgiving clear shots, every tip of
        ``self.tips`` and arrival speed of :data:`~agents.baselines.spin_play.ARRIVAL_SPEEDS`
        whose strike is in the speed range and that the aim mode can play. A shot is left
        out once its own pot chance is at most the best score so far (a score is at most
        the shot's own chance; the rest forgive less).

        Returns:
            The options, the shots they came from (most forgiving first) and the balls
            the aim refers to.
        """
        aim_on = on_table if reference is None else reference
        table, spec = self.spec.table, self.spec
        lo, top = spec.speed_range
        targets = self.legal_targets(positions, on_table)
        shots, sigma, scorer = self.forgiving_shots(positions, on_table, targets, POSITION_SHOTS)
        limit = spec.tip_limit or 1.0
        options: list[PositionOption] = []
        best = -math.inf
        for shot in shots:
            if options and pot_chance(shot.tolerance, sigma) <= best:
                break
            for tip in self.tips:
                for arrival in ARRIVAL_SPEEDS:
                    contact = plan_contact(table, self.mouths, shot, positions, tip, arrival)
                    if contact is None or not lo <= contact.speed <= top:
                        continue
                    action = shot_to_action(
                        contact.aim, contact.speed, positions, aim_on, spec, tip
                    )
                    if action is None:
                        continue
                    if contact.path.pocket >= 0:
                        options.append(PositionOption(shot, contact, arrival, action, None))
                        continue
                    score = scorer.score(shot, contact, positions, on_table)
                    score -= 0.002 * arrival + 0.001 * math.hypot(*tip) / limit
                    options.append(PositionOption(shot, contact, arrival, action, score))
                    best = max(best, score)
        return options, shots, aim_on

    def position_shot(
        self,
        positions: NDArray[np.float64],
        on_table: NDArray[np.bool_],
        reference: NDArray[np.bool_] | None = None,
    ) -> tuple[GhostShot | None, float, NDArray[np.float32] | None]:
        """The spin env's choice: shot, tip and speed for the best position (module doc).

        The best-scoring option of :meth:`position_options` whose cue ball stays out of
        the pockets; ties go to the first weighed (the softer and the less spin). If every
        one scratches, the most forgiving of them.
        """
        self.last_traced = None
        options, shots, aim_on = self.position_options(positions, on_table, reference)
        chosen = best_option(options)
        self.last_contact = chosen.contact if chosen and chosen.score is not None else None
        if chosen is None:
            return self._last_resort(shots, positions, on_table, aim_on)
        return chosen.shot, chosen.contact.speed, chosen.action

    def _last_resort(
        self,
        shots: list[GhostShot],
        positions: NDArray[np.float64],
        on_table: NDArray[np.bool_],
        aim_on: NDArray[np.bool_],
    ) -> tuple[GhostShot | None, float, NDArray[np.float32] | None]:
        """A shot for when no candidate of :meth:`position_shot` is playable.

        The most forgiving shot that can still reach its pocket, centre ball, as hard as
        the speed range allows (a thin cut whose gentle arrival needs more than the top
        speed), at its throw-corrected contact or, off the table (a ball frozen to a
        rail), at its plain ghost point. Failing that, a bank or carom found by
        tracing a fan of strikes (:func:`~agents.baselines.spin_play.traced_pots`); its
        shot is ``None`` (no ghost-ball shot), its action is returned.
        """
        lo, top = self.spec.speed_range
        for shot in shots:
            for rounds in (THROW_ROUNDS, 0):
                contact = self._at_speed(shot, positions, top, rounds)
                if contact is None:
                    continue
                speed = min(max(contact.speed, lo), top)
                action = shot_to_action(contact.aim, speed, positions, aim_on, self.spec)
                if action is not None:
                    return shot, speed, action
        targets = self.legal_targets(positions, on_table)
        for pot in traced_pots(self.spec.table, self.mouths, positions, on_table, targets, top):
            action = shot_to_action(pot.aim, pot.speed, positions, aim_on, self.spec)
            if action is not None and pot.speed >= lo:
                self.last_traced = pot
                return None, pot.speed, action
        return None, math.nan, None

    def _at_speed(
        self, shot: GhostShot, positions: NDArray[np.float64], speed: float, rounds: int
    ) -> Contact | None:
        """The centre-ball contact of ``shot`` struck at about ``speed``.

        A bisection on the arrival speed; ``None`` if even a ball that just reaches the
        pocket needs more.
        """
        table, mouths, centre = self.spec.table, self.mouths, (0.0, 0.0)
        slowest = plan_contact(table, mouths, shot, positions, centre, 0.0, rounds)
        if slowest is None or slowest.speed > speed:
            return None
        low, high, best = 0.0, 4.0, slowest
        for _ in range(12):
            mid = 0.5 * (low + high)
            contact = plan_contact(table, mouths, shot, positions, centre, mid, rounds)
            if contact is not None and contact.speed <= speed:
                low, best = mid, contact
            else:
                high = mid
        return best

    def _fallback(
        self,
        positions: NDArray[np.float64],
        on_table: NDArray[np.bool_],
        reference: NDArray[np.bool_] | None = None,
    ) -> NDArray:
        """A full hit on the nearest legal ball at the top speed (the nearest ball if it fails)."""
        aim_on = on_table if reference is None else reference
        cue = positions[0]
        targets = self.legal_targets(positions, on_table)
        if targets:
            j = min(targets, key=lambda b: float(np.hypot(*(positions[b] - cue))))
        else:
            j = nearest_object_ball(positions, on_table, 0)[0]
        speed = self.spec.speed_range[1]
        if j >= 0:
            d = positions[j] - cue
            action = shot_to_action(math.atan2(d[1], d[0]), speed, positions, aim_on, self.spec)
            if action is not None:
                return action
        # A legal ball that cut or relative aim cannot reach: a full hit on their reference
        # ball (the nearest), which action[0] = "aim parameter 0" is in both modes.
        action = np.zeros(4 if self.spec.spin else 2, dtype=np.float32)  # centre ball
        action[0] = min(max(to_unit(0.0, *self.spec.aim_range), -1.0), 1.0)
        action[1] = 1.0
        return action
