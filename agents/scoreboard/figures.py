"""A task's figures from its record, on any first ``n`` episodes; the normalized score.

A results file keeps each task's record episode by episode
(:func:`agents.scoreboard.play.play_task`):
``episodes`` keeps :class:`~agents.evaluation.metrics.EpisodeLog`'s lists, ``runouts`` each
rack's ending and whether its break made a ball, ``duel`` each rack's winner. Any figure of
the first ``n`` episodes is computed from it, so a player scored on the ``full`` suite is
also scored on the smaller suites' episodes, which are its first ones
(:mod:`agents.scoreboard.suite`): the normalized score compares players on the same seeds.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

from agents.evaluation.metrics import EpisodeLog, Estimate, wilson

__all__ = ["FIGURES", "figure", "normalized"]

Record = dict[str, list[Any]]


def _summary(key: str) -> Callable[[Record, int], Estimate]:
    """A figure of :meth:`EpisodeLog.summary` on the first ``n`` episodes."""

    def of(record: Record, n: int) -> Estimate:
        log = EpisodeLog(**{name: list(values[:n]) for name, values in record.items()})
        return log.summary()[key]

    return of


def _share(key: str, hit: Callable[[Any], bool]) -> Callable[[Record, int], Estimate]:
    """The share of the first ``n`` entries of ``record[key]`` that ``hit``, Wilson's interval."""

    def of(record: Record, n: int) -> Estimate:
        return wilson(float(sum(bool(hit(v)) for v in record[key][:n])), n)

    return of


#: The figures by name: (the table's label, the runner whose record it reads, the figure of
#: a record's first ``n`` episodes). Each is a rate in [0, 1] where more is better, except
#: the scratch, foul and draw rates, which are only shown beside.
FIGURES: dict[str, tuple[str, str, Callable[[Record, int], Estimate]]] = {
    "pots_per_shot": ("pots/shot", "episodes", _summary("pots_per_shot")),
    "clean_pot_rate": ("clean pots/shot", "episodes", _summary("clean_pot_rate")),
    "scratch_rate": ("scratches/shot", "episodes", _summary("scratch_rate")),
    "clear_rate": ("cleared", "episodes", _summary("clear_rate")),
    "run_out_rate": ("break-and-run", "runouts", _share("endings", lambda e: e == "run-out")),
    "break_made_rate": ("ball made on break", "runouts", _share("break_made", bool)),
    "foul_rate": (
        "ended by a foul", "runouts", _share("endings", lambda e: e in ("foul", "break scratch"))
    ),
    "win_rate": ("won", "duel", _share("winners", lambda w: w == "agent")),
    "draw_rate": ("drawn (shot limit)", "duel", _share("winners", lambda w: w is None)),
}  # fmt: skip


def figure(name: str, record: Record, n: int) -> Estimate:
    """Figure ``name`` of the first ``n`` episodes of ``record``.

    Raises:
        ValueError: If the record holds fewer than ``n`` episodes, or ``n < 1``.
    """
    held = max(len(values) for values in record.values())
    if not 1 <= n <= held:
        raise ValueError(f"figure {name!r} of {n} episodes: the record holds {held}")
    return FIGURES[name][2](record, n)


def normalized(value: float, random: float | None, best: float | None) -> float | None:
    """``(value - random) / (best - random)``: 0 at random play, 1 at the best player's.

    ``None`` where it is undefined: a reference missing, or the best no better than random
    (on few episodes both may pot nothing), so that no score is made of a zero divisor.
    """
    if random is None or best is None or not best > random:
        return None
    score = (value - random) / (best - random)
    return None if math.isnan(score) else score
