"""What the 9-ball and 8-ball rules cost in a step of the game ids (target: under 10%).

A random policy plays each game id on the raw ``PoolEnv`` (resets included). The rules'
own work in a step is timed by wrapping the functions :mod:`pool_env.game.step` calls for
them: ``place_in_hand`` (the cue ball in hand), the nearest-free-point search when the
requested point is covered (``_place``), ``judge_rules`` (the compiled rules, re-spotting,
rewards) and the rule features of the observation (``encode_rule_observations``, minus
the ball encoding every id pays). Their summed time over the whole step time is the share;
the median over repeats is reported, with the solitaire id's steps/s for comparison.

The timed share counts each rule call as it runs inside a step (a cold cache after the
simulation, the wrappers' own ~1 us, and whatever the load does); the *isolated* column
times the same calls repeated on arguments captured from a step (a warm cache), as a
share of the same step time, and the *marginal* one what the rules add to solitaire's
kernels (``judge_rules - judge``, ``executed_rule_shots - executed_shots``, plus
``place_in_hand``), both in isolation.

Run: ``python bench/rules_cost.py`` (prints a markdown table; results/games.md quotes it).
"""

from __future__ import annotations

import argparse
import os
import statistics
import time
from collections.abc import Callable
from typing import Any

import gymnasium as gym
import numpy as np

import pool_env  # noqa: F401  (registers the ids)
from pool_env import encode_observations
from pool_env.game import step as game_step

PAIRS = {"pool_env/NineBallGameRoll-v1": "pool_env/NineBallRoll-v1",
         "pool_env/EightBallGameRoll-v1": "pool_env/EightBallRoll-v1"}  # fmt: skip
RULE_FUNCTIONS = ("place_in_hand", "_place", "judge_rules", "encode_rule_observations")


class Timer:
    """Accumulated seconds inside the wrapped functions."""

    def __init__(self) -> None:
        self.seconds = 0.0

    def wrap(self, fn: Callable[..., Any]) -> Callable[..., Any]:
        """``fn``, its time added to :attr:`seconds`."""

        def timed(*args: Any, **kwargs: Any) -> Any:
            start = time.perf_counter()
            try:
                return fn(*args, **kwargs)
            finally:
                self.seconds += time.perf_counter() - start

        return timed


def play(env: gym.Env, steps: int, seed: int) -> float:
    """Seconds for ``steps`` random shots (resets included)."""
    actions = np.random.default_rng(seed).uniform(-1, 1, (steps, *env.action_space.shape))
    env.reset(seed=seed)
    start = time.perf_counter()
    for action in actions:
        _, _, terminated, truncated, _ = env.step(action)
        if terminated or truncated:
            env.reset()
    return time.perf_counter() - start


def rule_share(env_id: str, steps: int, seed: int) -> tuple[float, float]:
    """``(share of the step time in the rules, steps per second)`` of one run."""
    env = gym.make(env_id).unwrapped
    play(env, 50, 999)  # compiled kernels loaded
    timer = Timer()
    saved = {name: getattr(game_step, name) for name in RULE_FUNCTIONS}
    try:
        for name in RULE_FUNCTIONS:
            setattr(game_step, name, timer.wrap(saved[name]))
        total = play(env, steps, seed)
    finally:
        for name, fn in saved.items():
            setattr(game_step, name, fn)
    # The ball encoding inside the rule observation is every id's, not the rules': its
    # time per call (the observation of a step and of a reset) comes off.
    state, table = env._state, env.config.table
    reps = 2000
    start = time.perf_counter()
    for _ in range(reps):
        encode_observations(state.positions, state.on_table, table.length, table.width)
    balls = (time.perf_counter() - start) / reps * steps
    return (timer.seconds - balls) / total, steps / total


def captured(env_id: str, name: str) -> tuple[Callable[..., Any], tuple[Any, ...]]:
    """The function ``name`` of :mod:`pool_env.game.step` and its arguments in one step."""
    env = gym.make(env_id).unwrapped
    env.reset(seed=0)
    env.step(np.zeros(env.action_space.shape))  # the break: one of each call
    args: list[tuple[Any, ...]] = []
    fn = getattr(game_step, name)

    def keep(*a: Any) -> Any:
        args.append(tuple(x.copy() if isinstance(x, np.ndarray) else x for x in a))
        return fn(*a)

    setattr(game_step, name, keep)
    try:
        env.step(np.zeros(env.action_space.shape))
    finally:
        setattr(game_step, name, fn)
    return fn, args[0]


def isolated_us(env_id: str, name: str, reps: int = 20_000) -> float:
    """Microseconds per call of ``name`` repeated on the arguments of one step."""
    fn, args = captured(env_id, name)
    fn(*args)
    start = time.perf_counter()
    for _ in range(reps):
        fn(*args)
    return (time.perf_counter() - start) / reps * 1e6


def main() -> None:
    """Measure and print the table."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--steps", type=int, default=2000)
    args = parser.parse_args()
    print(
        "| id | rules' share of a step (timed) | isolated | marginal | steps/s (raw) "
        "| solitaire id steps/s (raw) |"
    )
    print("|---|---|---|---|---|---|")
    for game_id, solitaire in PAIRS.items():
        runs = [rule_share(game_id, args.steps, seed) for seed in range(args.repeats)]
        shares = [s for s, _ in runs]
        rates = [r for _, r in runs]
        solo_env = gym.make(solitaire).unwrapped
        play(solo_env, 50, 999)
        solo = [args.steps / play(solo_env, args.steps, seed) for seed in range(args.repeats)]
        step_us = 1e6 / statistics.median(rates)
        rule_us = {n: isolated_us(game_id, n) for n in ("judge_rules", "place_in_hand",
                                                         "executed_rule_shots")}  # fmt: skip
        solo_us = {n: isolated_us(solitaire, n) for n in ("judge", "executed_shots")}
        isolated = rule_us["judge_rules"] + rule_us["place_in_hand"]
        marginal = (
            rule_us["judge_rules"] - solo_us["judge"] + rule_us["place_in_hand"]
            + rule_us["executed_rule_shots"] - solo_us["executed_shots"]
        )  # fmt: skip
        print(
            f"| `{game_id}` | {100 * statistics.median(shares):.1f}% "
            f"[{100 * min(shares):.1f}-{100 * max(shares):.1f}] | "
            f"{100 * isolated / step_us:.1f}% ({isolated:.1f} us) | "
            f"{100 * marginal / step_us:.1f}% ({marginal:.1f} us) | "
            f"{statistics.median(rates):,.0f} | {statistics.median(solo):,.0f} (`{solitaire}`) |"
        )
    print(f"\nload average {os.getloadavg()[0]:.1f}; command: `python bench/rules_cost.py "
          f"--repeats {args.repeats} --steps {args.steps}`")  # fmt: skip


if __name__ == "__main__":
    main()
