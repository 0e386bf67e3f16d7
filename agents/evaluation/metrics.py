"""Episode statistics and their 95% confidence intervals.

Rates per episode (clear rate) use the Wilson interval. Rates per shot pool shots across
episodes, and the shots of one episode are not independent (a bad layout makes several bad
shots), so their interval is the ratio estimator's, clustered by episode (delta method); with
one shot per episode and 0/1 outcomes it is replaced by the Wilson interval of a proportion.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

Z95 = 1.959963984540054  # two-sided 95% normal quantile


@dataclass(frozen=True)
class Estimate:
    """A point estimate with a 95% confidence interval.

    Attributes:
        value: The estimate.
        low: Lower end of the interval.
        high: Upper end of the interval.
    """

    value: float
    low: float
    high: float

    def __str__(self) -> str:
        return f"{self.value:.3f} [{self.low:.3f}, {self.high:.3f}]"

    def as_percent(self) -> str:
        """``"57.3% [54.2, 60.4]"``."""
        return f"{100 * self.value:.1f}% [{100 * self.low:.1f}, {100 * self.high:.1f}]"


def wilson(successes: float, n: int, z: float = Z95) -> Estimate:
    """Wilson score interval of a proportion ``successes / n``."""
    if n <= 0:
        return Estimate(math.nan, math.nan, math.nan)
    p = successes / n
    denom = 1.0 + z * z / n
    centre = (p + z * z / (2 * n)) / denom
    half = z * math.sqrt(p * (1.0 - p) / n + z * z / (4 * n * n)) / denom
    return Estimate(p, max(0.0, centre - half), min(1.0, centre + half))


def mean_ci(values: NDArray[np.floating], z: float = Z95) -> Estimate:
    """Mean with a normal-approximation interval."""
    x = np.asarray(values, dtype=np.float64)
    if x.size == 0:
        return Estimate(math.nan, math.nan, math.nan)
    m = float(x.mean())
    half = z * float(x.std(ddof=1)) / math.sqrt(x.size) if x.size > 1 else math.inf
    return Estimate(m, m - half, m + half)


def ratio_ci(
    num: NDArray[np.floating],
    den: NDArray[np.floating],
    z: float = Z95,
    bounds: tuple[float, float] | None = None,
) -> Estimate:
    """``sum(num) / sum(den)`` over episodes, interval clustered by episode (delta method).

    With every ``den == 1`` and ``num`` in {0, 1} this is a plain proportion: Wilson.
    ``bounds`` clips the interval (a rate stays in [0, 1]).
    """
    a = np.asarray(num, dtype=np.float64)
    b = np.asarray(den, dtype=np.float64)
    n = a.size
    if n == 0 or b.sum() <= 0:
        return Estimate(math.nan, math.nan, math.nan)
    if np.all(b == 1.0) and np.all((a == 0.0) | (a == 1.0)):
        return wilson(float(a.sum()), n, z)
    r = float(a.sum() / b.sum())
    if n == 1:
        return Estimate(r, -math.inf, math.inf)
    resid = a - r * b
    se = math.sqrt(float(resid @ resid) / (n * (n - 1))) / float(b.mean())
    low, high = r - z * se, r + z * se
    if bounds is not None:
        low, high = max(low, bounds[0]), min(high, bounds[1])
    return Estimate(r, low, high)


@dataclass
class EpisodeLog:
    """Per-episode counts collected by an evaluation (one entry per episode).

    Attributes:
        shots: Shots played.
        pots: Object balls potted.
        clean: Shots that potted at least one ball without a scratch.
        scratches: Shots that potted the cue ball.
        turns: Turns (a turn ends with a shot that pots nothing or scratches, or at the end).
        rewards: Summed reward.
        cleared: Whether the table was cleared.
        run_out: Cleared in the first turn.
        fouls: Fouls (the game ids only; empty otherwise).
    """

    shots: list[int] = field(default_factory=list)
    pots: list[int] = field(default_factory=list)
    clean: list[int] = field(default_factory=list)
    scratches: list[int] = field(default_factory=list)
    turns: list[int] = field(default_factory=list)
    rewards: list[float] = field(default_factory=list)
    cleared: list[bool] = field(default_factory=list)
    run_out: list[bool] = field(default_factory=list)
    fouls: list[int] = field(default_factory=list)

    def summary(self) -> dict[str, Estimate]:
        """The reported statistics, each with its 95% interval."""
        shots = np.array(self.shots, dtype=np.float64)
        n = len(self.shots)
        out = {
            "pots_per_shot": ratio_ci(np.array(self.pots), shots),
            "clean_pot_rate": ratio_ci(np.array(self.clean), shots, bounds=(0.0, 1.0)),
            "scratch_rate": ratio_ci(np.array(self.scratches), shots, bounds=(0.0, 1.0)),
            "pots_per_turn": ratio_ci(np.array(self.pots), np.array(self.turns)),
            "clear_rate": wilson(float(sum(self.cleared)), n),
            "run_out_rate": wilson(float(sum(self.run_out)), n),
            "episode_reward": mean_ci(np.array(self.rewards)),
            "shots_per_episode": mean_ci(shots),
        }
        if self.fouls:
            out["fouls_per_shot"] = ratio_ci(np.array(self.fouls), shots, bounds=(0.0, 1.0))
        return out
