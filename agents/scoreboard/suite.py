"""The scoreboard's tasks: one table of what is played, on which seeds, how long, and scored how.

Each :class:`Task` names its env id and keywords, its execution noise (``--noise`` text,
:func:`agents.evaluation.noise_flag.parse_noise`), the seed of its first episode, its
episode count in each suite (:data:`SUITES`: ``smoke`` for CI, ``short`` for a first look
at a new model, ``full`` for the committed results), the runner that plays it (:data:`RUNNERS`)
and the figure it reports (:data:`agents.scoreboard.figures.FIGURES`), with figures beside
it that are shown but not scored.

Episode ``k`` of a task is reset with ``seed + k`` in every suite, so a suite's episodes
are the first ones of the suites above it: the ``short`` figures of a player scored on the
``full`` suite are its first ``short`` episodes (:func:`agents.scoreboard.figures.figure`).
The seeds (700000 and up) are used by no training run, no model selection and no other
results file of the repository.
"""

from __future__ import annotations

import difflib
from dataclasses import dataclass
from typing import Any

__all__ = ["IDENTITY", "RUNNERS", "SUITES", "TASKS", "Task", "suite_tasks"]

#: The suites, smallest first; a task plays its first ``episodes[suite]`` episodes.
SUITES = ("smoke", "short", "full")

#: How a task is played: ``episodes`` (:func:`agents.evaluation.episodes.run_episodes`),
#: ``runouts`` (:func:`agents.evaluation.runouts.play_racks`, run-out mode) or ``duel``
#: (:func:`agents.evaluation.duels.play_duels` against ``opponent``, alternating breaks).
RUNNERS = ("episodes", "runouts", "duel")

#: The fields that define what a task plays: a results file counts for a task only where
#: they are equal (:mod:`agents.scoreboard.results`); the episode counts may differ.
IDENTITY = ("env_id", "env_kwargs", "noise", "seed", "runner", "opponent")

#: Position play's table: a miss ends the episode, the noise of results/agents.md.
_POSITION = {"end_on_miss": True}
_POSITION_NOISE = "0.003,0.05,0.05"


@dataclass(frozen=True)
class Task:
    """One task of the scoreboard.

    Attributes:
        name: The task's name (the results files' key).
        env_id: The registered env id.
        env_kwargs: ``gymnasium.make`` keywords besides the noise.
        noise: The execution noise as ``--noise`` takes it (``"none"``: exact shots).
        seed: The seed of episode 0 (episode ``k``: ``seed + k``).
        episodes: The episode (rack) count per suite of :data:`SUITES`.
        runner: One of :data:`RUNNERS`.
        figure: The scored figure (a key of :data:`agents.scoreboard.figures.FIGURES`).
        beside: Figures shown beside it, not scored.
        opponent: The duel's opponent (a player name), ``None`` otherwise.
        what: One line for the table: what the figure counts.
    """

    name: str
    env_id: str
    env_kwargs: dict[str, Any]
    noise: str
    seed: int
    episodes: dict[str, int]
    runner: str
    figure: str
    beside: tuple[str, ...] = ()
    opponent: str | None = None
    what: str = ""

    def spec(self) -> dict[str, Any]:
        """What defines the task's play (:data:`IDENTITY`), as a results file stores it."""
        return {key: getattr(self, key) for key in IDENTITY}


#: The tasks of every suite, in the table's order.
TASKS = (
    Task(
        "oneball", "pool_env/OneBall-v1", {}, "none", 700_000,
        {"smoke": 4, "short": 300, "full": 1000}, "episodes", "pots_per_shot",
        ("clean_pot_rate", "scratch_rate"),
        what="one shot on one ball (spin table): pots a shot",
    ),
    Task(
        "position-3", "pool_env/Pool-v1", {"n_balls": 3, **_POSITION}, _POSITION_NOISE,
        710_000, {"smoke": 2, "short": 100, "full": 400}, "episodes", "clear_rate",
        ("pots_per_shot", "scratch_rate"),
        what="3 balls in one turn (a miss ends it): tables cleared",
    ),
    Task(
        "position-5", "pool_env/Pool-v1", {"n_balls": 5, **_POSITION}, _POSITION_NOISE,
        720_000, {"smoke": 2, "short": 100, "full": 200}, "episodes", "clear_rate",
        ("pots_per_shot", "scratch_rate"),
        what="5 balls in one turn (a miss ends it): tables cleared",
    ),
    Task(
        "nine-runout", "pool_env/NineBallGame-v2", {}, "fastfiz", 730_000,
        {"smoke": 2, "short": 50, "full": 100}, "runouts", "run_out_rate",
        ("break_made_rate", "foul_rate"),
        what="9-ball break-and-run (run-out mode: the first miss or foul ends the rack)",
    ),
    Task(
        "nine-duel", "pool_env/NineBallGame-v2", {}, "fastfiz", 740_000,
        {"smoke": 2, "short": 40, "full": 100}, "duel", "win_rate", ("draw_rate",),
        opponent="ghost",
        what="9-ball racks won against ghost-ball, breaks alternating",
    ),
    Task(
        "eight-duel", "pool_env/EightBallGame-v1", {}, "fastfiz", 750_000,
        {"smoke": 2, "short": 40, "full": 100}, "duel", "win_rate", ("draw_rate",),
        opponent="ghost",
        what="8-ball racks won against ghost-ball, breaks alternating",
    ),
    Task(
        "ten-runout", "pool_env/TenBallGame-v1", {}, "fastfiz", 760_000,
        {"smoke": 2, "short": 50, "full": 100}, "runouts", "run_out_rate",
        ("break_made_rate", "foul_rate"),
        what="10-ball break-and-run (run-out mode), with the ball made on the break",
    ),
)  # fmt: skip


def suite_tasks(suite: str) -> list[tuple[Task, int]]:
    """The tasks of ``suite`` with their episode counts.

    Raises:
        ValueError: On a suite not in :data:`SUITES`, naming it and the suites.
    """
    if suite not in SUITES:
        close = difflib.get_close_matches(suite, SUITES, n=1)
        hint = f" (did you mean {close[0]}?)" if close else ""
        raise ValueError(f"unknown suite {suite!r}{hint}: the suites are {', '.join(SUITES)}")
    return [(task, task.episodes[suite]) for task in TASKS]
