"""Agents for pool_env: baselines with SB3's ``predict``, evaluation, and training on SB3.

``RandomAgent(env)`` and ``GhostBallAgent(env)`` work with SB3's ``evaluate_policy``;
:func:`agents.evaluate.run_episodes` reports pots per shot, clean pots, scratches and clears.
Training (``agents.train_lib``, ``train.py``) needs the ``train`` extra (SB3, torch).
"""

from agents.evaluate import evaluate_agent, run_episodes
from agents.ghost_ball import GhostBallAgent
from agents.random_agent import RandomAgent

__all__ = ["GhostBallAgent", "RandomAgent", "evaluate_agent", "run_episodes"]
