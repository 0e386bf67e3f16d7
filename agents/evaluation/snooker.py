"""Snooker break-building: each player's breaks on the same seeded visits, at each noise.

Usage::

    python -m agents.evaluation.snooker --visits 200 --out results/snooker_players.md

Visit ``k`` of ``pool_env/SnookerBreak-v1`` (or its roll twin, ``--env``) is reset with seed
``seed + k``, so every player meets the same layouts (the reds spread at random over the
top half, the colours on their spots, the cue ball in hand in the D). A visit ends at the
first stroke that scores nothing or fouls, or when the table is cleared. Players:
``random`` (uniform actions: the trivial floor), ``ghost``
(:class:`agents.baselines.snooker_play.SnookerGhostBallAgent`) and ``search``
(:class:`agents.baselines.snooker_search.SnookerSearchAgent`, ``--budget`` seconds a
shot). Reported per player and noise: the mean break with its 95% interval, the best
break, how the visits end (a miss, each foul, cleared, the shot limit), legal pots per
visit, and seconds a shot with the machine's load average (a time is only comparable
when the load is below the cores' count). Each noise is the env's ``noise`` keyword
(:func:`agents.evaluation.noise_flag.parse_noise`: ``none``, ``fastfiz``,
``fastfiz:5``...). ``--aim`` sets the env's aim mode (the ids' cut aim strikes only
the nearest ball on; ``absolute`` any direction). Under the tables: the first player's
mean break over each other's on the same visits, with its interval.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from collections import Counter
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np

from agents.baselines.random_agent import RandomAgent
from agents.baselines.snooker_play import SnookerGhostBallAgent
from agents.baselines.snooker_search import SnookerSearchAgent
from agents.evaluation.metrics import Estimate, mean_ci, ratio_ci
from agents.evaluation.noise_flag import noise_label, parse_noise
from agents.policy import Policy
from pool_env import AIM_MODES

#: The one-visit ids this command plays.
ENVS = ("pool_env/SnookerBreak-v1", "pool_env/SnookerBreakRoll-v1")

#: The players by name: ``(env, seed, budget) -> player``.
PLAYERS: dict[str, Callable[[Any, int, float], Policy]] = {
    "random": lambda env, seed, budget: RandomAgent(env, seed=seed),
    "ghost": lambda env, seed, budget: SnookerGhostBallAgent(env),
    "search": lambda env, seed, budget: SnookerSearchAgent(env, budget=budget, seed=seed),
}

#: How a visit can end, in the table's order (the fouls by the game's ``info["foul"]``).
ENDS = ("miss", "in_off", "no_contact", "wrong_ball_first", "ball_not_on_potted", "push",
        "cleared", "limit")  # fmt: skip


@dataclass
class Visits:
    """What one player did on the visits at one noise.

    Attributes:
        breaks: Each visit's points.
        pots: Each visit's legal pots (balls potted by strokes without a foul).
        shots: Each visit's strokes.
        ends: How the visits ended (:data:`ENDS`).
        seconds: Seconds the player took to choose its strokes, in all.
        load: The one-minute load average before and after.
    """

    breaks: list[float] = field(default_factory=list)
    pots: list[int] = field(default_factory=list)
    shots: list[int] = field(default_factory=list)
    ends: Counter[str] = field(default_factory=Counter)
    seconds: float = 0.0
    load: tuple[float, float] = (0.0, 0.0)


def visit_end(info: dict[str, Any], truncated: bool, on_table: np.ndarray) -> str:
    """How a visit ended: its foul, ``cleared`` (no object ball left), ``limit`` or ``miss``."""
    if info["foul"] is not None:
        return str(info["foul"])
    if not on_table[1:].any():
        return "cleared"
    return "limit" if truncated else "miss"


def play_visits(
    name: str,
    env_id: str,
    noise: Any,
    visits: int,
    seed: int,
    budget: float,
    aim: str | None = None,
) -> Visits:
    """Play ``visits`` visits from seeds ``seed``, ``seed + 1``, ... with player ``name``.

    ``aim``: the env's aim mode, ``None`` the id's (cut).
    """
    env = gym.make(env_id, noise=noise, **({} if aim is None else {"aim": aim}))
    player = PLAYERS[name](env, seed, budget)
    out = Visits(load=(os.getloadavg()[0], 0.0))
    for k in range(visits):
        obs, _ = env.reset(seed=seed + k)
        points, pots, shots = 0.0, 0, 0
        while True:
            start = time.perf_counter()
            action, _ = player.predict(obs)
            out.seconds += time.perf_counter() - start
            obs, reward, terminated, truncated, info = env.step(action)
            points += float(reward)
            shots += 1
            if info["foul"] is None:
                pots += sum(1 for b in info["potted"] if b != 0)
            if terminated or truncated:
                out.ends[visit_end(info, truncated, env.unwrapped.on_table)] += 1
                break
        out.breaks.append(points)
        out.pots.append(pots)
        out.shots.append(shots)
    env.close()
    out.load = (out.load[0], os.getloadavg()[0])
    return out


def row(name: str, v: Visits) -> list[str]:
    """One player's row of the table."""
    breaks = np.array(v.breaks)
    mean: Estimate = mean_ci(breaks)
    ends = ", ".join(f"{e} {v.ends[e]}" for e in ENDS if v.ends[e])
    shots = int(sum(v.shots))
    return [
        name,
        f"{mean.value:.2f} [{mean.low:.2f}, {mean.high:.2f}]",
        f"{breaks.max():.0f}",
        f"{np.mean(v.pots):.2f}",
        ends,
        f"{v.seconds / shots:.3f} (load {v.load[0]:.1f}/{v.load[1]:.1f})",
    ]


HEADER = ["player", "mean break [95%]", "best", "pots/visit", "ends", "s/shot (load)"]


def table(rows: list[list[str]]) -> str:
    """A markdown table of the rows under :data:`HEADER`."""
    lines = ["| " + " | ".join(HEADER) + " |", "|" + "---|" * len(HEADER)]
    return "\n".join(lines + ["| " + " | ".join(r) + " |" for r in rows])


def ratios(names: list[str], results: dict[str, Visits]) -> list[str]:
    """The first player's mean break over each other's, paired on the same visits."""
    first = names[0]
    out = []
    for other in names[1:]:
        a, b = np.array(results[first].breaks), np.array(results[other].breaks)
        if b.sum() <= 0.0:
            out.append(f"- {first} / {other}: {other} scored no point")
            continue
        r = ratio_ci(a, b)
        out.append(f"- {first} / {other} mean break: {r.value:.2f} [{r.low:.2f}, {r.high:.2f}]")
    return out


def main(argv: list[str] | None = None) -> int:
    """Command-line entry point."""
    parser = argparse.ArgumentParser(
        prog="python -m agents.evaluation.snooker", description=__doc__.split("\n\n")[0]
    )
    parser.add_argument("--players", nargs="+", default=["search", "ghost", "random"])
    parser.add_argument("--env", default=ENVS[0], help=f"one of {', '.join(ENVS)}")
    parser.add_argument("--visits", type=int, default=200)
    parser.add_argument("--seed", type=int, default=450000)
    parser.add_argument(
        "--noise", nargs="+", default=["none", "fastfiz", "fastfiz:5"], help="noises played"
    )
    parser.add_argument(
        "--aim", default=None, choices=AIM_MODES, help="the env's aim mode (default: the id's)"
    )
    parser.add_argument("--budget", type=float, default=1.0, help="search: seconds a shot")
    parser.add_argument("--out", default=None, help="write the tables (markdown) here")
    args = parser.parse_args(argv)
    if args.visits < 1:
        parser.error(f"--visits must be >= 1, got {args.visits}")
    if not (np.isfinite(args.budget) and args.budget > 0.0):
        parser.error(f"--budget must be a number of seconds > 0, got {args.budget}")
    if args.env not in ENVS:
        parser.error(f"--env must be one of {', '.join(ENVS)}, got {args.env!r}")
    unknown = [p for p in args.players if p not in PLAYERS]
    if unknown:
        parser.error(f"--players: unknown {unknown}; choose from {', '.join(PLAYERS)}")
    noises = []
    for text in args.noise:
        try:
            noises.append((text, parse_noise(text)))
        except ValueError as err:
            parser.error(str(err))
    command = "python -m agents.evaluation.snooker " + " ".join(
        argv if argv is not None else sys.argv[1:]
    )
    lines = [
        "# Snooker break-building: the players' breaks",
        "",
        f"`{command}`",
        "",
        f"{args.env}, {args.visits} visits from seed {args.seed} (visit k: seed + k), "
        f"the same for every player; aim {args.aim or 'cut (the id default)'}; "
        f"search budget {args.budget:g} s a shot; "
        f"{os.cpu_count()} CPUs.",
    ]
    for text, noise in noises:
        results = {
            name: play_visits(name, args.env, noise, args.visits, args.seed, args.budget, args.aim)
            for name in args.players
        }
        part = ["", f"## Noise {text}: {noise_label(noise)}", ""]
        part += [table([row(n, results[n]) for n in args.players]), ""]
        part += ratios(args.players, results)
        print("\n".join(part), flush=True)
        lines += part
    if args.out:
        Path(args.out).parent.mkdir(parents=True, exist_ok=True)
        Path(args.out).write_text("\n".join(lines) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
