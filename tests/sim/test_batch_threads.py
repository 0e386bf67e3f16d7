"""The threaded batch from several Python threads at once (issue 11, item 4)."""

from __future__ import annotations

import threading

import numpy as np
import pytest

from pool_env import Table
from pool_env.sim import batch
from pool_env.sim.batch import simulate_batch, simulate_batch_threads


def test_callers_with_different_thread_counts_share_the_pool_safely() -> None:
    """Threads asking for different pool sizes never shut down a pool another one uses.

    Each round starts without a pool, so the callers race to create and grow it; a
    caller that grew it used to shut down the pool the others were submitting to
    (``RuntimeError: cannot schedule new futures after shutdown``).
    """
    table = Table(pockets="none")
    n = 24
    rng = np.random.default_rng(3)
    pos = np.stack([[[0.4, 0.3], [1.6, 0.9]]] * n) + rng.uniform(-0.05, 0.05, (n, 2, 2))
    vel = np.zeros_like(pos)
    vel[:, 0] = rng.uniform(-2.0, 2.0, (n, 2))
    on = np.ones((n, 2), np.bool_)
    serial = simulate_batch(table, pos, vel, active=on, parallel=False)
    thread_counts = [2, 3, 4, 5, 6, 7, 8, 9]
    errors: list[BaseException] = []
    mismatches: list[int] = []
    for _ in range(30):
        batch._pool = None
        barrier = threading.Barrier(len(thread_counts))

        def work(threads: int, barrier: threading.Barrier = barrier) -> None:
            barrier.wait()
            try:
                for _ in range(3):
                    out = simulate_batch_threads(table, pos, vel, on, threads)
                    if not np.array_equal(out.positions, serial.positions):
                        mismatches.append(threads)
            except BaseException as exc:  # reported by the assertion below
                errors.append(exc)

        workers = [threading.Thread(target=work, args=(k,)) for k in thread_counts]
        for w in workers:
            w.start()
        for w in workers:
            w.join()
    assert errors == []
    assert mismatches == []


def test_an_invalid_table_in_a_later_part_is_named_by_its_row() -> None:
    """The parts hand back codes, not messages: the row counts from the batch's start."""
    for model in ("roll", "spin"):
        table = Table(model=model)
        n = 10
        pos = np.stack([[[0.4, 0.3], [1.6, 0.9]]] * n)
        pos[7, 1] = pos[7, 0] + (0.01, 0.0)  # overlapping balls on table 7 (of part 3)
        pos[8, 0] = (-1.0, 0.5)  # off the table, after it
        vel = np.zeros_like(pos)
        vel[:, 0, 0] = 1.0
        on = np.ones((n, 2), np.bool_)
        for threads in (1, 2, 3):
            with pytest.raises(ValueError, match=r"^table 7: balls 0 and 1 overlap"):
                simulate_batch_threads(table, pos, vel, on, threads)
