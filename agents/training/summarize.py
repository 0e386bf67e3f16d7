"""Collect the ``evaluation.json`` of run folders into one markdown table.

Usage::

    python -m agents.training.summarize runs            # every run under runs/
    python -m agents.training.summarize runs/OneBallRoll-v1 --env pool_env/OneBallRoll-v1
    python -m agents.training.summarize runs --plot results/oneball_cut_learning.png --title "..."
    python -m agents.training.summarize runs/position3 --plot clears.png --metric clears \
        --baseline ghost=0.408

The means over seeds carry a 95% interval (Student's t over the seeds' values: it says how
much the *training* varies, the per-run brackets how much the evaluation does).
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
from collections import defaultdict
from pathlib import Path
from typing import Any

import yaml

#: Two-sided 95% Student t quantiles for 1..10 degrees of freedom (then ~10's).
T95 = (12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228)


def load_runs(root: str | Path, env_id: str | None = None) -> list[dict[str, Any]]:
    """Every run's ``evaluation.json`` (plus its folder and seed) under ``root``."""
    runs = []
    for path in sorted(Path(root).rglob("evaluation.json"), key=_run_order):
        report = json.loads(path.read_text())
        if env_id and report["env_id"] != env_id:
            continue
        config_path = path.with_name("config.yaml")
        config = yaml.safe_load(config_path.read_text()) if config_path.is_file() else {}
        # Runs that changed the environment are told apart from runs of the registered one.
        variant = {k: v for k, v in (config.get("env_kwargs") or {}).items()}
        if config.get("wrapper"):
            variant["wrapper"] = config["wrapper"]
        runs.append(
            {
                **report,
                "folder": str(path.parent),
                "seed": config.get("seed"),
                "variant": ", ".join(f"{k}={v}" for k, v in variant.items()) or "-",
            }
        )
    return runs


def table(runs: list[dict[str, Any]]) -> str:
    """Per run: pots, clean pots, scratches (95% intervals); then means over seeds."""
    lines = [
        "| env | variant | algo | steps | seed | pots/shot | clean pots/shot | scratch/shot "
        "| train s |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    groups: dict[tuple[str, str, str, int], list[dict[str, float]]] = defaultdict(list)
    for run in runs:
        model = next(k for k in run["results"] if k.endswith("(this run)"))
        res = run["results"][model]
        cells = [_pct(res[k]) for k in ("pots_per_shot", "clean_pot_rate", "scratch_rate")]
        lines.append(
            f"| {run['env_id']} | {run['variant']} | {run['algo']} | {run['n_timesteps']:,} "
            f"| {run['seed']} | " + " | ".join(cells) + f" | {run['train_seconds']:.0f} |"
        )
        key = (run["env_id"], run["variant"], run["algo"], run["n_timesteps"])
        groups[key].append({k: res[k][0] for k in ("pots_per_shot", "clean_pot_rate")})
    lines += [
        "",
        "| env | variant | algo | steps | seeds | pots/shot (mean [95%], sd) "
        "| clean (mean [95%], sd) |",
    ]
    lines.append("|---|---|---|---|---|---|---|")
    for (env, variant, algo, steps), rows in sorted(groups.items()):
        stats = []
        for k in ("pots_per_shot", "clean_pot_rate"):
            values = [r[k] for r in rows]
            mean = statistics.mean(values)
            if len(values) > 1:
                sd = statistics.stdev(values)
                half = T95[min(len(values) - 1, len(T95)) - 1] * sd / len(values) ** 0.5
                stats.append(
                    f"{100 * mean:.1f}% [{100 * (mean - half):.1f}, {100 * (mean + half):.1f}] "
                    f"({100 * sd:.1f})"
                )
            else:
                stats.append(f"{100 * mean:.1f}% (-)")
        lines.append(
            f"| {env} | {variant} | {algo} | {steps:,} | {len(rows)} | " + " | ".join(stats) + " |"
        )
    return "\n".join(lines)


def time_to_skill(points: list[tuple[int, float, float]], rate: float) -> tuple[int, float] | None:
    """``(steps, seconds)`` of the first periodic evaluation with pots/shot at least ``rate``.

    Args:
        points: ``(timesteps, seconds, pots/shot)`` of a run's ``curve.csv``, in order.
        rate: The pot rate to reach.

    Returns:
        The first point's steps and seconds (wall seconds since the process started, periodic
        evaluations excluded), or ``None`` when the run never reached ``rate``.
    """
    return next(((s, t) for s, t, p in points if p >= rate), None)


def curve_points(run: dict[str, Any]) -> list[tuple[int, float, float]]:
    """``(timesteps, seconds, pots/shot)`` of a run's ``curve.csv``."""
    lines = (Path(run["folder"]) / "curve.csv").read_text().splitlines()[1:]
    return [(int(c[0]), float(c[1]), float(c[2])) for c in (x.split(",") for x in lines)]


def skill_table(runs: list[dict[str, Any]], rates: list[float]) -> str:
    """Per run: steps and wall seconds to each pot rate, the best and the last evaluation."""
    heads = " | ".join(f"to {r:.0%}: steps, s" for r in rates)
    lines = [
        f"| algo | steps | seed | {heads} | best periodic | last periodic | env steps/s |",
        "|---|---|---|" + "---|" * len(rates) + "---|---|---|",
    ]
    for run in runs:
        points = curve_points(run)
        cells = []
        for rate in rates:
            hit = time_to_skill(points, rate)
            cells.append(f"{hit[0]:,}, {hit[1]:.0f}" if hit else "not reached")
        best = max(p for _, _, p in points)
        speed = run["n_timesteps"] / run["train_seconds"] if run["train_seconds"] else 0.0
        lines.append(
            f"| {run['algo']} | {run['n_timesteps']:,} | {run['seed']} | "
            + " | ".join(cells)
            + f" | {100 * best:.1f}% | {100 * points[-1][2]:.1f}% | {speed:,.0f} |"
        )
    return "\n".join(lines)


def _run_order(path: Path) -> tuple[str, int, str]:
    """Sort runs by algorithm, steps, then folder name (seed, time)."""
    report = json.loads(path.read_text())
    return report["algo"], report["n_timesteps"], path.parent.name


def _pct(values: list[float]) -> str:
    value, low, high = values
    return f"{100 * value:.1f}% [{100 * low:.1f}, {100 * high:.1f}]"


def main(argv: list[str] | None = None) -> int:
    """Command-line entry point."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("root", nargs="?", default="runs")
    parser.add_argument("--env", default=None, help="only runs on this env id")
    parser.add_argument("--plot", help="write every run's learning curve into this PNG")
    parser.add_argument("--title", default="", help="title of the --plot figure")
    parser.add_argument(
        "--baseline",
        nargs="*",
        default=[],
        metavar="NAME=RATE",
        help="baseline rates for --plot when no run evaluated them (random=0.082 ...)",
    )
    parser.add_argument(
        "--metric",
        choices=sorted(METRICS),
        default="pots",
        help="what --plot draws: pots (and clean pots) per shot, or the clear rate",
    )
    parser.add_argument(
        "--skill",
        nargs="*",
        type=float,
        default=[0.8, 0.9],
        metavar="RATE",
        help="pot rates of the time-to-skill table (default 0.8 0.9)",
    )
    args = parser.parse_args(argv)
    runs = load_runs(args.root, args.env)
    if not runs:
        print(f"no evaluation.json under {args.root}")
        return 1
    print(table(runs))
    print("\n" + skill_table(runs, args.skill))
    if args.plot:
        given = {}
        for item in args.baseline:
            name, sep, value = item.partition("=")
            if not sep:
                parser.error(f"--baseline expects NAME=RATE, got {item!r}")
            given[name] = float(value)
        plot(runs, args.plot, args.title, given, args.metric)
    return 0


#: What ``--metric`` plots: the ``curve.csv`` / result columns and the plot's words.
METRICS = {
    "pots": ("pots_per_shot", "clean_pot_rate", "pots/shot", "pots"),
    "clears": ("clear_rate", None, "clear rate", "clears"),
}


def plot(
    runs: list[dict[str, Any]],
    path: str | Path,
    title: str,
    given: dict[str, float] | None = None,
    metric: str = "pots",
) -> None:
    """Every run's ``curve.csv`` in one PNG, by algorithm and steps.

    The baselines are the first run's that evaluated them, else ``given`` (name: rate).

    Args:
        runs: The runs (:func:`load_runs`).
        path: Output PNG.
        title: The plot's title.
        given: Baseline rates by name, for those no run evaluated.
        metric: A key of :data:`METRICS`: pots and clean pots per shot, or the clear rate
            (the share of episodes that pot every ball; runs whose ``curve.csv`` has a
            ``clear_rate`` column).

    Raises:
        ValueError: On an unknown metric, or a run whose curve lacks its column.
    """
    from agents.training.plots import seeds_curve  # matplotlib only now

    if metric not in METRICS:
        raise ValueError(f"unknown metric {metric!r}: use one of {sorted(METRICS)}")
    key, second, words, unit = METRICS[metric]
    curves: dict[str, list] = defaultdict(list)
    baselines: dict[str, float] = dict(given or {})
    for run in runs:
        label = f"{run['algo'].upper()} {run['n_timesteps']:,}"
        head, *lines = (Path(run["folder"]) / "curve.csv").read_text().splitlines()
        columns = head.split(",")
        if key not in columns:
            raise ValueError(f"{run['folder']}/curve.csv has no {key} column (for --metric)")
        a = columns.index(key)
        b = columns.index(second) if second else None
        points = []
        for cells in (x.split(",") for x in lines):
            points.append(
                (int(cells[0]), float(cells[a]), float(cells[b]) if b is not None else None)
            )
        curves[label].append((run["seed"], points))
        for name, res in run["results"].items():
            if not name.endswith("(this run)") and key in res:
                baselines.setdefault(name, res[key][0])
    seeds_curve(path, dict(curves), baselines, title, words, unit)


if __name__ == "__main__":
    sys.exit(main())
