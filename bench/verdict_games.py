"""Our games' verdicts of a :class:`~bench.verdict_shots.Case`, through their envs.

:func:`game_judge` returns ``judge(case, outcome)``: the verdict (the form of
:mod:`bench.verdict_rules`) that our game's own rules give the shot, through a
:class:`pool_env.PoolEnv` of the game on the comparison's table, noise off: reset to the
case's layout and rule state (``options["positions"]``, ``on_table``, ``rules``), the
stroke encoded by :func:`pool_env.game.codec.encode_action` (the nomination too), one
``step``, the verdict read from the step's ``info``.

With ``outcome=None`` the simulator plays the shot (our physics). With an outcome
(pooltool's), the step's simulation is replaced by that outcome for this one call (the
module function :func:`pool_env.game.step._simulate`, patched in a ``with`` block): the
game's own shoot and judge run as in any step, on identical outcomes.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Any

import numpy as np

import pool_env.game.step as game_step
from bench.verdict_outcomes import Summary
from bench.verdict_shots import Case, table_of
from pool_env import PoolEnv
from pool_env.game.codec import encode_action
from pool_env.game.ruleset import Outcome
from pool_env.game.shots import Shot

Judge = Callable[[Case, Summary | None], dict[str, Any]]

#: Speeds the comparison's strokes use lie inside this action range (m/s).
SPEED_RANGE = (0.3, 7.0)
#: Tips: the strokes' lie within 0.5 R.
TIP_LIMIT = 0.6

#: Our snooker phases by the comparison's (``bench.verdict_shots.PHASES``).
SNOOKER_PHASES = {"reds": "red", "colour": "colour", "sequence": "in_order"}


def _outcome(case: Case, summary: Summary, vel: np.ndarray, spins: Any) -> Outcome:
    """The step's ``Outcome`` of ``summary`` (columns: the balls on the table, in order)."""
    balls = np.array(sorted(case.balls), dtype=np.intp)
    col = {int(b): k for k, b in enumerate(balls)}

    def row(name: str, as_column: bool) -> np.ndarray:
        values = [summary.rows[name][int(b)] for b in balls]
        if as_column:
            values = [col[v] if v >= 0 else -1 for v in values]
        return np.array([values], dtype=np.int64)

    first = np.array([[-1, -1]], dtype=np.int64)
    contacts = [e for e in summary.events if e[1] == "ball"]
    if contacts:
        i, j = sorted((col[contacts[0][2]], col[contacts[0][3]]))
        first[0] = (i, j)
    final = np.array([[summary.final[int(b)] for b in balls]], dtype=np.float64)
    return Outcome(
        final=final, pocketed=row("pocketed", False), first=first,
        cushions=row("cushions_after_contact", False), order=row("pocket_order", False),
        n_events=np.array([len(summary.events)]), capped=np.zeros(1, dtype=np.bool_),
        balls=balls, shot=None,
        velocities=vel, spins=spins, second_hit=row("second_hit", True),
        cushions_at_second=row("cushions_at_second", False),
    )  # fmt: skip


@contextmanager
def _given_outcome(case: Case, summary: Summary) -> Iterator[None]:
    """The step's simulator answers ``summary`` for as long as the block runs."""
    real = game_step._simulate

    def fake(table, state, tables, vel, spins, record, parallel):  # type: ignore[no-untyped-def]
        return _outcome(case, summary, vel, spins)

    game_step._simulate = fake  # type: ignore[assignment]
    try:
        yield
    finally:
        game_step._simulate = real  # type: ignore[assignment]


class _GameJudge:
    """One env per game, reset to each case."""

    def __init__(self) -> None:
        self.envs: dict[str, PoolEnv] = {}

    def env(self, game: str) -> PoolEnv:
        if game not in self.envs:
            self.envs[game] = PoolEnv(
                game=game, table=table_of(game), scene=game, noise=None,
                speed_range=SPEED_RANGE, tip_limit=TIP_LIMIT, aim="absolute",
            )  # fmt: skip
        return self.envs[game]

    def __call__(self, case: Case, outcome: Summary | None) -> dict[str, Any]:
        env = self.env(case.game)
        n = 3 if case.game == "three_cushion" else 22
        positions = np.zeros((n, 2))
        on = np.zeros(n, dtype=bool)
        positions[list(case.balls)] = case.positions
        on[list(case.balls)] = True
        free = np.flatnonzero(~on)  # off-table balls: anywhere clear (they are not read)
        positions[free] = case.positions[0]
        if case.game == "three_cushion":
            rules: dict[str, Any] = {"shooter": case.cue}
            ball = None
        else:
            rules = {"phase": SNOOKER_PHASES[case.state["phase"]]}
            ball = case.state["nominated"] if case.state["nominated"] >= 0 else None
        options = {"positions": positions, "on_table": on, "rules": rules}
        env.reset(seed=0, options=options)
        config = env.unwrapped.config
        shot = Shot(angle=case.angle, speed=case.speed, tip=case.tip, ball=ball)
        action = encode_action(config, shot, positions, on, env.unwrapped.rack)
        if outcome is None:
            _, _, _, _, info = env.step(action)
        else:
            with _given_outcome(case, outcome):
                _, _, _, _, info = env.step(action)
        return _verdict(case.game, info)


def _verdict(game: str, info: dict[str, Any]) -> dict[str, Any]:
    if game == "three_cushion":
        return {"point": bool(info["point"])}
    return {
        "foul": info["foul"] is not None,
        "penalty": int(info["penalty"]),
        "points": int(info["points"]),
        "turn_over": bool(info["turn_over"]),
    }


def game_judge(game: str) -> Judge | None:
    """The judge of our ``game``, or ``None`` while that game is not in this tree."""
    from pool_env.game.registry import BUILTIN

    return _GameJudge() if game in BUILTIN else None
