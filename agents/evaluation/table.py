"""The evaluation's table: one row per agent, each statistic with its 95% interval.

:func:`format_table` drops the columns a one-shot task repeats and notes the rows that
need a word (:data:`ROW_NOTES`); :func:`one_line` is the short form a training run prints.
"""

from __future__ import annotations

from agents.evaluation.metrics import Estimate

__all__ = ["COLUMNS", "GAME_COLUMNS", "format_table", "one_line", "one_shot"]

#: Statistics printed, with their labels; rates are shown as percentages.
COLUMNS: tuple[tuple[str, str, bool], ...] = (
    ("pots_per_shot", "pots/shot", True),
    ("clean_pot_rate", "clean pots/shot", True),
    ("scratch_rate", "scratch/shot", True),
    ("clear_rate", "clear rate", True),
    ("run_out_rate", "run-out rate", True),
    ("pots_per_turn", "pots/turn", False),
    ("shots_per_episode", "shots/episode", False),
    ("episode_reward", "episode reward", False),
)


#: The statistics of the game ids (rules): a won rack is a "clear", a run-out a rack won
#: in the first turn (every shot legal and keeping the table).
GAME_COLUMNS: tuple[tuple[str, str, bool], ...] = (
    ("fouls_per_shot", "fouls/shot", True),
    ("pots_per_shot", "pots/shot", False),
    ("scratch_rate", "scratch/shot", True),
    ("clear_rate", "racks won", True),
    ("run_out_rate", "run-outs", True),
    ("shots_per_episode", "shots/rack", False),
    ("episode_reward", "rack reward", False),
)


#: What a row is, printed under the table when the row is in it.
ROW_NOTES = {
    "first-row": "first-row: the observation's easiest ghost-ball shot (row 0 of its shot "
    "features: aim and speed, the tip at the centre) played exactly, learning nothing: the "
    "geometry alone, which a learner on that observation must beat.",
}


#: On a one-shot task, the columns that are others by construction: a cleared episode is
#: a pot, a run-out a clean pot, and each turn one shot.
ONE_SHOT_TWINS = {
    "clear_rate": "pots_per_shot",
    "run_out_rate": "clean_pot_rate",
    "pots_per_turn": "pots_per_shot",
}


def one_shot(rows: dict[str, dict[str, Estimate]]) -> bool:
    """Whether every episode of every row was one shot (a one-shot task: OneBall, ...)."""
    return all(
        (stats["shots_per_episode"].low, stats["shots_per_episode"].high) == (1.0, 1.0)
        for stats in rows.values()
    )


def format_table(rows: dict[str, dict[str, Estimate]], episodes: int) -> str:
    """A markdown table: one row per agent, each statistic with its 95% interval.

    On a one-shot task (:func:`one_shot`) a column that repeats its twin in every row
    (:data:`ONE_SHOT_TWINS`: clears and pots per turn are pots per shot, run-outs clean
    pots) is left out, and so is shots per episode (1); the note under the table says so. A row of
    :data:`ROW_NOTES` gets its note.
    """
    # Pots per shot is a rate only while no shot pots two balls (a break can pot several).
    multi = any(stats["pots_per_shot"].high > 1.0 for stats in rows.values())
    game = any("fouls_per_shot" in stats for stats in rows.values())
    columns = GAME_COLUMNS if game else COLUMNS
    dropped: list[str] = []
    if rows and one_shot(rows):
        labels = {key: label for key, label, _ in columns}
        kept: list[tuple[str, str, bool]] = []
        for key, label, pct in columns:
            twin = ONE_SHOT_TWINS.get(key)
            if key == "shots_per_episode":
                dropped.append(f"{label} (1)")
            elif twin and all(_same(stats[key], stats[twin]) for stats in rows.values()):
                dropped.append(f"{label} (= {labels[twin]})")
            else:
                kept.append((key, label, pct))
        columns = tuple(kept)
    head = "| agent | " + " | ".join(label for _, label, _ in columns) + " |"
    lines = [head, "|" + "---|" * (len(columns) + 1)]
    for agent, stats in rows.items():
        cells = [
            stats[key].as_percent()
            if pct and not (multi and key == "pots_per_shot")
            else str(stats[key])
            for key, _, pct in columns
        ]
        lines.append(f"| {agent} | " + " | ".join(cells) + " |")
    lines.append("")
    if game:
        lines.append(
            f"{episodes} racks each, same seeds; 95% confidence intervals in brackets. Racks "
            "won: the rack ended with the agent's win (the 9, the 10 or the 8 legally potted). "
            "Run-out: won without a foul or a missed turn."
        )
    else:
        lines.append(
            f"{episodes} episodes each, same seeds; 95% confidence intervals in brackets. Clean "
            "pot: a shot that pots without scratching. Run-out: cleared in the first turn."
        )
    if dropped:
        lines.append(f"One shot per episode, so these columns repeat others: {', '.join(dropped)}.")
    lines += [note for name, note in ROW_NOTES.items() if any(_base(r) == name for r in rows)]
    return "\n".join(lines)


def _same(a: Estimate, b: Estimate) -> bool:
    """Two statistics equal in value and interval (one column repeating another)."""
    return (a.value, a.low, a.high) == (b.value, b.low, b.high)


def _base(row: str) -> str:
    """A row's agent name without its label (``"best-const (+0.50, ...)"``: ``"best-const"``)."""
    return row.split(" ")[0]


def one_line(rows: dict[str, dict[str, Estimate]]) -> str:
    """``pots per shot: ppo 74.0% (clean 65.6%, scratch 17.1%) | random ... | ...``."""
    parts = [
        f"{name.split(' ')[0]} {stats['pots_per_shot'].value:.1%} "
        f"(clean {stats['clean_pot_rate'].value:.1%}, scratch {stats['scratch_rate'].value:.1%})"
        for name, stats in rows.items()
    ]
    return "pots per shot: " + " | ".join(parts)
