"""Rendering: frames that show the balls where they are, shot animations, files, windows."""

from __future__ import annotations

import importlib.util
import itertools
import sys

import gymnasium as gym
import numpy as np
import pytest

from pool_env import PoolEnv, Table
from pool_env.render import (
    BALL_COLOURS,
    Renderer,
    Window,
    save_animation,
    shot_frames,
    strike_frames,
)
from pool_env.render.cue import LEAD_HOLD, LEAD_STROKE

TABLE = Table()
LAYOUT = np.array([[0.6, 0.6], [0.3, 0.3], [1.9, 0.9], [1.2, 0.3]])  # ball 1 in front of a corner


def _pixel(renderer: Renderer, frame: np.ndarray, xy: np.ndarray) -> np.ndarray:
    col, row = renderer.to_pixels(np.asarray(xy, dtype=float))
    return frame[int(row), int(col)].astype(int)


def _rgb_env(**kwargs: object) -> PoolEnv:
    """The roll table (``TABLE``'s), whose shots the tests below work out."""
    kwargs = {"model": "roll", **kwargs}
    return PoolEnv(scene=LAYOUT, aim="absolute", render_mode="rgb_array", **kwargs)  # type: ignore[arg-type]


def test_rgb_array_frame_draws_each_ball_where_it_is() -> None:
    env = _rgb_env()
    env.reset(seed=0)
    frame = env.render()
    assert frame.dtype == np.uint8
    assert frame.ndim == 3
    assert frame.shape[2] == 3
    assert frame.shape[0] % 16 == 0  # video codecs want multiples of 16
    assert frame.shape[1] == 800
    renderer = env._get_renderer()
    cue = _pixel(renderer, frame, LAYOUT[0])
    assert cue.min() > 180  # white
    # Ball 2 is blue, ball 3 red: sample the coloured ring between the number disc and the rim.
    ring = np.array([0.75 * TABLE.ball_radius, 0.0])
    blue = _pixel(renderer, frame, LAYOUT[2] + ring)
    red = _pixel(renderer, frame, LAYOUT[3] + ring)
    assert blue[2] > blue[0] + 60
    assert red[0] > red[2] + 60
    empty = np.array([1.5, 0.9])
    assert np.array_equal(
        _pixel(renderer, frame, empty), _pixel(renderer, renderer.background, empty)
    )


def test_a_potted_ball_disappears_and_the_shot_leaves_trails() -> None:
    env = _rgb_env()
    env.reset(seed=0)
    before = env.render()
    env.step(np.array([-0.75, -0.8]))  # ball 1 straight into the corner
    after = env.render()
    renderer = env._get_renderer()
    assert not env.on_table[1]
    background = renderer.background
    col, row = renderer.to_pixels(LAYOUT[1])
    # Where ball 1 stood there is now only its own (yellow) trail over the cloth.
    assert not np.array_equal(after[int(row), int(col)], before[int(row), int(col)])
    clean = renderer.frame(env.positions, env.on_table)
    assert (after != clean).any(axis=2).sum() > 100  # the trails
    assert np.array_equal(clean[:4], background[:4])  # the rail band is untouched


def test_frames_are_deterministic() -> None:
    frames = []
    for _ in range(2):
        env = gym.make("pool_env/NineBallRoll-v1", render_mode="rgb_array")
        env.reset(seed=4)
        env.step(np.array([0.0, 0.7]))
        frames.append(env.render())
    np.testing.assert_array_equal(*frames)


def test_shot_animation_runs_from_the_strike_to_rest() -> None:
    env = _rgb_env()
    env.reset(seed=0)
    env.step(np.array([-0.75, -0.8]))
    shot, balls = env.last_shot, env.last_shot_balls
    frames = env.shot_frames(fps=20, max_seconds=3.0, lead_in=False)
    assert len(frames) == max(2, int(np.ceil(min(shot.duration, 3.0) * 20)) + 1)
    # By default the cue stick leads in (tests/envs/test_render_strike.py), then the same frames.
    led = env.shot_frames(fps=20, max_seconds=3.0)
    n_lead = int(np.ceil(LEAD_HOLD * 20) + np.ceil(LEAD_STROKE * 20))
    assert len(led) == n_lead + len(frames)
    np.testing.assert_array_equal(led[n_lead], frames[0])
    renderer = env._get_renderer()
    np.testing.assert_array_equal(frames[0], renderer.frame(LAYOUT, np.ones(4, bool), balls))
    np.testing.assert_array_equal(
        frames[-1], renderer.frame(shot.positions, shot.pocketed < 0, balls)
    )
    assert len(shot_frames(renderer, shot, balls, fps=10, speed=4.0)) < len(frames)


def test_shot_frames_need_a_recorded_shot() -> None:
    env = PoolEnv(model="roll")
    env.reset(seed=0)
    env.step(np.array([0.0, 0.0]))
    with pytest.raises(ValueError, match="render_mode"):
        env.shot_frames()
    with pytest.raises(ValueError, match="record=False"):
        shot_frames(Renderer(TABLE), env.last_shot, env.last_shot_balls)


def test_save_shot_as_gif(tmp_path: object) -> None:
    import imageio.v3 as iio

    env = _rgb_env(render_width=320)
    env.reset(seed=0)
    env.step(np.array([-0.75, -0.8]))
    path = tmp_path / "shot.gif"  # type: ignore[operator]
    env.save_shot(str(path), fps=10, max_seconds=2.0)
    gif = iio.imread(path)
    frames = env.shot_frames(fps=10, max_seconds=2.0)
    # A GIF merges a repeated frame into the one before (the held stick): same playback.
    runs = 1 + sum(not np.array_equal(a, b) for a, b in itertools.pairwise(frames))
    assert gif.shape[0] == runs
    with pytest.raises(ValueError, match=r"\.gif or \.mp4"):
        save_animation([gif[0]], tmp_path / "shot.avi")  # type: ignore[operator]


@pytest.mark.skipif(
    importlib.util.find_spec("imageio_ffmpeg") is None, reason="needs imageio-ffmpeg"
)
def test_save_shot_as_mp4(tmp_path: object) -> None:
    env = _rgb_env(render_width=320)
    env.reset(seed=0)
    env.step(np.array([-0.75, -0.8]))
    path = tmp_path / "shot.mp4"  # type: ignore[operator]
    env.save_shot(str(path), fps=10, max_seconds=1.0)
    assert path.stat().st_size > 1000


def test_human_mode_opens_a_window_and_animates(monkeypatch: pytest.MonkeyPatch) -> None:
    pytest.importorskip("pygame")
    monkeypatch.setenv("SDL_VIDEODRIVER", "dummy")  # headless CI
    env = gym.make("pool_env/OneBallRoll-v1", render_mode="human")
    env.reset(seed=0)
    raw = env.unwrapped
    assert raw._window is not None
    played: list[int] = []
    monkeypatch.setattr(raw._window, "play", lambda frames, fps=30: played.append(len(frames)))
    assert env.step(np.array([0.0, -0.9], np.float32))[0].shape == (6,)
    assert env.render() is None
    assert played
    assert played[0] >= 2
    env.close()
    assert raw._window is None


def test_human_mode_without_pygame_names_the_extra(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setitem(sys.modules, "pygame", None)  # import pygame -> ImportError
    with pytest.raises(gym.error.DependencyNotInstalled, match=r"pool_env\[render\]"):
        Window((64, 32))
    env = PoolEnv(render_mode="human")  # the window opens lazily, at the first render
    with pytest.raises(gym.error.DependencyNotInstalled, match=r"pool_env\[render\]"):
        env.reset(seed=0)


def test_render_without_a_mode_warns_and_returns_none() -> None:
    env = PoolEnv()
    env.reset(seed=0)
    with pytest.warns(UserWarning, match="render_mode"):
        assert env.render() is None


@pytest.mark.skipif(importlib.util.find_spec("moviepy") is None, reason="needs moviepy")
def test_record_video_writes_one_trail_frame_per_shot(tmp_path: object) -> None:
    from gymnasium.wrappers import RecordVideo

    env = gym.make(
        "pool_env/PoolRoll-v1", render_mode="rgb_array", render_width=320, max_episode_steps=5
    )
    folder = tmp_path / "videos"  # type: ignore[operator]
    env = RecordVideo(env, str(folder), episode_trigger=lambda episode: True, disable_logger=True)
    env.reset(seed=0)
    done = False
    steps = 0
    while not done:
        *_, terminated, truncated, _ = env.step(env.action_space.sample())
        steps += 1
        done = terminated or truncated
    assert len(env.recorded_frames) == steps + 1  # the layout, then each shot with its trails
    env.close()
    videos = list(folder.glob("*.mp4"))
    assert len(videos) == 1
    assert videos[0].stat().st_size > 1000


def test_ball_colours_cover_the_set() -> None:
    assert BALL_COLOURS.shape == (9, 3)
    renderer = Renderer(TABLE, 640)
    positions = np.array([[0.2 + 0.13 * k, 0.6] for k in range(16)])
    frame = renderer.frame(positions, np.ones(16, bool))
    # Stripes 9-15 show white above and below their colour band; solids do not.
    for k in (3, 11):
        top = _pixel(renderer, frame, positions[k] + np.array([0.0, 0.8 * TABLE.ball_radius]))
        assert (top.min() > 180) == (k > 8)


def _list_env(env_id: str = "pool_env/OneBallRoll-v1", **kwargs: object) -> gym.Env:
    return gym.make(env_id, render_mode="rgb_array_list", render_width=320, **kwargs)


def test_rgb_array_list_returns_the_layout_then_the_shot_from_its_trajectories() -> None:
    env = _list_env()
    env.reset(seed=3)
    raw = env.unwrapped
    renderer = raw._get_renderer()
    start = (raw.positions, raw.on_table)
    env.step(np.array([0.0, -0.5], np.float32))
    frames = env.render()
    assert env.render() == []  # everything since the last call, once
    shot, balls = raw.last_shot, raw.last_shot_balls
    np.testing.assert_array_equal(frames[0], renderer.frame(*start))  # the reset frame
    # The cue stick at the executed strike's aim, then the shot.
    at_strike = (shot.positions_at(0.0), ~shot.pocketed_at(0.0), balls)
    lead = strike_frames(renderer, *at_strike, raw.last_strike, 30)
    for a, b in zip(frames[1 : 1 + len(lead)], lead, strict=True):
        np.testing.assert_array_equal(a, b)
    clip = frames[1 + len(lead) :]
    n = len(clip)
    assert n >= 20
    # Playback at 2x real time, at most 4 s, at 30 fps: n - 1 intervals over the shot.
    assert n == max(20, int(np.ceil(min(shot.duration / 2.0, 4.0) * 30)) + 1)
    assert raw.metadata["render_fps"] == 30
    for k in (0, n // 3, n - 1):  # frame k is the exact state at k * duration / (n - 1)
        t = k * shot.duration / (n - 1)
        expected = renderer.frame(shot.positions_at(t), ~shot.pocketed_at(t), balls)
        np.testing.assert_array_equal(clip[k], expected)
    assert not np.array_equal(clip[1], clip[n // 3])  # the balls move between frames


def test_gymnasiums_record_video_keeps_one_frame_of_a_list_per_step(tmp_path: object) -> None:
    pytest.importorskip("moviepy")
    from gymnasium.wrappers import RecordVideo

    folder = str(tmp_path / "videos")  # type: ignore[operator]
    env = RecordVideo(_list_env(), folder, episode_trigger=lambda e: True)
    env.reset(seed=0)
    env.step(np.array([0.0, -0.5], np.float32))
    assert len(env.recorded_frames) == 2  # why RecordShots exists
    env.close()


def test_record_shots_records_every_frame_of_every_shot(tmp_path: object) -> None:
    pytest.importorskip("moviepy")
    import imageio_ffmpeg

    from pool_env.envs.record import RecordShots

    folder = tmp_path / "videos"  # type: ignore[operator]
    env = RecordShots(_list_env(), str(folder), episode_trigger=lambda e: True)
    assert env.frames_per_sec == 30
    env.reset(seed=1)
    durations = []
    done = False
    while not done:  # OneBallRoll-v1: one shot per episode
        *_, terminated, truncated, _ = env.step(env.action_space.sample())
        durations.append(env.unwrapped.last_shot.duration)
        done = terminated or truncated
    frames = len(env.recorded_frames)
    assert frames >= 1 + 20 * len(durations)  # the layout, then >= 20 frames a shot
    env.close()
    (video,) = folder.glob("*.mp4")
    # ffmpeg decodes and counts the frames (imageio's frame iterator leaves ffmpeg's pipes
    # open until garbage collection, a ResourceWarning at some later test).
    in_file, _ = imageio_ffmpeg.count_frames_and_secs(str(video))
    assert in_file >= 1 + 20 * len(durations)
    assert frames - 1 <= in_file <= frames  # moviepy may round the last frame off the clip
    with pytest.raises(ValueError, match="rgb_array_list"):
        RecordShots(gym.make("pool_env/OneBallRoll-v1", render_mode="rgb_array"), str(folder / "x"))


def test_save_video_writes_an_rgb_array_list_episode(tmp_path: object) -> None:
    pytest.importorskip("moviepy")
    from gymnasium.utils.save_video import save_video

    env = _list_env("pool_env/NineBallRoll-v1", max_episode_steps=2)
    env.reset(seed=0)
    for _ in range(2):
        env.step(env.action_space.sample())
    frames = env.render()
    assert len(frames) >= 1 + 2 * 20
    save_video(frames, str(tmp_path), fps=env.metadata["render_fps"], name_prefix="nine")
    assert next(iter(tmp_path.glob("nine*.mp4"))).stat().st_size > 1000  # type: ignore[attr-defined]


def test_headless_check_env_prints_no_display_error() -> None:
    import os
    import subprocess

    code = (
        "import gymnasium as gym, sys, pool_env\n"
        "from gymnasium.utils.env_checker import check_env\n"
        "for mode in ('rgb_array', 'rgb_array_list'):  # the v1 id: spin, the cue stick\n"
        "    env = gym.make('pool_env/OneBall-v1', render_mode=mode)\n"
        "    env.reset(seed=0); env.step(env.action_space.sample()); env.render()\n"
        "assert 'pygame' not in sys.modules  # no pygame unless a window is asked for\n"
        "check_env(gym.make('pool_env/OneBall-v1').unwrapped)\n"
        "print('checked')\n"
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
    assert "checked" in done.stdout
    output = done.stdout + done.stderr
    assert "XDG_RUNTIME_DIR" not in output
    assert "WARN" not in output


def test_the_table_shows_the_real_pocket_openings() -> None:
    """Jaws: cloth in the mouth, the hole behind the fall line, cushion beside the points.

    Capture circles: the discs.
    """
    from pool_env.render import CLOTH, CUSHION, POCKET

    renderer = Renderer(TABLE, width=1200)
    side = TABLE.jaws[1]
    behind = side.fall_line.mean(axis=0) - 0.01 * side.fall_normal
    mouth = side.points.mean(axis=0) + 0.001 * side.fall_normal
    beside = side.points[0] + np.array([-0.03, -0.01])  # under the rail, left of the point
    assert np.array_equal(_pixel(renderer, renderer.background, behind), POCKET)
    assert np.array_equal(_pixel(renderer, renderer.background, mouth), CLOTH)
    assert np.array_equal(_pixel(renderer, renderer.background, beside), CUSHION)
    corner = TABLE.jaws[0]
    assert np.array_equal(_pixel(renderer, renderer.background, corner.fall_line.mean(axis=0)
                                 - 0.01 * corner.fall_normal), POCKET)  # fmt: skip
    circles = Renderer(Table(pockets="circles"), width=1200)
    assert np.array_equal(_pixel(circles, circles.background, mouth - [0.0, 0.01]), POCKET)
