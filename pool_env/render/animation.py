"""Shot animations: frames sampled from the exact trajectories, and GIF/MP4 files."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from pool_env.extras import require
from pool_env.render.canvas import Renderer
from pool_env.render.cue import strike_frames
from pool_env.render.palette import Frame
from pool_env.render.paths import frame_times
from pool_env.sim.result import ShotResult


def shot_frames(
    renderer: Renderer,
    shot: ShotResult,
    balls: NDArray[np.int64],
    fps: int = 30,
    speed: float = 1.0,
    max_seconds: float = 8.0,
    min_frames: int = 2,
    strike: Any = None,
) -> list[Frame]:
    """Sample a recorded shot into animation frames, from the strike until all rest.

    With ``strike``, the frames start with the lead-in of
    :func:`~pool_env.render.cue.strike_frames` (the cue stick at the aim, drawn back then
    stroking to the ball, and on the spin level the tip marker). Then shot frame ``k`` of
    ``n`` shows the balls at ``positions_at(k * duration / (n - 1))``, the exact
    trajectories (a sliding ball's curve included), with the balls potted by then gone.

    Args:
        renderer: The renderer.
        shot: A shot simulated with ``record=True``.
        balls: Ball numbers of the shot's rows.
        fps: Frames per second of playback.
        speed: Playback speed (1 is real time).
        max_seconds: A longer shot is sped up to fit in this playback time.
        min_frames: At least this many shot frames (a shorter shot is slowed down).
        strike: ``(angle, speed, tip_side, tip_vertical)`` as executed (``PoolEnv.
            last_strike``), or None for no lead-in.

    Returns:
        The frames: the lead-in if any, then at least ``max(2, min_frames)`` of the shot.

    Raises:
        ValueError: If the shot was not recorded, on a non-positive ``fps``, ``speed`` or
            ``max_seconds``, or on a bad ``strike``.
    """
    if not shot.recorded:
        raise ValueError("the shot was simulated with record=False: no trajectories to animate")
    times = frame_times(shot.duration, fps, speed, max_seconds, min_frames)
    balls = np.asarray(balls)
    frames = []
    if strike is not None:
        frames += strike_frames(renderer, shot.positions_at(0.0), ~shot.pocketed_at(0.0), balls,
                                strike, fps)  # fmt: skip
    for t in times:
        visible = ~shot.pocketed_at(float(t))
        frames.append(renderer.frame(shot.positions_at(float(t)), visible, balls))
    return frames


#: The files :func:`save_animation` writes, by suffix (any case).
ANIMATION_SUFFIXES = (".gif", ".mp4")


def animation_suffix(path: str | os.PathLike[str]) -> str:
    """The suffix of an animation file, lower case: ``".gif"`` or ``".mp4"``.

    A command that writes one checks its path with this before it plays anything.

    Raises:
        ValueError: On another suffix, naming the path as given.
    """
    suffix = Path(path).suffix.lower()
    if suffix not in ANIMATION_SUFFIXES:
        raise ValueError(f"save an animation as .gif or .mp4, got {str(path)!r}")
    return suffix


def save_animation(frames: list[Frame], path: str | os.PathLike[str], fps: int = 30) -> None:
    """Write frames as an animated GIF (``.gif``) or an MP4 video (``.mp4``).

    A GIF keeps a run of identical frames as one frame shown as long (Pillow merges them),
    so its frame count can be below ``len(frames)``; its playing time is theirs.

    Raises:
        ValueError: On another file suffix (:func:`animation_suffix`) or no frames.
        gymnasium.error.DependencyNotInstalled: Without imageio (the ``render`` extra), or
            without ``imageio-ffmpeg`` (which the extra's moviepy brings) for MP4.
    """
    from gymnasium.error import DependencyNotInstalled

    suffix = animation_suffix(path)
    if not frames:
        raise ValueError("no frames to save")
    iio = require("imageio.v3", "render", "saving animations", DependencyNotInstalled)
    if suffix == ".gif":
        iio.imwrite(path, np.stack(frames), duration=1000.0 / fps, loop=0)
        return
    require("imageio_ffmpeg", "render", "saving MP4", DependencyNotInstalled)
    iio.imwrite(path, np.stack(frames), fps=fps, codec="libx264", plugin="FFMPEG")
