"""Sampling speed: RLlib with 1 and 2 EnvRunners against SB3, on the native vector env.

Env steps per second *sampled* (policy forward pass, action, one compiled step of every
table), not trained: sampling is what more EnvRunners scale; the learner is one process.
Every configuration uses a ``PoolVectorEnv`` of ``--tables`` tables of OneBallRoll-v1 and a
[64, 64] MLP on one torch thread, in the same run, on the same machine:

* RLlib: ``foreach_env_runner(sample)`` on every remote EnvRunner at once (they run in
  parallel), wall time of the round;
* SB3: ``PPO.collect_rollouts`` on ``agents.vec.native_vec`` (one process).

Usage::

    python bench/rllib_speed.py            # writes results/rllib_speed.md
    python bench/rllib_speed.py --quick
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
from pathlib import Path

ENV_ID = "pool_env/OneBallRoll-v1"


def load() -> str:
    """The 1-minute load average, as text."""
    return f"{os.getloadavg()[0]:.2f}"


def rllib_rate(
    runners: int, tables: int, steps: int, repeats: int
) -> tuple[float, float, list[str]]:
    """Sampling by ``runners`` EnvRunners at once.

    Returns:
        Median wall-clock env steps/s of all runners together, median env steps per
        CPU-second of one runner (its own process time), and the loads seen.
    """
    from agents.integrations.rllib_train import build_config, resolve_run

    run = resolve_run(ENV_ID, {"env_runners": runners, "n_envs": tables})
    algo = build_config(run).build_algo()
    group = algo.env_runner_group

    def sample(runner: object) -> tuple[int, float]:
        cpu = time.process_time()
        episodes = runner.sample(num_timesteps=steps, random_actions=False)  # type: ignore[attr-defined]
        return sum(len(e) for e in episodes), time.process_time() - cpu

    try:
        group.foreach_env_runner(sample, local_env_runner=False)  # warm-up: compile, connect
        rates, per_cpu, loads = [], [], []
        for _ in range(repeats):
            t0 = time.perf_counter()
            done = group.foreach_env_runner(sample, local_env_runner=False)
            rates.append(sum(n for n, _ in done) / (time.perf_counter() - t0))
            per_cpu += [n / cpu for n, cpu in done]
            loads.append(load())
    finally:
        algo.stop()
    return statistics.median(rates), statistics.median(per_cpu), loads


def sb3_rate(tables: int, steps: int, repeats: int) -> tuple[float, list[str]]:
    """Median env steps/s of SB3 PPO's rollout collection on the native vector env."""
    from stable_baselines3 import PPO
    from stable_baselines3.common.callbacks import CallbackList

    from agents.vec.native_vec import make_native_vec_env

    env = make_native_vec_env(ENV_ID, tables, 0)
    n_steps = max(1, steps // tables)
    model = PPO("MlpPolicy", env, n_steps=n_steps, batch_size=tables, device="cpu", seed=0)
    model._setup_learn(n_steps * tables * (repeats + 1), CallbackList([]))
    callback = CallbackList([])
    callback.init_callback(model)
    rates, loads = [], []
    for k in range(repeats + 1):
        t0 = time.perf_counter()
        model.collect_rollouts(env, callback, model.rollout_buffer, n_steps)
        if k:  # the first round compiles and warms up
            rates.append(n_steps * tables / (time.perf_counter() - t0))
            loads.append(load())
    env.close()
    return statistics.median(rates), loads


def main(argv: list[str] | None = None) -> int:
    """Measure, print, write the table."""
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--tables", type=int, default=64, help="tables per vector env")
    p.add_argument("--steps", type=int, default=8192, help="env steps per runner per round")
    p.add_argument("--repeats", type=int, default=5)
    p.add_argument("--quick", action="store_true", help="2 repeats, 2048 steps")
    p.add_argument("--out", default="results/rllib_speed.md")
    args = p.parse_args(argv)
    if args.quick:
        args.repeats, args.steps = 2, 2048

    import ray
    import torch

    torch.set_num_threads(1)  # as the trainers: small MLPs, one thread (see agents)
    cpus = os.cpu_count() or 1
    rows = []
    sb3, sb3_loads = sb3_rate(args.tables, args.steps, args.repeats)
    rows.append(("SB3 PPO rollouts, native vector env (1 process)", sb3, sb3_loads))
    print(f"SB3: {sb3:,.0f} steps/s (load {', '.join(sb3_loads)})", flush=True)
    ray.init(num_cpus=max(2, cpus), include_dashboard=False, log_to_driver=False)
    try:
        rates, per_cpu = {}, {}
        for runners in (1, 2):
            rate, cpu_rate, loads = rllib_rate(runners, args.tables, args.steps, args.repeats)
            rates[runners], per_cpu[runners] = rate, cpu_rate
            rows.append((f"RLlib PPO, {runners} EnvRunner{'s' * (runners > 1)}", rate, loads))
            print(
                f"RLlib {runners}: {rate:,.0f} steps/s, {cpu_rate:,.0f} per runner CPU-s "
                f"(load {', '.join(loads)})",
                flush=True,
            )
    finally:
        ray.shutdown()

    ratio = rates[2] / rates[1]
    command = "python bench/" + Path(__file__).name + " " + " ".join(argv or sys.argv[1:])
    lines = [
        "# Sampling speed: RLlib EnvRunners against SB3 (OneBallRoll-v1, native vector env)",
        "",
        f"Command: `{command.strip()}`; {cpus} CPUs; {args.tables} tables per vector env; "
        f"{args.steps} env steps per runner per round; median of {args.repeats} rounds; "
        "torch on one thread. Env steps per second sampled (policy + env), not trained.",
        "",
        "| sampler | env steps/s | load (1-min avg) per round |",
        "|---|---|---|",
    ]
    for name, rate, loads in rows:
        lines.append(f"| {name} | {rate:,.0f} | {', '.join(loads)} |")
    lines += [
        "",
        f"2 EnvRunners / 1 EnvRunner: {ratio:.2f}x (target >= 1.5x). "
        f"RLlib 1 EnvRunner / SB3: {rates[1] / sb3:.2f}x.",
        "",
        "Env steps per CPU-second of one EnvRunner's own process (median over runners and "
        f"rounds): {per_cpu[1]:,.0f} with 1 EnvRunner, {per_cpu[2]:,.0f} each with 2. "
        "A runner is one single-threaded process, so the wall-clock rate of N runners "
        "reaches N times one runner only while N cores are free; a load average above the "
        "core count means other processes hold them.",
        "",
        "RLlib's EnvRunner autoresets next-step: a one-shot episode costs two vector steps "
        "(one shot, one reset), which RLlib does not count as env steps; SB3's adapter "
        "resets in the same step.",
        "",
    ]
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    Path(args.out).write_text("\n".join(lines))
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    sys.exit(main())
