"""Agents for pool_env: baselines with SB3's ``predict``, evaluation, and training on SB3.

Every agent is a :class:`~agents.policy.Policy` (SB3's ``predict``). Where a change goes:

* ``baselines/``: agents that play from geometry or the simulator (``RandomAgent``,
  ``ConstantAgent``, ``GhostBallAgent``, ``SearchAgent``, and the same under the rules of
  the game ids); no stable-baselines3 needed.
* ``learned/``: what learns or was learned: the envs a learner sees (``envs``, ``features``,
  ``candidates``), :func:`agents.load` (``pretrained``), and the 9-ball players on the spin
  ids (``rack_play``: a learned value over the planner's pots; ``lookahead`` with
  ``layout_value`` and ``game_model``: candidates played out on the game's own step and
  valued by a learned layout value).
* ``evaluation/``: play episodes and count (``episodes``, ``metrics``: pots per shot, clean
  pots, scratches, clears, with 95% intervals), agents by name (``evaluate``), the best
  constant action (``constant_scan``) and head-to-head racks (``duels``).
* ``training/``: training on SB3 (the ``train`` extra), and fitting the 9-ball values.
* ``vec/``: vector-env adapters (SB3 ``VecEnv``, Gymnasium's same-step stack).
* ``integrations/``: Ray RLlib and RL Zoo.
* The commands: ``train`` (``python train.py``), ``evaluate`` (``python -m agents.evaluate``
  compares agents) and ``duels`` (``python -m agents.duels``); and ``policy``, the protocol
  every agent meets.

``agents.load("models/ppo_oneball.zip").predict(obs)`` plays on the env's own observations.
"""

from agents.baselines.ghost_ball import GhostBallAgent
from agents.baselines.random_agent import ConstantAgent, RandomAgent
from agents.baselines.search import SearchAgent
from agents.evaluation.episodes import run_episodes
from agents.evaluation.evaluate import evaluate_agent
from agents.learned.pretrained import load
from agents.policy import Planner, Policy

__all__ = [
    "ConstantAgent",
    "GhostBallAgent",
    "Planner",
    "Policy",
    "RandomAgent",
    "SearchAgent",
    "evaluate_agent",
    "load",
    "run_episodes",
]
