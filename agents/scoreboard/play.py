"""Play one task of the scoreboard with one policy, through the runner its commands use.

``episodes`` tasks go through :func:`agents.evaluation.episodes.run_episodes` (as
``python -m agents.evaluate``), ``runouts`` through
:func:`agents.evaluation.runouts.play_racks` (as ``python -m agents.evaluation.runouts``)
and ``duel`` through :func:`agents.evaluation.duels.play_duels` (as
``python -m agents.duels``): no second copy of any loop. Each returns the task's record,
episode by episode (:mod:`agents.scoreboard.figures`).
"""

from __future__ import annotations

from dataclasses import asdict
from typing import Any

from agents.evaluation.duels import play_duels
from agents.evaluation.episodes import run_episodes
from agents.evaluation.players import make_agent
from agents.evaluation.runouts import play_racks
from agents.learned.envs import make_env
from agents.scoreboard.policies import ScoredPolicy
from agents.scoreboard.suite import Task

__all__ = ["play_task"]


def play_task(policy: ScoredPolicy, task: Task, episodes: int) -> dict[str, list[Any]]:
    """Play the first ``episodes`` episodes (racks) of ``task`` with ``policy``.

    Returns:
        The record: ``episodes``: :class:`~agents.evaluation.metrics.EpisodeLog`'s lists;
        ``runouts``: ``endings`` (each rack's, :data:`agents.evaluation.runouts.ENDINGS`)
        and ``break_made``; ``duel``: ``winners`` (``"agent"``, ``"opponent"`` or ``None``).
    """
    kwargs = policy.env_kwargs(task)
    if task.runner == "episodes":
        env = make_env(task.env_id, kwargs)
        try:
            agent = (
                policy.build(env)
                if policy.build is not None
                else make_agent(policy.spec, env, task.seed)
            )
            return asdict(run_episodes(agent, env, episodes, task.seed))
        finally:
            env.close()
    if task.runner == "runouts":
        out = play_racks(policy.spec, task.env_id, episodes, task.seed, kwargs, policy.build)
        return {"endings": out["per_rack"], "break_made": out["break_per_rack"]}
    assert task.opponent is not None
    out = play_duels(
        policy.spec, task.opponent, episodes, task.seed, kwargs["noise"], task.env_id,
        policy.build,
    )  # fmt: skip
    return {"winners": out["per_rack"]}
