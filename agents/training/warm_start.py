"""A warm start on the env's own action: the policy's mean fitted to row 0 before RL.

On ``pool_env/OneBallRoll-v1``'s own ``Box(2)`` action PPO stalls near 68% pots where row 0
of the ``"shots"`` observation, played exactly, pots 96% (results/oneball_scratches.md). Its
misses are not imprecise aims (the pot window is about 0.09 of the aim action wide): most
aim *between* two pockets' rows, the mean of a one-mode Gaussian pulled by the pots its
samples find in two pockets at once. A warm start puts the mean on one mode first: a
supervised fit of the policy's deterministic action to the first-row agent's
(:class:`agents.baselines.shot_row.ShotRowAgent`: row 0's aim and speed, the tip at the
centre) on layouts drawn apart from every evaluation's seeds; RL then refines it. The
action space stays the env's own; only the network's starting point changes.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from agents.baselines.shot_row import ShotRowAgent
from agents.learned.envs import make_env
from agents.training.hyperparams import WARM_STARTS

if TYPE_CHECKING:
    from stable_baselines3.common.base_class import BaseAlgorithm

#: Seeds of the warm start's layouts: apart from the training envs' streams, the periodic
#: evaluations (20,000+), the final ones (10,000+) and the fresh seeds of model cards.
WARM_START_SEED = 700_000

#: Layouts fitted, and the fit's passes over them and minibatch size: a 128x128 net's mean
#: follows row 0 to a few thousandths in about 2 s of CPU (tests/agents/test_warm_start.py).
LAYOUTS, EPOCHS, BATCH = 8192, 30, 256


def first_row_targets(
    env_id: str, env_kwargs: dict[str, Any], layouts: int, seed: int = WARM_START_SEED
) -> tuple[NDArray[np.float32], NDArray[np.float32]]:
    """``(observations, actions)``: ``layouts`` resets and the first-row agent's action on each.

    Raises:
        ValueError: If the env has no ``"shots"`` observation (the first-row agent's).
    """
    env = make_env(env_id, env_kwargs)
    try:
        agent = ShotRowAgent(env)
        obs = np.stack([env.reset(seed=seed + k)[0] for k in range(layouts)]).astype(np.float32)
    finally:
        env.close()
    return obs, agent.act(obs)


def fit_policy_mean(
    model: BaseAlgorithm,
    observations: NDArray[np.float32],
    actions: NDArray[np.float32],
    epochs: int = EPOCHS,
    batch: int = BATCH,
    seed: int = 0,
) -> float:
    """Fit ``model``'s deterministic action to ``actions`` by mean squared error; the last loss.

    The policy's own optimizer and learning rate are left as they were (a separate Adam
    fits), so RL starts from the fitted weights with its schedule untouched. PPO's
    deterministic action is its Gaussian's mean (what the evaluations play); its
    ``log_std`` is not touched.
    """
    import torch

    policy = model.policy
    obs_t = torch.as_tensor(observations)
    act_t = torch.as_tensor(actions)
    optimizer = torch.optim.Adam(policy.parameters(), lr=1e-3)
    generator = np.random.default_rng(seed)
    n = obs_t.shape[0]
    loss = torch.zeros(())
    policy.set_training_mode(True)
    for _ in range(epochs):
        order = torch.as_tensor(generator.permutation(n))
        for start in range(0, n, batch):
            idx = order[start : start + batch]
            predicted = policy._predict(obs_t[idx], deterministic=True)
            loss = torch.mean((predicted - act_t[idx]) ** 2)
            optimizer.zero_grad()
            loss.backward()
            optimizer.step()
    policy.set_training_mode(False)
    return float(loss.detach())


def warm_start(model: BaseAlgorithm, name: str, env_id: str, env_kwargs: dict[str, Any]) -> float:
    """Apply the warm start ``name`` (one of :data:`WARM_STARTS`) to ``model``; the last loss.

    Raises:
        ValueError: On an unknown name, or an env without the ``"shots"`` observation.
    """
    if name not in WARM_STARTS:
        raise ValueError(f"warm_start {name!r}: use one of {list(WARM_STARTS)}")
    observations, actions = first_row_targets(env_id, env_kwargs, LAYOUTS)
    return fit_policy_mean(model, observations, actions)
