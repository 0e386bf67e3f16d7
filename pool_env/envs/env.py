"""PoolEnv: the Gymnasium environment. One step is one shot, simulated exactly to rest.

The class is a front: the decision process is :mod:`pool_env.game` (its config, state and
``step``), run here on one table (B = 1); :class:`pool_env.PoolVectorEnv` runs the same on
many. What stays here is Gymnasium's API, the generator, and rendering.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any, ClassVar

import gymnasium as gym
import numpy as np
from numpy.typing import ArrayLike, NDArray

from pool_env.envs.checks import check_render, check_seed
from pool_env.game import step as game
from pool_env.game.checks import check_actions
from pool_env.game.config import GameConfig, PoolConfig, make_config
from pool_env.game.info import potted_lookup, table_step
from pool_env.game.sections import resolve
from pool_env.game.state import GameState
from pool_env.sim.result import ShotResult

_ONE = np.zeros(1, dtype=np.intp)  # the rows of the single table


class PoolEnv(gym.Env[NDArray[np.float32], NDArray[np.float32]]):
    """Pool: pot the object balls, a shot per step, on an exact event-based table simulator.

    One step is one shot: the action (aim, speed; on the spin table, the default, also the
    cue tip; under rules also the cue ball's placement and a called pocket, in 10-ball a
    called ball, in 9-ball and 10-ball the option (push out, or hand the table back), each
    in ``[-1, 1]``) is played by the simulator to rest. The observation is each ball's
    ``(x, y, on_table)`` scaled to ``[-1, 1]`` (under rules, then the legal first balls and
    the rack state; with ``observation="shots"`` then the ghost-ball shot into each pocket:
    :func:`pool_env.obs_layout` names each part). The reward counts pots (and under rules
    fouls and the rack's result). The whole specification, with every ``info`` key, is
    ``docs/environments/specification.md``.

    The table, unless the config gives one, is the spin table that every
    ``pool_env/<Task>-v1`` id plays (``Table(model="spin")``:
    :data:`pool_env.game.sections.DEFAULT_MODEL`); ``model="roll"`` plays the roll table of
    the ``<Task>Roll-v1`` ids (no spin, no tip columns, a cheaper simulation).

    Args:
        config: The sectioned config (:class:`pool_env.PoolConfig`;
            ``None``: :func:`pool_env.default_config`).
        render_mode: ``"rgb_array"``, ``"rgb_array_list"``, ``"human"`` or ``None``.
        render_width: Frame width in pixels.
        id_defaults: The registered id's keywords, which ``gym.make`` passes (its scene,
            model, game...): they apply only when no ``config`` is given
            (:func:`pool_env.game.sections.resolve`).
        **overrides: Keys of the config, each overriding its section's (and the config's,
            when one is given):

            * table: ``table`` (a :class:`~pool_env.Table` or a dict of its
              arguments), ``model`` (``"spin"``, the default, or ``"roll"``);
            * task: ``scene``, ``n_balls``, ``rack_order`` (``"random"``: a rack scene
              racked as the WPA rules rack it, drawn by each reset; ``"fixed"``), ``aim``
              (``"cut"``, ``"relative"``, ``"absolute"``), ``aim_range``, ``observation``
              (``"balls"``, or ``"shots"``: per pocket the ghost-ball shot appended),
              ``speed_range`` (m/s), ``tip_limit`` (spin, fraction of R),
              ``end_on_miss``, ``max_shots``;
            * noise: ``noise`` (sigmas: rad, m/s and on a spin table the tip's, in R; or
              ``"fastfiz"`` / ``("fastfiz", k)``: the computer billiards championships'
              model times ``k``, :mod:`pool_env.game.noise`);
            * rules: ``game`` (``"solitaire"``, ``"nine"``, ``"ten"``, ``"eight"``, or a
              game of :func:`pool_env.game.registry.register_game`); the WPA games add
              ``end_on_foul`` and ``break_speed_range``;
            * rewards: ``reward_<term>`` per term of the game (solitaire: ``reward_pot``,
              ``reward_scratch``, ``reward_no_contact``, ``reward_shaping``; the WPA
              games: ``reward_pot``, ``reward_foul``, ``reward_win``), or ``rewards`` (a
              mapping of terms to scales).

            A section's name (``task``, ``rules``, ...) takes the section or a mapping of
            its keys.

    Raises:
        ValueError: On an unknown key or a bad value, naming it (never at a reset).

    Examples:
        >>> import numpy as np
        >>> from pool_env import PoolEnv
        >>> env = PoolEnv(scene="one_ball", end_on_miss=True)  # the spin table
        >>> obs, info = env.reset(seed=0)
        >>> obs.shape  # x, y and on-table flag of the cue ball and ball 1
        (6,)
        >>> env.action_space.shape  # aim, speed, the cue tip's side and height
        (4,)
        >>> obs, reward, terminated, truncated, info = env.step(np.array([0.0, 1.0, 0.0, -0.5]))
        >>> reward, info["potted"], info["first_contact"], terminated  # full, hard, with draw
        (1.0, (1,), 1, True)
        >>> _ = env.reset(seed=0)  # the same shot hit in the centre: the cue ball follows in
        >>> _, reward, *_, info = env.step(np.array([0.0, 1.0, 0.0, 0.0]))
        >>> reward, info["potted"], info["scratch"]
        (0.0, (1,), True)
    """

    metadata: ClassVar[dict[str, Any]] = {
        "render_modes": ["human", "rgb_array", "rgb_array_list"],
        "render_fps": 2,  # rgb_array's; an instance carries its mode's (render.RENDER_FPS)
    }

    def __init__(
        self,
        config: PoolConfig | None = None,
        *,
        render_mode: str | None = None,
        render_width: int = 800,
        id_defaults: Mapping[str, Any] | None = None,
        **overrides: Any,
    ) -> None:
        self.render_width = check_render(render_mode, self.metadata["render_modes"], render_width)
        self.render_mode = render_mode
        if render_mode is not None:
            from pool_env.render import RENDER_FPS

            self.metadata = {**self.metadata, "render_fps": RENDER_FPS[render_mode]}
        self.config: GameConfig = make_config(resolve(config, overrides, id_defaults), 1)
        config = self.config
        n = config.n_balls
        self.observation_space = gym.spaces.Box(-1.0, 1.0, (config.observation_size,), np.float32)
        self.action_space = gym.spaces.Box(-1.0, 1.0, (config.action_size,), np.float32)
        self._record = render_mode is not None  # trajectories only when something draws them
        self._state: GameState = self.config.new_state(1)
        self._started = False
        self._potted_lut = potted_lookup(config.n_object_balls)
        self._last_shot: ShotResult | None = None
        self._last_shots: NDArray[np.float64] | None = None  # the step's executed shot row
        self._shot_balls = np.arange(n)
        self._renderer: Any = None
        self._window: Any = None
        self._frames: list[NDArray[np.uint8]] = []  # rgb_array_list: since the last render()

    # -- Gymnasium API --------------------------------------------------------------------

    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[NDArray[np.float32], dict[str, Any]]:
        """Start an episode: a new layout from the scene, or ``options["positions"]``."""
        if seed is not None:  # a ValueError, as the vector env's, before anything changes;
            seed = check_seed(seed)  # a numpy integer becomes the int Gymnasium requires
        super().reset(seed=seed)
        self._use_generator()
        game.reset(self.config, self._state, _ONE, options)
        self._started = True
        self._last_shot = None
        self._last_shots = None
        if self.render_mode == "human":
            self.render()
        elif self.render_mode == "rgb_array_list":
            self._frames = [self._frame()]
        return self._observation(), {}

    def step(
        self, action: ArrayLike
    ) -> tuple[NDArray[np.float32], float, bool, bool, dict[str, Any]]:
        """Play one shot to rest; see the class docstring for the action, reward and end."""
        if not self._started:
            raise RuntimeError("call reset() before step()")
        actions = check_actions(action, 1, single=True, width=self.config.action_size)
        self._use_generator()
        result = game.step(self.config, self._state, _ONE, actions, record=self._record)
        self._last_shot, self._shot_balls = result.shot, result.balls
        self._last_shots = result.shots  # read by last_strike: a new array every step
        reward, terminated, truncated, info = table_step(result, self._potted_lut)
        if self.render_mode == "human":
            self.render()
        elif self.render_mode == "rgb_array_list":
            from pool_env.render import LIST_PLAYBACK, RENDER_FPS

            self._frames += self.shot_frames(RENDER_FPS["rgb_array_list"], **LIST_PLAYBACK)
        return self._observation(), reward, terminated, truncated, info

    # -- state ----------------------------------------------------------------------------

    def _use_generator(self) -> None:
        """Draw layouts and noise from ``self.np_random`` (Gymnasium may have replaced it)."""
        rng = self.np_random
        if rng is not self._state.generators[0]:
            self._state.use_generator(0, rng)

    def _observation(self) -> NDArray[np.float32]:
        return game.observe(self.config, self._state)[0]

    def _require_reset(self) -> None:
        if not self._started:
            raise RuntimeError("call reset() first")

    @property
    def positions(self) -> NDArray[np.float64]:
        """``(N, 2)`` ball centres in metres, cue first (a potted ball: where it was captured)."""
        self._require_reset()
        return self._state.positions[0].copy()

    @property
    def on_table(self) -> NDArray[np.bool_]:
        """``(N,)`` booleans: which balls are on the table, cue first."""
        return self._state.on_table[0].copy()

    @property
    def shots(self) -> int:
        """Shots played in this episode."""
        return int(self._state.shots[0])

    @property
    def rack(self) -> dict[str, Any]:
        """Under rules: the rack state (the game's ``Ruleset.state_dict``), a new dict."""
        return self.config.ruleset.state_dict(self._state.rack[0])

    @property
    def last_shot(self) -> ShotResult | None:
        """The :class:`~pool_env.ShotResult` of the last step (rows: ``last_shot_balls``).

        The simulator's result, not the environment's state: changing it changes nothing.
        """
        return self._last_shot

    @property
    def last_strike(self) -> tuple[float, float, float, float] | None:
        """The last shot as executed: ``(angle, speed, tip_side, tip_vertical)``, or None.

        After noise and the miscue limit: the cue's aim (radians from +x; on a spin table
        the ball leaves at it plus the squirt), the cue ball's speed (m/s) and the tip's
        axis offset (fractions of R; ``0.0, 0.0`` on a roll table). ``None`` before the
        first shot of an episode.
        """
        if self._last_shots is None:
            return None
        strike = self._last_shots[0].tolist()
        return (strike[0], strike[1], *(strike[2:] or (0.0, 0.0)))

    @property
    def last_shot_balls(self) -> NDArray[np.int64]:
        """Ball numbers of the rows of :attr:`last_shot` (the balls that were on the table)."""
        return self._shot_balls.copy()

    # -- rendering ------------------------------------------------------------------------

    def _get_renderer(self) -> Any:
        if self._renderer is None:
            from pool_env.render import Renderer

            self._renderer = Renderer.for_config(self.config, self.render_width)
        return self._renderer

    def _frame(self) -> NDArray[np.uint8]:
        from pool_env.render import trails

        renderer = self._get_renderer()
        paths = None
        if self._last_shot is not None and self._last_shot.recorded:
            paths = trails(self._last_shot, self._shot_balls)
        return renderer.frame(self.positions, self.on_table, trails=paths)

    def render(self) -> NDArray[np.uint8] | list[NDArray[np.uint8]] | None:
        """The frame(s) of the render mode (``docs/environments/specification.md``, "Rendering").

        ``rgb_array``: the current frame with the last shot's trails; ``rgb_array_list``:
        every frame since the last call (the shots animated); ``human``: animate the shot.
        ``None`` without a render mode (with a warning).
        """
        if self.render_mode is None:
            gym.logger.warn("render() called without a render_mode; pass render_mode='rgb_array'")
            return None
        if self.render_mode == "rgb_array":
            return self._frame()
        if self.render_mode == "rgb_array_list":
            frames, self._frames = self._frames, []
            return frames
        from pool_env.render import Window

        if self._window is None:
            renderer = self._get_renderer()
            self._window = Window(renderer.size, "pool_env")
        if self._last_shot is not None and self._last_shot.recorded:
            self._window.play(self.shot_frames(), fps=self.metadata["render_fps"])
        self._window.show(self._frame())
        return None

    def shot_frames(
        self,
        fps: int = 30,
        speed: float = 1.0,
        max_seconds: float = 8.0,
        min_frames: int = 2,
        lead_in: bool = True,
    ) -> list[NDArray[np.uint8]]:
        """Frames of the last shot: the cue stick at its aim, then the exact trajectories.

        Args:
            fps: Frames per second of playback.
            speed: Playback speed (1 is real time).
            max_seconds: Longer shots are sped up to fit in this playback time.
            min_frames: At least this many frames of the balls moving (shorter shots are
                slowed down).
            lead_in: Start with 0.6 s of the stick behind the cue ball along the aim of
                :attr:`last_strike` (held drawn back, then stroking to the ball; shifted
                sideways by the side offset), and on a spin table a ball face in a corner
                with a dot where the tip hits (:mod:`pool_env.render.cue`).

        Returns:
            The lead-in, then frames from the strike until everything rests, sliding curves
            included (the last frame shows a scratched cue ball in the pocket;
            :meth:`render` shows it re-spotted).

        Raises:
            ValueError: Without a render mode (no trajectories were kept) or before a shot.
        """
        from pool_env.render import shot_frames

        shot = self._last_shot
        if shot is None or not shot.recorded:
            raise ValueError("no recorded shot: create the env with a render_mode and step() first")
        renderer = self._get_renderer()
        strike = self.last_strike if lead_in else None
        return shot_frames(
            renderer, shot, self._shot_balls, fps, speed, max_seconds, min_frames, strike
        )

    def save_shot(
        self,
        path: str,
        fps: int = 30,
        speed: float = 1.0,
        max_seconds: float = 8.0,
        lead_in: bool = True,
    ) -> None:
        """Write the animation of the last shot to ``path`` (``.gif`` or ``.mp4``).

        Its frames are :meth:`shot_frames`' (``lead_in``: the cue stick first).
        """
        from pool_env.render import save_animation

        save_animation(self.shot_frames(fps, speed, max_seconds, lead_in=lead_in), path, fps)

    def close(self) -> None:
        """Close the window, if any."""
        if self._window is not None:
            self._window.close()
            self._window = None

    def __getstate__(self) -> dict[str, Any]:
        state = self.__dict__.copy()
        state["_window"] = None  # a window belongs to this process; the renderer is rebuilt
        state["_renderer"] = None
        return state
