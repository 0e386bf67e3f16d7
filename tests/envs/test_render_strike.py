"""The strike in pictures: the cue stick, the tip marker, curved paths drawn as they are."""

from __future__ import annotations

import itertools
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from pool_env import Table, shoot
from pool_env.render import (
    LIST_PLAYBACK,
    Renderer,
    shot_frames,
    strike_frames,
    trail_times,
    trails,
)
from pool_env.render.cue import (
    BUTT_WIDTH,
    LEAD_HOLD,
    LEAD_STROKE,
    draw_back,
    draw_tip_marker,
    marker_centre,
)
from pool_env.render.palette import MARKER_DOT
from pool_env.render.paths import CURVE_STEP

SPIN = Table(model="spin")
LAYOUT = np.array([[0.8, 0.5], [1.5, 0.7], [2.0, 1.0]])
ANGLE = math.atan2(0.23, 0.7)  # a cut on ball 1
SPEED = 2.5
TIP = (0.4, -0.55)  # right english and draw: the cue ball bends after the hit
FPS = 30


@pytest.fixture(scope="module")
def draw_shot() -> object:
    return shoot(SPIN, LAYOUT, ANGLE, SPEED, tip=TIP)


@pytest.fixture(scope="module")
def follow_shot() -> object:
    """Top spin on a cut: after the hit the cue ball slides on a parabola bending forward."""
    return shoot(SPIN, LAYOUT, ANGLE, SPEED, tip=(0.0, 0.6))


def _pixels_to_table(renderer: Renderer, rows: np.ndarray, cols: np.ndarray) -> np.ndarray:
    """Pixel centres back to table coordinates (m): the inverse of ``to_pixels``."""
    probe = renderer.to_pixels(np.array([[0.0, 0.0], [1.0, 1.0]]))
    scale = probe[1, 0] - probe[0, 0]
    x = (cols + 0.5 - probe[0, 0]) / scale
    y = (probe[0, 1] - (rows + 0.5)) / scale
    return np.stack([x, y], axis=-1)


def _outside_marker(renderer: Renderer, rows: np.ndarray, cols: np.ndarray) -> np.ndarray:
    x, y, rf = marker_centre(renderer, LAYOUT[0])
    return np.hypot(cols + 0.5 - x, rows + 0.5 - y) > rf + 4.0


def test_the_cue_stick_lies_on_the_aim_line_behind_the_ball_before_the_strike_only(
    draw_shot: object,
) -> None:
    renderer = Renderer(SPIN, 800)
    balls = np.arange(3)
    frames = shot_frames(renderer, draw_shot, balls, fps=FPS, strike=(ANGLE, SPEED, *TIP))
    n_lead = math.ceil(LEAD_HOLD * FPS) + math.ceil(LEAD_STROKE * FPS)
    still = renderer.frame(LAYOUT, np.ones(3, bool), balls)
    d = np.array([math.cos(ANGLE), math.sin(ANGLE)])
    left = np.array([-d[1], d[0]])
    r = SPIN.ball_radius
    px = 1.0 / renderer.scale
    nearest = []
    for frame in frames[:n_lead]:
        rows, cols = np.nonzero((frame != still).any(axis=2))
        keep = _outside_marker(renderer, rows, cols)
        xy = _pixels_to_table(renderer, rows[keep], cols[keep]) - LAYOUT[0]
        along, across = xy @ d, xy @ left
        assert xy.shape[0] > 200  # the stick is there: hundreds of pixels
        assert along.max() < -0.5 * r  # all of it behind the cue ball
        # Within the stick's half width of the cue axis, which is TIP[0] R right of centre.
        assert np.abs(across + TIP[0] * r).max() < BUTT_WIDTH / 2 + 2 * px
        nearest.append(-along.max())
    # Held drawn back, then stroking through to the ball.
    hold = math.ceil(LEAD_HOLD * FPS)
    assert nearest[0] == pytest.approx(nearest[hold - 1])
    assert nearest[0] > draw_back(SPEED) + 0.5 * r
    assert np.all(np.diff(nearest[hold - 1 :]) < 0)
    assert nearest[-1] < r + 2 * px  # the tip at the ball in the last lead-in frame
    # After the strike: the shot's frames exactly, no stick.
    plain = shot_frames(renderer, draw_shot, balls, fps=FPS)
    assert len(frames) == n_lead + len(plain)
    for a, b in zip(frames[n_lead:], plain, strict=True):
        np.testing.assert_array_equal(a, b)


def test_the_tip_marker_dot_moves_with_the_offset() -> None:
    renderer = Renderer(SPIN, 800)
    x, y, rf = marker_centre(renderer, LAYOUT[0])
    contact = 1.0 / (1.0 + SPIN.cue_tip_radius / SPIN.ball_radius)  # the tip meets nearer in

    def dot(tip: tuple[float, float]) -> np.ndarray:
        img = renderer.background.copy()
        draw_tip_marker(renderer, img, LAYOUT[0], tip)
        near = np.abs(img.astype(float) - MARKER_DOT).sum(axis=2) < 30
        rows, cols = np.nonzero(near)
        assert rows.size > 4
        return np.array([cols.mean() + 0.5 - x, rows.mean() + 0.5 - y])

    assert np.abs(dot((0.0, 0.0))).max() < 0.3  # centre ball: dot at the face's centre
    for tip in ((0.3, 0.0), (-0.5, 0.0), (0.0, 0.4), (0.0, -0.6), (0.35, -0.35)):
        expected = np.array([tip[0], -tip[1]]) * contact * rf  # right is right, top is up
        np.testing.assert_allclose(dot(tip), expected, atol=0.35)


def test_no_tip_marker_on_the_roll_level_and_bad_strikes_are_refused() -> None:
    roll = Table()
    renderer = Renderer(roll, 400)
    pos, on, balls = LAYOUT, np.ones(3, bool), np.arange(3)
    (first, *_) = strike_frames(renderer, pos, on, balls, (ANGLE, 1.0, 0.0, 0.0), FPS)
    assert not (np.abs(first.astype(float) - MARKER_DOT).sum(axis=2) < 30).any()
    spin_first = strike_frames(Renderer(SPIN, 400), pos, on, balls, (ANGLE, 1.0, 0.2, 0.0), FPS)
    assert (np.abs(spin_first[0].astype(float) - MARKER_DOT).sum(axis=2) < 30).any()
    for bad in ((ANGLE, -1.0, 0.0, 0.0), (math.nan, 1.0, 0.0, 0.0), (ANGLE, 1.0), "abcd"):
        with pytest.raises(ValueError, match="strike"):
            strike_frames(renderer, pos, on, balls, bad, FPS)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="cue ball"):
        strike_frames(renderer, pos, on, np.array([1, 2, 3]), (ANGLE, 1.0, 0.0, 0.0), FPS)


def _chord_gap(shot: object, ball: int) -> tuple[float, float]:
    """The widest gap (m) between a ball's path and the chords between events, and when."""
    times = np.unique(np.concatenate([[0.0, shot.duration], shot.event_times]))
    best = (0.0, 0.0)
    for t0, t1 in itertools.pairwise(times):
        p0, p1 = shot.positions_at(t0)[ball], shot.positions_at(t1)[ball]
        for f in (0.25, 0.5, 0.75):
            t = t0 + f * (t1 - t0)
            p = shot.positions_at(t)[ball]
            chord = p1 - p0
            n = np.hypot(*chord)
            off = p - p0
            gap = abs(chord[0] * off[1] - chord[1] * off[0]) / n if n > 1e-12 else 0.0
            best = max(best, (gap, t))
    return best


def test_a_curved_path_is_drawn_and_animated_as_it_is(follow_shot: object) -> None:
    shot = follow_shot
    renderer = Renderer(SPIN, 800)
    balls = np.arange(3)
    gap, t_curve = _chord_gap(shot, 0)
    assert gap * renderer.scale > 3.0  # straight lines between events would be pixels off
    # Animation frames: the balls exactly at positions_at(t), the curve's middle included.
    frames = shot_frames(renderer, shot, balls, fps=FPS)
    times = np.linspace(0.0, shot.duration, len(frames))
    k = int(np.argmin(np.abs(times - t_curve)))
    for j in (1, k, len(frames) // 2):
        t = float(times[j])
        expected = renderer.frame(shot.positions_at(t), ~shot.pocketed_at(t), balls)
        np.testing.assert_array_equal(frames[j], expected)
    # Trails: vertices at positions_at, close enough that the polyline follows the curve.
    samples = trail_times(shot)
    assert np.diff(samples).max() <= CURVE_STEP + 1e-12
    assert set(shot.event_times.tolist()) <= set(samples.tolist())
    (number, path), *_ = trails(shot, balls)
    assert number == 0
    for j in (0, len(samples) // 3, len(samples) - 1):
        np.testing.assert_array_equal(path[j], shot.positions_at(float(samples[j]))[0])
    mids = 0.5 * (samples[:-1] + samples[1:])
    exact = np.stack([shot.positions_at(float(t))[0] for t in mids])
    chord = 0.5 * (path[:-1] + path[1:])
    assert np.hypot(*(exact - chord).T).max() * renderer.scale < 0.25  # under a pixel


def test_roll_level_trails_keep_their_event_corners() -> None:
    roll = shoot(Table(), LAYOUT, ANGLE, SPEED)
    samples = trail_times(roll)
    # Straight lines between events are exact on the roll level: no extra samples.
    assert samples.tolist() == np.unique([0.0, roll.duration, *roll.event_times]).tolist()


def test_strike_frames_render_headless_without_pygame(tmp_path: Path) -> None:
    code = (
        "import math, sys, numpy as np, imageio.v3 as iio\n"
        "from pool_env import Table, shoot\n"
        "from pool_env.render import Renderer, save_animation, shot_frames\n"
        "t = Table(model='spin')\n"
        "pos = np.array([[0.8, 0.5], [1.5, 0.7]])\n"
        "a = math.atan2(0.2, 0.7)\n"
        "res = shoot(t, pos, a, 1.5, tip=(0.3, 0.4))\n"
        "frames = shot_frames(Renderer(t, 320), res, np.arange(2), fps=10, max_seconds=1.0,\n"
        "                     strike=(a, 1.5, 0.3, 0.4))\n"
        f"save_animation(frames, {str(tmp_path / 'shot.gif')!r}, fps=10)\n"
        "runs = 1 + sum(not np.array_equal(a, b) for a, b in zip(frames, frames[1:]))\n"
        "# GIF merges a repeated frame into the one before (the held stick): same playback\n"
        f"assert iio.imread({str(tmp_path / 'shot.gif')!r}).shape[0] == runs\n"
        "assert 'pygame' not in sys.modules\n"
        "print('drawn', len(frames))\n"
    )
    headless = {
        k: v
        for k, v in os.environ.items()
        if k not in ("DISPLAY", "WAYLAND_DISPLAY", "SDL_VIDEODRIVER", "XDG_RUNTIME_DIR")
    }
    done = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, env=headless, timeout=300
    )
    assert done.returncode == 0, done.stderr
    n_lead = math.ceil(LEAD_HOLD * 10) + math.ceil(LEAD_STROKE * 10)
    assert int(done.stdout.split()[-1]) > n_lead + 2


def test_a_spin_env_leads_each_shot_with_its_executed_strike() -> None:
    import gymnasium as gym

    env = gym.make("pool_env/OneBall-v1", render_mode="rgb_array_list", render_width=400)
    env.reset(seed=2)
    raw = env.unwrapped
    env.step(np.array([0.1, 0.3, 0.8, -0.6], np.float32))  # right english and draw
    frames = env.render()
    _, _, side, vertical = raw.last_strike
    assert side > 0.0 > vertical
    shot, balls = raw.last_shot, raw.last_shot_balls
    renderer = raw._get_renderer()
    at_strike = (shot.positions_at(0.0), ~shot.pocketed_at(0.0), balls)
    lead = strike_frames(renderer, *at_strike, raw.last_strike, 30)
    assert len(frames) > 1 + len(lead) + 2
    for a, b in zip(frames[1 : 1 + len(lead)], lead, strict=True):
        np.testing.assert_array_equal(a, b)
    # The marker's dot sits right of and below the face's centre: right english, draw.
    cue = at_strike[0][int(np.flatnonzero(balls == 0)[0])]
    x, y, _ = marker_centre(renderer, cue)
    rows, cols = np.nonzero(np.abs(lead[0].astype(float) - MARKER_DOT).sum(axis=2) < 30)
    assert cols.mean() + 0.5 - x > 1.0
    assert rows.mean() + 0.5 - y > 1.0
    # After the lead-in the frames are the shot's, with no stick.
    plain = raw.shot_frames(30, **LIST_PLAYBACK, lead_in=False)
    for a, b in zip(frames[1 + len(lead) :], plain, strict=True):
        np.testing.assert_array_equal(a, b)
