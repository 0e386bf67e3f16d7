"""Demo: a 9-ball break, its events as a table, and a GIF of it (``python -m pool_env.demo``).

Options: ``--gif PATH`` (default ``break.gif``; ``--gif ""`` writes none), ``--speed``
(m/s of the cue ball), ``--width`` (GIF pixels).
"""

from __future__ import annotations

import argparse
import time
from collections.abc import Sequence

import numpy as np

from pool_env.sim.layouts import break_scene
from pool_env.sim.result import Event, ShotResult
from pool_env.sim.simulate import shoot
from pool_env.sim.table import Table

#: Rails by index (``Event.j`` of a cushion event): the head is the end the break is from.
RAIL_NAMES = ("head rail", "foot rail", "bottom rail", "top rail")

#: What each event kind is called in the table.
KIND_NAMES = {"ball": "impact", "cushion": "cushion", "pocket": "pocket", "stop": "rest"}


def ball_name(number: int) -> str:
    """``0`` -> ``"cue"``, ``9`` -> ``"9-ball"``."""
    return "cue" if number == 0 else f"{number}-ball"


def pocket_name(table: Table, k: int) -> str:
    """Where pocket ``k`` is: ``"top-left corner"``, ``"bottom side"``, ... (by position)."""
    x, y, _ = table.pockets[k]
    vertical = "bottom" if y < table.width / 2.0 else "top"
    if table.length / 3.0 < x < 2.0 * table.length / 3.0:
        return f"{vertical} side pocket"
    horizontal = "left" if x < table.length / 2.0 else "right"
    return f"{vertical}-{horizontal} corner"


def describe(event: Event, table: Table) -> tuple[str, str, str]:
    """``(kind, ball, with what)`` of an event, in words."""
    kind = KIND_NAMES.get(event.kind, event.kind)
    ball = ball_name(event.i)
    if event.kind == "ball":
        return kind, ball, ball_name(event.j)
    if event.kind == "cushion":
        return kind, ball, RAIL_NAMES[event.j] if 0 <= event.j < 4 else f"rail {event.j}"
    if event.kind == "pocket":
        return kind, ball, pocket_name(table, event.j)
    return kind, ball, ""


def event_table(result: ShotResult, table: Table) -> list[str]:
    """The shot's events as aligned lines: time, kind, ball, with what.

    Events that print the same (the pairwise impacts of a touching rack, resolved at one
    instant, can repeat a pair) are one line with a count, so no line repeats.
    """
    rows: list[list[str]] = []
    counts: list[int] = []
    seen: dict[tuple[str, ...], int] = {}
    for event in result.events:
        key = (f"{event.time:.6f}", *describe(event, table))
        if key in seen:
            counts[seen[key]] += 1
            continue
        seen[key] = len(rows)
        rows.append(list(key))
        counts.append(1)
    for row, count in zip(rows, counts, strict=True):
        if count > 1:
            row[3] = f"{row[3]} (x{count})"
    head = ["time (s)", "event", "ball", "with"]
    widths = [max(len(r[c]) for r in [head, *rows]) for c in range(4)]
    lines = ["  ".join(cell.ljust(w) for cell, w in zip(r, widths, strict=True)).rstrip()
             for r in [head, *rows]]  # fmt: skip
    lines.insert(1, "  ".join("-" * w for w in widths))
    return lines


def main(argv: Sequence[str] | None = None) -> None:
    """Break a 9-ball rack, print the events and the pots, write the GIF."""
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--gif", default="break.gif", help='GIF path ("" for none)')
    p.add_argument("--speed", type=float, default=8.0, help="cue ball speed, m/s")
    p.add_argument("--width", type=int, default=400, help="GIF width, pixels")
    args = p.parse_args(argv)
    table = Table()
    positions = break_scene(table, "nine")
    started = time.perf_counter()
    result = shoot(table, positions, angle=0.0, speed=args.speed)
    elapsed = time.perf_counter() - started
    print(
        f"9-ball break at {args.speed:g} m/s: {result.n_events} events, "
        f"rest after {result.duration:.2f} s\n"
    )
    print("\n".join(event_table(result, table)))
    potted = [ball_name(int(i)) for i in np.flatnonzero(result.pocketed >= 0)]
    print(f"\npotted: {', '.join(potted) or 'nothing'}")
    print(f"first shot (compile or cache load included): {elapsed * 1e3:.1f} ms")
    if args.gif:
        from pool_env.render import Renderer, save_animation, shot_frames

        renderer = Renderer(table, args.width)
        balls = np.arange(positions.shape[0])
        frames = shot_frames(renderer, result, balls, fps=15, max_seconds=8.0)
        save_animation(frames, args.gif, fps=15)
        print(f"wrote {args.gif} ({len(frames)} frames)")


if __name__ == "__main__":
    main()
