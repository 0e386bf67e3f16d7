"""The rack agent's learning curve: run-outs and pots per shot against the racks it learned from.

Usage (run from the repository root; one line)::

    python -m agents.training.rack_curve results/racks_eval.md
        --points rack-planner=0 runs/racks/m1k.npz=1500 models/rack_value.npz=3000
        --baselines ghost random --out results/nineball_rack_learning.png

It reads the tables :mod:`agents.evaluation.evaluate` printed (``--out`` files or their logs, every
row with its 95% interval) for the same racks of ``pool_env/NineBallGame-v2`` in run-out
mode, and draws each ``agent=racks`` point (a rack model, or ``rack-planner`` for the
untrained candidates ranked by the planner's score) against the racks of training data
it was fitted on, the baselines as horizontal lines. The evaluations are not re-run: the
figure is the tables' numbers.
"""

from __future__ import annotations

import argparse
import re
from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # files only
import matplotlib.pyplot as plt

from agents.evaluation.metrics import Estimate

#: The statistics drawn: (column of the evaluate table, label).
PANELS = (("run-outs", "run-outs per rack"), ("pots/shot", "pots per shot"))
_CELL = re.compile(r"^(-?[\d.]+)(%?) \[(-?[\d.]+), (-?[\d.]+)\]$")


def read_tables(paths: list[str]) -> dict[str, dict[str, Estimate]]:
    """The rows of the markdown tables in ``paths``: agent -> column -> estimate."""
    rows: dict[str, dict[str, Estimate]] = {}
    for path in paths:
        header: list[str] = []
        for line in Path(path).read_text().splitlines():
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            if not line.startswith("|") or set(cells[0]) <= {"-"}:
                continue
            if cells[0] == "agent":
                header = cells
                continue
            stats = {}
            for name, cell in zip(header[1:], cells[1:], strict=False):
                m = _CELL.match(cell)
                if m:
                    k = 0.01 if m.group(2) else 1.0
                    stats[name] = Estimate(*(k * float(m.group(i)) for i in (1, 3, 4)))
            rows[cells[0]] = stats
    return rows


def plot(
    path: str | Path,
    points: list[tuple[int, dict[str, Estimate]]],
    baselines: dict[str, dict[str, Estimate]],
    episodes: int,
) -> None:
    """Two panels: each statistic of the models (95% bars) against racks, baselines as lines."""
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.6), dpi=110)
    colors = ("tab:red", "tab:gray", "tab:purple", "tab:brown")
    for ax, (key, label) in zip(axes, PANELS, strict=True):
        xs = [p[0] for p in points]
        est = [p[1][key] for p in points]
        ax.errorbar(
            xs, [e.value for e in est],
            yerr=[[e.value - e.low for e in est], [e.high - e.value for e in est]],
            marker="o", capsize=3, color="tab:blue", label="learned (fitted Q)",
        )  # fmt: skip
        for (name, summary), color in zip(baselines.items(), colors, strict=False):
            ax.axhline(summary[key].value, color=color, ls="--", label=name)
        ax.set_xlabel("training racks (0: untrained)")
        ax.set_title(label)
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=8)
    fig.suptitle(f"9-ball run-out mode, spin table, {episodes} racks per point", fontsize=10)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def main(argv: list[str] | None = None) -> int:
    """The command line (module doc)."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n", 1)[0])
    parser.add_argument("tables", nargs="+", help="files holding agents.evaluation.evaluate tables")
    parser.add_argument("--points", nargs="+", required=True, help="agent=racks pairs")
    parser.add_argument("--baselines", nargs="*", default=["ghost", "random"])
    parser.add_argument("--episodes", type=int, default=300, help="racks per evaluation")
    parser.add_argument("--out", required=True)
    args = parser.parse_args(argv)
    rows = read_tables(args.tables)
    points = []
    for spec in args.points:
        name, _, racks = spec.rpartition("=")
        if not name or not racks.isdigit() or name not in rows:
            parser.error(f"--points takes agent=racks pairs of the tables' agents, got {spec!r}")
        points.append((int(racks), rows[name]))
    missing = [b for b in args.baselines if b not in rows]
    if missing:
        parser.error(f"no rows for the baselines {missing}")
    plot(args.out, points, {b: rows[b] for b in args.baselines}, args.episodes)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
