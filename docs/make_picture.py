"""Draw the docs' pictures with the project's renderer: ``shot.png``, ``shot.gif``, ``break.png``.

A cut shot on four object balls: ``shot.png`` is the frame with the paths the shot left,
``shot.gif`` the shot animated from its exact trajectories; ``break.png`` a 9-ball break
with its paths; all on the roll table (``model="roll"``), where they were drawn. They are
committed, so that the README and the docs pages show them on GitHub as on the site;
``tests/repo/test_docs_links.py`` checks that the PNGs are what today's renderer draws.

Run: ``python docs/make_picture.py``.
"""

from __future__ import annotations

import math
from pathlib import Path

import imageio.v3 as iio
import numpy as np

from pool_env import PoolEnv

# Cue ball, then balls 1-4. Ball 1 is the nearest: cut it into the top-right corner pocket.
LAYOUT = np.array([[1.45, 0.75], [2.0, 0.85], [0.7, 0.95], [2.1, 0.3], [1.0, 0.35]])
SPEED = 1.3  # m/s


def cut_shot_env(render_mode: str = "rgb_array", width: int = 800) -> PoolEnv:
    """The env after the cut shot: ghost-ball aim at ball 1, into the top-right corner."""
    env = PoolEnv(
        scene=LAYOUT, aim="cut", model="roll", render_mode=render_mode, render_width=width
    )
    env.reset(seed=0)
    table = env.config.table
    cue, ball = LAYOUT[0], LAYOUT[1]
    pocket = np.array([table.length, table.width])
    to_pocket = (pocket - ball) / np.linalg.norm(pocket - ball)
    ghost = ball - 2 * table.ball_radius * to_pocket  # where the cue ball must be at contact
    aim = ghost - cue
    line = ball - cue
    # Offset of the cue ball's path from ball 1's centre, in ball diameters (+ = left side).
    offset = (aim[0] * line[1] - aim[1] * line[0]) / np.linalg.norm(aim) / (2 * table.ball_radius)
    low, high = env.config.speed_range
    speed = 2 * (SPEED - low) / (high - low) - 1
    _, reward, *_, info = env.step(np.array([-offset, speed]))
    print(
        f"reward {reward}, potted {info['potted']}, cut {math.degrees(math.asin(offset)):.1f} deg"
    )
    return env


def break_env(width: int = 480) -> PoolEnv:
    """The env after a 9-ball break at 10 m/s from the head spot, full on the 1 ball.

    The rack in its fixed order (``rack_order="fixed"``), as the committed picture shows it.
    """
    env = PoolEnv(
        scene="nine_ball",
        game="nine",
        rack_order="fixed",
        model="roll",
        render_mode="rgb_array",
        render_width=width,
    )
    env.reset(seed=0)
    # Cue ball on the head spot (x = L/4, y = W/2), a full hit at the middle of 8-12 m/s.
    env.step(np.array([0.0, 0.0, 1.0, 0.0, 0.0, -1.0], dtype=np.float32))  # no push-out
    return env


def main() -> None:
    """Play the shot, save the frame with its trails and the animation."""
    here = Path(__file__).parent
    png = here / "shot.png"
    iio.imwrite(png, cut_shot_env().render(), optimize=True)
    gif = here / "shot.gif"
    cut_shot_env(width=480).save_shot(str(gif))
    rack = here / "break.png"
    iio.imwrite(rack, break_env(800).render(), optimize=True)
    for out in (png, gif, rack):
        print(f"wrote {out} ({out.stat().st_size / 1024:.0f} KB)")


if __name__ == "__main__":
    main()
