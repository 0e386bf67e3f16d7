"""RecordShots: Gymnasium's ``RecordVideo`` keeping every frame of ``rgb_array_list``.

Gymnasium's ``RecordVideo`` (1.2.2, and 1.4.0 alike) captures one frame per ``step()``:
from a list render mode it keeps the last frame only, so a pool shot (one step) shows up as
a single picture. :class:`RecordShots` is ``RecordVideo`` with that one method changed: it
keeps the whole list, so the video shows each shot: the cue stick at its aim for a moment
(with the tip marker on the spin level), then the balls moving (at least 20 frames a shot
with ``PoolEnv``'s ``rgb_array_list``, sampled from the exact trajectories at 30 fps).
Triggers, file names, ``video_length`` and ``close()`` are ``RecordVideo``'s.
"""

from __future__ import annotations

from typing import Any

import gymnasium as gym
from gymnasium.wrappers import RecordVideo

from pool_env.extras import require


class RecordShots(RecordVideo):
    """Record videos of episodes, every frame of every shot (``render_mode="rgb_array_list"``).

    Args:
        env: An environment made with ``render_mode="rgb_array_list"``.
        video_folder: Where the ``.mp4`` files go.
        **kwargs: ``RecordVideo``'s (``episode_trigger``, ``name_prefix``, ``fps``, ...).

    Raises:
        ValueError: If ``env`` renders in another mode.
        gymnasium.error.DependencyNotInstalled: Without moviepy (the ``render`` extra).
    """

    def __init__(self, env: gym.Env, video_folder: str, **kwargs: Any) -> None:
        require("moviepy", "render", "RecordShots", gym.error.DependencyNotInstalled)
        super().__init__(env, video_folder, **kwargs)  # first: its __del__ needs its state
        if env.render_mode != "rgb_array_list":
            raise ValueError(
                "RecordShots needs an env made with render_mode='rgb_array_list', got "
                f"{env.render_mode!r} (use gymnasium's RecordVideo for 'rgb_array')"
            )

    def _capture_frame(self) -> None:
        """Append every frame rendered since the last capture (RecordVideo: the last one)."""
        frames = self.env.render()
        if not isinstance(frames, list):
            raise TypeError(f"rgb_array_list render() returned {type(frames).__name__}")
        self.recorded_frames.extend(frames)
