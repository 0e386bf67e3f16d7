"""ThreeCushionSearchAgent: the three-cushion search played through an env's action.

The env is ``pool_env/ThreeCushion-v1`` (or a duel's ``game="three_cushion"``), wrapped or
not. Each ``predict`` reads the layout (the env's exact state when it matches the
observation), asks the game's rules who shoots and whether it is the break
(:func:`pool_env.shot_constraints`: yellow's cue ball when its first balls are white and
red; the break's red), plans with :class:`~agents.baselines.three_cushion_search.
ThreeCushionSearch` under the env's own noise, speed range and tip limit, and writes the
shot as the env's action (:func:`pool_env.encode_action`). In an aim mode other than
``"absolute"`` (the id's default is ``"cut"``: the cue ball goes at the nearest ball) only
the shots the aim can express are chosen (:func:`pool_env.game.codec.encode_shots`'s
``playable``).
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from agents.baselines.base import BaselineAgent, LayoutSource, env_spec
from agents.baselines.three_cushion_search import CaromPlan, ThreeCushionSearch
from pool_env import Shot, encode_action, shot_constraints
from pool_env.game.codec import encode_shots
from pool_env.game.formulas import decode_on_layout

__all__ = ["ThreeCushionSearchAgent"]

#: The game the agent plays.
GAME = "three_cushion"
#: The red: the break's first ball.
RED = 2


class ThreeCushionSearchAgent(BaselineAgent):
    """SB3's ``predict`` over :class:`ThreeCushionSearch` on a three-cushion env.

    Args:
        env: The env (``gym.Env``, wrapped or not) of the game ``"three_cushion"``.
        budget: Search seconds per shot.
        threads: Threads of the search's rollouts.
        seed: Seed of the search's noise draws.

    Raises:
        ValueError: If the env is not a three-cushion env (or on the search's settings).
    """

    def __init__(self, env: Any, budget: float = 1.0, threads: int = 2, seed: int = 0) -> None:
        spec = env_spec(env)
        config = spec.config
        name = getattr(config.ruleset, "name", None)
        if name != GAME:
            raise ValueError(f"the three-cushion agent plays game={GAME!r}, not {name!r}")
        self.config = config
        self.env = env
        self.layouts = LayoutSource(env, config.table, config.n_balls)
        self.search = ThreeCushionSearch(
            config.table,
            noise=config.noise,
            budget=budget,
            threads=threads,
            speed_range=config.speed_range,
            tip_limit=config.tip_limit,
            seed=seed,
        )
        self.last_plan: dict[str, Any] = {}

    def act(self, observations: NDArray[np.floating]) -> NDArray[np.float32]:
        """One planned action per observation."""
        out = np.zeros((observations.shape[0], self.config.action_size), dtype=np.float32)
        for k, (positions, on_table) in enumerate(self.layouts.layouts(observations)):
            rules = shot_constraints(self.config, observations[k])
            cue = 1 if 1 not in rules.first_balls and 0 in rules.first_balls else 0
            first = RED if rules.breaking else None
            own, refer = self._own_layout(positions, on_table, cue, first)
            self.search.playable = self._playable(own, refer)
            plan = self.search.plan(positions, cue, first, self._window(own, refer))
            out[k] = self._action(plan, positions, on_table)
            self.last_plan = {"kind": plan.kind, "cue": cue, "plan": plan}
        return out

    @staticmethod
    def _own_layout(
        positions: NDArray[np.float64], on_table: NDArray[np.bool_], cue: int, first: int | None
    ) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        """The layout as the codec reads it, and the balls its aim refers to.

        The striker's cue ball goes in column 0; on the break the aim refers to the red alone.
        """
        own = positions.copy()
        own[[0, cue]] = own[[cue, 0]]
        refer = on_table.copy()
        if first is not None:
            refer[:] = False
            refer[first] = True
        return own, refer

    def _window(self, own: NDArray[np.float64], refer: NDArray[np.bool_]) -> Any:
        """The directions the aim reaches, or ``None`` under absolute aim (all round).

        The env's own decoding of aim -1 and +1.
        """
        if self.config.aim == "absolute":
            return None
        ends = np.zeros((2, self.config.action_size))
        ends[:, 0] = (-1.0, 1.0)
        (lo, hi), _ = decode_on_layout(self.config, ends, own, refer)
        return (float(lo), float(lo + (hi - lo) % (2.0 * np.pi)))

    def _playable(self, own: NDArray[np.float64], refer: NDArray[np.bool_]) -> Any:
        """The aim mode's filter of shot rows (``None`` under absolute aim: all play)."""
        if self.config.aim == "absolute":
            return None

        def playable(rows: NDArray[np.float64]) -> NDArray[np.bool_]:
            _, ok = encode_shots(
                self.config, own[None], refer[None], rows[None, :, 0], rows[None, :, 1],
                rows[None, :, 2:4],
            )  # fmt: skip
            return ok[0]

        return playable

    def _action(
        self, plan: CaromPlan, positions: NDArray[np.float64], on_table: NDArray[np.bool_]
    ) -> NDArray[np.float32]:
        """The env's action for ``plan``, on the env's own rack when the layout is its own."""
        rack = getattr(self.env.unwrapped, "rack", None)
        shot = Shot(angle=plan.angle, speed=plan.speed, tip=plan.tip)
        try:
            action = encode_action(self.config, shot, positions, on_table, rack=rack, clip=True)
        except ValueError:
            action = encode_action(self.config, shot, positions, on_table, clip=True)
        return action.astype(np.float32)
