"""Rendering: top-down frames drawn with numpy, a pygame window, and shot animations.

Frames need numpy only, so ``rgb_array`` and ``rgb_array_list`` work headless and without
the ``render`` extra. pygame (the window) and imageio (GIF/MP4 files) are imported only
when used, and pygame's display only when a window is asked for.

Render modes and their frame rates (:data:`RENDER_FPS`, the env's ``metadata["render_fps"]``):
``rgb_array`` gives one frame per shot (the balls at rest with the shot's trails) and plays
at 2 fps; ``rgb_array_list`` gives every frame since the last ``render()`` call: the layout
at reset, then each shot, led in by the cue stick at its aim (and on the spin level the tip
marker), sampled from its exact trajectories (:func:`shot_frames` with
:data:`LIST_PLAYBACK`) at 30 fps; ``human`` animates each shot in a window at 30 fps.

Modules, one concern each: :mod:`.palette` (colours, digits), :mod:`.canvas` (the table and
balls), :mod:`.paths` (trails and frame times, curved paths sampled as they are),
:mod:`.cue` (the stick and the tip marker), :mod:`.animation` (shot frames, files),
:mod:`.window` (the pygame window).
"""

from pool_env.render.animation import (
    ANIMATION_SUFFIXES,
    animation_suffix,
    save_animation,
    shot_frames,
)
from pool_env.render.canvas import Renderer
from pool_env.render.cue import Strike, draw_cue, draw_tip_marker, strike_frames
from pool_env.render.palette import (
    BALL_COLOURS,
    CLOTH,
    CUSHION,
    POCKET,
    RAIL,
    SIGHT,
    WOOD,
    Frame,
)
from pool_env.render.paths import trail_times, trails
from pool_env.render.window import Window, has_display

#: ``metadata["render_fps"]`` of each render mode (``RecordVideo`` plays at this rate).
RENDER_FPS = {"rgb_array": 2, "rgb_array_list": 30, "human": 30}

#: How ``rgb_array_list`` samples a shot: at twice real time, at most 4 s of playback (a
#: 20 s shot at 800 px would otherwise hold 600 MB of frames), at least 20 frames (a
#: shot shorter than 0.7 s is slowed down). The frames are the exact trajectories.
LIST_PLAYBACK = {"speed": 2.0, "max_seconds": 4.0, "min_frames": 20}

__all__ = [
    "ANIMATION_SUFFIXES",
    "BALL_COLOURS",
    "CLOTH",
    "CUSHION",
    "LIST_PLAYBACK",
    "POCKET",
    "RAIL",
    "RENDER_FPS",
    "SIGHT",
    "WOOD",
    "Frame",
    "Renderer",
    "Strike",
    "Window",
    "animation_suffix",
    "draw_cue",
    "draw_tip_marker",
    "has_display",
    "save_animation",
    "shot_frames",
    "strike_frames",
    "trail_times",
    "trails",
]
