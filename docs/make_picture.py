"""Draw ``docs/shot.png``: a cut shot on four object balls, with the paths it left.

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


def main() -> None:
    """Aim with the ghost ball, play the shot, save the frame with its trails."""
    env = PoolEnv(scene=LAYOUT, aim="cut", render_mode="rgb_array", render_width=800)
    env.reset(seed=0)
    table = env.table
    cue, ball = LAYOUT[0], LAYOUT[1]
    pocket = np.array([table.length, table.width])
    to_pocket = (pocket - ball) / np.linalg.norm(pocket - ball)
    ghost = ball - 2 * table.ball_radius * to_pocket  # where the cue ball must be at contact
    aim = ghost - cue
    line = ball - cue
    # Offset of the cue ball's path from ball 1's centre, in ball diameters (+ = left side).
    offset = (aim[0] * line[1] - aim[1] * line[0]) / np.linalg.norm(aim) / (2 * table.ball_radius)
    speed = 2 * (SPEED - env.speed_range[0]) / (env.speed_range[1] - env.speed_range[0]) - 1
    _, reward, *_, info = env.step(np.array([-offset, speed]))
    print(
        f"reward {reward}, potted {info['potted']}, cut {math.degrees(math.asin(offset)):.1f} deg"
    )
    out = Path(__file__).with_name("shot.png")
    iio.imwrite(out, env.render(), optimize=True)
    print(f"wrote {out} ({out.stat().st_size / 1024:.0f} KB)")


if __name__ == "__main__":
    main()
