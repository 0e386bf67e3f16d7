"""Same-shot A/B of the simulator: every fuzz shot's events and final state, bit for bit.

Records, for the first ``--shots`` shots of the fuzz (:func:`tools.fuzz.cases`, either
level), a digest of the shot's exact outcome: the event sequence (times, kinds, balls), the
final positions, the pockets, the final angular velocities and motion states (spin), each
as raw bytes. ``--save`` writes the digests of the code checked out now; ``--compare``
recomputes them and lists the shots whose digest differs from a saved file. A kernel change
that claims to be exact (a culled test, a cheaper prediction) must compare equal on every
shot of both levels.

Usage::

    python -m bench.sim_ab --model spin --shots 100000 --save /tmp/ab_spin.npy
    python -m bench.sim_ab --model spin --shots 100000 --compare /tmp/ab_spin.npy
"""

from __future__ import annotations

import argparse
import hashlib
import sys
import time
from itertools import islice
from pathlib import Path

import numpy as np

from pool_env.sim.result import ShotResult
from tools.fuzz import cases

#: Bytes of one shot's digest (``blake2b``).
DIGEST = 16
#: The digest of a shot the simulator refuses (the refusal itself is part of the outcome).
REFUSED = b"\xff" * DIGEST


def shot_digest(result: ShotResult) -> bytes:
    """The digest of everything a shot's outcome is: its events and its final state."""
    h = hashlib.blake2b(digest_size=DIGEST)
    arrays = [
        result.event_times,
        result.event_kinds,
        result.event_i,
        result.event_j,
        result.positions,
        result.pocketed,
        result.first_hit,
        result.stopped_by_cap,
    ]
    if hasattr(result, "motion_states"):
        arrays += [result.angular_velocities, result.motion_states]
    for arr in arrays:
        h.update(np.ascontiguousarray(arr).tobytes())
    return h.digest()


def digests(model: str, shots: int, seed: int) -> np.ndarray:
    """``(shots, DIGEST)`` uint8 digests of the first ``shots`` fuzz shots of ``model``."""
    out = np.empty((shots, DIGEST), dtype=np.uint8)
    for k, (_table, _pos, _vel, _masses, run) in enumerate(islice(cases(seed, model), shots)):
        try:
            d = shot_digest(run())
        except ValueError:
            d = REFUSED
        out[k] = np.frombuffer(d, dtype=np.uint8)
    return out


def main() -> int:
    """Save or compare digests; exit 1 if any shot differs."""
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--model", choices=["roll", "spin"], default="roll")
    parser.add_argument("--shots", type=int, default=10_000)
    parser.add_argument("--seed", type=int, default=0)
    group = parser.add_mutually_exclusive_group(required=True)
    group.add_argument("--save", type=Path)
    group.add_argument("--compare", type=Path)
    args = parser.parse_args()
    started = time.perf_counter()
    got = digests(args.model, args.shots, args.seed)
    took = time.perf_counter() - started
    refused = int(np.all(got == 0xFF, axis=1).sum())
    if args.save is not None:
        np.save(args.save, got)
        print(f"{args.model}: {args.shots} shots ({refused} refused) saved to {args.save}"
              f" in {took:.0f} s")  # fmt: skip
        return 0
    want = np.load(args.compare)
    if want.shape != got.shape:
        print(f"shape differs: saved {want.shape}, now {got.shape}")
        return 1
    bad = np.flatnonzero(np.any(want != got, axis=1))
    print(
        f"{args.model}: {args.shots} shots ({refused} refused), {bad.size} differ"
        f" from {args.compare} ({took:.0f} s)"
        + (f"; first: {bad[:10].tolist()}" if bad.size else "")
    )
    return 1 if bad.size else 0


if __name__ == "__main__":
    sys.exit(main())
