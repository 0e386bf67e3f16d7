"""Pictures in a game's colours: a ruleset's ``ball_colours`` and ``cloth``.

A tiny test game (rotation, ``tests/user_game/rotation.py``, with the colours of carom
and of snooker set) played on the carom and snooker presets: each ball's centre pixel is
its colour, the balls carry no numbers, the cloth is the game's, a pocketless table shows
no pocket; a bad colour is refused naming it.
"""

from __future__ import annotations

import numpy as np
import pytest
from numpy.typing import NDArray

from pool_env import PoolEnv, Table
from pool_env.game.registry import register_game
from pool_env.game.ruleset import Ruleset, Setup
from pool_env.render import POCKET, Renderer
from tests.user_game.rotation import Rotation

WHITE, YELLOW, RED = (250, 250, 245), (240, 200, 20), (200, 20, 30)
BLUE_CLOTH = (30, 70, 160)
SNOOKER_COLOURS = (
    (250, 250, 245),  # the cue ball
    *((200, 20, 30),) * 15,  # the reds
    (240, 200, 20), (20, 120, 50), (120, 70, 30), (20, 60, 200), (240, 130, 170), (15, 15, 15),
)  # fmt: skip


class CaromColours(Rotation):
    name = "test_carom_colours"
    ball_colours = (WHITE, YELLOW, RED)
    cloth = BLUE_CLOTH

    def configure(self, setup: Setup) -> NDArray[np.float64]:
        """Any table: the pictures are under test, not the rule (which needs pockets)."""
        return Ruleset.configure(self, setup)


class SnookerColours(Rotation):
    name = "test_snooker_colours"
    ball_colours = SNOOKER_COLOURS
    cloth = (20, 110, 50)


register_game(CaromColours(), replace=True)
register_game(SnookerColours(), replace=True)


def _pixel(renderer: Renderer, frame: np.ndarray, xy) -> np.ndarray:
    col, row = renderer.to_pixels(np.asarray(xy, dtype=float))
    return frame[int(row), int(col)].astype(int)


def _env(game: str, table: Table, layout: np.ndarray) -> PoolEnv:
    return PoolEnv(game=game, table=table, scene=layout, render_mode="rgb_array")


def test_carom_balls_and_cloth_in_the_games_colours():
    layout = np.array([[0.7, 0.7], [1.4, 0.4], [2.1, 1.0]])
    env = _env("test_carom_colours", Table.preset("carom"), layout)
    env.reset(seed=0)
    frame = env.render()
    renderer = env._get_renderer()
    for xy, colour in zip(layout, (WHITE, YELLOW, RED), strict=True):
        assert np.abs(_pixel(renderer, frame, xy) - colour).max() <= 2, colour
    assert np.array_equal(_pixel(renderer, frame, [1.4, 1.2]), BLUE_CLOTH)
    # Pocketless: the cloth runs into every corner, no pocket is drawn.
    for corner in ([0.005, 0.005], [2.835, 1.415], [1.42, 0.003]):
        pixel = _pixel(renderer, frame, corner)
        assert np.array_equal(pixel, BLUE_CLOTH)
        assert not np.array_equal(pixel, POCKET)


def test_snooker_balls_are_plain_colours_without_numbers():
    table = Table.preset("snooker")
    layout = np.array([[0.4 + 0.14 * (k % 11), 0.5 + 0.5 * (k // 11)] for k in range(22)])
    env = _env("test_snooker_colours", table, layout)
    env.reset(seed=0)
    frame = env.render()
    renderer = env._get_renderer()
    r = table.ball_radius
    for k, xy in enumerate(layout):
        colour = np.array(SNOOKER_COLOURS[k])
        assert np.abs(_pixel(renderer, frame, xy) - colour).max() <= 2, k
        # No number disc and no digits: the inner half of the ball is its colour, shaded.
        for offset in ([0.3 * r, 0.0], [-0.3 * r, 0.2 * r], [0.0, -0.4 * r]):
            pixel = _pixel(renderer, frame, xy + np.array(offset))
            assert np.abs(pixel - colour * (1 - 0.25 * 0.16)).max() <= 6, (k, offset)


def test_pool_keeps_its_numbered_balls():
    """Without ``ball_colours`` a ball shows its number disc (white) round a dark digit."""
    layout = np.array([[0.6, 0.6], [1.2, 0.6]])
    env = PoolEnv(scene=layout, render_mode="rgb_array", model="roll")
    env.reset(seed=0)
    frame = env.render()
    renderer = env._get_renderer()
    assert renderer.ball_colours is None
    disc = _pixel(renderer, frame, layout[1] + [0.4 * 0.028575, 0.0])
    assert disc.min() > 180  # the white number disc of ball 1


def test_bad_colours_are_refused_naming_them():
    table = Table.preset("carom")
    with pytest.raises(ValueError, match=r"cloth must be an RGB triple.*\(300, 0, 0\)"):
        Renderer(table, cloth=(300, 0, 0))
    with pytest.raises(ValueError, match=r"ball_colours\[1\] must be an RGB triple.*'red'"):
        Renderer(table, ball_colours=[WHITE, "red", RED])

    class TooFew(CaromColours):
        name = "test_too_few_colours"
        ball_colours = (WHITE, YELLOW)

    register_game(TooFew(), replace=True)
    env = _env("test_too_few_colours", table, np.array([[0.7, 0.7], [1.4, 0.4], [2.1, 1.0]]))
    env.reset(seed=0)
    with pytest.raises(ValueError, match=r"ball_colours has 2 colours for 3 balls"):
        env.render()
