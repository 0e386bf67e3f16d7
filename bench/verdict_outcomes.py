"""Both engines' shots as one outcome summary, read from their event lists alike.

:func:`ours` plays a :class:`~bench.verdict_shots.Case` through :func:`pool_env.shoot`
(events recorded), :func:`from_pooltool` reads the worker's result
(``bench/engines/pooltool_verdicts.py``); both become an event list ``[time, kind,
balls, other]`` in our ball numbers (``kind``: ``"ball"``, ``"linear"`` for a straight
cushion: our rails and jaw facings, pooltool's linear segments; ``"circular"`` for a
round jaw: our points, pooltool's circular segments; ``"pocket"`` with ``other`` our
pocket index, pooltool's pockets matched to ours by their centres), and :func:`summarise`
reads either into the same :class:`Summary`: what the verdicts depend on.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from bench.verdict_shots import Case, ids_of
from pool_env import shoot
from pool_env.interop.pooltool import xy_from_pooltool
from pool_env.sim.table import Table


@dataclass(frozen=True)
class Summary:
    """What one shot did, as the rules read it (ball numbers are ours).

    Attributes:
        first: The first ball the cue ball touched, -1 if none.
        second: The second distinct ball it touched, -1 if none.
        cushions_second: Its straight-cushion impacts at or before that second contact
            (pooltool's ``is_point`` count), -1 without a second contact.
        circular_second: Its round-jaw impacts then (0 on a pocketless table), -1 as above.
        potted: ``(ball, pocket)`` in the order they dropped.
        final: ``{ball: (x, y)}`` final positions, our frame.
        rows: Per-ball rows by ball number, as the simulator's results hold them:
            ``first_hit``, ``second_hit``, ``cushions_at_second`` (every cushion kind),
            ``cushions_after_contact`` (after the shot's first ball-ball impact),
            ``pocketed``, ``pocket_order``.
        events: The event list it was read from.
    """

    first: int
    second: int
    cushions_second: int
    circular_second: int
    potted: tuple[tuple[int, int], ...]
    final: dict[int, tuple[float, float]]
    rows: dict[str, dict[int, int]]
    events: list[list[Any]]

    def point_made(self) -> bool:
        """A carom's point by the count pooltool's ``is_point`` makes (for the search)."""
        return self.second >= 0 and self.cushions_second + self.circular_second >= 3

    def key(self, game: str) -> tuple[Any, ...]:
        """The fields a verdict of ``game`` reads: equal keys mean the same outcome."""
        if game == "three_cushion":
            return (self.first, self.second, self.cushions_second, self.circular_second)
        return (self.first, tuple(sorted(b for b, _ in self.potted)))


def summarise(events: list[list[Any]], balls: tuple[int, ...], cue: int,
              final: dict[int, tuple[float, float]]) -> Summary:  # fmt: skip
    """Read an event list (chronological) into a :class:`Summary`.

    A ball's cushions "at its second contact" are those at a time at or before that
    contact's (as pooltool's ``is_point`` counts them: an impact at the same instant counts).
    """
    touched: dict[int, list[int]] = {b: [] for b in balls}
    second_time = {b: np.inf for b in balls}
    after_contact = {b: 0 for b in balls}
    pocketed = {b: -1 for b in balls}
    order = {b: -1 for b in balls}
    contact = False
    potted: list[tuple[int, int]] = []
    for time, kind, who, other in events:
        if kind == "ball":
            contact = True
            for b, o in ((who, other), (other, who)):
                if o not in touched[b]:
                    touched[b].append(o)
                    if len(touched[b]) == 2:
                        second_time[b] = time
        elif kind in ("linear", "circular"):
            after_contact[who] += contact
        elif kind == "pocket":
            pocketed[who], order[who] = other, len(potted)
            potted.append((who, other))

    def count(b: int, kinds: tuple[str, ...]) -> int:
        if len(touched[b]) < 2:
            return -1
        return sum(1 for t, k, w, _ in events if w == b and k in kinds and t <= second_time[b])

    rows = {
        "first_hit": {b: touched[b][0] if touched[b] else -1 for b in balls},
        "second_hit": {b: touched[b][1] if len(touched[b]) > 1 else -1 for b in balls},
        "cushions_at_second": {b: count(b, ("linear", "circular")) for b in balls},
        "cushions_after_contact": after_contact,
        "pocketed": pocketed,
        "pocket_order": order,
    }
    return Summary(
        rows["first_hit"][cue], rows["second_hit"][cue], count(cue, ("linear",)),
        count(cue, ("circular",)), tuple(potted), final, rows, events,
    )  # fmt: skip


#: Our event kinds as the summary's (rails and jaw facings are straight, points round).
_OUR_KINDS = {"ball": "ball", "cushion": "linear", "jaw": "linear", "point": "circular",
              "pocket": "pocket"}  # fmt: skip


def ours(case: Case, table: Table) -> Summary:
    """Play ``case`` on our simulator; its :class:`Summary`."""
    cue_row = case.balls.index(case.cue)
    shot = shoot(
        table, case.positions, case.angle, case.speed, cue=cue_row, tip=case.tip, record=True
    )
    events = []
    for e in shot.events:
        kind = _OUR_KINDS.get(e.kind)
        if kind is None:
            continue
        other = case.balls[e.j] if kind == "ball" else e.j
        events.append([e.time, kind, case.balls[e.i], other])
    final = {b: (float(x), float(y)) for b, (x, y) in zip(case.balls, shot.positions, strict=True)}
    out = summarise(events, case.balls, case.cue, final)
    return out


def pocket_index(table: Table, centre_ours: np.ndarray) -> int:
    """Our pocket nearest a pooltool pocket's centre (given in our frame)."""
    return int(np.argmin(np.hypot(*(table.pockets[:, :2] - centre_ours).T)))


def from_pooltool(case: Case, table: Table, result: dict[str, Any]) -> Summary:
    """The worker's result for ``case`` as a :class:`Summary` (our numbers and frame)."""
    number = {pid: b for b, pid in enumerate(ids_of(case.game))}
    pockets = {
        pid: pocket_index(table, xy_from_pooltool(np.array([xy]), table.width)[0])
        for pid, xy in result["pockets"].items()
    }
    kinds = {"ball": "ball", "cushion": "linear", "jaw": "circular", "pocket": "pocket"}
    events = []
    for t, kind, ids in result["events"]:
        k = kinds[kind]
        if k == "ball":
            events.append([t, k, number[ids[0]], number[ids[1]]])
        elif k == "pocket":
            events.append([t, k, number[ids[0]], pockets[ids[1]]])
        else:
            events.append([t, k, number[ids[0]], -1])
    xy = {number[pid]: p for pid, p in result["final"].items()}
    final = {}
    for b, p in xy.items():
        x, y = xy_from_pooltool(np.array([p]), table.width)[0]
        final[b] = (float(x), float(y))
    return summarise(events, case.balls, case.cue, final)
