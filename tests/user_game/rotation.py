"""Rotation practice: pot the balls in order, one player, a foul ends the rack.

A complete game of its own, written against ``pool_env``'s public game interface only
(``docs/own_game.md`` walks through it): its rules section, its reward terms, its rule,
its ``info`` keys and its id.

The rule: the cue ball must first hit the lowest-numbered ball on the table. A shot that
does so without scratching is clean, and every ball it pots scores; a shot that hits
another ball first, hits nothing, or scratches is a foul, which scores the ``foul``
term and, with ``end_on_foul`` (the default), ends the episode. The rack is won when
the table is cleared.
"""

from __future__ import annotations

from dataclasses import dataclass

import gymnasium as gym
import numpy as np
from numpy.typing import NDArray

from pool_env.game.registry import register_game
from pool_env.game.ruleset import (
    CLEARED,
    FIRST_BALL,
    N_FLAGS,
    N_HITS,
    POTTED_BITS,
    SCRATCH,
    TERMINATED,
    TRUNCATED,
    Executed,
    Judged,
    Outcome,
    Ruleset,
    RulesSection,
    Setup,
    Turn,
    settle_shots,
)
from pool_env.sim import Table
from pool_env.sim.layouts import break_scene


@dataclass(frozen=True)
class RotationRules(RulesSection):
    """The rules section: ``gym.make(..., end_on_foul=False)`` plays on after a foul.

    Attributes:
        game: ``"rotation"``.
        end_on_foul: A foul ends the episode.
    """

    game: str = "rotation"
    end_on_foul: bool = True


def rotation_rack(table: Table, rng: np.random.Generator) -> NDArray[np.float64]:
    """The game's own scene: the 9-ball rack, the cue ball anywhere in the kitchen."""
    layout = break_scene(table, "nine")
    margin = 2 * table.ball_radius  # off the rails
    x = rng.uniform(margin, table.length / 4)
    layout[0] = (x, rng.uniform(margin, table.width - margin))
    return layout


#: The game's own scenes, by name.
SCENES = {"rotation_rack": rotation_rack}

#: The reward terms and their default scales: ``reward_pot=...``, ``reward_foul=...``.
REWARD_TERMS = {"pot": 1.0, "foul": -1.0}

#: The judge's integer result columns after the shared ones: the ball on before the
#: shot, and whether the shot was a foul.
BALL_ON, FOUL = N_HITS, N_HITS + 1


class Rotation(Ruleset):
    """Rotation practice (``game="rotation"``)."""

    name = "rotation"
    section = RotationRules
    reward_terms = REWARD_TERMS
    info_keys = ("foul", "ball_on")
    scenes = SCENES  # ``scene="rotation_rack"`` on its tables

    def configure(self, setup: Setup) -> NDArray[np.float64]:
        """One player on a table with pockets; the rule needs no kernel parameters."""
        if setup.players != 1:
            raise ValueError("rotation practice has one player")
        if setup.table.n_pockets == 0:
            raise ValueError("rotation practice needs a table with pockets")
        if not isinstance(setup.rules.end_on_foul, bool):  # type: ignore[attr-defined]
            raise ValueError("end_on_foul must be a bool")
        return super().configure(setup)

    def judge(self, turn: Turn, out: Outcome, executed: Executed) -> Judged:
        """The rule above, on every table that shot (numpy: no compiled code needed)."""
        config, state, tables = turn
        before = state.on_table[tables]
        ball_on = np.argmax(before[:, 1:], axis=1) + 1  # the lowest object ball on
        settled = settle_shots(turn, out)  # balls moved, potted ones off, shot counted
        foul = settled.scratch | (settled.first != ball_on)
        pots = settled.potted[:, 1:].sum(axis=1)
        scales = config.rewards
        pot = np.where(foul | (pots == 0), 0.0, scales["pot"] * pots)
        penalty = np.where(foul, scales["foul"], 0.0)
        values = np.stack([pot + penalty, pot, penalty], axis=1)
        cleared = ~state.on_table[tables, 1:].any(axis=1)
        flags = np.zeros((tables.size, N_FLAGS), dtype=np.bool_)
        flags[:, TERMINATED] = cleared | (foul & config.rules.end_on_foul)
        limit = config.shot_limit
        flags[:, TRUNCATED] = (limit > 0) & (state.shots[tables] >= limit)
        flags[:, CLEARED] = cleared
        flags[:, SCRATCH] = settled.scratch
        hits = np.zeros((tables.size, N_HITS + 2), dtype=np.int64)
        hits[:, POTTED_BITS], hits[:, FIRST_BALL] = settled.bits, settled.first
        hits[:, BALL_ON], hits[:, FOUL] = ball_on, foul
        return Judged(values, flags, hits)

    def info_columns(self, hits: NDArray[np.int64]) -> dict[str, NDArray[np.generic]]:
        """``foul``: the shot was a foul; ``ball_on``: the ball it had to hit first."""
        return {"foul": hits[:, FOUL] != 0, "ball_on": hits[:, BALL_ON]}


#: The game, registered: ``gym.make("pool_env/NineBall-v1", game="rotation")`` plays it.
GAME = register_game(Rotation())

#: Its own id: its rack on the spin table, 30 shots at most.
ID = "my_games/Rotation-v0"
if ID not in gym.registry:
    gym.register(
        ID, entry_point="pool_env:PoolEnv", max_episode_steps=30,
        kwargs={"game": "rotation", "scene": "rotation_rack", "model": "spin"},
    )  # fmt: skip
