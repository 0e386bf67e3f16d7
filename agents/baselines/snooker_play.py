"""Snooker players' shared parts, and the ghost-ball player that nominates by value.

What every snooker player here does the same way (``game="snooker"``, the ids
``pool_env/SnookerBreak-v1``, ``SnookerFrame-v1`` and their roll twins):

* **The action's columns** (:func:`snooker_action`): ``(aim, speed, cue x, cue y,
  nomination)``, then a spin table's tip; the placement and the nomination are written by
  the env's own codec (:func:`pool_env.game.codec.encode_placement`,
  :func:`pool_env.game.codec.encode_ball`).
* **The D** (:class:`TheD`): read from the rules' placement box
  (:func:`pool_env.shot_constraints`), with the points a cue ball in hand is tried on.
* **The balls' values** (:func:`ball_value`: a red 1, yellow 2 .. black 7) and the pot's
  worth to a player: ``value x chance``, the chance of the most forgiving clear ghost-ball
  pot under the env's aim noise (:func:`agents.baselines.spin_play.pot_chance`).

:class:`SnookerGhostBallAgent` plays the ghost-ball heuristic of
:class:`agents.baselines.ghost_ball.GhostBallAgent` (closed form, no simulation) on the
balls the rules put on:

* a red on: the most forgiving pot among the reds (a free ball is not used);
* a colour on (after a red): it **nominates by value**: the colour whose best pot is worth
  the most points on average, ``value x chance`` (:meth:`SnookerGhostBallAgent.nominate`);
  at no noise the chance is taken at :data:`~agents.baselines.ghost_ball.MIN_SIGMA`, so
  the highest colour with a clear pot forgiving a few milliradians is chosen;
* the colours in order: the ball on;
* the cue ball in hand: the point of the D (a grid of it, and the straight-in points of
  each ball on and pocket that lie in it, :meth:`TheD.candidates`) from which that best
  pot is worth the most;
* no pot at all: a full hit on the nearest ball on at the top speed (no safeties).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from agents.baselines.game_agents import RulesGhostBase
from agents.baselines.ghost_ball import ARRIVAL_SPEED, MIN_SIGMA
from agents.baselines.spin_play import pot_chance
from pool_env import ShotConstraints, obs_layout, shot_constraints
from pool_env.game.codec import encode_ball, encode_placement
from pool_env.game.config import GameConfig
from pool_env.game.games.snooker.rack_state import VALUES

#: The colours' ball numbers, yellow .. black (16 .. 21); below them the reds (1 .. 15).
COLOURS: tuple[int, ...] = tuple(range(16, 22))
#: The nomination component that names nothing: the first of its seven bins over [-1, 1]
#: (read only where the rules ask for a nomination; every snooker player writes it then).
NO_NOMINATION = -1.0
#: Ball centres of the D grid a cue ball in hand is tried on: depths and across.
D_DEPTHS = (0.05, 0.3, 0.55, 0.8)
D_ACROSS = (-0.8, -0.4, 0.0, 0.4, 0.8)
#: A cue ball in hand keeps this far (ball radii) from every ball: no touching ball.
PLACE_CLEARANCE = 2.2


def ball_value(ball: int) -> int:
    """A ball's points (WPBSA Section 2 Rule 4): a red 1, yellow 2 .. black 7."""
    return int(VALUES[ball])


def check_snooker(config: GameConfig, who: str) -> None:
    """Refuse an env of another game.

    Raises:
        ValueError: Naming the player and the game it got.
    """
    if config.game != "snooker":
        raise ValueError(
            f"{who} plays game='snooker' (pool_env/SnookerBreak-v1), got {config.game!r}"
        )


def snooker_action(
    config: GameConfig,
    strike: NDArray[np.floating],
    place: tuple[float, float] | NDArray[np.floating] = (0.0, 0.0),
    colour: int | None = None,
) -> NDArray[np.float64]:
    """The full action: the strike, the placement components and the nomination.

    Args:
        config: The env's config.
        strike: ``(aim, speed)`` or, on a spin env, ``(aim, speed, side, vertical)``
            components (a roll strike on a spin env plays centre ball).
        place: ``action[2]``, ``action[3]`` (read only with the cue ball in hand).
        colour: The colour nominated (16 .. 21), or ``None``.

    Returns:
        ``(config.action_size,)`` float64.
    """
    out = np.zeros(config.action_size)
    part = np.asarray(strike, dtype=np.float64)
    out[0], out[1] = part[0], part[1]
    out[2], out[3] = place[0], place[1]
    out[4] = NO_NOMINATION if colour is None else encode_ball(config, colour)
    if config.tip_columns is not None and part.shape[0] >= 4:
        out[list(config.tip_columns)] = part[2:4]
    return out


@dataclass(frozen=True)
class TheD:
    """The D (a half disc on the baulk side of the baulk line), where a cue ball in hand goes.

    Attributes:
        baulk_x: The baulk line (``x``).
        radius: The D's radius.
        centre_y: Its centre (``y``).
    """

    baulk_x: float
    radius: float
    centre_y: float

    @classmethod
    def of(cls, rules: ShotConstraints) -> TheD:
        """The D of the rules' placement box ``((bx - r, bx), (cy - r, cy + r))``.

        Raises:
            ValueError: Without ball in hand (no box).
        """
        if rules.placement is None:
            raise ValueError("the D is read from a ball-in-hand shot's placement box")
        (x_low, x_high), (y_low, y_high) = rules.placement
        return cls(float(x_high), float(x_high - x_low), 0.5 * float(y_low + y_high))

    def contains(self, point: NDArray[np.float64], margin: float = 0.0) -> bool:
        """Whether ``point`` lies in the D, ``margin`` inside its edge."""
        x, y = float(point[0]), float(point[1])
        return (
            x <= self.baulk_x - margin
            and math.hypot(x - self.baulk_x, y - self.centre_y) <= self.radius - margin
        )

    def grid(self) -> list[NDArray[np.float64]]:
        """The grid points of :data:`D_DEPTHS` x :data:`D_ACROSS`, inside the D."""
        out = []
        for u in D_DEPTHS:
            depth = u * self.radius
            half = math.sqrt(max(self.radius**2 - depth**2, 0.0))
            out += [np.array([self.baulk_x - depth, self.centre_y + v * half]) for v in D_ACROSS]
        return out

    def straight_in(
        self, ball: NDArray[np.float64], pocket: NDArray[np.float64], radius: float
    ) -> NDArray[np.float64] | None:
        """The middle of the stretch of the line pocket -> ball, beyond the ball, in the D."""
        d = ball - pocket
        u = d / max(float(np.hypot(*d)), 1e-12)
        reach = np.arange(4.0 * radius, 5.0, 0.01)
        inside = [s for s in reach if self.contains(ball + s * u, radius / 2.0)]
        if not inside:
            return None
        return ball + 0.5 * (inside[0] + inside[-1]) * u

    def candidates(
        self,
        positions: NDArray[np.float64],
        on: NDArray[np.bool_],
        targets: list[int],
        pockets: NDArray[np.float64],
        radius: float,
    ) -> list[NDArray[np.float64]]:
        """The points a cue ball in hand is tried on: straight-in points, then the grid.

        Each keeps :data:`PLACE_CLEARANCE` radii from every ball on the table.
        """
        points = [
            p
            for b in targets
            for k in range(pockets.shape[0])
            if (p := self.straight_in(positions[b], pockets[k, :2], radius)) is not None
        ] + self.grid()
        others = positions[[j for j in range(1, on.shape[0]) if on[j]]]
        reach = PLACE_CLEARANCE * radius
        return [p for p in points if not (np.hypot(*(others - p).T) < reach).any()]


def phase_of(config: GameConfig, obs: NDArray[np.floating]) -> str:
    """``"red"``, ``"colour"`` or ``"in_order"``: what the observation says is on."""
    layout = obs_layout(config)
    if obs[layout["colour_on"]][0] > 0.5:
        return "colour"
    return "in_order" if obs[layout["in_order"]][0] > 0.5 else "red"


class SnookerGhostBallAgent(RulesGhostBase):
    """The ghost-ball heuristic under snooker's rules, nominating by value (module doc).

    Args:
        env: A snooker env (``gym.make("pool_env/SnookerBreak-v1")``, wrapped or not).
        arrival_speed: As :class:`GhostBallAgent`.
        spin: On a spin env, whether to play position with the tip (else centre ball).

    Raises:
        ValueError: On an env of another game.
    """

    def __init__(self, env: Any, arrival_speed: float = ARRIVAL_SPEED, spin: bool = True) -> None:
        config = env.unwrapped.config
        check_snooker(config, "SnookerGhostBallAgent")
        self._start(env, config, arrival_speed, spin)
        noise = config.noise
        #: The aim noise (rad) pot chances are taken at: the env's, at least MIN_SIGMA.
        self.sigma = max(float(noise[0]) if noise else 0.0, MIN_SIGMA)
        #: The points of the D tried at the last placement, with their worth, best first.
        self.last_places: list[tuple[float, NDArray[np.float64]]] = []

    # -- the plan --------------------------------------------------------------------------

    def _plan(
        self, obs: NDArray[np.floating], positions: NDArray[np.float64], on: NDArray[np.bool_]
    ) -> NDArray[np.float64]:
        return self.plan(obs, positions, on)

    def plan(
        self, obs: NDArray[np.floating], positions: NDArray[np.float64], on: NDArray[np.bool_]
    ) -> NDArray[np.float64]:
        """The action for one observation and its layout (``positions``, ``on``)."""
        rules = shot_constraints(self.config, obs)
        phase = phase_of(self.config, obs)
        targets, reference = self.balls_on(rules, phase, on)
        place: NDArray[np.float64] = np.zeros(2)
        if rules.ball_in_hand:
            positions, place = self.place(rules, positions, on, reference, targets)
        colour = None
        if phase == "colour":
            colour, _ = self.nominate(positions, on, reference, targets)
            if colour is not None:
                targets = [colour]
        self._targets = targets
        shot, _, action = self.ghost.best_shot(positions, on, reference)
        if action is None:
            self._targets = [j for j in range(1, on.shape[0]) if reference[j]]
            action = self.ghost._fallback(positions, on, reference)
            colour = self._nearest(positions) if phase == "colour" else None
            self.last_plan = {"kind": "fallback", "colour": colour}
        else:
            traced = self.ghost.last_traced if shot is None else None  # a bank (spin envs)
            ball = shot.ball if shot is not None else (traced.ball if traced else None)
            if phase == "colour" and ball is not None and ball >= COLOURS[0]:
                colour = ball  # the colour struck: the nominated one, or a bank's
            self.last_plan = {"kind": "ghost", "shot": shot, "colour": colour}
        self.last_plan["cue"] = positions[0].copy()  # placed, with the cue ball in hand
        return snooker_action(self.config, action, place, colour)

    def balls_on(
        self, rules: ShotConstraints, phase: str, on: NDArray[np.bool_]
    ) -> tuple[list[int], NDArray[np.bool_]]:
        """The balls it pots (reds only on a red: no free ball) and the aim's reference.

        The reference is every ball the rules let the cue ball hit first (the env's cut aim
        refers to the nearest of them).
        """
        first = list(rules.first_balls)
        reference = np.zeros_like(on)
        reference[first] = on[first]
        reference[0] = on[0]
        targets = [j for j in first if j < COLOURS[0]] if phase == "red" else first
        return (targets or first), reference

    def best_pot(
        self,
        positions: NDArray[np.float64],
        on: NDArray[np.bool_],
        reference: NDArray[np.bool_],
        ball: int,
    ) -> float:
        """The pot chance of ``ball``'s most forgiving playable pot (0: none)."""
        self._targets = [ball]
        shot, _, action = self.ghost.easiest_shot(positions, on, reference)
        if shot is None or action is None:
            return 0.0
        return pot_chance(shot.tolerance, self.sigma)

    def nominate(
        self,
        positions: NDArray[np.float64],
        on: NDArray[np.bool_],
        reference: NDArray[np.bool_],
        colours: list[int],
    ) -> tuple[int | None, float]:
        """The colour to nominate and its worth: the most points on average.

        Each colour's worth is its value times the chance of its most forgiving playable
        pot (:meth:`best_pot`); a tie goes to the higher value. ``(None, 0.0)`` when no
        colour has a pot.
        """
        best: tuple[float, int] | None = None
        for c in colours:
            worth = ball_value(c) * self.best_pot(positions, on, reference, c)
            if worth > 0.0 and (best is None or (worth, c) > best):
                best = (worth, c)
        return (None, 0.0) if best is None else (best[1], best[0])

    def worth(
        self,
        positions: NDArray[np.float64],
        on: NDArray[np.bool_],
        reference: NDArray[np.bool_],
        targets: list[int],
    ) -> float:
        """The best pot's worth among ``targets``: ``value x chance`` (a red's value 1)."""
        if targets and targets[0] >= COLOURS[0]:
            return self.nominate(positions, on, reference, targets)[1]
        self._targets = targets
        shot, _, action = self.ghost.easiest_shot(positions, on, reference)
        if shot is None or action is None:
            return 0.0
        return ball_value(shot.ball) * pot_chance(shot.tolerance, self.sigma)

    def placements(
        self,
        rules: ShotConstraints,
        positions: NDArray[np.float64],
        on: NDArray[np.bool_],
        reference: NDArray[np.bool_],
        targets: list[int],
    ) -> list[tuple[float, NDArray[np.float64]]]:
        """The cue ball in hand's points of the D with their worth, the best first.

        Each candidate (:meth:`TheD.candidates`) with the worth of its best pot
        (:meth:`worth`), then the D's middle (worth 0: the point when none has a pot).
        """
        d = TheD.of(rules)
        table = self.config.table
        trial = positions.copy()
        out = []
        for point in d.candidates(positions, on, targets, table.pockets, table.ball_radius):
            trial[0] = point
            out.append((self.worth(trial, on, reference, targets), point))
        out.sort(key=lambda item: -item[0])
        return out + [(0.0, np.array([d.baulk_x - 0.5 * d.radius, d.centre_y]))]

    def place(
        self,
        rules: ShotConstraints,
        positions: NDArray[np.float64],
        on: NDArray[np.bool_],
        reference: NDArray[np.bool_],
        targets: list[int],
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """The cue ball in hand's point of the D: ``(positions with it there, action[2:4])``.

        The best of :meth:`placements`.
        """
        self.last_places = self.placements(rules, positions, on, reference, targets)
        best = self.last_places[0][1]
        placed = positions.copy()
        placed[0] = best
        return placed, self.place_components(best)

    def place_components(self, point: NDArray[np.float64]) -> NDArray[np.float64]:
        """``action[2:4]`` that put the cue ball in hand on ``point`` (the env's codec)."""
        return np.array(encode_placement(self.config, point, clip=True))

    def _nearest(self, positions: NDArray[np.float64]) -> int | None:
        """The nearest ball the fallback's full hit aims at, nominated if it is a colour."""
        balls = self._targets
        if not balls:
            return None
        j = min(balls, key=lambda b: float(np.hypot(*(positions[b] - positions[0]))))
        return j if j >= COLOURS[0] else None
