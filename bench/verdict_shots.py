"""The seeded shots of ``bench/verdicts_vs_pooltool.py``: tables, layouts, rule states, strokes.

Each game's table is ours made equal to pooltool 0.6's where the two can be equal:
pooltool's default physics engine (``Table.preset("pooltool-0.6")``'s models) with its
table size, cushion height and its game's ball (``BILLIARD_GENERIC`` / ``SNOOKER_GENERIC``).

* three-cushion: pooltool's ``BilliardTableSpecs()`` (2.84 x 1.42 m, cushions 37 mm) and
  ``BILLIARD_GENERIC`` (R = 30.75 mm, 0.210 kg, f_c = 0.15): pocketless on both sides, so
  the physics is the same (``results/models_vs_pooltool.md``: ~1e-10 m);
* snooker: pooltool's ``SnookerTableSpecs()`` (3.5445 x 1.7465 m, cushions 28 mm) and
  ``SNOOKER_GENERIC`` (R = 26.19375 mm, 0.140 kg, u_s = f_c = 0.5). The pockets cannot be
  equal: pooltool's are its circular pocket segments and fall circles, ours the jaw model
  of ``Table.preset("snooker")`` (:data:`pool_env.sim.presets.SNOOKER_POCKETS`: pooltool's
  mouths, cut, depths and jaw radii). A ball near a pocket may drop on one engine and not on
  the other: such shots are told apart (the outcome summaries differ) from rules
  disagreements (the same outcome judged differently).

A :class:`Case` is one shot: the layout (our frame and ball numbers), the rule state, the
stroke ``(angle, speed, tip)`` (level cue: pooltool's ``theta = 0``; the envs have no
elevation component). Layouts leave every ball at least :data:`GAP` from every other and
from the cushions (a touching ball is outside both rulesets' common ground: pooltool has no
touching-ball rule).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from pool_env import Table
from pool_env.interop.pooltool import (
    POOLTOOL_CUE_MASS,
    ball_params_from_table,
    cue_to_pooltool,
    xy_to_pooltool,
)
from pool_env.sim.presets import SNOOKER_POCKETS

#: Clearance (m) between balls, and from a ball to a cushion, in every layout.
GAP = 0.002

#: Ball names of pooltool's rulesets, by our ball number.
THREE_CUSHION_IDS = ("white", "yellow", "red")
COLOURS = ("yellow", "green", "brown", "blue", "pink", "black")
SNOOKER_IDS = ("white", *(f"red_{k:02d}" for k in range(1, 16)), *COLOURS)
#: Our ball number of the yellow (the first colour); colour ``c`` (0 yellow .. 5 black) is
#: ball ``YELLOW + c``, worth ``c + 2``.
YELLOW = 16

#: The states a snooker shot is played from (``Case.state["phase"]``).
PHASES = ("reds", "colour", "sequence")


def three_cushion_table() -> Table:
    """Our table equal to pooltool's carom table with its default physics (pocketless)."""
    return Table.preset(
        "pooltool-0.6", pockets="none", length=2.84, width=1.42, cushion_height=0.037,
        ball_radius=0.0615 / 2, ball_mass=0.210, cushion_friction=0.15,
    )  # fmt: skip


def snooker_table() -> Table:
    """Our table as close as it gets to pooltool's snooker table (pockets: see the module)."""
    return Table.preset(
        "pooltool-0.6", pockets=SNOOKER_POCKETS, length=3.5445, width=1.7465,
        cushion_height=0.028, ball_radius=0.02619375, ball_mass=0.140, mu_slide=0.5,
        cushion_friction=0.5,
    )  # fmt: skip


def table_of(game: str) -> Table:
    """The comparison's table of ``game``."""
    return three_cushion_table() if game == "three_cushion" else snooker_table()


def ids_of(game: str) -> tuple[str, ...]:
    """The ball ids of pooltool's ruleset, by our ball number."""
    return THREE_CUSHION_IDS if game == "three_cushion" else SNOOKER_IDS


@dataclass(frozen=True)
class Case:
    """One shot of the comparison.

    Attributes:
        game: ``"three_cushion"`` or ``"snooker"``.
        index: Its place in the seeded sequence.
        balls: Our ball numbers on the table (the cue ball's first for snooker: ball 0).
        positions: ``(len(balls), 2)`` their centres, our frame.
        cue: The cue ball's number (three-cushion: 0 white or 1 yellow; snooker: 0).
        angle: The aim (radians, our frame).
        speed: The cue ball's speed after the strike (m/s).
        tip: The cue axis's offset ``(side, vertical)``, fractions of ``R``.
        state: Snooker: ``phase`` (:data:`PHASES`), ``on`` (the ball numbers that are on:
            the reds, or one colour) and ``nominated`` (the colour called, our ball
            number, or -1 on reds). Three-cushion: empty.
    """

    game: str
    index: int
    balls: tuple[int, ...]
    positions: np.ndarray
    cue: int
    angle: float
    speed: float
    tip: tuple[float, float]
    state: dict[str, Any] = field(default_factory=dict)

    def pooltool_shot(self, table: Table) -> dict[str, Any]:
        """The worker's shot (``bench/engines/pooltool_verdicts.py``): pooltool's names."""
        ids = ids_of(self.game)
        xy = xy_to_pooltool(self.positions, table.width)
        stroke = cue_to_pooltool(table, self.angle, self.speed, self.tip)
        shot: dict[str, Any] = {
            "game": self.game,
            "balls": {ids[b]: [float(xy[k, 0]), float(xy[k, 1])] for k, b in enumerate(self.balls)},
            "cue_ball": ids[self.cue],
            "stroke": stroke._asdict(),
        }
        if self.game == "snooker":
            shot.update(snooker_constraints(self.state))
        return shot


def snooker_constraints(state: dict[str, Any]) -> dict[str, Any]:
    """The ``ShotConstraints`` of pooltool (hittable, call) of a snooker state.

    On reds: every red id, no call. On a colour after a red (or after the last red): every
    colour, the nominated one called. In the colours' sequence: the lowest colour alone,
    called (as pooltool's ``next_shot_constraints`` sets them).
    """
    if state["phase"] == "reds":
        return {"hittable": list(SNOOKER_IDS[1:16]), "call_shot": False, "ball_call": None}
    if state["phase"] == "colour":
        return {"hittable": list(COLOURS), "call_shot": True,
                "ball_call": SNOOKER_IDS[state["nominated"]]}  # fmt: skip
    lowest = SNOOKER_IDS[state["on"][0]]
    return {"hittable": [lowest], "call_shot": True, "ball_call": lowest}


def pooltool_job(
    game: str, cases: list[Case], min_dist: float | None = 1e-12, timeout: float = 60.0
) -> dict[str, Any]:
    """The worker's input for ``cases`` of one game (``min_dist``: pooltool's spacer)."""
    table = table_of(game)
    params = ball_params_from_table(table)
    return {
        "timeout": timeout,
        "min_dist": min_dist,
        "table": {"kind": "billiard" if game == "three_cushion" else "snooker",
                  "l": table.length, "w": table.width, "cushion_height": table.cushion_height},
        "ball": params,
        "cue": {"M": POOLTOOL_CUE_MASS, "tip_radius": table.cue_tip_radius,
                "end_mass": table.cue_end_mass},
        "shots": [case.pooltool_shot(table) for case in cases],
    }  # fmt: skip


# -- layouts ---------------------------------------------------------------------------------


def _free_point(rng: np.random.Generator, table: Table, placed: list[np.ndarray],
                near: np.ndarray | None = None, spread: float = 0.0) -> np.ndarray:  # fmt: skip
    """A point clear of the cushions and of ``placed`` (near ``near`` if given)."""
    r = table.ball_radius
    lo = np.array([r + GAP, r + GAP])
    hi = np.array([table.length - r - GAP, table.width - r - GAP])
    for _ in range(10_000):
        if near is None:
            p = rng.uniform(lo, hi)
        else:
            p = near + rng.normal(0.0, spread, 2)
            if not ((p >= lo) & (p <= hi)).all():
                continue
        if table.n_pockets and _in_mouth(table, p):
            continue
        if all(np.hypot(*(p - q)) >= 2 * r + GAP for q in placed):
            return p
    raise RuntimeError("no free point (layout too crowded)")


def _in_mouth(table: Table, p: np.ndarray) -> bool:
    """Whether a ball at ``p`` would overlap a pocket's capture circle (not a layout)."""
    centres = table.pockets[:, :2]
    return bool((np.hypot(*(centres - p).T) < table.pockets[:, 2] + table.ball_radius).any())


def _spots(table: Table) -> np.ndarray:
    """The six colour spots (yellow .. black) on the comparison's table, our frame.

    pooltool's ``snooker_color_locs`` (fractions of its width across and its length along)
    turned into our frame.
    """
    fractions = {"yellow": (0.333, 0.2), "green": (0.666, 0.2), "brown": (0.5, 0.2),
                 "blue": (0.5, 0.5), "pink": (0.5, 0.75), "black": (0.5, 10 / 11)}  # fmt: skip
    return np.array([[fy * table.length, table.width - fx * table.width]
                     for fx, fy in (fractions[c] for c in COLOURS)])  # fmt: skip


def three_cushion_case(
    rng: np.random.Generator, index: int, scores: Callable[[Case], bool] | None = None
) -> Case:
    """Three balls anywhere; the white's or the yellow's shot.

    Aimed at an object ball at any thickness (some miss it) or anywhere; or, for two
    shots in five when ``scores`` is given, the first of up to 200 random strokes that
    ``scores`` (our simulator) makes a point with (random shots score 2% of the time, and
    a comparison of verdicts needs points), else the last stroke tried.
    """
    table = three_cushion_table()
    placed: list[np.ndarray] = []
    for _ in range(3):
        placed.append(_free_point(rng, table, placed))
    pos = np.array(placed)
    cue = int(rng.integers(0, 2))
    search = scores is not None and rng.random() < 0.4
    for _ in range(200 if search else 1):
        if rng.random() < 0.6:
            target = pos[int(rng.choice([b for b in range(3) if b != cue]))]
            angle = _aim_at(rng, pos[cue], target, table.ball_radius, 1.2)
        else:
            angle = float(rng.uniform(-math.pi, math.pi))
        speed = float(rng.uniform(1.0, 6.0))
        case = Case("three_cushion", index, (0, 1, 2), pos, cue, angle, speed, _tip(rng))
        if not search or scores(case):  # type: ignore[misc]
            break
    return case


def snooker_case(rng: np.random.Generator, index: int) -> Case:
    """A snooker layout and state of a random phase, the shot aimed at or near a ball."""
    table = snooker_table()
    phase = PHASES[int(rng.integers(0, 3))]
    if phase == "sequence":
        lowest = int(rng.integers(0, 6))
        reds: list[int] = []
        colours = list(range(YELLOW + lowest, YELLOW + 6))
    else:
        n_reds = int(rng.integers(0 if phase == "colour" else 1, 16))
        reds = sorted(rng.choice(np.arange(1, 16), n_reds, replace=False).tolist())
        colours = list(range(YELLOW, YELLOW + 6))
    spots = _spots(table)
    placed: list[np.ndarray] = []
    kept: list[int] = []
    for b in colours:  # on its spot, or anywhere
        spot = spots[b - YELLOW]
        clear = all(np.hypot(*(spot - q)) >= 2 * table.ball_radius + GAP for q in placed)
        placed.append(spot if clear and rng.random() < 0.5 else _free_point(rng, table, placed))
        kept.append(b)
    pack = _free_point(rng, table, placed)  # reds gather about a point, as they lie in play
    for b in reds:
        placed.append(_free_point(rng, table, placed, pack, 0.25) if rng.random() < 0.6
                      else _free_point(rng, table, placed))  # fmt: skip
        kept.append(b)
    placed.insert(0, _free_point(rng, table, placed))
    balls = (0, *kept)
    pos = np.array(placed)
    if phase == "reds":
        on, nominated = reds, -1
    elif phase == "colour":
        nominated = int(rng.choice(colours))
        on = [nominated]
    else:
        on, nominated = [colours[0]], -1
    state = {"phase": phase, "on": on, "nominated": nominated}
    # mostly at a ball that is on (a pot or a safety), else at any ball or anywhere
    u = rng.random()
    row = {b: k for k, b in enumerate(balls)}
    if u < 0.75:
        target = int(rng.choice(on)) if rng.random() < 0.8 else int(rng.choice(balls[1:]))
        if rng.random() < 0.6:
            angle = _pot_aim(rng, table, pos[0], pos[row[target]])
        else:
            angle = _aim_at(rng, pos[0], pos[row[target]], table.ball_radius, 1.1)
    else:
        angle = float(rng.uniform(-math.pi, math.pi))
    speed = float(rng.uniform(0.5, 4.0))
    return Case("snooker", index, balls, pos, 0, angle, speed, _tip(rng), state)


def _tip(rng: np.random.Generator) -> tuple[float, float]:
    """A cue tip offset inside a disk of radius 0.5 R."""
    r, t = 0.5 * math.sqrt(rng.random()), rng.uniform(-math.pi, math.pi)
    return (r * math.cos(t), r * math.sin(t))


def _aim_at(rng: np.random.Generator, cue: np.ndarray, target: np.ndarray, radius: float,
            reach: float) -> float:  # fmt: skip
    """An aim that meets ``target`` at a random thickness (``reach`` > 1: may miss it)."""
    d = target - cue
    dist = float(np.hypot(*d))
    offset = rng.uniform(-reach, reach) * 2 * radius
    return float(math.atan2(d[1], d[0]) + math.asin(max(-1.0, min(1.0, offset / dist))))


def _pot_aim(rng: np.random.Generator, table: Table, cue: np.ndarray, target: np.ndarray) -> float:
    """A ghost-ball aim sending ``target`` at a random pocket (a little error), if it cuts."""
    r = table.ball_radius
    for k in rng.permutation(table.n_pockets):
        to_pocket = table.pockets[k, :2] - target
        u = to_pocket / np.hypot(*to_pocket)
        ghost = target - 2 * r * u
        aim = ghost - cue
        if np.dot(aim, u) / np.hypot(*aim) > 0.2:  # a cut under about 78 degrees
            return float(math.atan2(aim[1], aim[0]) + rng.normal(0.0, 0.003))
    return _aim_at(rng, cue, target, r, 1.0)


def make_cases(
    game: str, n: int, seed: int, scores: Callable[[Case], bool] | None = None
) -> list[Case]:
    """``n`` seeded cases of ``game`` (``scores``: see :func:`three_cushion_case`)."""
    rng = np.random.default_rng([seed, 0 if game == "three_cushion" else 1])
    if game == "three_cushion":
        return [three_cushion_case(rng, k, scores) for k in range(n)]
    return [snooker_case(rng, k) for k in range(n)]
