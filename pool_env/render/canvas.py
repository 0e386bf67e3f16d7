"""The renderer: a table and its balls drawn as ``(H, W, 3)`` uint8 frames with numpy."""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
from numpy.typing import NDArray

from pool_env.render.palette import (
    CLOTH,
    CUSHION,
    POCKET,
    RAIL,
    SIGHT,
    WHITE,
    WOOD,
    Frame,
    ball_colour,
    glyph,
)
from pool_env.sim.pockets import PocketJaws
from pool_env.sim.table import Table


def _blend(
    img: Frame,
    cx: float,
    cy: float,
    margin: float,
    colour: NDArray[Any],
    coverage: Callable[[NDArray[np.float64]], NDArray[np.float64]],
) -> None:
    """Blend ``colour`` into the pixels within ``margin`` px of ``(cx, cy)``.

    ``coverage`` maps each pixel centre's distance from ``(cx, cy)`` to its opacity.
    """
    r0, r1 = max(int(cy - margin), 0), min(int(cy + margin + 1), img.shape[0])
    c0, c1 = max(int(cx - margin), 0), min(int(cx + margin + 1), img.shape[1])
    if r0 >= r1 or c0 >= c1:
        return
    yy, xx = np.mgrid[r0:r1, c0:c1]
    alpha = coverage(np.hypot(xx + 0.5 - cx, yy + 0.5 - cy))[..., None]
    patch = img[r0:r1, c0:c1]
    patch[:] = (patch * (1.0 - alpha) + np.asarray(colour, dtype=np.float64) * alpha).astype(
        np.uint8
    )


def blend_disc(img: Frame, cx: float, cy: float, rp: float, colour: NDArray[Any]) -> None:
    """Blend an anti-aliased disc of radius ``rp`` px centred at pixel ``(cx, cy)``."""
    _blend(img, cx, cy, rp + 1, colour, lambda d: np.clip(rp + 0.5 - d, 0.0, 1.0))


def blend_ring(
    img: Frame, cx: float, cy: float, rp: float, colour: NDArray[Any], opacity: float
) -> None:
    """Blend a 1 px circle outline of radius ``rp`` px at pixel ``(cx, cy)``."""
    _blend(
        img, cx, cy, rp + 2, colour,
        lambda d: opacity * np.clip(1.0 - np.abs(d - rp + 0.5), 0.0, 1.0),
    )  # fmt: skip


def _rgb(name: str, value: Any) -> NDArray[np.float64]:
    """``value`` as one RGB triple of numbers in ``[0, 255]`` (``ValueError`` naming ``name``)."""
    try:
        arr = np.array(value, dtype=np.float64)
    except (TypeError, ValueError):
        arr = np.full(0, np.nan)
    if arr.shape != (3,) or not np.all((arr >= 0.0) & (arr <= 255.0)):
        raise ValueError(f"{name} must be an RGB triple of numbers in [0, 255], got {value!r}")
    return arr


class Renderer:
    """Draws a table and its balls as ``(H, W, 3)`` uint8 frames.

    Args:
        table: The table.
        width: Frame width in pixels (rounded up to a multiple of 16, as video codecs like).
        ball_colours: One RGB triple per ball number (a game's own balls, e.g. snooker's
            reds and colours): the balls are drawn plain in these colours, without numbers
            or stripes. ``None`` (default): pool balls by number (:data:`.BALL_COLOURS`).
        cloth: The cloth's RGB triple (the cushions a shade darker); ``None``: pool green.

    Raises:
        ValueError: A colour that is not an RGB triple in ``[0, 255]``, named.
    """

    def __init__(
        self,
        table: Table,
        width: int = 800,
        ball_colours: Any = None,
        cloth: Any = None,
    ) -> None:
        self.table = table
        self.ball_colours = (
            None
            if ball_colours is None
            else np.array([_rgb(f"ball_colours[{k}]", c) for k, c in enumerate(ball_colours)])
        )
        self.cloth = CLOTH if cloth is None else _rgb("cloth", cloth).astype(np.uint8)
        # The cushion rubber: the pool one, or a darker shade of the game's cloth.
        self.cushion = CUSHION if cloth is None else (self.cloth * 0.75).astype(np.uint8)
        w = int(math.ceil(width / 16.0) * 16)
        self.scale = w / (table.length + 2.0 * RAIL)  # pixels per metre
        h = int(math.ceil((table.width + 2.0 * RAIL) * self.scale / 16.0) * 16)
        self.size = (w, h)
        self._oy = (h - table.width * self.scale) / 2.0  # bottom margin, px
        self._ox = RAIL * self.scale
        self.ball_px = table.ball_radius * self.scale
        self._digit = max(1, round(self.ball_px / 9.0))
        self._glyphs = {k: glyph(k, self._digit) for k in range(1, 16)}
        self.background = self._draw_table()

    @classmethod
    def for_config(cls, config: Any, width: int = 800) -> Renderer:
        """The renderer of an env's config: its table in its game's colours.

        Reads the ruleset's ``ball_colours`` and ``cloth``
        (:class:`~pool_env.game.ruleset.Ruleset`; ``None``: the pool palette).

        Raises:
            ValueError: ``ball_colours`` with fewer triples than the game has balls, or a
                colour that is not an RGB triple, naming the ruleset.
        """
        ruleset = config.ruleset
        colours = getattr(ruleset, "ball_colours", None)
        if colours is not None and len(colours) < config.n_balls:
            raise ValueError(
                f"{ruleset!r}.ball_colours has {len(colours)} colours for "
                f"{config.n_balls} balls: give one RGB triple per ball"
            )
        try:
            return cls(config.table, width, colours, getattr(ruleset, "cloth", None))
        except ValueError as exc:
            raise ValueError(f"{ruleset!r}: {exc}") from None

    def colour_of(self, number: int) -> NDArray[np.float64]:
        """The colour ball ``number`` is drawn in (its game's, or pool's by number)."""
        if self.ball_colours is not None:
            return self.ball_colours[number]
        return ball_colour(number)

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
        cushion = self.cushion
        img[int(r0 - band) : math.ceil(r1 + band), int(c0 - band) : math.ceil(c1 + band)] = cushion
        img[round(r0) : round(r1), round(c0) : round(c1)] = self.cloth
        # Sights: diamonds every eighth of the length and quarter of the width, on the wood.
        sight_r = max(1.5, 0.008 * self.scale)
        mid = 0.5 * RAIL + 0.01
        for k in range(1, 8):
            if k != 4:
                for y in (-mid, t.width + mid):
                    self.disc(img, np.array([k * t.length / 8.0, y]), sight_r / self.scale, SIGHT)
        for k in (1, 2, 3):
            for x in (-mid, t.length + mid):
                self.disc(img, np.array([x, k * t.width / 4.0]), sight_r / self.scale, SIGHT)
        # Head string and foot spot, faint.
        hx = self.to_pixels(np.array([t.length / 4.0, 0.0]))[0]
        img[round(r0) : round(r1), int(hx)] = (self.cloth * 0.8 + 255 * 0.2).astype(np.uint8)
        self.disc(img, np.array([0.75 * t.length, t.width / 2.0]), 1.5 / self.scale, SIGHT)
        if t.jaws:
            for jaw in t.jaws:
                self._draw_jaw(img, jaw)
        else:
            for px, py, pr in t.pockets:
                self.disc(img, np.array([px, py]), pr, POCKET)
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
        self.fill(img, corners, self.cloth, None)
        self.fill(img, corners, POCKET, (jaw.fall_line[0], jaw.fall_normal))
        for side in range(2):
            self.disc(img, jaw.tip_centres[side], jaw.tip_radius + 0.5 / self.scale, self.cushion)

    def fill(
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

    def disc(
        self, img: Frame, centre: NDArray[np.float64], radius: float, colour: NDArray[Any]
    ) -> None:
        """Blend an anti-aliased disc of ``radius`` metres at ``centre`` into ``img``."""
        (cx, cy), rp = self.to_pixels(centre), radius * self.scale
        blend_disc(img, cx, cy, rp, colour)

    def _ball(self, img: Frame, centre: NDArray[np.float64], number: int) -> None:
        """Draw ball ``number``: solid (1-8), striped (9-15) or the cue (0), with its number.

        In a game's own colours (``ball_colours``) every ball is plain, without a number.
        """
        cx, cy = self.to_pixels(centre)
        rp = self.ball_px
        r0, r1 = max(int(cy - rp - 1), 0), min(int(cy + rp + 2), img.shape[0])
        c0, c1 = max(int(cx - rp - 1), 0), min(int(cx + rp + 2), img.shape[1])
        yy, xx = np.mgrid[r0:r1, c0:c1]
        dx, dy = xx + 0.5 - cx, yy + 0.5 - cy
        d = np.hypot(dx, dy)
        base = self.colour_of(number)
        colour = np.broadcast_to(base, (*d.shape, 3)).copy()
        pool = self.ball_colours is None  # pool balls carry their numbers
        if pool and number > 8:  # stripe: white caps above and below a coloured band
            colour[np.abs(dy) > 0.55 * rp] = WHITE
        if pool and number > 0:
            colour[d < 0.52 * rp] = WHITE
        # A soft highlight up-left and a darker rim give the balls some volume.
        shade = 1.0 - 0.25 * np.clip((d / max(rp, 1e-9)) ** 2, 0.0, 1.0)
        colour *= shade[..., None]
        alpha = np.clip(rp + 0.5 - d, 0.0, 1.0)[..., None]
        patch = img[r0:r1, c0:c1]
        patch[:] = (patch * (1.0 - alpha) + colour * alpha).astype(np.uint8)
        if pool and number > 0:
            glyph = self._glyphs[number]
            gr = round(cy - glyph.shape[0] / 2.0)
            gc = round(cx - glyph.shape[1] / 2.0)
            rows, cols = np.nonzero(glyph)
            rows, cols = rows + gr, cols + gc
            keep = (rows >= 0) & (rows < img.shape[0]) & (cols >= 0) & (cols < img.shape[1])
            img[rows[keep], cols[keep]] = (20, 20, 20)

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
        (cx, cy) = self.to_pixels(centre)
        blend_ring(img, cx, cy, self.ball_px, self.colour_of(number), 0.55)

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
        colour = self.colour_of(number)
        img[rows, cols] = (img[rows, cols] * 0.45 + colour * 0.55).astype(np.uint8)
