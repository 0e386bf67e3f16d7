"""The strike as a picture: the cue stick at its aim and a marker of where its tip hits.

Before a shot's first frame the animation shows the stick behind the cue ball along the aim,
drawn back and then stroking through to contact, and (on the spin level, where the tip is a
choice) a ball face in a corner of the frame with a dot where the tip meets the ball. Seen
from above, the stick is shifted sideways by the side offset, as a real cue is for english.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import NDArray

from pool_env.render.canvas import Renderer, blend_disc, blend_ring
from pool_env.render.palette import (
    BALL_COLOURS,
    CUE_BUTT,
    CUE_FERRULE,
    CUE_SHAFT,
    CUE_TIP,
    MARKER_BACK,
    MARKER_DOT,
    MARKER_RING,
    Frame,
)

#: The executed strike, as ``PoolEnv.last_strike``: ``(angle, speed, tip_side,
#: tip_vertical)``, the aim in radians from +x, the cue ball's speed (m/s) and the tip's
#: offsets from the ball's centre in fractions of its radius (+ right english, + follow).
Strike = tuple[float, float, float, float]

CUE_LENGTH = 1.2  # m drawn (a real cue is 1.47 m; the frame clips the butt anyway)
TIP_WIDTH = 0.013  # m, a 13 mm tip
BUTT_WIDTH = 0.03  # m
#: Stretches of the stick from its tip (m): chalked tip, ferrule, shaft, butt.
CUE_PARTS = ((0.0, 0.008, CUE_TIP), (0.008, 0.03, CUE_FERRULE), (0.03, 0.75, CUE_SHAFT),
             (0.75, CUE_LENGTH, CUE_BUTT))  # fmt: skip
#: Playback seconds of the lead-in: the stick held drawn back, then the stroke to contact.
LEAD_HOLD = 0.4
LEAD_STROKE = 0.2
#: The contact offset (fraction of R) beyond which real cues miscue: the marker's ring.
MISCUE_CONTACT = 0.5


def draw_back(speed: float) -> float:
    """How far (m) the tip stands off the ball before the stroke: longer for a harder shot."""
    return float(np.clip(0.03 + 0.025 * speed, 0.03, 0.3))


def check_strike(strike: Any) -> Strike:
    """``strike`` as four finite floats.

    Raises:
        ValueError: If it is not four finite numbers, or its speed is negative.
    """
    try:
        values = tuple(float(v) for v in strike)
    except (TypeError, ValueError):
        raise ValueError(
            f"strike must be (angle, speed, tip_side, tip_vertical), got {strike!r}"
        ) from None
    if len(values) != 4 or not all(math.isfinite(v) for v in values) or values[1] < 0.0:
        raise ValueError(
            "strike must be four finite numbers (angle, speed >= 0, tip_side, tip_vertical), "
            f"got {strike!r}"
        )
    return values  # type: ignore[return-value]


def draw_cue(
    renderer: Renderer,
    img: Frame,
    cue_ball: NDArray[np.float64],
    angle: float,
    tip_side: float,
    gap: float,
) -> None:
    """Paint the cue stick behind ``cue_ball`` along the aim ``angle``, in place.

    Args:
        renderer: The renderer (scale and table frame).
        img: The frame to paint.
        cue_ball: The cue ball's centre (m).
        angle: The aim (radians from +x).
        tip_side: Side offset (fraction of R, + right english): shifts the stick sideways.
        gap: Distance (m) from the tip to where it touches the ball (0: in contact).
    """
    r = renderer.table.ball_radius
    d = np.array([math.cos(angle), math.sin(angle)])
    left = np.array([-d[1], d[0]])
    side = min(abs(tip_side), 1.0)
    # The cue axis passes tip_side * R right of the centre; its tip meets the ball where the
    # ball's outline is at that offset.
    front = np.asarray(cue_ball, dtype=np.float64) - left * tip_side * r
    front = front - d * (r * math.sqrt(1.0 - side * side) + gap)
    for s0, s1, colour in CUE_PARTS:
        w0, w1 = (TIP_WIDTH + (BUTT_WIDTH - TIP_WIDTH) * s / CUE_LENGTH for s in (s0, s1))
        a, b = front - d * s0, front - d * s1
        quad = np.array(
            [a + left * w0 / 2, a - left * w0 / 2, b - left * w1 / 2, b + left * w1 / 2]
        )
        renderer.fill(img, quad, colour, None)


def marker_centre(renderer: Renderer, cue_ball: NDArray[np.float64]) -> tuple[float, float, float]:
    """Pixel centre and radius of the tip marker: the frame corner farthest from the cue ball."""
    w, h = renderer.size
    rf = max(10.0, 0.06 * h)
    pad = rf + 4.0
    cx, cy = renderer.to_pixels(np.asarray(cue_ball, dtype=np.float64))
    x = pad if cx > w / 2.0 else w - pad
    y = pad if cy > h / 2.0 else h - pad
    return x, y, rf


def draw_tip_marker(
    renderer: Renderer, img: Frame, cue_ball: NDArray[np.float64], tip: tuple[float, float]
) -> None:
    """Paint the ball face seen from behind the cue, with a dot where the tip meets it.

    The dot sits at the contact offset, the cue axis offset ``tip`` scaled by
    ``R / (R + cue_tip_radius)`` (the rounded tip meets the ball nearer its centre); the ring
    is the miscue limit, half a radius.

    Args:
        renderer: The renderer.
        img: The frame to paint.
        cue_ball: The cue ball's centre (m): the marker goes in the farthest corner.
        tip: ``(side, vertical)`` cue axis offsets, fractions of R (+ right, + top).
    """
    table = renderer.table
    scale = 1.0 + table.cue_tip_radius / table.ball_radius
    ca, cb = tip[0] / scale, tip[1] / scale
    x, y, rf = marker_centre(renderer, cue_ball)
    blend_disc(img, x, y, rf + 2.0, MARKER_BACK)
    blend_disc(img, x, y, rf, BALL_COLOURS[0])
    blend_ring(img, x, y, MISCUE_CONTACT * rf, MARKER_RING, 0.8)
    blend_disc(img, x + ca * rf, y - cb * rf, max(2.0, 0.16 * rf), MARKER_DOT)


def strike_frames(
    renderer: Renderer,
    positions: NDArray[np.float64],
    on_table: NDArray[np.bool_],
    balls: NDArray[np.int64],
    strike: Strike,
    fps: int,
) -> list[Frame]:
    """The lead-in: the stick held drawn back, then stroking through to the cue ball.

    Args:
        renderer: The renderer.
        positions: ``(M, 2)`` centres at the strike.
        on_table: ``(M,)`` which balls are drawn.
        balls: ``(M,)`` ball numbers; the cue ball is number 0.
        strike: The executed strike (:data:`Strike`).
        fps: Frames per second of playback.

    Returns:
        ``ceil((LEAD_HOLD + LEAD_STROKE) * fps)`` frames, the last with the tip at the ball.

    Raises:
        ValueError: If no row is ball 0, or on a bad strike.
    """
    angle, speed, side, vertical = check_strike(strike)
    rows = np.flatnonzero(np.asarray(balls) == 0)
    if rows.size == 0:
        raise ValueError("no cue ball (ball 0) among the shot's balls: nothing to strike")
    cue_ball = np.asarray(positions, dtype=np.float64)[rows[0]]
    base = renderer.frame(positions, on_table, balls)
    n_hold = max(1, math.ceil(LEAD_HOLD * fps))
    n_stroke = max(1, math.ceil(LEAD_STROKE * fps))
    back = draw_back(speed)
    gaps = [back] * n_hold + [back * (1.0 - k / n_stroke) for k in range(1, n_stroke + 1)]
    frames = []
    for gap in gaps:
        img = base.copy()
        draw_cue(renderer, img, cue_ball, angle, side, gap)
        if renderer.table.has_spin:  # the tip is a choice only on the spin level
            draw_tip_marker(renderer, img, cue_ball, (side, vertical))
        frames.append(img)
    return frames
