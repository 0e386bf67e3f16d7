"""Learning-curve plot of a run: pot rate over training, with the baselines for scale."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import matplotlib

matplotlib.use("Agg")  # files only: no display on a training machine
import matplotlib.pyplot as plt

from agents.evaluation.metrics import Estimate


def learning_curve(
    path: str | Path,
    history: list[tuple[int, float, dict[str, Estimate]]],
    final: dict[str, dict[str, Estimate]],
    config: Any,
) -> None:
    """Write a PNG: pots per shot and clean pots per shot (95% bands) against steps.

    Args:
        path: Output PNG.
        history: ``(timesteps, seconds, summary)`` of each periodic evaluation.
        final: Final evaluation rows by agent (the baselines among them drawn as lines).
        config: The run's config (title).
    """
    fig, ax = plt.subplots(figsize=(7, 4.2), dpi=110)
    steps = [h[0] for h in history]
    for key, label, color in (
        ("pots_per_shot", "pots per shot", "tab:blue"),
        ("clean_pot_rate", "clean pots per shot (no scratch)", "tab:green"),
        ("scratch_rate", "scratches per shot", "tab:red"),
    ):
        if not history:
            break
        est = [h[2][key] for h in history]
        ax.plot(steps, [e.value for e in est], marker="o", ms=3, color=color, label=label)
        ax.fill_between(steps, [e.low for e in est], [e.high for e in est], color=color, alpha=0.15)
    for name, label, style, color in (
        ("random", "random", ":", "gray"),
        ("const", "full hit, hardest (const)", (0, (1, 3)), "gray"),
        ("best-const", "best constant action", "-.", "tab:purple"),
        ("ghost", "ghost-ball (geometric)", "--", "black"),
        ("search", "search (simulator, oracle)", (0, (5, 1)), "tab:brown"),
        ("first-row", "feature row 0 exactly", (0, (3, 1, 1, 1)), "tab:green"),
    ):
        if name in final:
            value = final[name]["pots_per_shot"].value
            ax.axhline(value, color=color, ls=style, lw=1, label=f"{label}: {value:.0%} pots")
    ax.set_xlabel("environment steps")
    ax.set_ylabel("rate (periodic evaluation)")
    ax.set_ylim(0.0, 1.05)
    ax.set_title(f"{config.algo.upper()} on {config.env_id} (seed {config.seed})")
    ax.grid(alpha=0.3)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=8, loc="lower right")
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


#: Baselines drawn as horizontal lines on the seed plots: name, label, style, colour.
BASELINE_LINES = (
    ("random", "random", ":", "gray"),
    ("best-const", "best constant action", "-.", "tab:purple"),
    ("ghost", "ghost-ball (geometric)", "--", "black"),
    ("search", "search (simulator, oracle)", (0, (5, 1)), "tab:brown"),
    ("first-row", "feature row 0 exactly", (0, (3, 1, 1, 1)), "tab:green"),
)


def seeds_curve(
    path: str | Path,
    curves: dict[str, list[tuple[int, list[tuple[int, float, float | None]]]]],
    baselines: dict[str, float],
    title: str,
    words: str = "pots/shot",
    unit: str = "pots",
) -> None:
    """Write a PNG: every seed's learning curve of every configuration, baselines as lines.

    Args:
        path: Output PNG.
        curves: By configuration label, ``(seed, [(timesteps, rate, clean/shot), ...])``
            of each run (the rate is pots/shot, or what ``words`` names; clean/shot
            ``None`` when not drawn).
        baselines: The baselines' rates by name (:data:`BASELINE_LINES`).
        title: The plot's title (the task).
        words: The rate's name in the legend (``"pots/shot"``, ``"clear rate"``).
        unit: The baselines' unit in the legend (``"pots"``, ``"clears"``).
    """
    fig, ax = plt.subplots(figsize=(7.5, 4.5), dpi=110)
    colors = ("tab:blue", "tab:orange", "tab:green", "tab:red", "tab:cyan", "tab:olive")
    for (label, runs), color in zip(curves.items(), colors, strict=False):
        for k, (_, points) in enumerate(sorted(runs, key=lambda run: run[0])):
            steps = [p[0] for p in points]
            ax.plot(steps, [p[1] for p in points], color=color, lw=1.2, marker="o", ms=2,
                    label=f"{label}: {words}" if k == 0 else None)  # fmt: skip
            if points and points[0][2] is not None:
                ax.plot(steps, [p[2] for p in points], color=color, lw=0.8, ls="--", alpha=0.7,
                        label=f"{label}: clean pots/shot" if k == 0 else None)  # fmt: skip
    for name, label, style, color in BASELINE_LINES:
        if name in baselines:
            value = baselines[name]
            ax.axhline(value, color=color, ls=style, lw=1, label=f"{label}: {value:.1%} {unit}")
    ax.set_xlabel("environment steps")
    ax.set_ylabel("rate (periodic evaluation)")
    ax.set_ylim(0.0, 1.05)
    ax.set_title(title)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="lower right")
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)
