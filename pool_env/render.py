"""Rendering: top-down frames drawn with numpy, a pygame window, and shot animations.

Frames need numpy only, so ``rgb_array`` and ``rgb_array_list`` work headless and without
the ``render`` extra. pygame (the window) and imageio (GIF/MP4 files) are imported only
when used, and pygame's display only when a window is asked for.

Render modes and their frame rates (:data:`RENDER_FPS`, the env's ``metadata["render_fps"]``):
``rgb_array`` gives one frame per shot (the balls at rest with the shot's trails) and plays
at 2 fps; ``rgb_array_list`` gives every frame since the last ``render()`` call: the layout
at reset, then each shot sampled from its exact trajectories (:func:`shot_frames` with
:data:`LIST_PLAYBACK`) at 30 fps; ``human`` animates each shot in a window at 30 fps.
"""

from __future__ import annotations

import math
import os
import sys
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from pool_env.sim.pockets import PocketJaws
from pool_env.sim.result import ShotResult
from pool_env.sim.table import Table

Frame = NDArray[np.uint8]

#: Ball colours by number (0 is the cue ball); 9-15 are the stripes of 1-7.
BALL_COLOURS = np.array(
    [
        (245, 245, 235),  # cue
        (250, 200, 20),  # 1 yellow
        (20, 60, 200),  # 2 blue
        (215, 30, 30),  # 3 red
        (100, 40, 150),  # 4 purple
        (245, 120, 20),  # 5 orange
        (20, 140, 60),  # 6 green
        (130, 25, 35),  # 7 maroon
        (15, 15, 15),  # 8 black
    ],
    dtype=np.float64,
)
CLOTH = np.array((28, 110, 62), dtype=np.uint8)
CUSHION = np.array((20, 85, 46), dtype=np.uint8)
WOOD = np.array((92, 52, 24), dtype=np.uint8)
POCKET = np.array((12, 12, 12), dtype=np.uint8)
SIGHT = np.array((235, 225, 200), dtype=np.uint8)
WHITE = np.array((250, 250, 245), dtype=np.float64)

RAIL = 0.09  # rail width drawn around the playing surface (m)

#: ``metadata["render_fps"]`` of each render mode (``RecordVideo`` plays at this rate).
RENDER_FPS = {"rgb_array": 2, "rgb_array_list": 30, "human": 30}

#: How ``rgb_array_list`` samples a shot: at twice real time, at most 4 s of playback (a
#: 20 s shot at 800 px would otherwise hold 600 MB of frames), at least 20 frames (a
#: shot shorter than 0.7 s is slowed down). The frames are the exact trajectories.
LIST_PLAYBACK = {"speed": 2.0, "max_seconds": 4.0, "min_frames": 20}

# 3x5 bitmap digits, one string per row.
_DIGITS = {
    "0": ("111", "101", "101", "101", "111"),
    "1": ("010", "110", "010", "010", "111"),
    "2": ("111", "001", "111", "100", "111"),
    "3": ("111", "001", "011", "001", "111"),
    "4": ("101", "101", "111", "001", "001"),
    "5": ("111", "100", "111", "001", "111"),
    "6": ("111", "100", "111", "101", "111"),
    "7": ("111", "001", "010", "010", "010"),
    "8": ("111", "101", "111", "101", "111"),
    "9": ("111", "101", "111", "001", "111"),
}


def _glyph(number: int, scale: int) -> NDArray[np.bool_]:
    """The digits of ``number`` as a boolean bitmap (1 px between digits), scaled up."""
    rows = ["0".join(_DIGITS[d][r] for d in str(number)) for r in range(5)]
    bitmap = np.array([[c == "1" for c in row] for row in rows])
    return np.kron(bitmap, np.ones((scale, scale), dtype=bool)).astype(bool)


class Renderer:
    """Draws a table and its balls as ``(H, W, 3)`` uint8 frames.

    Args:
        table: The table.
        width: Frame width in pixels (rounded up to a multiple of 16, as video codecs like).
    """

    def __init__(self, table: Table, width: int = 800) -> None:
        self.table = table
        w = int(math.ceil(width / 16.0) * 16)
        self.scale = w / (table.length + 2.0 * RAIL)  # pixels per metre
        h = int(math.ceil((table.width + 2.0 * RAIL) * self.scale / 16.0) * 16)
        self.size = (w, h)
        self._oy = (h - table.width * self.scale) / 2.0  # bottom margin, px
        self._ox = RAIL * self.scale
        self.ball_px = table.ball_radius * self.scale
        self._digit = max(1, round(self.ball_px / 9.0))
        self._glyphs = {k: _glyph(k, self._digit) for k in range(1, 16)}
        self.background = self._draw_table()

    def to_pixels(self, xy: NDArray[np.float64]) -> NDArray[np.float64]:
        """Table coordinates (m) to ``(column, row)`` pixel coordinates (y up on screen)."""
        xy = np.asarray(xy, dtype=np.float64)
        col = self._ox + xy[..., 0] * self.scale
        row = self.size[1] - (self._oy + xy[..., 1] * self.scale)
        return np.stack([col, row], axis=-1)

    def _draw_table(self) -> Frame:
        w, h = self.size
        t = self.table
        img = np.empty((h, w, 3), dtype=np.uint8)
        img[:] = WOOD
        (c0, r1), (c1, r0) = self.to_pixels(np.array([[0.0, 0.0], [t.length, t.width]]))
        band = 0.02 * self.scale  # cushion rubber, inside the wood
        img[int(r0 - band) : math.ceil(r1 + band), int(c0 - band) : math.ceil(c1 + band)] = CUSHION
        img[round(r0) : round(r1), round(c0) : round(c1)] = CLOTH
        # Sights: diamonds every eighth of the length and quarter of the width, on the wood.
        sight_r = max(1.5, 0.008 * self.scale)
        mid = 0.5 * RAIL + 0.01
        for k in range(1, 8):
            if k != 4:
                for y in (-mid, t.width + mid):
                    self._disc(img, np.array([k * t.length / 8.0, y]), sight_r / self.scale, SIGHT)
        for k in (1, 2, 3):
            for x in (-mid, t.length + mid):
                self._disc(img, np.array([x, k * t.width / 4.0]), sight_r / self.scale, SIGHT)
        # Head string and foot spot, faint.
        hx = self.to_pixels(np.array([t.length / 4.0, 0.0]))[0]
        img[round(r0) : round(r1), int(hx)] = (CLOTH * 0.8 + 255 * 0.2).astype(np.uint8)
        self._disc(img, np.array([0.75 * t.length, t.width / 2.0]), 1.5 / self.scale, SIGHT)
        if t.jaws:
            for jaw in t.jaws:
                self._draw_jaw(img, jaw)
        else:
            for px, py, pr in t.pockets:
                self._disc(img, np.array([px, py]), pr, POCKET)
        return img

    def _draw_jaw(self, img: Frame, jaw: PocketJaws) -> None:
        """Draw one real pocket opening.

        The throat between the facings is cloth up to the fall line (the shelf) and the hole
        behind it; the round points are cushion.
        """
        corners = np.array(
            [jaw.points[0], jaw.facings[0][1], jaw.facings[1][1], jaw.points[1]]
        )  # a convex quadrilateral: the mouth, the two facings and their inner ends
        # The rails stop at the points: cloth across the throat, then the hole behind the
        # fall line.
        self._fill(img, corners, CLOTH, None)
        self._fill(img, corners, POCKET, (jaw.fall_line[0], jaw.fall_normal))
        for side in range(2):
            self._disc(img, jaw.tip_centres[side], jaw.tip_radius + 0.5 / self.scale, CUSHION)

    def _fill(
        self,
        img: Frame,
        polygon: NDArray[np.float64],
        colour: NDArray[Any],
        behind: tuple[NDArray[np.float64], NDArray[np.float64]] | None,
    ) -> None:
        """Paint the pixels inside a convex ``polygon`` (m).

        With ``behind = (point, normal)``, only those behind that line (``(p - point) .
        normal <= 0``).
        """
        px = self.to_pixels(polygon)
        c0, c1 = max(int(px[:, 0].min()) - 1, 0), min(int(px[:, 0].max()) + 2, img.shape[1])
        r0, r1 = max(int(px[:, 1].min()) - 1, 0), min(int(px[:, 1].max()) + 2, img.shape[0])
        if r0 >= r1 or c0 >= c1:
            return
        rows, cols = np.mgrid[r0:r1, c0:c1]
        x = (cols + 0.5 - self._ox) / self.scale
        y = (self.size[1] - (rows + 0.5) - self._oy) / self.scale
        inside = np.ones(x.shape, dtype=bool)
        centre = polygon.mean(axis=0)
        for k in range(len(polygon)):
            a, b = polygon[k], polygon[(k + 1) % len(polygon)]
            normal = np.array([a[1] - b[1], b[0] - a[0]])
            if normal @ (centre - a) < 0:
                normal = -normal  # pointing inside
            inside &= (x - a[0]) * normal[0] + (y - a[1]) * normal[1] >= 0
        if behind is not None:
            point, normal = behind
            inside &= (x - point[0]) * normal[0] + (y - point[1]) * normal[1] <= 0
        img[r0:r1, c0:c1][inside] = colour

    def _disc(
        self, img: Frame, centre: NDArray[np.float64], radius: float, colour: NDArray[Any]
    ) -> None:
        """Blend an anti-aliased disc of ``radius`` metres at ``centre`` into ``img``."""
        (cx, cy), rp = self.to_pixels(centre), radius * self.scale
        r0, r1 = max(int(cy - rp - 1), 0), min(int(cy + rp + 2), img.shape[0])
        c0, c1 = max(int(cx - rp - 1), 0), min(int(cx + rp + 2), img.shape[1])
        if r0 >= r1 or c0 >= c1:
            return
        yy, xx = np.mgrid[r0:r1, c0:c1]
        d = np.hypot(xx + 0.5 - cx, yy + 0.5 - cy)
        alpha = np.clip(rp + 0.5 - d, 0.0, 1.0)[..., None]
        patch = img[r0:r1, c0:c1]
        patch[:] = (patch * (1.0 - alpha) + np.asarray(colour, dtype=np.float64) * alpha).astype(
            np.uint8
        )

    def _ball(self, img: Frame, centre: NDArray[np.float64], number: int) -> None:
        """Draw ball ``number``: solid (1-8), striped (9-15) or the cue (0), with its number."""
        cx, cy = self.to_pixels(centre)
        rp = self.ball_px
        r0, r1 = max(int(cy - rp - 1), 0), min(int(cy + rp + 2), img.shape[0])
        c0, c1 = max(int(cx - rp - 1), 0), min(int(cx + rp + 2), img.shape[1])
        yy, xx = np.mgrid[r0:r1, c0:c1]
        dx, dy = xx + 0.5 - cx, yy + 0.5 - cy
        d = np.hypot(dx, dy)
        base = BALL_COLOURS[(number - 1) % 8 + 1] if number > 0 else BALL_COLOURS[0]
        colour = np.broadcast_to(base, (*d.shape, 3)).copy()
        if number > 8:  # stripe: white caps above and below a coloured band
            colour[np.abs(dy) > 0.55 * rp] = WHITE
        if number > 0:
            colour[d < 0.52 * rp] = WHITE
        # A soft highlight up-left and a darker rim give the balls some volume.
        shade = 1.0 - 0.25 * np.clip((d / max(rp, 1e-9)) ** 2, 0.0, 1.0)
        colour *= shade[..., None]
        alpha = np.clip(rp + 0.5 - d, 0.0, 1.0)[..., None]
        patch = img[r0:r1, c0:c1]
        patch[:] = (patch * (1.0 - alpha) + colour * alpha).astype(np.uint8)
        if number > 0:
            glyph = self._glyphs[number]
            gr = round(cy - glyph.shape[0] / 2.0)
            gc = round(cx - glyph.shape[1] / 2.0)
            rows, cols = np.nonzero(glyph)
            rows, cols = rows + gr, cols + gc
            keep = (rows >= 0) & (rows < img.shape[0]) & (cols >= 0) & (cols < img.shape[1])
            img[rows[keep], cols[keep]] = (20, 20, 20)

    def trails(
        self, shot: ShotResult, balls: NDArray[np.int64]
    ) -> list[tuple[int, NDArray[np.float64]]]:
        """Paths of the balls that moved in ``shot``: ``(ball number, (T, 2) polyline)``.

        Between events every ball moves on a straight line, so its positions at the event
        times are the exact corners of its path.
        """
        times = np.unique(np.concatenate([[0.0], shot.event_times, [shot.duration]]))
        times = times[(times >= 0.0) & (times <= shot.duration)]
        if times.shape[0] > 2000:  # a pathological shot: a dense sample is enough for a picture
            times = np.linspace(0.0, shot.duration, 2000)
        path = np.stack([shot.positions_at(float(t)) for t in times])  # (T, M, 2)
        moved = np.any(np.abs(path - path[:1]) > 1e-9, axis=(0, 2))
        return [(int(balls[k]), path[:, k]) for k in np.flatnonzero(moved)]

    def frame(
        self,
        positions: NDArray[np.float64],
        on_table: NDArray[np.bool_],
        numbers: NDArray[np.int64] | None = None,
        trails: list[tuple[int, NDArray[np.float64]]] | None = None,
    ) -> Frame:
        """Draw a frame.

        Args:
            positions: ``(M, 2)`` ball centres (m).
            on_table: ``(M,)`` which balls to draw.
            numbers: ``(M,)`` ball numbers (colours and labels); ``0..M-1`` by default.
            trails: ``(ball number, (T, 2) polyline)`` paths to draw under the balls.

        Returns:
            The ``(H, W, 3)`` uint8 frame.
        """
        img = self.background.copy()
        for number, line in trails or ():
            self._polyline(img, line, number)
            self._ring(img, line[0], number)  # where the ball started
        numbers = np.arange(len(positions)) if numbers is None else numbers
        for k in np.flatnonzero(on_table):
            self._ball(img, positions[k], int(numbers[k]))
        return img

    def _ring(self, img: Frame, centre: NDArray[np.float64], number: int) -> None:
        """Blend a thin ball-sized circle outline at ``centre`` (m), half transparent."""
        (cx, cy), rp = self.to_pixels(centre), self.ball_px
        r0, r1 = max(int(cy - rp - 2), 0), min(int(cy + rp + 3), img.shape[0])
        c0, c1 = max(int(cx - rp - 2), 0), min(int(cx + rp + 3), img.shape[1])
        yy, xx = np.mgrid[r0:r1, c0:c1]
        d = np.hypot(xx + 0.5 - cx, yy + 0.5 - cy)
        alpha = (0.55 * np.clip(1.0 - np.abs(d - rp + 0.5), 0.0, 1.0))[..., None]
        colour = BALL_COLOURS[(number - 1) % 8 + 1] if number > 0 else BALL_COLOURS[0]
        patch = img[r0:r1, c0:c1]
        patch[:] = (patch * (1.0 - alpha) + colour * alpha).astype(np.uint8)

    def _polyline(self, img: Frame, line: NDArray[np.float64], number: int) -> None:
        """Blend a 2 px line along ``line`` (m) in the ball's colour, half transparent."""
        px = self.to_pixels(line)
        seg = np.diff(px, axis=0)
        steps = np.maximum(np.ceil(np.hypot(seg[:, 0], seg[:, 1]) * 2.0), 1).astype(np.int64)
        owner = np.repeat(np.arange(seg.shape[0]), steps)
        frac = (np.arange(owner.shape[0]) - np.repeat(np.cumsum(steps) - steps, steps)) / steps[
            owner
        ]
        pts = px[owner] + seg[owner] * frac[:, None]
        pts = np.concatenate([pts, px[-1:]])
        cols = np.concatenate([pts[:, 0] + dc for dc in (-0.5, 0.5, -0.5, 0.5)]).astype(np.int64)
        rows = np.concatenate([pts[:, 1] + dr for dr in (-0.5, -0.5, 0.5, 0.5)]).astype(np.int64)
        keep = (rows >= 0) & (rows < img.shape[0]) & (cols >= 0) & (cols < img.shape[1])
        rows, cols = rows[keep], cols[keep]
        colour = BALL_COLOURS[(number - 1) % 8 + 1] if number > 0 else BALL_COLOURS[0]
        img[rows, cols] = (img[rows, cols] * 0.45 + colour * 0.55).astype(np.uint8)


def shot_frames(
    renderer: Renderer,
    shot: ShotResult,
    balls: NDArray[np.int64],
    fps: int = 30,
    speed: float = 1.0,
    max_seconds: float = 8.0,
    min_frames: int = 2,
) -> list[Frame]:
    """Sample a recorded shot into animation frames, from the strike until all rest.

    Frame ``k`` of ``n`` shows the balls at ``positions_at(k * duration / (n - 1))``, the
    exact trajectories, with the balls potted by then gone.

    Args:
        renderer: The renderer.
        shot: A shot simulated with ``record=True``.
        balls: Ball numbers of the shot's rows.
        fps: Frames per second of playback.
        speed: Playback speed (1 is real time).
        max_seconds: A longer shot is sped up to fit in this playback time.
        min_frames: At least this many frames (a shorter shot is slowed down).

    Returns:
        The frames (at least ``max(2, min_frames)``: the strike, ..., the rest).

    Raises:
        ValueError: If the shot was not recorded, or on a non-positive ``fps``, ``speed`` or
            ``max_seconds``.
    """
    if not shot.recorded:
        raise ValueError("the shot was simulated with record=False: no trajectories to animate")
    if not (fps > 0 and speed > 0 and max_seconds > 0):
        raise ValueError(
            f"fps, speed and max_seconds must be positive, got {fps}, {speed}, {max_seconds}"
        )
    rate = max(float(speed), shot.duration / float(max_seconds))  # shot seconds per second
    n = max(2, int(min_frames), math.ceil(shot.duration / rate * fps) + 1)
    balls = np.asarray(balls)
    frames = []
    for t in np.linspace(0.0, shot.duration, n):
        visible = ~shot.pocketed_at(float(t))
        frames.append(renderer.frame(shot.positions_at(float(t)), visible, balls))
    return frames


def save_animation(frames: list[Frame], path: str | os.PathLike[str], fps: int = 30) -> None:
    """Write frames as an animated GIF (``.gif``) or an MP4 video (``.mp4``).

    Raises:
        ValueError: On another file suffix or no frames.
        gymnasium.error.DependencyNotInstalled: Without imageio (the ``render`` extra), or
            without ``imageio-ffmpeg`` for MP4.
    """
    from gymnasium.error import DependencyNotInstalled

    suffix = Path(path).suffix.lower()
    if suffix not in (".gif", ".mp4"):
        raise ValueError(f"save an animation as .gif or .mp4, got {str(path)!r}")
    if not frames:
        raise ValueError("no frames to save")
    try:
        import imageio.v3 as iio
    except ImportError:
        raise DependencyNotInstalled(
            'saving animations needs imageio: pip install "pool_env[render]"'
        ) from None
    if suffix == ".gif":
        iio.imwrite(path, np.stack(frames), duration=1000.0 / fps, loop=0)
        return
    try:
        import imageio_ffmpeg  # noqa: F401
    except ImportError:
        raise DependencyNotInstalled(
            "saving MP4 needs imageio-ffmpeg: pip install imageio-ffmpeg"
        ) from None
    iio.imwrite(path, np.stack(frames), fps=fps, codec="libx264", plugin="FFMPEG")


def has_display() -> bool:
    """Whether a window can be shown: on Linux and BSD, an X11 or Wayland display is set."""
    if not sys.platform.startswith(("linux", "freebsd", "openbsd", "netbsd")):
        return True  # macOS and Windows always have their own display
    return bool(os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"))


class Window:
    """A pygame window that shows frames (``render_mode="human"``).

    On a machine without a display (no ``DISPLAY`` / ``WAYLAND_DISPLAY``, e.g. a headless
    server or CI running ``check_env``) and no ``SDL_VIDEODRIVER`` chosen, the window is
    drawn off screen (SDL's ``dummy`` driver) instead of SDL printing display errors such
    as ``XDG_RUNTIME_DIR is invalid``; ``rgb_array_list`` gives the frames there.

    Raises:
        gymnasium.error.DependencyNotInstalled: Without pygame (the ``render`` extra).
    """

    def __init__(self, size: tuple[int, int], title: str = "pool_env") -> None:
        from gymnasium.error import DependencyNotInstalled

        os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")
        try:
            import pygame
        except ImportError:
            raise DependencyNotInstalled(
                'render_mode="human" needs pygame: pip install "pool_env[render]"'
            ) from None
        if "SDL_VIDEODRIVER" not in os.environ and not has_display():
            # Silently: check_env opens every render mode and must pass without warnings.
            os.environ["SDL_VIDEODRIVER"] = "dummy"  # read by SDL at display.init()
        self._pg = pygame
        pygame.display.init()
        pygame.display.set_caption(title)
        self.screen = pygame.display.set_mode(size)
        self.clock = pygame.time.Clock()

    def show(self, frame: Frame) -> None:
        """Display one frame and keep the window responsive."""
        pg = self._pg
        pg.event.pump()
        surface = pg.surfarray.make_surface(np.ascontiguousarray(frame.swapaxes(0, 1)))
        self.screen.blit(surface, (0, 0))
        pg.display.flip()

    def play(self, frames: list[Frame], fps: int = 30) -> None:
        """Show frames at ``fps``."""
        for frame in frames:
            self.show(frame)
            self.clock.tick(fps)

    def close(self) -> None:
        """Close the window."""
        self._pg.display.quit()
