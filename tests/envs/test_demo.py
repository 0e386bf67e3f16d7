"""The demo: a readable event table without repeated lines, and a GIF of the break."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

from pool_env import Table, shoot
from pool_env.demo import event_table, main, pocket_name
from pool_env.sim.layouts import break_scene


def test_pockets_are_named_by_where_they_are() -> None:
    names = [pocket_name(Table(), k) for k in range(6)]
    # standard_pockets order: bottom-left, bottom-middle, bottom-right, top-left, ...
    assert names == [
        "bottom-left corner",
        "bottom side pocket",
        "bottom-right corner",
        "top-left corner",
        "top side pocket",
        "top-right corner",
    ]


def test_event_table_has_every_event_once_and_no_repeated_line() -> None:
    table = Table()
    result = shoot(table, break_scene(table, "nine"), angle=0.0, speed=8.0)
    lines = event_table(result, table)
    body = lines[2:]
    assert len(set(lines)) == len(lines)
    counts = [int(m.group(1)) if (m := re.search(r"\(x(\d+)\)$", line)) else 1 for line in body]
    assert sum(counts) == result.n_events  # merged, none lost
    pots = [line for line in body if " pocket " in f" {line} "]
    assert len(pots) == int(np.sum(result.pocketed >= 0))
    assert all(("corner" in line) or ("side pocket" in line) for line in pots)
    assert body[0].split()[:4] == ["0.151747", "impact", "cue", "1-ball"]  # the break


def test_demo_prints_the_table_and_writes_a_gif(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    import imageio.v3 as iio

    gif = tmp_path / "break.gif"
    main(["--gif", str(gif), "--width", "160"])
    out = capsys.readouterr().out
    assert "time (s)" in out
    assert "potted:" in out
    frames = iio.imread(gif)
    assert frames.shape[0] == 121  # an 11.3 s break sped up to 8 s at 15 fps
    assert not np.array_equal(frames[0], frames[10])  # the balls move
