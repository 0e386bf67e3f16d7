"""The compiled snooker rules and their plain-Python reference on the same outcome.

:func:`random_case` draws a stroke's outcome (a frame state, where the balls stopped,
the first ball hit, the balls potted, the nomination, the balls touched);
:func:`compare` judges it with :func:`pool_env.game.games.snooker.rules.judge_stroke`
and with :func:`pool_env.testing.reference.snooker_rules.referee`, and returns the
differences (an empty list when they agree).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache
from typing import Any

import numpy as np

from pool_env.game.config import GameConfig, make_config
from pool_env.game.games.snooker import rack_state as sk
from pool_env.game.games.snooker.rules import (
    R_FOUL,
    R_FRAME_OVER,
    R_FREE,
    R_PENALTY,
    R_POINTS,
    R_TIE,
    judge_stroke,
)
from pool_env.sim.table import Table
from pool_env.testing.reference import snooker_rules as ref

N = 22
COLOURS = tuple(range(16, 22))


@cache
def config(model: str = "roll") -> GameConfig:
    """A snooker config on the snooker table (the rules read its markings)."""
    return make_config(
        table=Table.preset("snooker", model=model), scene="snooker", game="snooker",
        players=2,
    )  # fmt: skip


@cache
def spec() -> ref.TableSpec:
    """The reference's view of the same table."""
    t = config().table
    return ref.TableSpec(t.length, t.width, t.ball_radius,
                         tuple(tuple(float(v) for v in p) for p in t.pockets))  # fmt: skip


@dataclass
class Case:
    """One stroke's outcome on one frame state."""

    row: np.ndarray  # the frame state (N_RACK,)
    on: np.ndarray  # (N,) balls on before
    after: np.ndarray  # (N, 2) where they stopped
    potted: np.ndarray  # (N,) incl. the cue ball
    first: int
    nominated: int
    touching: np.ndarray  # (N,)


def _free(point: np.ndarray, placed: list[np.ndarray], table: Table) -> bool:
    r = table.ball_radius
    if not (r <= point[0] <= table.length - r and r <= point[1] <= table.width - r):
        return False
    if any(np.hypot(*(point - p[:2])) <= p[2] + 1e-6 for p in table.pockets):
        return False
    return all(np.hypot(*(point - q)) >= 2 * r + 1e-6 for q in placed)


def random_case(rng: np.random.Generator) -> Case:
    """A random outcome, biased towards the rules' corners (covered spots, the black)."""
    table = config().table
    r = table.ball_radius
    on = np.zeros(N, dtype=bool)
    on[0] = True
    kind = rng.integers(6)
    if kind == 0:  # only the black left (end of frame, re-spotted black)
        on[21] = True
        phase = sk.IN_ORDER
    elif kind == 1:  # colours in order
        on[int(rng.integers(16, 22)) :] = True
        phase = sk.IN_ORDER
    else:
        n_reds = int(rng.integers(0 if kind == 2 else 1, 16))
        on[1 : 1 + n_reds] = True
        on[16:] = True
        phase = sk.COLOUR_ON if (kind == 2 or rng.random() < 0.4) else sk.RED_ON
        if n_reds == 0:
            phase = sk.COLOUR_ON
    row = np.zeros(sk.N_RACK, dtype=np.int64)
    row[sk.SHOOTER] = rng.integers(2)
    row[sk.SCORE_0], row[sk.SCORE_1] = rng.integers(0, 60, size=2)
    if rng.random() < 0.3:
        row[sk.SCORE_1] = row[sk.SCORE_0] + rng.choice([-7, 0, 7])
        row[sk.SCORE_1] = max(row[sk.SCORE_1], 0)
    row[sk.PHASE] = phase
    row[sk.FREE_BALL] = int(phase != sk.COLOUR_ON and rng.random() < 0.4)
    row[sk.BREAK] = rng.integers(0, 40)
    row[sk.RESPOTTED] = int(kind == 0 and rng.random() < 0.3)
    row[sk.WINNER] = -1
    spots = {c: np.array(spec().spot(c)) for c in COLOURS}
    after = np.zeros((N, 2))
    placed: list[np.ndarray] = []
    for j in np.flatnonzero(on):
        for _ in range(1000):
            if rng.random() < 0.25:  # near a spot: covers it
                c = COLOURS[int(rng.integers(6))]
                p = spots[c] + rng.uniform(-2 * r, 2 * r, size=2)
            elif rng.random() < 0.2:  # near the D
                p = np.array([rng.uniform(0.4, 0.75), rng.uniform(0.55, 1.25)])
            else:
                p = np.array([rng.uniform(r, table.length - r), rng.uniform(r, table.width - r)])
            if _free(p, placed, table):
                break
        after[j] = p
        placed.append(p)
    objects = np.flatnonzero(on[1:]) + 1
    potted = np.zeros(N, dtype=bool)
    potted[objects] = rng.random(objects.size) < (0.5 if objects.size < 3 else 0.12)
    potted[0] = rng.random() < 0.15
    first = int(rng.choice(objects)) if rng.random() < 0.85 else -1
    if rng.random() < 0.3 and first > 0 and on[first]:
        potted[first] = True
    nominated = int(rng.integers(16, 22)) if rng.random() < 0.7 else 0
    touching = np.zeros(N, dtype=bool)
    if rng.random() < 0.2:
        touching[int(rng.choice(objects))] = True
    return Case(row, on, after, potted, first, nominated, touching)


def compiled(case: Case) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The product's verdict: (results, row after, on_table after, positions after)."""
    cfg = config()
    row, on, pos = case.row.copy(), case.on.copy(), case.after.copy()
    res = judge_stroke(
        cfg.params, cfg.table.pockets, row, pos, on, case.potted.copy(), case.first,
        case.nominated, case.touching.copy(), np.empty((N, 2)),
    )  # fmt: skip
    return res, row, on, pos


def referenced(case: Case) -> tuple[ref.Frame, dict[int, tuple[float, float]], ref.Verdict]:
    """The reference's verdict on the same case."""
    row = case.row
    frame = ref.Frame(
        striker=int(row[sk.SHOOTER]), scores=(int(row[sk.SCORE_0]), int(row[sk.SCORE_1])),
        on=("red", "colour", "in_order")[int(row[sk.PHASE])], in_hand=bool(row[sk.IN_HAND]),
        free_ball=bool(row[sk.FREE_BALL]), current_break=int(row[sk.BREAK]),
        respotted_black=bool(row[sk.RESPOTTED]),
    )  # fmt: skip
    before = {int(j): tuple(case.after[j]) for j in np.flatnonzero(case.on)}
    after = {j: tuple(case.after[j]) for j in before}
    return ref.referee(
        spec(),
        frame,
        before,
        after,
        None if case.first < 0 else case.first,
        {int(j) for j in np.flatnonzero(case.potted)},
        case.nominated or None,
        {int(j) for j in np.flatnonzero(case.touching)},
    )


FOULS = (None, "in_off", "no_contact", "wrong_ball_first", "ball_not_on_potted", "push")


def compare(case: Case) -> list[str]:
    """The differences between the two verdicts (empty: they agree)."""
    res, row, on, pos = compiled(case)
    frame, balls, verdict = referenced(case)
    diffs: list[Any] = []
    mine = {
        "foul": FOULS[res[R_FOUL]], "penalty": int(res[R_PENALTY]),
        "points": int(res[R_POINTS]), "free": bool(res[R_FREE]),
        "frame_over": bool(res[R_FRAME_OVER]), "tie": bool(res[R_TIE]),
        "striker": int(row[sk.SHOOTER]), "scores": (int(row[sk.SCORE_0]), int(row[sk.SCORE_1])),
        "on": ("red", "colour", "in_order")[int(row[sk.PHASE])],
        "in_hand": bool(row[sk.IN_HAND]), "free_ball": bool(row[sk.FREE_BALL]),
        "break": int(row[sk.BREAK]), "respotted": bool(row[sk.RESPOTTED]),
        "winner": None if row[sk.WINNER] < 0 else int(row[sk.WINNER]),
        "balls": sorted(int(j) for j in np.flatnonzero(on)),
    }  # fmt: skip
    theirs = {
        "foul": verdict.foul, "penalty": verdict.penalty, "points": verdict.points,
        "free": verdict.free_ball_played, "frame_over": verdict.frame_over, "tie": verdict.tie,
        "striker": frame.striker, "scores": frame.scores, "on": frame.on,
        "in_hand": frame.in_hand, "free_ball": frame.free_ball, "break": frame.current_break,
        "respotted": frame.respotted_black, "winner": frame.winner, "balls": sorted(balls),
    }  # fmt: skip
    for key, value in mine.items():
        if theirs[key] != value:
            diffs.append(f"{key}: compiled {value!r}, reference {theirs[key]!r}")
    for j in balls:
        if on[j] and np.hypot(*(pos[j] - np.array(balls[j]))) > 1e-8:
            diffs.append(f"ball {j} at {pos[j].tolist()}, reference {balls[j]}")
    return diffs
