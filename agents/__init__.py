"""Agents for pool_env: baselines with SB3's ``predict``, evaluation, and training on SB3.

Where a change goes:

* ``baselines/``: agents that play from geometry or the simulator (``RandomAgent``,
  ``ConstantAgent``, ``GhostBallAgent``, ``SearchAgent``); no stable-baselines3 needed.
* ``episodes``, ``metrics``, ``evaluate``: play episodes and count (pots per shot, clean
  pots, scratches, clears, with 95% intervals); ``python -m agents.evaluate`` compares agents.
* ``envs``, ``features``: the envs a learner sees (observation wrappers by name).
* ``pretrained``: :func:`agents.load`, a saved model with the wrapper of its config.
* ``rack_play``, ``lookahead`` (with ``layout_value`` and ``game_model``), ``duels``: 9-ball
  players on the spin ids (a learned value over the planner's pots; candidates played out
  on the game's own step and valued by a learned layout value) and head-to-head racks.
* ``training/`` and ``train`` (``python train.py``): training on SB3 (the ``train`` extra).
* ``vec/``: vector-env adapters (SB3 ``VecEnv``, Gymnasium's same-step stack).
* ``integrations/``: Ray RLlib and RL Zoo.

``agents.load("models/ppo_oneball.zip").predict(obs)`` plays on the env's own observations.
"""

from typing import Any

from agents.baselines.ghost_ball import GhostBallAgent
from agents.baselines.random_agent import ConstantAgent, RandomAgent
from agents.baselines.search import SearchAgent
from agents.episodes import run_episodes
from agents.pretrained import load

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
    # Lazy, so that ``python -m agents.evaluate`` does not import its own module twice
    # (runpy warns when the package has already imported the module it runs as __main__).
    if name == "evaluate_agent":
        from agents import evaluate

        return evaluate.evaluate_agent
    raise AttributeError(f"module 'agents' has no attribute {name!r}")
