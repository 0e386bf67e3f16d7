"""Agents for pool_env: baselines with SB3's ``predict``, evaluation, and training on SB3.

``RandomAgent(env)``, ``ConstantAgent(env)``, ``GhostBallAgent(env)`` (the geometric
heuristic, no simulation) and ``SearchAgent(env)`` (candidate shots checked on the simulator)
work with SB3's ``evaluate_policy``;
:func:`agents.evaluate.run_episodes` reports pots per shot, clean pots, scratches and clears.
Training (``agents.train_lib``, ``train.py``) needs the ``train`` extra (SB3, torch).
"""

from typing import Any

from agents.ghost_ball import GhostBallAgent
from agents.random_agent import ConstantAgent, RandomAgent
from agents.search import SearchAgent

__all__ = [
    "ConstantAgent",
    "GhostBallAgent",
    "RandomAgent",
    "SearchAgent",
    "evaluate_agent",
    "run_episodes",
]


def __getattr__(name: str) -> Any:
    # Lazy, so that ``python -m agents.evaluate`` does not import its own module twice.
    if name in ("evaluate_agent", "run_episodes"):
        from agents import evaluate

        return getattr(evaluate, name)
    raise AttributeError(f"module 'agents' has no attribute {name!r}")
