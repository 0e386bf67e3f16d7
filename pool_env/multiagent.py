"""Two players at one table under the rules (PettingZoo AEC), and one against a fixed policy.

:class:`VersusPolicyEnv` is the single-agent Gymnasium env against a fixed opponent.

``PoolDuelEnv(game="nine" | "eight")``: ``player_0`` breaks; the players alternate as
:func:`pool_env.game.wpa.judge` decides (a player keeps the table after a legal shot that
pots, the opponent comes to the table after a miss or a foul, with ball in hand after a
foul). The rack ends with a win (+1 to the winner, -1 to the loser) or is truncated after
``max_shots`` shots (0 to both).

Action (``Box(-1, 1, (5,))``, every component mapped linearly):

| Num | Action | -1 .. +1 maps to | used |
|-----|--------|------------------|------|
| 0 | aim | -pi .. pi, radians from the table's +x axis | always |
| 1 | speed | ``speed_range`` (m/s) | always |
| 2 | cue ball x | ``R .. L - R`` | only with the cue ball in hand |
| 3 | cue ball y | ``R .. W - R`` | only with the cue ball in hand |
| 4 | called pocket | pockets 0..5, in six equal slices | only when shooting at the 8 |

A placement that is not free (on a ball, in a pocket, ahead of the head string when the
rules ask for behind it) is moved to the nearest free point
(:func:`pool_env.game.placement.nearest_free_point`). The break is played with the cue ball
in hand behind the head string.

Observation of each agent (``Box(-1, 1)``): per ball ``x, y`` scaled to ``[-1, 1]`` and
on-table flag (0 for a potted ball, whose coordinates are 0), then: the cue ball in hand,
behind the head string only, the next shot is the break, the ball on (9-ball: its number
/ 15; 8-ball: 1 when on the 8), the observer's group and the opponent's (8-ball: 0 open,
0.5 solids, 1 stripes), the observer's and the opponent's successive fouls / 2, and
whether the observer is the one to shoot. Everything the rules read is there: the game is
Markov in this observation.

This front has its own small action decoding (absolute aim, no execution noise options
beyond ``noise``); it will run on the decision process of :mod:`pool_env.game` once that
carries the rules.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import replace
from typing import Any, ClassVar

import gymnasium as gym
import numpy as np
from gymnasium import spaces
from numpy.typing import NDArray
from pettingzoo import AECEnv

from pool_env.game.placement import nearest_free_point, respot_point
from pool_env.game.wpa import N_BALLS, RackState, Verdict, judge, outcome_of
from pool_env.sim.layouts import break_scene, foot_spot, head_spot
from pool_env.sim.simulate import shoot, simulate
from pool_env.sim.table import Table

AGENTS = ("player_0", "player_1")
N_RULE_FEATURES = 9


class PoolDuelEnv(AECEnv):
    """Two agents play one rack of 9-ball or 8-ball (see the module docstring).

    Args:
        game: ``"nine"`` or ``"eight"``.
        table: The table (default ``Table()``).
        speed_range: Cue ball speeds (m/s) for action[1] = -1 and +1.
        noise: Optional execution noise ``(sigma_angle, sigma_speed)`` (rad, m/s), drawn
            from the generator seeded by ``reset(seed=...)``.
        max_shots: Shots after which the rack is truncated.

    Raises:
        ValueError: On an unknown game, a bad speed range, noise or shot limit.
    """

    metadata: ClassVar[dict[str, Any]] = {
        "render_modes": [],
        "name": "pool_duel_v0",
        "is_parallelizable": False,
    }

    def __init__(
        self,
        game: str = "nine",
        table: Table | None = None,
        speed_range: tuple[float, float] = (0.5, 10.0),
        noise: tuple[float, float] | None = None,
        max_shots: int = 200,
    ) -> None:
        super().__init__()
        if game not in N_BALLS:
            raise ValueError(f"game must be 'nine' or 'eight', got {game!r}")
        lo, hi = (float(v) for v in speed_range)
        if not (math.isfinite(lo) and math.isfinite(hi) and 0.0 <= lo <= hi):
            raise ValueError(f"speed_range must be 0 <= low <= high, got {speed_range!r}")
        if noise is not None and not all(math.isfinite(s) and s >= 0.0 for s in noise):
            raise ValueError(f"noise must be two non-negative sigmas, got {noise!r}")
        if not (isinstance(max_shots, int) and max_shots > 0):
            raise ValueError(f"max_shots must be a positive integer, got {max_shots!r}")
        self.game = game
        self.table = table if table is not None else Table()
        self.speed_range = (lo, hi)
        self.noise = None if noise is None else (float(noise[0]), float(noise[1]))
        self.max_shots = max_shots
        self.possible_agents = list(AGENTS)
        n = N_BALLS[game]
        self._action_space = spaces.Box(-1.0, 1.0, (5,), np.float32)
        self._observation_space = spaces.Box(-1.0, 1.0, (3 * n + N_RULE_FEATURES,), np.float32)
        self.np_random = np.random.default_rng()
        self.positions: NDArray[np.float64] = break_scene(self.table, game)
        self.state_: RackState = RackState.new_rack(game)
        self.last_verdict: Verdict | None = None
        self.shots = 0

    def observation_space(self, agent: str) -> spaces.Box:
        """The observation space (the same for both agents)."""
        return self._observation_space

    def action_space(self, agent: str) -> spaces.Box:
        """The action space (the same for both agents)."""
        return self._action_space

    def reset(self, seed: int | None = None, options: dict[str, Any] | None = None) -> None:
        """Rack the balls; ``player_0`` breaks with the cue ball in hand behind the head string.

        ``options={"positions": (N, 2), "on_table": (N,)}`` starts instead from that layout
        (ball ``k`` in row ``k``, the cue ball on the table), ``player_0`` to shoot, not a
        break, the cue ball where it lies, an open table.

        Raises:
            ValueError: On a malformed or invalid layout (overlap, off the table, in a pocket).
        """
        if seed is not None:
            self.np_random = np.random.default_rng(seed)
        if options and "positions" in options:
            self.positions, on = self._layout(options["positions"], options.get("on_table"))
            self.state_ = RackState(game=self.game, on_table=on, breaking=False)
        else:
            self.positions = break_scene(self.table, self.game)
            self.state_ = replace(
                RackState.new_rack(self.game), ball_in_hand=True, behind_head_string=True
            )
        self.last_verdict = None
        self.shots = 0
        self.agents = list(self.possible_agents)
        self.rewards = {a: 0.0 for a in self.agents}
        self._cumulative_rewards = {a: 0.0 for a in self.agents}
        self.terminations = {a: False for a in self.agents}
        self.truncations = {a: False for a in self.agents}
        self.infos = {a: {} for a in self.agents}
        self.agent_selection = AGENTS[self.state_.shooter]

    def _layout(self, positions: Any, on_table: Any) -> tuple[NDArray[np.float64], tuple]:
        n = N_BALLS[self.game]
        pos = np.array(positions, dtype=np.float64)
        on = np.ones(n, bool) if on_table is None else np.asarray(on_table, dtype=bool)
        if pos.shape != (n, 2) or on.shape != (n,):
            raise ValueError(f"positions must be ({n}, 2) and on_table ({n},) for {self.game}")
        if not on[0]:
            raise ValueError("the cue ball (row 0) must be on the table")
        simulate(self.table, pos[on], np.zeros((int(on.sum()), 2)), record=False)  # validates
        return pos, tuple(bool(b) for b in on)

    def observe(self, agent: str) -> NDArray[np.float32]:
        """The observation of ``agent`` (a fresh array)."""
        s = self.state_
        me = AGENTS.index(agent)
        on = np.asarray(s.on_table, dtype=bool)
        scale = np.array([2.0 / self.table.length, 2.0 / self.table.width])
        xy = (self.positions * scale - 1.0) * on[:, None]
        balls = np.column_stack([xy, on]).reshape(-1)
        ball_on = s.ball_on
        on_feature = 0.0 if ball_on is None else (ball_on / 15.0 if self.game == "nine" else 1.0)
        rules = [
            float(s.ball_in_hand),
            float(s.behind_head_string),
            float(s.breaking),
            on_feature,
            s.groups[me] / 2.0,
            s.groups[1 - me] / 2.0,
            min(s.fouls[me], 2) / 2.0,
            min(s.fouls[1 - me], 2) / 2.0,
            float(s.shooter == me),
        ]
        return np.clip(np.concatenate([balls, rules]), -1.0, 1.0).astype(np.float32)

    def step(self, action: NDArray[np.float32] | None) -> None:
        """Play the selected agent's shot (or remove a finished agent, as AEC requires)."""
        agent = self.agent_selection
        if self.terminations[agent] or self.truncations[agent]:
            self._was_dead_step(action)
            return
        a = np.asarray(action, dtype=np.float64).reshape(-1)
        if a.shape != (5,) or np.any(np.isnan(a)):
            raise ValueError(f"action must be 5 numbers in [-1, 1], got {action!r}")
        a = np.clip(a, -1.0, 1.0)
        state = self.state_
        if state.ball_in_hand:
            self._place_cue_ball(a[2], a[3], state.behind_head_string)
        angle, speed = self._shot(a[0], a[1])
        numbers = np.flatnonzero(np.asarray(state.on_table))
        result = shoot(self.table, self.positions[numbers], angle, speed, record=False)
        self.positions[numbers] = result.positions
        called = min(int((a[4] + 1.0) / 2.0 * self.table.n_pockets), self.table.n_pockets - 1)
        outcome = outcome_of(result, numbers)
        verdict, after = judge(state, outcome, called)
        self._respot(verdict.respot, after, outcome.scratch)
        self.state_ = after
        self.last_verdict = verdict
        self.shots += 1
        self._clear_rewards()
        self._cumulative_rewards[agent] = 0.0
        info = {
            "foul": verdict.foul,
            "legal": verdict.legal,
            "ball_on": verdict.ball_on,
            "scratch": outcome.scratch,
            "potted": outcome.potted,
            "winner": None if after.winner is None else AGENTS[after.winner],
        }
        self.infos = {a_: dict(info) for a_ in self.agents}
        if after.winner is not None:
            for k, name in enumerate(AGENTS):
                self.rewards[name] = 1.0 if k == after.winner else -1.0
                self.terminations[name] = True
        elif self.shots >= self.max_shots:
            self.truncations = {name: True for name in self.agents}
        self.agent_selection = AGENTS[after.shooter]
        self._accumulate_rewards()

    def _shot(self, aim: float, power: float) -> tuple[float, float]:
        lo, hi = self.speed_range
        angle = math.pi * aim
        speed = lo + (power + 1.0) / 2.0 * (hi - lo)
        if self.noise is not None:
            angle += self.noise[0] * self.np_random.standard_normal()
            speed = max(0.0, speed + self.noise[1] * self.np_random.standard_normal())
        return angle, speed

    def _place_cue_ball(self, ax: float, ay: float, behind: bool) -> None:
        r = self.table.ball_radius
        target = (r + (ax + 1.0) / 2.0 * (self.table.length - 2 * r),
                  r + (ay + 1.0) / 2.0 * (self.table.width - 2 * r))  # fmt: skip
        others = np.asarray(self.state_.on_table, dtype=bool).copy()
        others[0] = False
        self.positions[0] = nearest_free_point(
            self.table, self.positions, others, target, behind_head_string=behind
        )

    def _respot(self, balls: tuple[int, ...], after: RackState, scratch: bool) -> None:
        """Put re-spotted balls back (foot spot or behind it) and a scratched cue ball out.

        The scratched cue ball goes to the free point nearest the head spot: it is in hand,
        so the next shooter places it anyway.
        """
        on = np.asarray(after.on_table, dtype=bool).copy()
        for ball in balls:
            on[ball] = False
            self.positions[ball] = respot_point(
                self.table, self.positions, on, foot_spot(self.table)
            )
            on[ball] = True
        if scratch:
            on[0] = False
            self.positions[0] = nearest_free_point(
                self.table, self.positions, on, head_spot(self.table)
            )

    def render(self) -> None:
        """No rendering in this front (``render_modes`` is empty)."""

    def close(self) -> None:
        """Nothing to release."""


Policy = Callable[[NDArray[np.float32]], NDArray[np.float32]]


class VersusPolicyEnv(gym.Env[NDArray[np.float32], NDArray[np.float32]]):
    """One agent against a fixed opponent policy, as a single-agent Gymnasium env.

    The agent is ``player_0`` of a :class:`PoolDuelEnv` (so it breaks); after each of its
    shots the opponent plays its own shots (``opponent(observation) -> action``) until the
    table comes back or the rack ends. Reward: +1 for a won rack, -1 for a lost one, 0
    otherwise; the episode terminates when the rack is decided and is truncated after
    ``max_shots`` shots of both players. ``info`` is that of the agent's own shot (the
    keys of :class:`PoolDuelEnv`), plus ``opponent_shots``.

    Args:
        opponent: The opponent's policy (default: uniformly random actions from the env's
            generator).
        **kwargs: :class:`PoolDuelEnv` arguments.
    """

    metadata: ClassVar[dict[str, Any]] = {"render_modes": []}

    def __init__(self, opponent: Policy | None = None, **kwargs: Any) -> None:
        self.duel = PoolDuelEnv(**kwargs)
        self.opponent = opponent
        self.action_space = self.duel.action_space(AGENTS[0])
        self.observation_space = self.duel.observation_space(AGENTS[0])

    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[NDArray[np.float32], dict[str, Any]]:
        """Rack (or set up ``options``' layout) and return the agent's first observation."""
        super().reset(seed=seed)
        self.duel.reset(seed=None if seed is None else int(self.np_random.integers(2**31)),
                        options=options)  # fmt: skip
        self._opponent_plays()
        return self.duel.observe(AGENTS[0]), {}

    def step(
        self, action: NDArray[np.float32]
    ) -> tuple[NDArray[np.float32], float, bool, bool, dict[str, Any]]:
        """The agent's shot, then the opponent's until the agent is back at the table."""
        if self._over():
            raise ValueError("the rack is over: call reset()")
        self.duel.step(action)
        info = dict(self.duel.infos[AGENTS[0]])
        info["opponent_shots"] = self._opponent_plays()
        return (
            self.duel.observe(AGENTS[0]),
            float(self.duel.rewards[AGENTS[0]]),
            bool(self.duel.terminations[AGENTS[0]]),
            bool(self.duel.truncations[AGENTS[0]]),
            info,
        )

    def _over(self) -> bool:
        duel = self.duel
        return duel.terminations[AGENTS[0]] or duel.truncations[AGENTS[0]]

    def _opponent_plays(self) -> int:
        shots = 0
        while self.duel.agent_selection == AGENTS[1] and not self._over():
            obs = self.duel.observe(AGENTS[1])
            if self.opponent is None:
                action = self.np_random.uniform(-1.0, 1.0, 5).astype(np.float32)
            else:
                action = np.asarray(self.opponent(obs), dtype=np.float32)
            self.duel.step(action)
            shots += 1
        return shots
