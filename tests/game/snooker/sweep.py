"""The compiled snooker rules against the reference on many random outcomes.

``python -m tests.game.snooker.sweep 100000 [seed]`` prints how many of that many
outcomes the two judge differently (and the first few differences).
"""

from __future__ import annotations

import sys
import time

import numpy as np

from tests.game.snooker.harness import compare, random_case


def main(n: int, seed: int = 0) -> int:
    """Judge ``n`` random outcomes both ways; return the number of disagreements."""
    rng = np.random.default_rng(seed)
    start, bad = time.perf_counter(), 0
    for k in range(n):
        diffs = compare(random_case(rng))
        if diffs:
            bad += 1
            if bad <= 5:
                print(f"case {k}: {diffs}")
    print(f"{bad} disagreements in {n} random outcomes (seed {seed}), "
          f"{time.perf_counter() - start:.0f} s")  # fmt: skip
    return bad


if __name__ == "__main__":
    args = [int(a) for a in sys.argv[1:]]
    sys.exit(1 if main(*(args or [100000])) else 0)
