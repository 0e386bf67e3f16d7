"""Colours, sizes and the bitmap digits the frames are drawn with."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

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

#: The cue stick, tip to butt: chalked tip, ferrule, maple shaft, dark butt.
CUE_TIP = np.array((40, 90, 200), dtype=np.uint8)
CUE_FERRULE = np.array((240, 240, 228), dtype=np.uint8)
CUE_SHAFT = np.array((222, 190, 135), dtype=np.uint8)
CUE_BUTT = np.array((58, 28, 14), dtype=np.uint8)
#: The tip marker: a dark backing, the ball face, the miscue ring and the chalk dot.
MARKER_BACK = np.array((25, 25, 25), dtype=np.float64)
MARKER_RING = np.array((150, 150, 140), dtype=np.float64)
MARKER_DOT = np.array((30, 80, 210), dtype=np.float64)

RAIL = 0.09  # rail width drawn around the playing surface (m)

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


def glyph(number: int, scale: int) -> NDArray[np.bool_]:
    """The digits of ``number`` as a boolean bitmap (1 px between digits), scaled up."""
    rows = ["0".join(_DIGITS[d][r] for d in str(number)) for r in range(5)]
    bitmap = np.array([[c == "1" for c in row] for row in rows])
    return np.kron(bitmap, np.ones((scale, scale), dtype=bool)).astype(bool)


def ball_colour(number: int) -> NDArray[np.float64]:
    """The colour of ball ``number`` (a stripe has its solid's colour)."""
    return BALL_COLOURS[(number - 1) % 8 + 1] if number > 0 else BALL_COLOURS[0]
