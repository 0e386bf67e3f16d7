"""Collect the ``evaluation.json`` of run folders into one markdown table.

Usage::

    python -m agents.summarize runs            # every run under runs/
    python -m agents.summarize runs/OneBall-v0 --env pool_env/OneBall-v0
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
        "| env | variant | algo | steps | seeds | pots/shot (mean, sd) | clean (mean, sd) |",
    ]
    lines.append("|---|---|---|---|---|---|---|")
    for (env, variant, algo, steps), rows in sorted(groups.items()):
        stats = []
        for k in ("pots_per_shot", "clean_pot_rate"):
            values = [r[k] for r in rows]
            sd = f"{100 * statistics.stdev(values):.1f}" if len(values) > 1 else "-"
            stats.append(f"{100 * statistics.mean(values):.1f}% ({sd})")
        lines.append(
            f"| {env} | {variant} | {algo} | {steps:,} | {len(rows)} | " + " | ".join(stats) + " |"
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
    args = parser.parse_args(argv)
    runs = load_runs(args.root, args.env)
    if not runs:
        print(f"no evaluation.json under {args.root}")
        return 1
    print(table(runs))
    return 0


if __name__ == "__main__":
    sys.exit(main())
