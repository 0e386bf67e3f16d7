"""Speed of the ghost-ball feature wrappers that sit in the training loop.

Run: ``python -m bench.feature_speed`` (about 30 s; hold ``/work``'s CPU lock or a quiet
machine). Prints, best of three: steps per second of the native vector env (64 OneBallRoll-v1
tables) behind ``GhostFeaturesVecEnv`` and behind ``GhostCandidatesVecEnv`` (200 steps of
random actions drawn before timing), and the time of one
:meth:`agents.learned.features.GhostShotFeatures.of_observations` call on NineBallRoll-v1
observations in batches of 1, 64 and 256. ``results/feature_speed.md`` quotes it.
"""

from __future__ import annotations

import time

import gymnasium as gym
import numpy as np

from agents.baselines.base import env_spec
from agents.learned.features import GhostShotFeatures
from agents.training.run_config import TrainConfig
from agents.training.train_lib import make_vec

N_ENVS, STEPS, REPEATS = 64, 200, 3


def wrapper_speed(wrapper: str) -> float:
    """Steps per second (tables x steps) of the native vector env behind ``wrapper``."""
    venv = make_vec(TrainConfig(n_envs=N_ENVS, vec="native", wrapper=wrapper, seed=3))
    try:
        width = venv.action_space.shape[0]
        actions = np.random.default_rng(0).uniform(-1, 1, (STEPS, N_ENVS, width))
        actions = actions.astype(np.float32)
        venv.reset()
        for action in actions[:20]:  # warm-up: compiled code loaded, caches filled
            venv.step(action)
        best = np.inf
        for _ in range(REPEATS):
            start = time.perf_counter()
            for action in actions:
                venv.step(action)
            best = min(best, time.perf_counter() - start)
        return STEPS * N_ENVS / best
    finally:
        venv.close()


def feature_call_us(batch: int) -> float:
    """Microseconds of one ``of_observations`` call on ``batch`` NineBallRoll-v1 observations."""
    env = gym.make("pool_env/NineBallRoll-v1")
    features = GhostShotFeatures(env_spec(env))
    obs = np.stack([env.reset(seed=k)[0] for k in range(batch)])
    features.of_observations(obs)
    calls = max(20, 20000 // batch)
    best = np.inf
    for _ in range(REPEATS):
        start = time.perf_counter()
        for _ in range(calls):
            features.of_observations(obs)
        best = min(best, (time.perf_counter() - start) / calls)
    return best * 1e6


def main() -> None:
    """Print the figures."""
    for wrapper in ("ghost_features", "ghost_candidates"):
        print(f"{wrapper}: {wrapper_speed(wrapper):,.0f} steps/s ({N_ENVS} tables)")
    for batch in (1, 64, 256):
        print(f"of_observations, NineBallRoll-v1, batch {batch}: {feature_call_us(batch):,.1f} us")


if __name__ == "__main__":
    main()
