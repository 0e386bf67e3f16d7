"""agents.evaluation.watch: one rack written frame for frame, its shots told as played."""

from __future__ import annotations

from itertools import pairwise
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from agents.evaluation.players import make_agent
from agents.evaluation.watch import Playback, describe_shot, main, watch
from agents.learned.envs import make_env

ENV = "pool_env/NineBallGame-v2"
#: Ghost-ball at FastFiz x1 in run-out mode: the break makes the 3, the next shot misses.
SEED = 1
KWARGS = {"noise": "fastfiz", "end_on_foul": True}
PLAYBACK = Playback(fps=10, speed=2.0, max_seconds=0.5, hold=0.0)  # 10 fps: 10 cs a frame
WIDTH = 128


def replay(playback: Playback) -> tuple[list[dict], list[list[np.ndarray]]]:
    """The same rack played again here: each step's info and its shot's frames."""
    env = make_env(ENV, {**KWARGS, "render_mode": "rgb_array", "render_width": WIDTH})
    agent = make_agent("ghost", env, SEED)
    obs, _ = env.reset(seed=SEED)
    infos, frames, done = [], [], False
    while not done:
        obs, _, terminated, truncated, info = env.step(agent.predict(obs, deterministic=True)[0])
        infos.append(info)
        frames.append(env.unwrapped.shot_frames(playback.fps, playback.speed, playback.max_seconds))
        done = terminated or truncated
    env.close()
    return infos, frames


def gif_frames(path: Path) -> tuple[int, int]:
    """A GIF's frame count and its playing time in ms (the sum of its frames' delays)."""
    with Image.open(path) as image:
        total = 0
        for k in range(image.n_frames):
            image.seek(k)
            total += image.info["duration"]
        return image.n_frames, total


def distinct_runs(frames: list[np.ndarray]) -> int:
    """How many runs of identical consecutive frames: what a GIF stores (Pillow merges)."""
    return 1 + sum(not np.array_equal(a, b) for a, b in pairwise(frames))


def test_an_mp4_holds_every_frame_of_every_shot(tmp_path: Path) -> None:
    ffmpeg = pytest.importorskip("imageio_ffmpeg")
    out = tmp_path / "rack.mp4"
    shots = watch("ghost", ENV, SEED, out, KWARGS, PLAYBACK, WIDTH, echo=lambda _: None)
    infos, frames = replay(PLAYBACK)
    assert [len(f) for f in frames] == [s.frames for s in shots]
    assert len(shots) >= 2 and all(s.frames > 1 for s in shots)
    # ffmpeg's own count (imageio's FFMPEG reader leaves its process to the collector)
    count, seconds = ffmpeg.count_frames_and_secs(str(out))
    assert count == sum(len(f) for f in frames)
    assert seconds == pytest.approx(count / PLAYBACK.fps, abs=0.05)
    assert [i["potted"] for i in infos] == [s.info["potted"] for s in shots]


def test_a_gif_plays_every_frame_and_holds_the_last(tmp_path: Path) -> None:
    out = tmp_path / "rack.gif"
    playback = Playback(fps=10, speed=2.0, max_seconds=0.5, hold=1.5)
    shots = watch("ghost", ENV, SEED, out, KWARGS, playback, WIDTH, echo=lambda _: None)
    _, frames = replay(playback)
    drawn = [frame for shot in frames for frame in shot]
    assert len(drawn) == sum(s.frames for s in shots) > 2 * len(shots)
    count, ms = gif_frames(out)
    with Image.open(out) as image:
        assert image.size == (WIDTH, drawn[0].shape[0])
    # Pillow keeps a run of identical frames (the stick held back, the 15 held copies of
    # the last one) as one frame shown as long: the playing time is every frame's.
    assert count == distinct_runs(drawn)
    assert ms == (len(drawn) + 15) * 100


def test_each_shot_is_told_as_the_env_reports_it(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "rack.gif"
    argv = ["--agent", "ghost", "--env", ENV, "--seed", str(SEED), "--run-out", "--out",
            str(out), "--width", str(WIDTH), "--fps", "10", "--speed", "2",
            "--max-seconds-per-shot", "0.5", "--hold", "0"]  # fmt: skip
    assert main(argv) == 0
    lines = capsys.readouterr().out.splitlines()
    infos, frames = replay(PLAYBACK)
    shot_lines = [line for line in lines if line.startswith("shot ")]
    assert len(shot_lines) == len(infos) == 2
    for k, (line, info) in enumerate(zip(shot_lines, infos, strict=True), start=1):
        assert line.startswith(f"shot {k}: ")
        potted = ", ".join(str(b) for b in info["potted"])
        assert (f"potted {potted}" if potted else "nothing potted") in line
        assert (f"foul: {info['foul']}" in line) == (info["foul"] is not None)
        assert ("turn over" in line) == (info["turn_over"] and info["winner"] == -1)
    assert infos[0]["potted"] and not infos[1]["potted"]  # the rack this test is about
    total = sum(len(f) for f in frames)
    assert lines[-1].startswith(f"wrote {out}: 2 shots, {total} frames")
    assert gif_frames(out)[1] == total * 100


@pytest.mark.parametrize(
    ("info", "line"),
    [
        ({"potted": (1, 9), "foul": None, "winner": 0}, "shot 1: potted 1, 9; rack won"),
        (
            {"potted": (), "foul": "scratch", "turn_over": True, "winner": -1},
            "shot 2: nothing potted; foul: scratch; turn over",
        ),
        (
            {"potted": (), "foul": "no_rail", "winner": 1, "loss": "three_fouls"},
            "shot 2: nothing potted; foul: no_rail; rack lost: three_fouls",
        ),
        ({"potted": (), "foul": None, "push_out": True, "turn_over": True, "winner": -1},
         "shot 2: nothing potted; push-out; turn over"),
        ({"potted": (), "foul": None, "handed_back": True, "turn_over": True, "winner": -1},
         "shot 2: handed the table back; turn over"),
        ({"potted": (), "scratch": True}, "shot 2: nothing potted; scratch"),  # no rules
    ],
)  # fmt: skip
def test_a_shot_in_words(info: dict, line: str) -> None:
    assert describe_shot(int(line.split()[1].rstrip(":")), info) == line


@pytest.mark.parametrize(
    ("flags", "words"),
    [
        (["--fps", "0"], ["--fps", "got 0"]),
        (["--fps", "60"], ["--fps 60", "GIF", "50"]),
        (["--speed", "-1"], ["--speed", "-1.0"]),
        (["--max-seconds-per-shot", "nan"], ["--max-seconds-per-shot", "nan"]),
        (["--hold", "-0.5"], ["--hold", "-0.5"]),
        (["--out", "rack.png"], ["--out", "rack.png", ".gif or .mp4"]),
        (["--agent", "gost"], ["gost", "did you mean ghost"]),
        (["--env", "pool_env/NineBallGame-v9"], ["pool_env/NineBallGame-v9"]),
        (["--noise", "fastfizz"], ["--noise", "fastfizz"]),
        (["--players", "3"], ["--players", "3"]),
        (["--width", "10"], ["render_width", "10"]),
        (["--env-kwargs", "[1, 2]"], ["--env-kwargs", "mapping", "[1, 2]"]),
        (["--env-kwargs", "{max_shot: 3}"], ["max_shot"]),
        (["--env", "pool_env/OneBall-v1", "--run-out"], ["end_on_foul", "solitaire"]),
    ],
)
def test_bad_input_is_a_usage_error_naming_it(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], flags: list[str], words: list[str]
) -> None:
    out = tmp_path / "rack.gif"
    argv = ["--agent", "ghost", "--env", ENV, "--out", str(out), *flags]
    with pytest.raises(SystemExit) as exit_info:
        main(argv)
    assert exit_info.value.code == 2
    error = capsys.readouterr().err.strip().splitlines()[-1]
    assert "error: " in error
    for word in words:
        assert word in error, (word, error)
    assert not out.exists() and not (tmp_path / "rack.png").exists()


def test_a_directory_is_no_file_to_write(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    folder = tmp_path / "rack.gif"
    folder.mkdir()
    with pytest.raises(SystemExit) as exit_info:
        main(["--agent", "ghost", "--out", str(folder)])
    assert exit_info.value.code == 2
    assert "is a directory" in capsys.readouterr().err


@pytest.mark.parametrize(
    ("kwargs", "words"),
    [
        ({"fps": 0}, "--fps must be an integer >= 1, got 0"),
        ({"fps": 2.5}, "--fps must be an integer >= 1, got 2.5"),
        ({"speed": float("inf")}, "--speed must be a finite number > 0, got inf"),
        ({"speed": True}, "--speed must be a finite number > 0, got True"),
        ({"max_seconds": 0.0}, "--max-seconds-per-shot must be a finite number > 0, got 0.0"),
        ({"hold": -1.0}, "--hold must be a finite number of seconds >= 0, got -1.0"),
    ],
)
def test_a_playback_is_checked_when_made(kwargs: dict, words: str) -> None:
    with pytest.raises(ValueError, match=words.replace(".", r"\.").replace("+", r"\+")):
        Playback(**kwargs)


def test_the_file_is_checked_before_the_rack_is_played(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match=r"--out: save an animation as \.gif or \.mp4.*x\.png"):
        watch("ghost", ENV, SEED, tmp_path / "x.png", KWARGS, PLAYBACK, WIDTH)
    with pytest.raises(ValueError, match="--fps 51 is too fast for a GIF"):
        Playback(fps=51).check_file("x.gif")
    assert Playback(fps=60).check_file("x.MP4") == ".mp4"
