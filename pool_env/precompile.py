"""Compile every kernel the registered environments use, ahead of a first shot, in parallel.

numba compiles the simulator's kernels on their first call and caches the machine code on
disk (:mod:`pool_env.sim.jit`); from an empty cache a first shot waits for the compiler.
This command plays a few shots on every registered id (earlier versions included), as a
single env and as a vector env (rendering each shot), in as many processes as the machine
has cores: each kernel
compiles once, in whichever process needs it first (:mod:`pool_env.sim.compile_lock`), and
every later process loads it::

    python -m pool_env.precompile

Run it once after installing (the README's install does); with the cache already filled it
only loads, in a few seconds. Agents' and benchmarks' own kernels compile when first used.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
import warnings
from concurrent.futures import ProcessPoolExecutor, as_completed
from multiprocessing import get_context
from typing import Any

import numpy as np

#: One job: an env id and how it is played. "env": ``gym.make``, a frame rendered after
#: each shot; "vector": ``gym.make_vec`` over two tables; "shots": both, with the
#: ``observation="shots"`` features (what ``train.py`` trains on).
Job = tuple[str, str]

KINDS = ("env", "vector", "shots")


def jobs() -> list[Job]:
    """Every registered id in every kind, in an order that keeps two processes busy.

    The spin table's event loop is the costliest compile (about half of all): its first id
    goes first, then every roll job, which a second process compiles meanwhile (a roll job
    waiting for a spin kernel would sit idle), then the rest of the current spin jobs, which
    mostly load what the first compiled, and last the earlier versions that still play
    (``NineBallGame-v1``: another rack order and no push-out, some kernels of their own).
    """
    from gymnasium import registry

    from pool_env.envs.registration import CURRENT_IDS, ROLL_IDS

    spin = [i for i in CURRENT_IDS if i not in ROLL_IDS]
    roll = [i for i in CURRENT_IDS if i in ROLL_IDS]
    earlier = sorted(i for i in registry if i.startswith("pool_env/") and i not in CURRENT_IDS)
    every = (
        [(spin[0], "env")]
        + [(i, kind) for kind in KINDS for i in roll]
        + [(i, kind) for kind in KINDS for i in spin if (i, kind) != (spin[0], "env")]
        + [(i, kind) for i in earlier for kind in KINDS]
    )
    return [(i, kind) for i, kind in every if kind != "shots" or plays_shots(i)]


def plays_shots(env_id: str) -> bool:
    """Whether ``env_id`` takes ``observation="shots"`` (three-cushion refuses it)."""
    from gymnasium import registry

    from pool_env.game.config import make_config

    try:
        make_config(**registry[env_id].kwargs["id_defaults"], observation="shots")
    except ValueError:
        return False
    return True


def _play(env: Any, render: bool = False) -> None:
    """Reset, play three random shots (rendering each), close."""
    env.reset(seed=0)
    env.action_space.seed(0)
    for _ in range(3):
        _, _, terminated, truncated, _ = env.step(env.action_space.sample())
        if render:
            env.render()  # the shot's paths: the timeline kernels
        if np.any(terminated) or np.any(truncated):
            env.reset()
    env.close()


def run_job(job: Job) -> tuple[Job, float]:
    """Play ``job`` (:data:`Job`) to compile, or load, the kernels it needs.

    A single env plays both with and without a render mode: rendering records the shot's
    paths, which calls the rules' kernels with other arguments (SB3's envs render nothing,
    the README's quick start renders).

    Returns:
        The job and the seconds it took in its process.
    """
    start = time.perf_counter()
    warnings.filterwarnings("ignore", message=".*out of date.*")  # an older id's version
    import gymnasium as gym

    import pool_env  # noqa: F401  (registers the ids)
    from pool_env.sim.jit import COMPILE_NOTICE

    COMPILE_NOTICE.silence()  # the command's own lines say what compiles
    env_id, kind = job
    extra = {"observation": "shots"} if kind == "shots" else {}
    if kind != "vector":
        _play(gym.make(env_id, **extra))
        _play(gym.make(env_id, render_mode="rgb_array", **extra), render=True)
    if kind != "env":
        _play(gym.make_vec(env_id, 2, vectorization_mode="vector_entry_point", **extra))
    return job, time.perf_counter() - start


def main(argv: list[str] | None = None) -> int:
    """Run every job in ``--workers`` processes; print one line a job and the total."""
    parser = argparse.ArgumentParser(
        prog="python -m pool_env.precompile", description=__doc__.split("\n")[0]
    )
    parser.add_argument(
        "--workers",
        type=int,
        default=os.cpu_count() or 1,
        help="processes compiling side by side (default: the machine's cores)",
    )
    parser.add_argument("--quiet", action="store_true", help="print the total only")
    args = parser.parse_args(argv)
    if args.workers < 1:
        parser.error(f"--workers must be at least 1, got {args.workers}")
    from pool_env.sim.jit import CACHE_FOLDER

    todo = jobs()
    where = CACHE_FOLDER if CACHE_FOLDER is not None else "memory (no writable cache folder)"
    ids = len({env_id for env_id, _ in todo})
    print(f"pool_env: compiling the kernels of {ids} ids into {where}", flush=True)
    start = time.perf_counter()
    # Fresh interpreters (spawn), as every later process is: nothing inherited half-compiled.
    with ProcessPoolExecutor(args.workers, mp_context=get_context("spawn")) as pool:
        for done in as_completed([pool.submit(run_job, job) for job in todo]):
            (env_id, kind), seconds = done.result()
            if not args.quiet:
                print(f"  {env_id} ({kind}): {seconds:.1f} s", flush=True)
    print(f"pool_env: compiled in {time.perf_counter() - start:.1f} s", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
