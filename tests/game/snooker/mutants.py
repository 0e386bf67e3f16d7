"""Mutants of the snooker rules: each must make the compiled rules differ from the reference.

``python -m tests.game.snooker.mutants [cases]`` copies ``pool_env`` and ``tests`` to a
temporary folder, applies one mutant at a time to the copy of the package, and runs the
random-outcome sweep (:mod:`tests.game.snooker.sweep`) there with numba's JIT off (pure
Python: no compile, and the worktree's cache untouched); it prints each mutant's
disagreements. A mutant with none survived.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[3]
GAME = Path("pool_env/game/games/snooker")

#: (file, original, mutant): each a rule the reference must catch.
MUTANTS = (
    ("rack_state.py", "MIN_PENALTY = 4", "MIN_PENALTY = 3"),
    ("rules.py", "penalty = max(penalty, VALUES[free_ball])", "penalty = penalty"),
    ("rules.py", "            to_spot[colour] = True", "            to_spot[colour] = False"),
    ("rules.py", "deemed = touch_on and not push", "deemed = False"),
    ("rules.py", "        if free and is_colour and nominated != low:",
     "        if is_colour and nominated != low:"),
    ("rules.py", "row[SCORE_0 + 1 - shooter] += out[R_PENALTY]",
     "row[SCORE_0 + shooter] += out[R_PENALTY]"),
    ("rules.py", "        else:  # S3 R4(b): the black re-spotted",
     "        elif False:  # S3 R4(b): the black re-spotted"),
    ("rules.py", "    only_black = phase != COLOUR_ON and low == BLACK",
     "    only_black = phase != COLOUR_ON and low == BLACK - 1"),
    ("geometry.py", "    for colour in range(BLACK, FIRST_COLOUR - 1, -1):  # (d)",
     "    for colour in range(FIRST_COLOUR, BLACK + 1):  # (d)"),
    ("geometry.py", "        for spot in range(BLACK, FIRST_COLOUR - 1, -1):  # (c)",
     "        for spot in range(FIRST_COLOUR, BLACK + 1):  # (c)"),
    ("geometry.py", "        if ex * ex + ey * ey < two_r * two_r:",
     "        if ex * ex + ey * ey < radius * radius:"),
)  # fmt: skip


def main(cases: int = 400) -> int:
    """Run every mutant; return how many survived."""
    survived = 0
    with tempfile.TemporaryDirectory() as tmp:
        copy = Path(tmp)
        for name in ("pool_env", "tests"):
            shutil.copytree(ROOT / name, copy / name, ignore=shutil.ignore_patterns("numba-*"))
        env = {**os.environ, "PYTHONPATH": str(copy), "NUMBA_DISABLE_JIT": "1"}
        for file, original, mutant in MUTANTS:
            path = copy / GAME / file
            text = path.read_text()
            assert original in text, (file, original)
            path.write_text(text.replace(original, mutant, 1))
            out = subprocess.run(
                [sys.executable, "-m", "tests.game.snooker.sweep", str(cases), "9"],
                cwd=copy, env=env, capture_output=True, text=True, check=False,
            )  # fmt: skip
            path.write_text(text)
            last = (out.stdout.strip().splitlines() or [out.stderr[-200:]])[-1]
            survived += out.returncode == 0
            print(f"{file}: {mutant.strip()[:60]!r} -> {last}")
    print(f"{len(MUTANTS) - survived} of {len(MUTANTS)} mutants killed")
    return survived


if __name__ == "__main__":
    sys.exit(1 if main(*(int(a) for a in sys.argv[1:])) else 0)
