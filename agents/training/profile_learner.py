"""Where a training step's time goes: the env against torch.

Run: ``python -m agents.training.profile_learner --steps 100000``.

Trains the hyperparameter file's recipe (PPO on ``OneBall-v1`` by default) for a number of
steps with three clocks: the vector env's ``step`` (the simulator, the ghost-ball features
and the candidate decoding), the policy's forward pass while collecting rollouts, and
PPO's ``train`` (the gradient epochs). What is left is SB3's Python around them (rollout
buffer, callbacks, tensor conversion). Prints one markdown table row per part with its
seconds, its share of the run and env steps per second of the whole.
"""

from __future__ import annotations

import argparse
import functools
import sys
import time
from collections.abc import Callable
from typing import Any

from agents.training import hyperparams
from agents.training.run_config import ALGOS, resolve_config
from agents.training.train_lib import make_vec, warm_up


def _timed(clock: dict[str, float], key: str, fn: Callable[..., Any]) -> Callable[..., Any]:
    """``fn`` that adds its wall seconds to ``clock[key]``."""

    @functools.wraps(fn)
    def wrapper(*args: Any, **kwargs: Any) -> Any:
        t0 = time.perf_counter()
        try:
            return fn(*args, **kwargs)
        finally:
            clock[key] += time.perf_counter() - t0

    return wrapper


def profile(env_id: str, algo: str, steps: int, seed: int = 0) -> dict[str, float]:
    """Train ``steps`` steps of the file's recipe; the seconds of each part and in all.

    Returns:
        ``{"env", "forward", "train", "total"}`` wall seconds and ``"steps"``.
    """
    import torch

    torch.set_num_threads(1)
    config = resolve_config(env_id, algo, {"seed": seed, "n_timesteps": steps})
    warm_up(config)  # compiling is not a step's cost
    venv = make_vec(config)
    clock = {"env": 0.0, "forward": 0.0, "train": 0.0}
    venv.step = _timed(clock, "env", venv.step)  # type: ignore[method-assign]
    model = ALGOS[algo](
        config.policy,
        venv,
        seed=seed,
        device="cpu",
        verbose=0,
        **hyperparams.to_sb3(config.algo_kwargs),
    )
    model.policy.forward = _timed(clock, "forward", model.policy.forward)  # type: ignore[method-assign]
    model.train = _timed(clock, "train", model.train)  # type: ignore[method-assign]
    t0 = time.perf_counter()
    model.learn(steps)
    total = time.perf_counter() - t0
    venv.close()
    return {**clock, "total": total, "steps": float(model.num_timesteps)}


def main(argv: list[str] | None = None) -> int:
    """Profile and print the table."""
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--env", default="pool_env/OneBall-v1")
    p.add_argument("--algo", default="ppo", choices=sorted(ALGOS))
    p.add_argument("--steps", type=int, default=100_000)
    p.add_argument("--seed", type=int, default=0)
    args = p.parse_args(argv)
    if args.steps <= 0:
        p.error("--steps must be positive")
    out = profile(args.env, args.algo, args.steps, args.seed)
    total = out["total"]
    rest = total - out["env"] - out["forward"] - out["train"]
    print(f"{args.algo.upper()} on {args.env}, {out['steps']:,.0f} steps: "
          f"{out['steps'] / total:,.0f} env steps/s of training")  # fmt: skip
    print("| part | seconds | share |\n|---|---|---|")
    parts = [
        ("env step (simulator, features, decoding)", out["env"]),
        ("policy forward in rollouts (torch)", out["forward"]),
        ("gradient epochs (torch)", out["train"]),
        ("SB3 Python around them", rest),
        ("total", total),
    ]
    for name, seconds in parts:
        print(f"| {name} | {seconds:.1f} | {seconds / total:.0%} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
