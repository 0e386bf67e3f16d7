"""Where the balls go: the shot's paths as polylines and the times animation frames sample.

On the roll level every ball moves on a straight line between events, so its positions at
the event times are the exact corners of its path. On the spin level a sliding ball follows
a parabola between events (``p + v t + a t^2 / 2``: a draw shot's cue ball bending after the
hit, a masse curve), so its path is also sampled between the events, densely enough that the
polyline stays within a fraction of a pixel of the curve.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from pool_env.sim.result import ShotResult, SpinShotResult

#: Spin level: the longest time step between trail samples (s). A sliding ball's
#: acceleration is at most ``mu_slide g`` (about 2 m/s^2), so a chord of ``h`` seconds
#: leaves the parabola by at most ``a h^2 / 8``: 0.1 mm at 0.02 s, well under a pixel.
CURVE_STEP = 0.02
#: At most this many trail samples a shot (a pathological shot: dense is enough to look at).
MAX_TRAIL_SAMPLES = 2000

Trail = tuple[int, NDArray[np.float64]]


def trail_times(shot: ShotResult) -> NDArray[np.float64]:
    """The times the shot's paths are sampled at: every event, and between them on a curve.

    Args:
        shot: A shot simulated with ``record=True``.

    Returns:
        Sorted unique times in ``[0, duration]``, from 0 to the duration.
    """
    times = [np.array([0.0, shot.duration]), shot.event_times]
    if isinstance(shot, SpinShotResult):  # sliding paths bend between events
        n = max(2, math.ceil(shot.duration / CURVE_STEP) + 1)
        times.append(np.linspace(0.0, shot.duration, n))
    out = np.unique(np.concatenate(times))
    out = out[(out >= 0.0) & (out <= shot.duration)]
    if out.shape[0] > MAX_TRAIL_SAMPLES:
        out = np.linspace(0.0, shot.duration, MAX_TRAIL_SAMPLES)
    return out


def trails(shot: ShotResult, balls: NDArray[np.int64]) -> list[Trail]:
    """Paths of the balls that moved in ``shot``: ``(ball number, (T, 2) polyline)``.

    Each vertex is the ball's exact position (``positions_at``) at a time of
    :func:`trail_times`.

    Args:
        shot: A shot simulated with ``record=True``.
        balls: Ball numbers of the shot's rows.

    Returns:
        One ``(number, polyline)`` per ball that moved, in row order.
    """
    path = np.stack([shot.positions_at(float(t)) for t in trail_times(shot)])  # (T, M, 2)
    moved = np.any(np.abs(path - path[:1]) > 1e-9, axis=(0, 2))
    return [(int(balls[k]), path[:, k].copy()) for k in np.flatnonzero(moved)]


def frame_times(
    duration: float, fps: int, speed: float, max_seconds: float, min_frames: int
) -> NDArray[np.float64]:
    """Shot times of the animation frames, from the strike (0) to the rest (``duration``).

    Args:
        duration: The shot's duration (s).
        fps: Frames per second of playback.
        speed: Playback speed (1 is real time).
        max_seconds: A longer shot is sped up to fit in this playback time.
        min_frames: At least this many frames (a shorter shot is slowed down).

    Returns:
        ``n >= max(2, min_frames)`` evenly spaced times.

    Raises:
        ValueError: On a non-positive ``fps``, ``speed`` or ``max_seconds``.
    """
    if not (fps > 0 and speed > 0 and max_seconds > 0):
        raise ValueError(
            f"fps, speed and max_seconds must be positive, got {fps}, {speed}, {max_seconds}"
        )
    rate = max(float(speed), duration / float(max_seconds))  # shot seconds per second
    n = max(2, int(min_frames), math.ceil(duration / rate * fps) + 1)
    return np.linspace(0.0, duration, n)
