"""Mutation runner: plant each bug of the catalogue, run its tests, see whether they notice.

Usage (from the repository root)::

    python -m tools.mutants                       # every mutant, 2 workers
    python -m tools.mutants --only tie-kind-order zeno-threshold-1e-3
    python -m tools.mutants --workers 1 --out results/mutants.md
    python -m tools.mutants --budget 20           # start no mutant after 20 min

Cost, measured on the shared 2-core machine at load average 10 (``nice -n 5``, 2 workers,
99 mutants, 2026-12-02): 33 min in all. The baselines (the union of each mode's subsets)
took 6 min (compiled) and 8.5 min (interpreted); an interpreted mutant 4-50 s (median 8);
a compiled one recompiles the kernels before its tests, 11-290 s (median 2 min). Most
mutants die in the first seconds of their subset (``-x``); a survivor runs all of it.

What a verdict means (killed, survived, stale, timeout, not run), the scratch copies and the
interpreted and compiled modes: :mod:`tools.mutant_runner`; the table: :mod:`tools.mutant_report`.
With ``--budget`` no mutant starts once that many minutes have passed (the running ones
finish) and the kill rate counts only the mutants that ran; ``--compiled`` compiles every
mutant (no interpreted runs).
"""

from __future__ import annotations

import argparse
import os
import shlex
import signal
import sys
import time
from collections.abc import Sequence

from tools.mutant_catalogue import CATALOGUE
from tools.mutant_report import commit_label, report
from tools.mutant_runner import ROOT, TIMEOUT, run


def main(argv: Sequence[str] | None = None) -> int:
    """Command line: run the catalogue (or ``--only`` some), write the table."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--only", nargs="+", metavar="NAME", help="run only these mutants")
    parser.add_argument("--workers", type=int, default=2, help="parallel scratch copies")
    parser.add_argument("--out", default="results/mutants.md", help="Markdown table ('' none)")
    parser.add_argument("--timeout", type=float, default=TIMEOUT, help="seconds per mutant")
    parser.add_argument(
        "--compiled", action="store_true", help="compile every mutant (no interpreted runs)"
    )
    parser.add_argument(
        "--budget", type=float, default=None, metavar="MIN", help="start no job after MIN min"
    )
    args = parser.parse_args(argv)
    names = {m.name for m in CATALOGUE}
    unknown = set(args.only or ()) - names
    if unknown:
        parser.error(f"unknown mutants {sorted(unknown)}")
    mutants = [m for m in CATALOGUE if not args.only or m.name in args.only]
    # A SIGTERM ends the run as Ctrl-C does: the scratch copies are removed on the way out.
    signal.signal(signal.SIGTERM, signal.default_int_handler)
    load_start = os.getloadavg()[0]
    commit = commit_label(ROOT)  # the tree the snapshot is taken from, not the tree at the end
    start = time.perf_counter()
    try:
        budget = None if args.budget is None else 60.0 * args.budget
        baselines, outcomes = run(
            mutants, max(1, args.workers), args.timeout, args.compiled, budget
        )
    except KeyboardInterrupt:
        print("interrupted: the running subsets were killed and the scratch copies removed")
        return 130
    wall = time.perf_counter() - start
    given = sys.argv[1:] if argv is None else list(argv)
    command = shlex.join(["python", "-m", "tools.mutants", *given])
    text = report(baselines, outcomes, command, wall, load_start, commit)
    print(text)
    if args.out:
        out = ROOT / args.out
        out.parent.mkdir(parents=True, exist_ok=True)
        out.write_text(text)
    failed = [b for b in baselines if b.status != "survived"]
    if failed:
        print(f"a baseline failed ({failed[0].detail}): the kills mean nothing", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
