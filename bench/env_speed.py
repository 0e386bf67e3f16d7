"""Environment speed: steps per second of every registered id, through make() and raw.

A random policy (uniform actions in [-1, 1], drawn before timing so that the policy costs
nothing) plays each id; episodes reset as a training loop would, and resets count in the
time. Each configuration runs several repeats with different seeds; the table shows the
median and the range. A fresh process's first step (imports, numba cache load, first
shot) is timed too, since every ``SubprocVecEnv`` worker pays it.

Run: ``python bench/env_speed.py`` (writes ``results/env_speed.md``).
"""

from __future__ import annotations

import argparse
import os
import platform
import statistics
import subprocess
import sys
import time
from pathlib import Path

import gymnasium as gym
import numpy as np

import pool_env  # noqa: F401  (registers the ids)
from pool_env.envs.registration import ENV_IDS

STEPS = {
    "pool_env/PoolRoll-v1": 20_000,
    "pool_env/OneBallRoll-v1": 40_000,
    "pool_env/NineBallRoll-v1": 10_000,
    "pool_env/EightBallRoll-v1": 6_000,
    "pool_env/NineBallGameRoll-v2": 6_000,
    "pool_env/EightBallGameRoll-v1": 4_000,
    # the spin level (v1): ~2x the simulator's cost per shot
    "pool_env/Pool-v1": 10_000,
    "pool_env/OneBall-v1": 20_000,
    "pool_env/NineBall-v1": 5_000,
    "pool_env/EightBall-v1": 3_000,
    "pool_env/NineBallGame-v2": 4_000,
    "pool_env/EightBallGame-v1": 2_000,
}
TARGETS = {
    "pool_env/OneBallRoll-v1": 20_000,
    "pool_env/NineBallRoll-v1": 3_000,
    "pool_env/OneBall-v1": 15_000,  # issue 23
    "pool_env/NineBallGame-v2": 5_000,
}


def run(env: gym.Env, steps: int, seed: int) -> tuple[float, float, float]:
    """Play ``steps`` random shots.

    Returns:
        Steps per wall second, steps per CPU second of this thread (what the machine's
        load does not change: other processes take wall time, not this thread's CPU time)
        and the mean number of simulator events per shot.
    """
    size = (steps, *env.action_space.shape)  # (aim, speed), or the rules' Box(5)
    actions = np.random.default_rng(seed).uniform(-1.0, 1.0, size).astype(np.float32)
    env.reset(seed=seed)
    events = 0
    cpu_start = time.thread_time()
    start = time.perf_counter()
    for action in actions:
        _, _, terminated, truncated, info = env.step(action)
        events += info["n_events"]
        if terminated or truncated:
            env.reset()
    elapsed = time.perf_counter() - start
    return steps / elapsed, steps / (time.thread_time() - cpu_start), events / steps


def first_step_seconds(env_id: str) -> float:
    """Wall time of a fresh process: import, make, reset and one step (warm disk cache)."""
    code = (
        "import time; t = time.perf_counter(); import gymnasium as gym, pool_env;"
        f"env = gym.make({env_id!r}); env.reset(seed=0); env.step(env.action_space.sample());"
        "print(time.perf_counter() - t)"
    )
    out = subprocess.run([sys.executable, "-c", code], check=True, capture_output=True, text=True)
    return float(out.stdout.strip().splitlines()[-1])


def cpu_name() -> str:
    """The CPU model, from /proc/cpuinfo where there is one."""
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


def main() -> None:
    """Measure every id and write the table."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--scale", type=float, default=1.0, help="multiply the step counts")
    parser.add_argument("--ids", nargs="*", default=list(ENV_IDS), help="ids to measure")
    parser.add_argument(
        "--out", default=str(Path(__file__).parent.parent / "results" / "env_speed.md")
    )
    args = parser.parse_args()

    rows = []
    load_start = os.getloadavg()[0]
    for env_id in args.ids:
        steps = max(100, int(STEPS.get(env_id, 5_000) * args.scale))
        made, raw = gym.make(env_id), gym.make(env_id).unwrapped
        run(made, 200, 999)  # warm up: load compiled kernels, first allocations
        run(raw, 200, 999)
        # Alternate make/raw runs, so that load from other processes hits both alike.
        samples: dict[str, list[tuple[float, float, float]]] = {"make": [], "raw": []}
        for seed in range(args.repeats):
            samples["make"].append(run(made, steps, seed))
            samples["raw"].append(run(raw, steps, seed))
        results = {}
        for name, runs in samples.items():
            rates = [rate for rate, _, _ in runs]
            cpu = statistics.median(rate for _, rate, _ in runs)
            events = statistics.mean(ev for _, _, ev in runs)
            results[name] = (statistics.median(rates), min(rates), max(rates), events, cpu)
        first = first_step_seconds(env_id)
        rows.append((env_id, steps, results, first))
        m, r = results["make"], results["raw"]
        print(
            f"{env_id:24s} make {m[0]:9,.0f}/s  raw {r[0]:9,.0f}/s  CPU {m[4]:9,.0f}/s  "
            f"({1e6 / m[0]:6.1f} us/step, {m[3]:5.1f} events/shot, first step {first:.2f} s)"
        )

    lines = [
        "# Environment speed",
        "",
        "Steps per second of a random policy (uniform actions in [-1, 1], drawn before timing),",
        "resets included, median of "
        f"{args.repeats} seeds (range in brackets). `make`: `gymnasium.make(id)` with its",
        "wrappers (TimeLimit, OrderEnforcing, PassiveEnvChecker); `raw`: `.unwrapped`.",
        "First step: a fresh process importing, making, resetting and stepping once (warm",
        "numba disk cache), as every `SubprocVecEnv` worker does. Steps per CPU second: the",
        "same runs through make, counted against this thread's CPU time instead of the wall",
        "clock, which the load of other processes on the shared machine does not change.",
        "",
        "| id | steps/s via make | steps/s raw | steps per CPU s (make) | us/step (make) "
        "| events/shot | target | first step |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for env_id, _, res, first in rows:
        m, r = res["make"], res["raw"]
        target = TARGETS.get(env_id)
        verdict = (
            "" if target is None else f">= {target:,}: {'met' if m[0] >= target else 'MISSED'}"
        )
        lines.append(
            f"| `{env_id}` | {m[0]:,.0f} [{m[1]:,.0f}-{m[2]:,.0f}] | {r[0]:,.0f} "
            f"[{r[1]:,.0f}-{r[2]:,.0f}] | {m[4]:,.0f} | {1e6 / m[0]:.1f} | {m[3]:.1f} | {verdict} "
            f"| {first:.2f} s |"
        )
    lines += [
        "",
        f"Machine: {cpu_name()}, {os.cpu_count()} cores, one process; load average "
        f"{load_start:.1f} at the start and {os.getloadavg()[0]:.1f} at the end (other "
        f"processes share the machine), {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}. "
        "Python "
        f"{platform.python_version()}, numpy {np.__version__}, gymnasium {gym.__version__}.",
        "",
        "Command: `" + " ".join(["python bench/env_speed.py", *sys.argv[1:]]) + "`",
        "",
    ]
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    Path(args.out).write_text("\n".join(lines))
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
