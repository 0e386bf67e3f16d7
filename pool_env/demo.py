"""Demo: simulate a 9-ball break and print what happened (``python -m pool_env.demo``)."""

from __future__ import annotations

import time

from pool_env import Table, shoot
from pool_env.sim.layouts import break_scene


def main() -> None:
    """Break a 9-ball rack at 8 m/s and print the events, the pots and the time taken."""
    table = Table()
    positions = break_scene(table, "nine")
    started = time.perf_counter()
    result = shoot(table, positions, angle=0.0, speed=8.0)
    elapsed = time.perf_counter() - started
    print(f"9-ball break at 8 m/s: {result.n_events} events, rest after {result.duration:.2f} s")
    for event in result.events[:12]:
        print(f"  t={event.time:9.6f} s  {event.kind:8s} i={event.i} j={event.j}")
    print("  ...")
    potted = [int(i) for i in (result.pocketed >= 0).nonzero()[0]]
    print(f"potted balls (0 is the cue): {potted}")
    print(f"first shot (compile or cache load included): {elapsed * 1e3:.1f} ms")


if __name__ == "__main__":
    main()
