"""The ``human`` render mode's window (pygame), and whether a display exists."""

from __future__ import annotations

import os
import sys

import numpy as np

from pool_env.extras import require
from pool_env.render.palette import Frame


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
        pygame = require("pygame", "render", 'render_mode="human"', DependencyNotInstalled)
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
