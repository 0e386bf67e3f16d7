"""Agents for pool_env: baselines with SB3's ``predict``, evaluation, and training on SB3.

``RandomAgent(env)``, ``ConstantAgent(env)``, ``GhostBallAgent(env)`` (the geometric
heuristic, no simulation) and ``SearchAgent(env)`` (candidate shots checked on the simulator)
work with SB3's ``evaluate_policy``;
:func:`agents.evaluate.run_episodes` reports pots per shot, clean pots, scratches and clears.
Training (``agents.train_lib``, ``train.py``) needs the ``train`` extra (SB3, torch).
:func:`agents.load` loads a pretrained model with the observation wrapper of its saved
config (:mod:`agents.pretrained`), so ``agents.load("models/ppo_oneball.zip").predict(obs)``
plays on the env's own observations.
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
    "load",
    "run_episodes",
]


def __getattr__(name: str) -> Any:
    # Lazy, so that ``python -m agents.evaluate`` does not import its own module twice.
    if name in ("evaluate_agent", "run_episodes"):
        from agents import evaluate

        return getattr(evaluate, name)
    if name == "load":  # SB3 and torch only when a model is loaded
        from agents.pretrained import load

        return load
    raise AttributeError(f"module 'agents' has no attribute {name!r}")
