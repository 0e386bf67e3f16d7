"""Play episodes and count: pots per shot, clean pots, scratches, turns, clears, reward.

The loop every evaluation shares (:mod:`agents.evaluation.evaluate`, the best-constant scan of
:mod:`agents.evaluation.constant_scan`, the training runs' periodic evaluations). It needs only
an agent with SB3's ``predict`` signature and a Gymnasium env, not SB3 itself.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from agents.evaluation.metrics import EpisodeLog
from agents.policy import Policy

__all__ = ["run_episodes"]


def run_episodes(
    agent: Policy,
    env: Any,
    episodes: int,
    seed: int,
    deterministic: bool = True,
    progress: Callable[[int], object] | None = None,
) -> EpisodeLog:
    """Play ``episodes`` episodes (episode ``k`` reset with ``seed + k``) and count.

    Args:
        agent: A :class:`~agents.policy.Policy` (SB3's ``predict``).
        env: A Gymnasium ``PoolEnv`` (wrapped or not).
        episodes: Number of episodes.
        seed: Seed of the first episode.
        deterministic: Passed to ``predict``.
        progress: Called with 1 after each episode (a progress bar's ``update``).

    Returns:
        The per-episode counts.

    Examples:
        >>> import gymnasium as gym
        >>> from agents import GhostBallAgent, RandomAgent, run_episodes
        >>> env = gym.make("pool_env/OneBallRoll-v1")
        >>> log = run_episodes(GhostBallAgent(env), env, episodes=20, seed=10000)
        >>> print(log.summary()["pots_per_shot"])  # rate [95% interval]
        1.000 [0.839, 1.000]
        >>> random = run_episodes(RandomAgent(env, seed=0), env, episodes=20, seed=10000)
        >>> random.summary()["pots_per_shot"].value < 0.5
        True
    """
    log = EpisodeLog()
    for k in range(episodes):
        obs, _ = env.reset(seed=seed + k)
        shots = pots = clean = scratches = turns = fouls = 0
        reward, first_turn = 0.0, True
        while True:
            action, _ = agent.predict(obs, deterministic=deterministic)
            obs, r, terminated, truncated, info = env.step(action)
            n_pot, scratch = len(info["potted"]), bool(info["scratch"])
            shots, pots, reward = shots + 1, pots + n_pot, reward + float(r)
            clean += n_pot > 0 and not scratch
            scratches += scratch
            rules = "foul" in info  # a game id: the rules say when the turn ends
            fouls += rules and info["foul"] is not None
            turn_over = bool(info["turn_over"]) if rules else (n_pot == 0 or scratch)
            if turn_over:
                turns += 1
                first_turn = False
            if terminated or truncated:
                turns += not turn_over  # the last turn ends with the episode
                break
        cleared = bool(info.get("is_success", False))
        log.shots.append(shots)
        log.pots.append(pots)
        log.clean.append(clean)
        log.scratches.append(scratches)
        log.turns.append(turns)
        log.rewards.append(reward)
        log.cleared.append(cleared)
        log.run_out.append(cleared and first_turn)
        if rules:
            log.fouls.append(fouls)
        if progress is not None:
            progress(1)
    return log
