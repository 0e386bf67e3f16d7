"""ThreeCushionSearch: a three-cushion player that searches the batched rollout, anytime.

A carom has no ghost-ball shot: the cue ball's path off three cushions is the shot, and
spin bends every leg of it. So the player asks the simulator. Each shot it plans in stages,
each a few :func:`pool_env.sim.rollout` calls of thousands of rows, until its wall-clock
budget is spent (anytime: every stage ends with a best shot in hand):

1. **Grid.** Aim all round (:data:`GRID_ANGLES` directions), :data:`GRID_SPEEDS` speeds
   and the tips of :data:`GRID_TIPS` (centre, running and reverse english, follow, draw),
   each played exactly; the points are read from the rows (:mod:`agents.baselines.carom`).
   A point whose neighbours in aim also score sits in a wide window: those are kept first.
   No point on the grid: random shots over the whole range until one scores.
2. **Noise.** The kept points are replayed under the env's execution noise with common
   random draws (the same :data:`DRAWS` normal draws for every candidate, so candidates
   differ by their shot alone), and ranked by their success rate.
   More candidates are ranked while :data:`RANK_SHARE` of the budget lasts.
3. **Refine.** The best few are perturbed (aim, speed, tip a, tip b, with shrinking steps,
   the first at least the noise's sigma) and a neighbour that scores more often under the
   same draws replaces its parent, round after round until :data:`REFINE_SHARE` of the
   budget is spent.
4. **Final.** The finalists are replayed under fresh draws (:data:`FINAL_DRAWS`) and
   weighed by their leave (the inning goes on after a point): a small search from where
   the nominal shot leaves the balls (a coarser grid, its widest points under a few draws)
   gives the next shot's success rate ``q``, and the finalist of the largest
   ``p (1 + q)`` is played (``p`` its own success rate): the points expected from this shot
   and the next.

When nothing scores, the shot that came nearest (both balls met after the most cushions;
:func:`agents.baselines.carom.near_scores`) is played. Without noise (FastFiz x0) the
replays use :data:`FLOOR_MULTIPLE` of FastFiz's sigmas, so that a shot on a knife edge is
still avoided.

:class:`ThreeCushionSearch` plans on the raw simulator (a table, the layout, the cue ball);
:class:`ThreeCushionSearchAgent` plays it through an env's action (SB3's ``predict``).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from agents.baselines.carom import near_scores, noisy_rows, points_of_rows
from pool_env import Table
from pool_env.game.checks import default_tip_limit
from pool_env.game.noise import fastfiz_sigmas
from pool_env.sim import rollout

__all__ = ["CaromPlan", "ThreeCushionSearch"]

#: Aim directions of the grid, evenly all round (0.5 degree apart).
GRID_ANGLES = 720
#: Cue ball speeds of the grid, as fractions of the way from :data:`SLOWEST` (or the range's
#: low end if higher) to the range's high end.
GRID_SPEEDS = (0.0, 0.25, 0.5, 0.75, 1.0)
#: The slowest speed (m/s) the grid tries: slower shots rarely reach three cushions.
SLOWEST = 1.5
#: Tips of the grid as fractions of the tip limit ``(a side, b vertical)``.
GRID_TIPS = (
    (0.0, 0.0),
    (0.6, 0.0),
    (-0.6, 0.0),
    (0.0, 0.5),
    (0.0, -0.5),
    (0.6, 0.5),
    (-0.6, 0.5),
    (0.6, -0.5),
    (-0.6, -0.5),
)
#: Candidates replayed under noise in one call; more calls while :data:`RANK_SHARE` of the
#: budget lasts, widest windows first.
CANDIDATES = 96
#: The grid points kept for ranking, at most.
MAX_RANKED = 1536
#: Share of the budget the ranking may use; refining goes on until :data:`REFINE_SHARE`.
RANK_SHARE = 0.35
REFINE_SHARE = 0.7
#: Refining rounds at most (the steps halve each round, back to coarse after four).
REFINE_ROUNDS = 12
#: Noise draws per candidate in the ranking and refining stages.
DRAWS = 64
#: Candidates refined by local perturbation.
REFINED = 12
#: Noise draws per finalist in the final stage.
FINAL_DRAWS = 256
#: Finalists whose leave is weighed.
FINALISTS = 6
#: Random shots per call while the grid has no point.
RANDOM_BATCH = 8192
#: FastFiz multiple the replays use when the env has less noise (x0).
FLOOR_MULTIPLE = 0.5
#: Aim directions, speeds and tips of the leave's grid.
LEAVE_ANGLES = 360
LEAVE_TIPS = ((0.0, 0.0), (0.6, 0.0), (-0.6, 0.0), (0.0, 0.5), (0.0, -0.5))
LEAVE_SPEEDS = (0.4, 0.8)
#: The leave's points replayed under noise, and their draws.
LEAVE_CANDIDATES = 16
LEAVE_DRAWS = 16


@dataclass
class CaromPlan:
    """The shot the search chose and why.

    Attributes:
        angle: Aim direction (radians from +x).
        speed: Cue ball speed (m/s).
        tip: Cue tip ``(a, b)`` in fractions of R.
        kind: ``"point"`` (it scores without noise), ``"near_miss"`` (nothing scored: the
            shot that came nearest).
        success: Its success rate under the noise draws (0 for a near miss).
        leave: The next shot's success rate from where it leaves the balls, as the leave's
            small search finds it (``nan`` if not weighed).
        simulated: Shots simulated to plan it.
        seconds: Wall-clock seconds spent.
        stages: The stages that ran, in order.
    """

    angle: float
    speed: float
    tip: tuple[float, float]
    kind: str
    success: float
    leave: float = math.nan
    simulated: int = 0
    seconds: float = 0.0
    stages: list[str] = field(default_factory=list)

    @property
    def row(self) -> NDArray[np.float64]:
        """The ``(5,)`` rollout row ``(angle, speed, a, b, elevation 0)``."""
        return np.array([self.angle, self.speed, self.tip[0], self.tip[1], 0.0])


class _BudgetSpentError(Exception):
    """The budget ran out inside a stage."""


class ThreeCushionSearch:
    """Plans three-cushion shots by searching the batched rollout (see the module's text).

    Args:
        table: A spin table (``Table.preset("carom")`` by default).
        noise: The env's execution noise sigmas ``(angle rad, speed m/s, tip in R)``, or
            ``None`` for none (x0).
        budget: Wall-clock seconds per shot (> 0).
        threads: Threads of each rollout (>= 1).
        speed_range: The speeds (m/s) the player may choose: ``(low, high)``,
            ``0 <= low < high``.
        tip_limit: The miscue circle (fraction of R; the env's default for the table by
            default).
        seed: Seed of the noise draws.
        playable: ``rows -> (S,)`` booleans, the shots the caller's action can express
            (an env's aim mode; all by default): only those are chosen.

    Raises:
        ValueError: On a roll table, a non-positive budget or thread count, a bad speed
            range, tip limit or noise.
    """

    def __init__(
        self,
        table: Table | None = None,
        noise: tuple[float, ...] | None = None,
        budget: float = 1.0,
        threads: int = 2,
        speed_range: tuple[float, float] = (0.5, 7.0),
        tip_limit: float | None = None,
        seed: int = 0,
        playable: Callable[[NDArray[np.float64]], NDArray[np.bool_]] | None = None,
    ) -> None:
        table = Table.preset("carom") if table is None else table
        if not isinstance(table, Table) or not table.has_spin:
            raise ValueError(f"table must be a spin Table (three-cushion is spin), got {table!r}")
        if not (isinstance(budget, int | float) and math.isfinite(budget) and budget > 0):
            raise ValueError(f"budget must be a positive number of seconds, got {budget!r}")
        if isinstance(threads, bool) or not isinstance(threads, int) or threads < 1:
            raise ValueError(f"threads must be a positive integer, got {threads!r}")
        low, high = (float(v) for v in speed_range)
        if not (math.isfinite(high) and 0.0 <= low < high):
            raise ValueError(
                f"speed_range must be (low, high) with 0 <= low < high, got {speed_range!r}"
            )
        limit = default_tip_limit(table) if tip_limit is None else float(tip_limit)
        if not 0.0 < limit <= 1.0:
            raise ValueError(f"tip_limit must lie in (0, 1], got {tip_limit!r}")
        if noise is not None:
            sig = tuple(float(v) for v in noise)
            if len(sig) != 3 or not all(math.isfinite(v) and v >= 0 for v in sig):
                raise ValueError(
                    "noise must be None or 3 non-negative sigmas (angle, speed, tip), got "
                    f"{noise!r}"
                )
            noise = sig
        self.table = table
        self.noise = noise
        self.budget = float(budget)
        self.threads = threads
        self.speed_range = (low, high)
        self.tip_limit = limit
        self.rng = np.random.default_rng(seed)
        self.playable = playable
        floor = fastfiz_sigmas(table, FLOOR_MULTIPLE)
        self.sigmas = tuple(max(a, b) for a, b in zip(noise or (0.0, 0.0, 0.0), floor, strict=True))
        self._grid = self._grid_rows(GRID_ANGLES, GRID_SPEEDS, GRID_TIPS)
        self._leave_grid = self._grid_rows(LEAVE_ANGLES, LEAVE_SPEEDS, LEAVE_TIPS)

    def _grid_rows(
        self,
        n_angles: int,
        speeds: tuple[float, ...],
        tips: tuple[tuple[float, float], ...],
        aim_window: tuple[float, float] | None = None,
    ) -> NDArray[np.float64]:
        """``(len(speeds) * len(tips) * n_angles, 5)`` rows, angle fastest.

        The angles go all round, or evenly across ``aim_window`` (both ends included).
        """
        low, high = self.speed_range
        slowest = min(max(low, SLOWEST), high)
        kept = [slowest + f * (high - slowest) for f in speeds]
        if aim_window is None:
            angles = np.arange(n_angles) * (2.0 * math.pi / n_angles)
        else:
            angles = np.linspace(aim_window[0], aim_window[1], n_angles)
        blocks = []
        for v in kept:
            for a, b in tips:
                block = np.zeros((n_angles, 5))
                block[:, 0], block[:, 1] = angles, v
                block[:, 2], block[:, 3] = a * self.tip_limit, b * self.tip_limit
                blocks.append(block)
        return np.concatenate(blocks)

    def plan(
        self,
        positions: ArrayLike,
        cue: int = 0,
        first_ball: int | None = None,
        aim_window: tuple[float, float] | None = None,
    ) -> CaromPlan:
        """The shot to play from ``positions`` with cue ball ``cue``.

        Args:
            positions: ``(3, 2)`` ball centres (white, yellow, red).
            cue: The striker's cue ball (0 white or 1 yellow).
            first_ball: A ball the cue ball must meet first (the break's red, 2), or
                ``None``.
            aim_window: ``(low, high)`` the directions (radians, ``low < high <= low +
                2 pi``) the caller's action can aim (a cut aim's cone at the nearest ball):
                the grid spreads its directions across it. ``None``: all round.

        Returns:
            The :class:`CaromPlan`.

        Raises:
            ValueError: On a layout that is not 3 balls, a bad cue, first ball or window.
        """
        pos = np.array(positions, dtype=np.float64)
        if pos.shape != (3, 2):
            raise ValueError(f"positions must be (3, 2) ball centres, got shape {pos.shape}")
        if isinstance(cue, bool) or cue not in (0, 1):
            raise ValueError(f"cue must be 0 (white) or 1 (yellow), got {cue!r}")
        if first_ball is not None and (first_ball not in (0, 1, 2) or first_ball == cue):
            raise ValueError(
                f"first_ball must be an object ball of cue {cue} or None, got {first_ball!r}"
            )
        grid = self._grid
        if aim_window is not None:
            lo, hi = (float(v) for v in aim_window)
            if not (math.isfinite(lo) and lo < hi <= lo + 2.0 * math.pi):
                raise ValueError(
                    f"aim_window must be (low, high) with low < high <= low + 2 pi, got "
                    f"{aim_window!r}"
                )
            grid = self._grid_rows(GRID_ANGLES, GRID_SPEEDS, GRID_TIPS, (lo, hi))
        start = time.perf_counter()
        search = _Search(self, pos, cue, first_ball, start + self.budget, grid)
        plan = search.run()
        plan.seconds = time.perf_counter() - start
        return plan


class _Search:
    """One plan's state: the layout, the draws, the best shot so far."""

    def __init__(
        self,
        player: ThreeCushionSearch,
        positions: NDArray[np.float64],
        cue: int,
        first_ball: int | None,
        deadline: float,
        grid: NDArray[np.float64],
    ) -> None:
        self.p = player
        self.grid_rows = grid
        self.pos = positions
        self.cue = cue
        self.first_ball = first_ball
        self.deadline = deadline
        self.simulated = 0
        self.stages: list[str] = []
        self.draws = player.rng.standard_normal((DRAWS, 4))
        self.best: CaromPlan | None = None

    def roll(self, rows: NDArray[np.float64], pos: NDArray[np.float64] | None = None) -> Any:
        """Rollout of ``rows`` from ``pos`` (the layout by default).

        Raises :class:`_BudgetSpentError` past the deadline once a shot is in hand.
        """
        if time.perf_counter() > self.deadline and self.best is not None:
            raise _BudgetSpentError
        self.simulated += rows.shape[0]
        layout = self.pos if pos is None else pos
        return rollout(self.p.table, layout, rows, cue=self.cue, threads=self.p.threads)

    def points(self, out: Any, first_ball: int | None) -> NDArray[np.bool_]:
        """Points that also meet the first-ball rule (``None``: none)."""
        ok = points_of_rows(out, self.cue)
        if first_ball is not None:
            ok &= np.asarray(out.first_hit)[:, self.cue] == first_ball
        return ok

    def choosable(self, rows: NDArray[np.float64]) -> NDArray[np.bool_]:
        """The rows the caller's action can play (all without a ``playable``)."""
        if self.p.playable is None:
            return np.ones(rows.shape[0], dtype=np.bool_)
        return np.asarray(self.p.playable(rows), dtype=np.bool_)

    def success(
        self,
        rows: NDArray[np.float64],
        draws: NDArray[np.float64],
        pos: NDArray[np.float64] | None = None,
    ) -> NDArray[np.float64]:
        """``(S,)`` success rates of ``rows`` under ``draws`` (common random numbers).

        From the layout by default (its first-ball rule applies), else from ``pos`` (a
        leave: the next shot, no first-ball rule).
        """
        # The env adds the noise to the action's shot (in the range): no clipping after it.
        played = noisy_rows(rows, draws, self.p.sigmas, self.p.tip_limit)
        first = self.first_ball if pos is None else None
        ok = self.points(self.roll(played, pos), first)
        return ok.reshape(rows.shape[0], draws.shape[0]).mean(axis=1)

    def leave(self, pos: NDArray[np.float64]) -> float:
        """The next shot's success rate from ``pos``, by a small search (grid, then noise)."""
        grid = self.p._leave_grid
        ok = self.points(self.roll(grid, pos), None)
        if not ok.any():
            return 0.0
        picked = grid[_widest(ok, LEAVE_ANGLES)[:LEAVE_CANDIDATES]]
        return float(self.success(picked, self.draws[:LEAVE_DRAWS], pos).max())

    def clip(self, rows: NDArray[np.float64]) -> None:
        """Keep speeds in the range and tips in the circle, in place."""
        low, high = self.p.speed_range
        np.clip(rows[:, 1], 0.0, high, out=rows[:, 1])
        rows[:, 1] = np.where(rows[:, 1] < low, low, rows[:, 1]) if low > 0 else rows[:, 1]
        h = np.hypot(rows[:, 2], rows[:, 3])
        scale = np.where(h > self.p.tip_limit, self.p.tip_limit / np.maximum(h, 1e-300), 1.0)
        rows[:, 2] *= scale
        rows[:, 3] *= scale

    def set_best(
        self, row: NDArray[np.float64], kind: str, success: float, leave: float = math.nan
    ) -> None:
        self.best = CaromPlan(
            angle=float(row[0]) % (2.0 * math.pi),
            speed=float(row[1]),
            tip=(float(row[2]), float(row[3])),
            kind=kind,
            success=success,
            leave=leave,
        )

    def run(self) -> CaromPlan:
        try:
            candidates = self.grid()
            if candidates is not None:
                self.rank_refine_final(candidates)
        except _BudgetSpentError:
            pass
        assert self.best is not None
        self.best.simulated = self.simulated
        self.best.stages = self.stages
        return self.best

    def grid(self) -> NDArray[np.float64] | None:
        """Stage 1: the grid's points, widest window first; ``None`` after a near miss."""
        self.stages.append("grid")
        rows = self.grid_rows
        out = self.roll(rows)
        can = self.choosable(rows)
        ok = self.points(out, self.first_ball) & can
        near = np.where(can, near_scores(out, self.cue), -np.inf)
        self.set_best(rows[int(np.argmax(near))], "near_miss", 0.0)
        if not ok.any():
            return self.random_points(near.max())
        picked = rows[_widest(ok, GRID_ANGLES)[:MAX_RANKED]].copy()
        self.set_best(picked[0], "point", 0.0)
        return picked

    def random_points(self, nearest: float) -> NDArray[np.float64] | None:
        """Random shots until one scores (its points) or half the budget is gone."""
        self.stages.append("random")
        low, high = self.p.speed_range
        half = self.deadline - 0.5 * self.p.budget
        while time.perf_counter() < half:
            n = RANDOM_BATCH
            rows = np.zeros((n, 5))
            rows[:, 0] = self.p.rng.uniform(0.0, 2.0 * math.pi, n)
            rows[:, 1] = self.p.rng.uniform(min(max(low, 1.0), high), high, n)
            r = self.p.tip_limit * np.sqrt(self.p.rng.uniform(0.0, 0.8, n))
            t = self.p.rng.uniform(0.0, 2.0 * math.pi, n)
            rows[:, 2], rows[:, 3] = r * np.cos(t), r * np.sin(t)
            out = self.roll(rows)
            can = self.choosable(rows)
            ok = self.points(out, self.first_ball) & can
            if ok.any():
                picked = rows[ok][:CANDIDATES].copy()
                self.set_best(picked[0], "point", 0.0)
                return picked
            near = np.where(can, near_scores(out, self.cue), -np.inf)
            if near.max() > nearest:
                nearest = float(near.max())
                self.set_best(rows[int(np.argmax(near))], "near_miss", 0.0)
        return None

    def rank_refine_final(self, candidates: NDArray[np.float64]) -> None:
        """Stages 2-4: rank under noise, refine the best, weigh the finalists' leaves."""
        self.stages.append("noise")
        start = self.deadline - self.p.budget
        rate = np.full(candidates.shape[0], -1.0)
        for lo in range(0, candidates.shape[0], CANDIDATES):
            if lo and time.perf_counter() > start + RANK_SHARE * self.p.budget:
                break
            rate[lo : lo + CANDIDATES] = self.success(candidates[lo : lo + CANDIDATES], self.draws)
            k = int(np.argmax(rate))
            self.set_best(candidates[k], "point", float(rate[k]))
        order = np.argsort(-rate, kind="stable")[:REFINED]
        top, top_rate = candidates[order].copy(), rate[order].copy()
        self.stages.append("refine")
        sig_angle, sig_speed, sig_tip = self.p.sigmas
        first = np.array(
            [max(math.radians(0.25), sig_angle), max(0.3, 2 * sig_speed)]
            + [max(0.08, 2 * sig_tip)] * 2
        )
        for r in range(REFINE_ROUNDS):
            if time.perf_counter() > start + REFINE_SHARE * self.p.budget:
                break
            top, top_rate = self.refine(top, top_rate, first * 0.5 ** (r % 4))
            k = int(np.argmax(top_rate))
            self.set_best(top[k], "point", float(top_rate[k]))
        self.final(top)

    def refine(
        self, top: NDArray[np.float64], rate: NDArray[np.float64], steps: NDArray[np.float64]
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """One round: each of ``top`` against its 8 axis neighbours under the same draws."""
        n = top.shape[0]
        moves = np.zeros((8, 5))
        for axis in range(4):
            moves[2 * axis, axis], moves[2 * axis + 1, axis] = steps[axis], -steps[axis]
        neigh = (top[:, None, :] + moves[None]).reshape(-1, 5)
        self.clip(neigh)
        neigh_rate = self.success(neigh, self.draws)
        neigh_rate = np.where(self.choosable(neigh), neigh_rate, -1.0).reshape(n, 8)
        best = np.argmax(neigh_rate, axis=1)
        better = neigh_rate[np.arange(n), best] > rate
        new = top.copy()
        new[better] = neigh.reshape(n, 8, 5)[np.arange(n), best][better]
        return new, np.where(better, neigh_rate[np.arange(n), best], rate)

    def final(self, top: NDArray[np.float64]) -> None:
        """Stage 4: fresh draws for the finalists; the leave breaks near-ties."""
        self.stages.append("final")
        draws = self.p.rng.standard_normal((FINAL_DRAWS, 4))
        rate = self.success(top, draws)
        order = np.argsort(-rate, kind="stable")[:FINALISTS]
        k = int(order[0])
        self.set_best(top[k], "point", float(rate[k]))
        self.stages.append("leave")
        nominal = self.roll(top[order])
        best = -1.0
        for j, k in enumerate(order):  # a deadline inside keeps the best weighed so far
            leave = self.leave(nominal.positions[j])
            if rate[k] * (1.0 + leave) > best:
                best = rate[k] * (1.0 + leave)
                self.set_best(top[k], "point", float(rate[k]), leave)


def _widest(ok: NDArray[np.bool_], n_angles: int) -> NDArray[np.intp]:
    """The indices of a grid's points, widest window first (angle the fastest axis).

    A point's window: itself and how many of its two neighbours in aim (same speed and
    tip) also score.
    """
    blocks = ok.reshape(-1, n_angles)
    width = blocks.astype(np.int64) + np.roll(blocks, 1, axis=1) + np.roll(blocks, -1, axis=1)
    width = np.where(blocks, width, 0).reshape(-1)
    return np.argsort(-width, kind="stable")[: int(ok.sum())]
