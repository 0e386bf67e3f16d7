"""Results files of the scoreboard: one per scored player, and the references they give.

``results/scoreboard/<player>.json`` (``<player>.<suite>.json`` for a suite other than
``full``) holds what :func:`score_policy` measured: the policy as written, the suite, and
per task its definition (:meth:`~agents.scoreboard.suite.Task.spec`), its episode count,
either its figures as text and its record episode by episode or ``"n/a"`` with the reason,
and how it was measured: the command, the date, the 1, 5 and 15-minute load averages
before and after, and the git revision (``+modified``: the code differed from it).

A task's **normalized score** is ``(figure - random's) / (best's - random's)``
(:func:`~agents.scoreboard.figures.normalized`), where random's and the best player's
figures are those of the results files in the same folder on the same task (an equal
definition) and the same first episodes (:func:`references`): random play scores 0, the best
file of the folder 1.
"""

from __future__ import annotations

import datetime
import json
import os
import re
import subprocess
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

from agents.evaluation.metrics import Estimate
from agents.scoreboard.figures import FIGURES, figure, normalized
from agents.scoreboard.play import play_task
from agents.scoreboard.policies import ScoredPolicy
from agents.scoreboard.suite import TASKS, Task, suite_tasks

__all__ = [
    "RANDOM",
    "RESULTS",
    "dump_results",
    "label",
    "load_results",
    "merge_results",
    "references",
    "results_path",
    "row_figures",
    "score_policy",
    "task_by_name",
]

#: The folder of the committed results files.
RESULTS = Path("results/scoreboard")
#: The player whose figures are the normalized score's zero.
RANDOM = "random"


def _git_revision() -> str:
    """The checkout's commit, ``+modified`` if the code (agents/, pool_env/) differs from it."""
    try:
        rev = subprocess.run(
            ["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True, check=True
        ).stdout.strip()
        dirty = subprocess.run(["git", "diff", "--quiet", "HEAD", "--", "agents", "pool_env"])
    except (OSError, subprocess.CalledProcessError):
        return "unknown (no git checkout)"
    return rev + ("+modified" if dirty.returncode else "")


def score_policy(
    policy: ScoredPolicy,
    suite: str,
    command: str,
    only: list[str] | None = None,
    progress: Callable[[str], object] | None = None,
) -> dict[str, Any]:
    """Play the tasks of ``suite`` with ``policy``: the results file's content.

    Each task's entry carries its own provenance (the command, the date, the load before
    and after, the git revision), so that tasks scored by separate commands
    (``--tasks``, :func:`merge_results`) each say how they were measured.

    Args:
        policy: The policy (:func:`~agents.scoreboard.policies.resolve_policy`).
        suite: One of :data:`~agents.scoreboard.suite.SUITES`.
        command: The command line, stored as written.
        only: The names of the tasks to play (default: all).
        progress: Called with one line after each task.

    Raises:
        ValueError: On an unknown suite or task name, or a factory that breaks the
            protocol.
    """
    tasks: dict[str, Any] = {}
    chosen = suite_tasks(suite)
    if only is not None:
        names = [task.name for task, _ in chosen]
        unknown = [name for name in only if name not in names]
        if unknown:
            raise ValueError(f"unknown task {unknown[0]!r}: the tasks are {', '.join(names)}")
        chosen = [(task, n) for task, n in chosen if task.name in only]
    git = _git_revision()
    for task, n in chosen:
        load_before = os.getloadavg()
        entry: dict[str, Any] = {"spec": task.spec(), "episodes": n}
        reason = policy.refusal(task)
        if reason is not None:
            entry.update(status="n/a", reason=reason)
        else:
            start = time.perf_counter()
            record = play_task(policy, task, n)
            entry.update(status="ok", seconds=round(time.perf_counter() - start, 1))
            entry["figures"] = {
                key: figure(key, record, n).as_percent() for key in (task.figure, *task.beside)
            }
        entry.update(
            command=command,
            date=datetime.datetime.now(datetime.UTC).strftime("%Y-%m-%d %H:%M UTC"),
            load=[round(v, 2) for v in (*load_before, *os.getloadavg())],
            git=git,
        )
        if entry["status"] == "ok":
            entry["record"] = record  # last: the long lists after what a reader wants
        tasks[task.name] = entry
        if progress is not None:
            shown = entry.get("figures", {}).get(task.figure) or f"n/a: {entry.get('reason')}"
            seconds = f" ({entry['seconds']} s)" if "seconds" in entry else ""
            progress(f"{task.name}: {shown}{seconds}")
    return {"player": policy.spec, "suite": suite, "tasks": tasks}


def merge_results(old: dict[str, Any], new: dict[str, Any]) -> dict[str, Any]:
    """``new``'s tasks over ``old``'s, in the suite's order (one player, one suite).

    Raises:
        ValueError: If the two are not the same player's on the same suite.
    """
    if (old["player"], old["suite"]) != (new["player"], new["suite"]):
        raise ValueError(
            f"results of {new['player']!r} on {new['suite']!r} cannot be merged into a file "
            f"of {old['player']!r} on {old['suite']!r}"
        )
    tasks = {**old["tasks"], **new["tasks"]}
    order = [task.name for task in TASKS]
    ordered = sorted(tasks, key=lambda k: order.index(k) if k in order else len(order))
    return {**old, "tasks": {name: tasks[name] for name in ordered}}


def dump_results(data: dict[str, Any]) -> str:
    """A results file's text: indented JSON with each list of numbers or words on one line."""
    text = json.dumps(data, indent=1)
    flat = re.sub(r"\[([^\[\]{}]*)\]", lambda m: "[" + " ".join(m.group(1).split()) + "]", text)
    return flat + "\n"


def results_path(folder: Path, slug: str, suite: str) -> Path:
    """Where ``--save`` writes: ``<folder>/<slug>.json``, ``<slug>.<suite>.json`` off ``full``."""
    return folder / (f"{slug}.json" if suite == "full" else f"{slug}.{suite}.json")


def load_results(folder: Path) -> dict[str, dict[str, Any]]:
    """Every results file of ``folder`` by its path (``*.json``, sorted).

    Raises:
        ValueError: On a file that is not a results file (JSON without ``player`` and
            ``tasks``), naming it.
    """
    out = {}
    for path in sorted(folder.glob("*.json")):
        try:
            data = json.loads(path.read_text())
        except json.JSONDecodeError as err:
            raise ValueError(f"results file {str(path)!r} is not JSON: {err}") from None
        if not isinstance(data, dict) or not {"player", "tasks"} <= set(data):
            raise ValueError(f"results file {str(path)!r} holds no player and tasks")
        out[str(path)] = data
    return out


def _figure_of(data: dict[str, Any], task: Task, n: int) -> Estimate | None:
    """A results file's figure on ``task``'s first ``n`` episodes, if it played them."""
    entry = data["tasks"].get(task.name)
    if (
        entry is None
        or entry.get("status") != "ok"
        or entry.get("spec") != json.loads(json.dumps(task.spec()))  # as JSON stores it
        or entry["episodes"] < n
    ):
        return None
    return figure(task.figure, entry["record"], n)


def references(
    files: dict[str, dict[str, Any]], task: Task, n: int
) -> tuple[float | None, float | None]:
    """Random's figure and the best file's on ``task``'s first ``n`` episodes (or ``None``)."""
    random = best = None
    for data in files.values():
        estimate = _figure_of(data, task, n)
        if estimate is None:
            continue
        if data["player"] == RANDOM and random is None:
            random = estimate.value
        best = estimate.value if best is None else max(best, estimate.value)
    return random, best


def row_figures(
    entry: dict[str, Any], task: Task, files: dict[str, dict[str, Any]]
) -> tuple[Estimate, float | None]:
    """A played task's figure (its own episodes) and its normalized score against ``files``."""
    n = entry["episodes"]
    estimate = figure(task.figure, entry["record"], n)
    return estimate, normalized(estimate.value, *references(files, task, n))


def task_by_name(name: str) -> Task | None:
    """The suite's task called ``name`` (``None`` for a task no longer in it)."""
    return next((task for task in TASKS if task.name == name), None)


def label(key: str) -> str:
    """A figure's label in the tables."""
    return FIGURES[key][0]
