"""The baselines under the rules of the game ids: ghost-ball and search, 9-ball, 10-ball, 8-ball.

Both read the rules from the observation (the balls they may hit first, ball in hand,
behind the head string, the break, the push-out and the option), place the cue ball in
hand the same way, break the same way and make the rules' other choices the same way
(:mod:`agents.baselines.rule_play`: 10-ball's calls, the option, the push-out); they
differ in how they choose the shot: :class:`GameGhostBallAgent` in closed form
(:class:`agents.baselines.ghost_ball.GhostBallAgent`, position play with the tip on a spin
env), :class:`GameSearchAgent` by checking candidates on the simulator
(:class:`agents.baselines.search.SearchAgent`, judged by the rules: a legal first contact,
the ball on or the group, the 8 only when it is on).
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from agents.baselines.aiming import shot_to_action
from agents.baselines.base import BaselineAgent
from agents.baselines.ghost_ball import ARRIVAL_SPEED, MIN_SIGMA, GhostBallAgent
from agents.baselines.rule_play import (
    ROTATION,
    may_push,
    push_outcomes,
    push_value,
    rule_action,
    take_table,
)
from agents.baselines.search import SearchAgent, Shot
from agents.baselines.spin_play import pot_chance
from pool_env import ShotConstraints, ShotResult, obs_layout, shot_constraints
from pool_env.game.codec import encode_placement
from pool_env.game.config import GameConfig
from pool_env.game.geometry import points_free

#: Distances (m) behind the ghost-ball point where a cue ball in hand is tried: a
#: straight-in shot from close enough to aim well, far enough to follow through.
PLACE_DISTANCES = (0.12, 0.25, 0.45)


class RulesGhostBase(BaselineAgent):
    """The ghost-ball planner restricted to the balls the rules allow.

    What every game's ghost-ball agent shares (the WPA games' here, snooker's in
    :mod:`agents.baselines.snooker_play`).
    A subclass sets ``self._targets`` (the legal first balls) before it asks ``self.ghost``
    for a shot, and plans one table in :meth:`_plan`.
    """

    def _start(self, env: Any, config: GameConfig, arrival_speed: float, spin: bool) -> None:
        self.config: GameConfig = config
        self.ghost = GhostBallAgent(
            env, arrival_speed, self._legal, spin=spin, next_targets=self._next_legal
        )
        self._targets: list[int] = []
        self.last_plan: dict[str, Any] = {}

    def _legal(self, positions: NDArray[np.float64], on_table: NDArray[np.bool_]) -> list[int]:
        return [j for j in self._targets if on_table[j]]

    def _next_legal(
        self, positions: NDArray[np.float64], after: NDArray[np.bool_], potted: int
    ) -> list[int]:
        """The legal balls once ``potted`` drops (``after``: the balls left).

        The game's :meth:`~pool_env.game.ruleset.Ruleset.first_balls_after`.
        """
        return list(self.config.ruleset.first_balls_after(after, potted))

    def act(self, observations: NDArray[np.floating]) -> NDArray[np.float32]:
        """The planned actions: ``(B, config.action_size)`` (the tip last on a spin env)."""
        balls = obs_layout(self.config)["balls"]
        layouts = self.ghost.source.layouts(np.ascontiguousarray(observations[:, balls]))
        pairs = zip(observations, layouts, strict=True)
        out = [self._plan(obs, pos, on) for obs, (pos, on) in pairs]
        return np.stack(out).astype(np.float32)

    def _plan(
        self, obs: NDArray[np.floating], positions: NDArray[np.float64], on: NDArray[np.bool_]
    ) -> NDArray[np.float64]:
        raise NotImplementedError


class GameGhostBallAgent(RulesGhostBase):
    """The ghost-ball heuristic under the rules of the game ids (9-ball, 10-ball, 8-ball).

    It reads the rules from the observation (the balls it may hit first, ball in hand,
    behind the head string, the break) and plays :class:`GhostBallAgent`'s most forgiving
    shot on those balls only: the ball on (9-ball, 10-ball), its group (8-ball; any ball but
    the 8 on an open table), the 8 once the group is cleared, with the called pocket set to
    the shot's pocket and, in 10-ball, the called ball to the ball it pots (its planners pot
    the ball they hit first, which the rules make the ball on). With the cue ball in hand it
    tries straight-in placements (:data:`PLACE_DISTANCES` behind the ghost-ball point of
    each legal ball and pocket, inside the allowed region and clear of the balls) and keeps
    the one whose best shot forgives the most. The break: the cue ball on the head spot, a
    full hit on the nearest legal ball at the top of the break speed range.

    With the option it plays on or hands the table back, and on the shot after a legal
    break (against an opponent) it may push out, both by the layout's best pot chance
    (:meth:`best_chance`) as :mod:`agents.baselines.rule_play` decides.

    Args:
        env: A game-id environment (``gym.make("pool_env/NineBallGameRoll-v2")``, wrapped or not).
        arrival_speed: As :class:`GhostBallAgent`.
        spin: On a spin env, whether to use the tip (else centre ball).
        players: 2 when it plays against an opponent (the push-out is then worth playing),
            ``None``: the env's (``config.players``; the duel fronts build their agents on
            the one-player id and pass 2).
    """

    #: ``last_plan["kind"]`` of a planned shot.
    KIND = "ghost"

    def __init__(
        self,
        env: Any,
        arrival_speed: float = ARRIVAL_SPEED,
        spin: bool = True,
        players: int | None = None,
    ) -> None:
        config = env.unwrapped.config
        if not config.ruleset.has_rack:
            raise ValueError("GameGhostBallAgent plays the game ids (game='nine', 'ten', 'eight')")
        self.players = config.players if players is None else int(players)
        if self.players not in (1, 2):
            raise ValueError(f"players must be 1 or 2, got {players!r}")
        self._start(env, config, arrival_speed, spin)
        self._chosen: Any = None

    def _plan(
        self, obs: NDArray[np.floating], positions: NDArray[np.float64], on: NDArray[np.bool_]
    ) -> NDArray[np.float64]:
        rules = shot_constraints(self.config, obs)
        in_hand, behind, breaking = rules.ball_in_hand, rules.behind_head_string, rules.breaking
        self._targets = list(rules.first_balls)
        reference = np.zeros_like(on)
        reference[0] = on[0]
        reference[self._targets] = on[self._targets]
        place = np.zeros(2)
        table = self.config.table
        if breaking:
            place = self._place_action(np.array([table.length / 4.0, table.width / 2.0]), behind)
            positions = positions.copy()
            positions[0] = table.length / 4.0, table.width / 2.0
            action = self.ghost._fallback(positions, on, reference)
            action[1] = 1.0  # the top of the break speed range
            self.last_plan = {"kind": "break"}
            return rule_action(self.config, action, place, ball=self._ball_on())
        if in_hand:
            positions, place = self._place(positions, on, reference, behind)
        declared = self._option_or_push(rules, positions, on, reference)
        if declared is not None:
            return declared
        called, action = self._choose(positions, on, reference)
        if action is None:
            action = self.ghost._fallback(positions, on, reference)
            self.last_plan = {"kind": "fallback", "in_hand": in_hand}
            called = -1
        else:
            self.last_plan = {
                "kind": self.KIND,
                "shot": self._chosen,
                "pocket": called,
                "in_hand": in_hand,
            }
        return rule_action(self.config, action, place, called, self._ball_on())

    def _ball_on(self) -> int | None:
        """The ball a rotation game's shot calls: the lowest legal ball (10-ball's ball on).

        The planners here pot the ball they hit first (direct pots, banks; no combinations),
        and 10-ball's rules let it be the ball on only.
        """
        if self.config.game not in ROTATION:
            return None
        return min(self._targets, default=1)  # none legal: a decided rack, any call

    def best_chance(
        self, positions: NDArray[np.float64], on: NDArray[np.bool_], reference: NDArray[np.bool_]
    ) -> float:
        """The layout's best pot chance: the most forgiving shot on a legal ball, under noise.

        What the option and the push-out are decided by (:mod:`agents.baselines.rule_play`):
        the chance of the roll level's easiest shot that does not scratch
        (:meth:`GhostBallAgent.easiest_shot`), 0 when there is none.
        """
        shot, _, action = self.ghost.easiest_shot(positions, on, reference)
        if shot is None or action is None:
            return 0.0
        return pot_chance(shot.tolerance, self._sigma())

    def _sigma(self) -> float:
        """The aim noise (rad) pot chances are taken at: the env's, at least MIN_SIGMA."""
        noise = self.ghost.spec.noise
        return max(float(noise[0]) if noise else 0.0, MIN_SIGMA)

    def _option_or_push(
        self,
        rules: ShotConstraints,
        positions: NDArray[np.float64],
        on: NDArray[np.bool_],
        reference: NDArray[np.bool_],
    ) -> NDArray[np.float64] | None:
        """The action that hands the table back or pushes out, ``None`` to shoot.

        With the option: hand back when the best pot chance is below
        :data:`~agents.baselines.rule_play.TAKE_CHANCE`. On a push-out shot (with an
        opponent): push when the best roll's :func:`~agents.baselines.rule_play.push_value`
        beats that chance.
        """
        pushing = rules.push_out and may_push(self.config, self.players)
        if not (rules.option or pushing):
            return None
        chance = self.best_chance(positions, on, reference)
        if rules.option and not take_table(chance):
            self.last_plan = {"kind": "hand back", "chance": chance}
            return rule_action(self.config, np.zeros(2), ball=self._ball_on(), option=True)
        if not pushing:
            return None
        best: tuple[float, NDArray[np.float32]] | None = None
        targets = self._targets
        for push in push_outcomes(self.config, positions, on, min(targets)):
            strike = shot_to_action(push.angle, push.speed, positions, reference, self.ghost.spec)
            if strike is None:
                continue  # the aim mode cannot play it
            # The opponent's view of the leave: the ball on then (the lowest left).
            self._targets = list(self.config.ruleset.first_balls_after(push.on_table, -1))
            seen = np.zeros_like(push.on_table)
            seen[0] = True
            seen[self._targets] = True
            value = push_value(self.best_chance(push.positions, push.on_table, seen))
            self._targets = targets
            if best is None or value > best[0]:
                best = (value, strike)
        if best is None or best[0] <= chance:
            return None
        self.last_plan = {"kind": "push out", "chance": chance, "value": best[0]}
        return rule_action(self.config, best[1], ball=self._ball_on(), option=True)

    def _choose(
        self, positions: NDArray[np.float64], on: NDArray[np.bool_], reference: NDArray[np.bool_]
    ) -> tuple[int, NDArray[np.float32] | None]:
        """The shot to play: ``(called pocket or -1, action)``; action ``None``: no shot."""
        shot, _, action = self.ghost.best_shot(positions, on, reference)
        self._chosen = shot
        if shot is None and action is not None and self.ghost.last_traced is not None:
            return self.ghost.last_traced.pocket, action  # a bank or carom
        return (-1 if shot is None else shot.pocket), action

    def _place_action(self, point: NDArray[np.float64], behind: bool) -> NDArray[np.float64]:
        """The action components that place the cue ball on ``point`` (the env's codec)."""
        return np.array(encode_placement(self.config, point, behind, clip=True))

    def _place(
        self,
        positions: NDArray[np.float64],
        on: NDArray[np.bool_],
        reference: NDArray[np.bool_],
        behind: bool,
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """The best straight-in placement: ``(positions with the cue ball there, action)``."""
        t = self.config.table
        r = t.ball_radius
        others = [j for j in range(1, on.shape[0]) if on[j]]
        balls = positions[others]
        best, best_tol = positions[0].copy(), -1.0
        trial = positions.copy()
        for b in self._targets:
            for p in range(t.n_pockets):
                d = positions[b] - t.pockets[p, :2]
                u = d / max(float(np.hypot(*d)), 1e-12)
                for dist in PLACE_DISTANCES:
                    point = positions[b] + (2.0 * r + dist) * u
                    if not points_free(t, point[None], balls, behind)[0]:
                        continue  # the game's placement rule
                    # The agent's own margins, wider than the rule's: no touching cue ball.
                    if any(np.hypot(*(positions[j] - point)) < 2.2 * r for j in others):
                        continue
                    if np.any(np.hypot(*(t.pockets[:, :2] - point).T) < t.pockets[:, 2] + r):
                        continue
                    trial[0] = point
                    # The roll level's easiest shot ranks placements (cheap); the spin
                    # planner then plays from the one chosen.
                    shot, _, action = self.ghost.easiest_shot(trial, on, reference)
                    if action is not None and shot is not None and shot.tolerance > best_tol:
                        best, best_tol = point.copy(), shot.tolerance
        placed = positions.copy()
        placed[0] = best
        return placed, self._place_action(best, behind)


#: What a shot that wins the rack (the 9, or the 8 when it is on) is worth to the search.
WIN_VALUE = 10.0


class RulesSearch(SearchAgent):
    """:class:`~agents.baselines.search.SearchAgent` whose shots are judged by the rules.

    Args:
        env: The game-id environment.
        game: The agent whose legal balls (``_targets``) and game it follows.
        seed: Seed of the random fallback search.
    """

    def __init__(self, env: Any, game: GameGhostBallAgent, seed: int | None = 0) -> None:
        super().__init__(env, seed=seed, legal_targets=game._legal)
        self.game = game

    def value(self, result: ShotResult) -> float:
        """The shot by the rules: -1 for a foul, else the pots that keep the table.

        A foul: no legal first contact, a scratch, the 8 too early. Pots: any ball in
        9-ball, the group's in 8-ball, the ball on in 10-ball (the ball the agent calls);
        :data:`WIN_VALUE` for the rack's winning ball (10-ball: the 10 as the ball on).
        """
        rows = self._rows
        legal = set(self.game._targets)
        first = int(result.first_hit[0])
        pocketed = result.pocketed
        if first < 0 or int(rows[first]) not in legal or pocketed[0] >= 0:
            return -1.0
        potted = [int(rows[k]) for k in range(1, len(rows)) if pocketed[k] >= 0]
        config = self.game.config
        money = config.ruleset.money_ball
        if money in potted:
            if money in legal or config.game == "nine":  # 10-ball: the 10 called, as the ball on
                return WIN_VALUE
            return -1.0 if config.game == "eight" else 0.0  # 10-ball: re-spotted, turn over
        if config.game == "nine":
            return float(len(potted))
        return float(sum(b in legal for b in potted))  # the group; 10-ball: the called ball on

    def rank(self, result: ShotResult) -> float:
        """A random action's first key: its value (legal shots first)."""
        return self.value(result)

    def order_key(self, shot: Shot) -> tuple[float, ...]:
        """Replay the easiest potting candidates first: a run-out needs sure pots."""
        return (shot.difficulty,)

    def choice_key(self, shot: Shot) -> tuple[float, ...]:
        """Robustness first (a lucky two-ball pot is worth less than a sure one), then value."""
        return (shot.robustness, shot.value, -shot.difficulty)


class GameSearchAgent(GameGhostBallAgent):
    """The search agent under the rules of the game ids (placement and break as ghost-ball).

    Args:
        env: A game-id environment.
        seed: Seed of the random fallback search.
        players: As :class:`GameGhostBallAgent`.
    """

    KIND = "search"

    def __init__(self, env: Any, seed: int | None = 0, players: int | None = None) -> None:
        super().__init__(env, players=players)
        self.search = RulesSearch(env, self, seed)

    def _choose(
        self, positions: NDArray[np.float64], on: NDArray[np.bool_], reference: NDArray[np.bool_]
    ) -> tuple[int, NDArray[np.float32] | None]:
        self.search.reference = reference
        action = self.search.plan(positions, on)
        shot = self._chosen = self.search.last_plan.get("shot")
        if self.search.last_plan.get("kind") == "search" and shot is not None and shot.value < 0:
            return -1, None  # nothing legal found: the ghost agent's safe full hit instead
        return (-1 if shot is None else shot.pocket), action
