"""The rack agent's learning curve: run-outs and pots per shot against the racks it learned from.

Usage (run from the repository root)::

    python -m agents.training.rack_curve --models rack-planner:0 runs/racks/m1.npz:1500
        models/rack_value.npz:3000 --baselines ghost random --episodes 300
        --out results/nineball_rack_learning.png

(one line).

Each ``model:racks`` (a rack model ``.npz``, or ``rack-planner`` for the untrained
candidates ranked by the planner's score) and each baseline is evaluated by
:func:`agents.evaluate.evaluate_agent` on the same racks (seeds ``--seed``..) of
``pool_env/NineBallGame-v1`` in run-out mode with the evaluation's noise; the models are
drawn against the racks of training data they were fitted on, the baselines as lines.
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # files only
import matplotlib.pyplot as plt

from agents.evaluate import evaluate_agent, format_table
from agents.metrics import Estimate

ENV_ID = "pool_env/NineBallGame-v1"
ENV_KWARGS = {"end_on_foul": True, "noise": (0.003, 0.05, 0.05)}
#: The statistics drawn: (summary key, label).
PANELS = (("run_out_rate", "run-outs per rack"), ("pots_per_shot", "pots per shot"))


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
        ax.set_xlabel("training racks")
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
    parser.add_argument("--models", nargs="+", required=True, help="model:racks pairs")
    parser.add_argument("--baselines", nargs="*", default=["ghost", "random"])
    parser.add_argument("--episodes", type=int, default=300)
    parser.add_argument("--seed", type=int, default=10_000)
    parser.add_argument("--out", required=True)
    args = parser.parse_args(argv)
    rows: dict[str, dict[str, Estimate]] = {}
    points = []
    for spec in args.models:
        name, _, racks = spec.rpartition(":")
        if not name or not racks.isdigit():
            parser.error(f"--models takes model:racks pairs, got {spec!r}")
        start = time.perf_counter()
        summary = evaluate_agent(name, ENV_ID, args.episodes, args.seed, dict(ENV_KWARGS))
        print(f"{name}: {time.perf_counter() - start:.0f} s", flush=True)
        rows[f"{name} ({racks} racks)"] = summary
        points.append((int(racks), summary))
    baselines = {}
    for name in args.baselines:
        baselines[name] = evaluate_agent(name, ENV_ID, args.episodes, args.seed, dict(ENV_KWARGS))
        rows[name] = baselines[name]
    print(format_table(rows, args.episodes))
    plot(args.out, points, baselines, args.episodes)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
