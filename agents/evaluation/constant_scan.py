"""The best constant action: a grid of constant actions scanned, the best pot rate kept.

A learner that aims must beat every policy that ignores the layout, not only the one
constant that happens to be named (the full hit). The scan plays each action of a
``grid x grid`` lattice on ``[-1, 1]^2`` for the same episodes and keeps the one with the
highest pots per shot (ties: the first in the lattice). On a spin env the two tip
components join the lattice with ``tip_grid`` points each (centre and the limits by
default). Its seeds (:data:`SCAN_SEED`) lie apart from the evaluation seeds, so the
figure reported for it on the evaluation seeds is not inflated by the choice.
"""

from __future__ import annotations

import itertools
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from agents.baselines.random_agent import ConstantAgent
from agents.evaluation.episodes import run_episodes
from agents.evaluation.metrics import Estimate

#: First seed of the scan's episodes (evaluations use 10_000 and 20_000 onwards).
SCAN_SEED = 30_000


@dataclass(frozen=True)
class ConstantScan:
    """The result of :func:`scan_constant_actions`.

    Attributes:
        action: The best action.
        pots_per_shot: Its pots per shot on the scan's episodes.
        table: Every action tried with its pots per shot, in lattice order.
    """

    action: tuple[float, ...]
    pots_per_shot: Estimate
    table: list[tuple[tuple[float, ...], float]]


def scan_constant_actions(
    env: Any,
    grid: int = 9,
    episodes: int = 1000,
    seed: int = SCAN_SEED,
    tip_grid: int = 3,
    progress: Callable[[int], object] | None = None,
) -> ConstantScan:
    """Play every action of a ``grid x grid`` lattice on ``env`` and keep the best.

    Args:
        env: A Gymnasium ``PoolEnv`` (wrapped or not).
        grid: Points per aim and speed component (``grid >= 2``: the lattice includes +-1).
        episodes: Episodes per action (the same seeds for each).
        seed: Seed of the first episode.
        tip_grid: Points per tip component of a spin env's ``Box(4)`` (``>= 2``).
        progress: Called with 1 after each action's episodes (a progress bar's ``update``).

    Raises:
        ValueError: On ``grid < 2``, ``tip_grid < 2`` or ``episodes < 1``.
    """
    if grid < 2 or tip_grid < 2:
        raise ValueError(
            f"grid and tip_grid must be at least 2 (the corners of the action box), got "
            f"{grid}, {tip_grid}"
        )
    if episodes < 1:
        raise ValueError(f"episodes must be at least 1, got {episodes}")
    values = np.linspace(-1.0, 1.0, grid).tolist()
    tips = np.linspace(-1.0, 1.0, tip_grid).tolist()
    width = int(env.action_space.shape[0])
    axes = [values, values] + [tips] * (width - 2)
    best: tuple[tuple[float, ...], Estimate] | None = None
    table = []
    for point in itertools.product(*axes):
        action = tuple(float(a) for a in point)
        stats = run_episodes(ConstantAgent(env, action), env, episodes, seed).summary()
        rate = stats["pots_per_shot"]
        table.append((action, rate.value))
        if best is None or rate.value > best[1].value:
            best = (action, rate)
        if progress is not None:
            progress(1)
    assert best is not None
    return ConstantScan(best[0], best[1], table)


def lattice_size(env: Any, grid: int = 9, tip_grid: int = 3) -> int:
    """Actions :func:`scan_constant_actions` plays: ``grid^2`` (and ``tip_grid^2`` on spin)."""
    return grid * grid * tip_grid ** (int(env.action_space.shape[0]) - 2)


def best_constant_agent(
    env: Any,
    grid: int = 9,
    episodes: int = 1000,
    progress: Callable[[int], object] | None = None,
) -> ConstantAgent:
    """A :class:`ConstantAgent` playing the best action of :func:`scan_constant_actions`."""
    scan = scan_constant_actions(env, grid, episodes, progress=progress)
    return ConstantAgent(env, scan.action)
