"""PoolEnv: the Gymnasium environment. One step is one shot, simulated exactly to rest.

The class holds state and glue only: the action decoding, observation encoding and reward
are the pure functions of :mod:`pool_env.mdp`, the layouts those of :mod:`pool_env.scenes`,
so that a batched environment can reuse them.
"""

from __future__ import annotations

import math
from typing import Any, ClassVar

import gymnasium as gym
import numpy as np
from numpy.typing import ArrayLike, NDArray

from pool_env import checks, scenes
from pool_env.mdp import (
    AIM_MODES,
    DEFAULT_AIM_RANGE,
    DEFAULT_SPEED_RANGE,
    AimMode,
    check_action,
    decode_shots,
    encode_observations,
    pocket_potentials,
    shot_rewards,
)
from pool_env.sim.result import ShotResult
from pool_env.sim.simulate import shoot
from pool_env.sim.table import Table


class PoolEnv(gym.Env[NDArray[np.float32], NDArray[np.float32]]):
    r"""Pool: pot the object balls, one shot per step, on an exact event-based table simulator.

    ## Description

    A cue ball and ``n`` object balls lie on a pool table (a 9-ft table with six pockets by
    default). Each step is one shot: the action is decoded to a direction and a speed, the
    cue ball is struck, and the simulator runs the shot exactly to rest (rolling resistance,
    ball-ball and cushion impacts, pockets as capture circles; no spin). The goal is to pot
    every object ball. Ball ``0`` is the cue ball; object balls are numbered ``1..n``.

    ## Action Space

    ``Box(-1, 1, (2,), float32)``, each component mapped linearly onto a range:

    | Num | Action | -1 maps to | +1 maps to | default range |
    |-----|--------|------------|------------|---------------|
    | 0   | aim    | ``aim_range[0]`` | ``aim_range[1]`` | by ``aim``, below |
    | 1   | speed  | ``speed_range[0]`` | ``speed_range[1]`` | 0.45 .. 4.5 m/s |

    The speed is the cue ball's, from a slow shot to a power shot (the speeds real play uses). The
    aim is relative to the nearest object ball on the table, or absolute, by ``aim``:

    * ``"cut"`` (default): where the cue ball meets the nearest object ball, as the offset
      of its path from that ball's centre in ball diameters; default -1 .. 1 (0 is a full
      hit, +-1 a grazing one; +1 passes on the counter-clockwise side). The object ball
      leaves at ``asin(offset)`` from the cue ball's line whatever the distance, so the
      best action is a smooth function of the layout, and every action in (-1, 1) hits the
      ball (unless another ball is in the way).
    * ``"relative"``: radians, counter-clockwise, from the line joining the cue ball to the
      nearest object ball; default +-10 degrees. Action 0 hits that ball full too, but the
      angle a cut needs shrinks with the distance (``~2R sin(cut) / d``), so the best
      action is a steep function of the layout.
    * ``"absolute"``: radians from the table's +x axis (its length); default +-pi.

    Why ``cut`` is the default: PPO (SB3 defaults but ``gamma=0``, 8 envs, 200k steps, two
    seeds) on ``OneBall-v0`` pots 71% of its shots (64% without a scratch) with ``cut`` aim,
    and 10-11% with ``relative``. Note that a constant full hit at the top speed already
    pots ~81% (66% without a scratch) on ``OneBall-v0``: see ``results/agents.md``.

    Out-of-range actions (infinities included) are clipped to ``[-1, 1]``. An action with a
    NaN raises ``ValueError`` and changes nothing. With ``noise=(sigma_angle, sigma_speed)``
    Gaussian execution noise (radians, m/s; from ``self.np_random``) is added to the shot's
    direction and speed (the speed is then clipped at 0).

    ## Observation Space

    ``Box(-1, 1, (3 (n + 1),), float32)``: for each ball, in the fixed order cue, 1, ..., n:

    | Num       | Observation                     | Min | Max | potted ball |
    |-----------|---------------------------------|-----|-----|-------------|
    | 3 k       | ball k: x scaled, 2 x / L - 1    | -1  | 1   | 0           |
    | 3 k + 1   | ball k: y scaled, 2 y / W - 1    | -1  | 1   | 0           |
    | 3 k + 2   | ball k on the table (1) or not (0) | 0 | 1   | 0           |

    ``L``, ``W`` are the table's length and width; the origin is a corner of the playing
    surface. Exact positions in metres are ``env.unwrapped.positions``.

    ## Rewards

    ``reward_pot`` (+1) for each object ball the shot pots and ``reward_scratch`` (-1) when the
    cue ball is potted (a scratch: the cue ball is put back on the head spot, or the free
    point nearest to it). Optional shaping, off by default: ``reward_no_contact`` when the
    cue ball touches no ball, and ``reward_shaping`` times the change of the potential
    ``-sum(distance of each object ball to its nearest pocket) / table diagonal`` (potential
    based, so it does not change which policies are optimal for an undiscounted return).

    ## Starting State

    Set by ``scene`` (see :mod:`pool_env.scenes`): ``"one_ball"`` (cue and one object ball
    uniformly at random), ``"random"`` (cue and ``n_balls`` object balls uniformly at random,
    3 by default), ``"nine_ball"`` / ``"eight_ball"`` (the rack on the foot spot, the cue
    ball anywhere in the kitchen: the first shot is the break), a fixed ``(N, 2)`` layout, or
    a callable ``(table, np_random) -> (N, 2)``. Random layouts never overlap and keep out of
    the pockets. ``reset(options={"positions": ..., "on_table": ...})`` starts one episode
    from a given layout (``on_table`` optional; the cue ball must be on the table).

    ## Episode End

    1. Termination: every object ball is potted (``info["is_success"]``).
    2. Termination, with ``end_on_miss=True``: the shot pots no object ball, or scratches
       (the turn passes).
    3. Truncation: ``max_episode_steps`` of the registered id (``TimeLimit``), or
       ``max_shots`` shots when given (the raw environment's own limit).

    ## Info

    ``potted`` (tuple of object balls potted by the shot), ``scratch`` (bool),
    ``first_contact`` (first ball the cue ball hit, -1 for none), ``n_events`` (simulator
    events), ``hit_event_cap`` (bool), ``angle`` and ``speed`` (the executed shot, radians
    from +x and m/s), ``is_success`` (the table is cleared). ``reset`` returns ``{}``.

    ## Arguments

    | Parameter | Type | Default | Description |
    |---|---|---|---|
    | ``table`` | Table, dict or None | ``Table()`` | the table, or ``Table`` keyword arguments |
    | ``scene`` | str, array or callable | ``"random"`` | starting layout (above) |
    | ``n_balls`` | int or None | scene's | object balls (``"random"``: 1..15, default 3) |
    | ``aim`` | str | ``"cut"`` | ``"cut"``, ``"relative"`` or ``"absolute"`` |
    | ``aim_range`` | (float, float) | by ``aim`` | what action[0] = -1 and +1 map to |
    | ``speed_range`` | (float, float) | (0.45, 4.5) | m/s for action -1 and +1 |
    | ``noise`` | (float, float) or None | None | execution noise sigmas (rad, m/s) |
    | ``end_on_miss`` | bool | False | a shot that pots nothing ends the episode |
    | ``max_shots`` | int or None | None | truncate the raw env after this many shots |
    | ``reward_pot`` | float | 1.0 | per object ball potted |
    | ``reward_scratch`` | float | -1.0 | when the cue ball is potted |
    | ``reward_no_contact`` | float | 0.0 | when the cue ball hits no ball |
    | ``reward_shaping`` | float | 0.0 | weight of the pocket-distance potential |
    | ``render_mode`` | str or None | None | ``"rgb_array"``, ``"rgb_array_list"``, ``"human"`` |
    | ``render_width`` | int | 800 | frame width in pixels |

    Registered ids (``import pool_env``): ``pool_env/Pool-v0`` (these defaults, 50 shots),
    ``pool_env/OneBall-v0`` (``scene="one_ball"``, ``end_on_miss=True``: one shot per
    episode, since a pot clears the table and a miss ends the turn; 10 shots with
    ``end_on_miss=False``), ``pool_env/NineBall-v0`` (break, 50 shots) and
    ``pool_env/EightBall-v0`` (break, 80 shots). In ``SubprocVecEnv`` workers use the id
    ``"pool_env:pool_env/OneBall-v0"`` (or import ``pool_env`` in the main script), so that
    each worker imports the package that registers the ids.

    ## Rendering

    ``"rgb_array"``: ``render()`` returns an ``(H, W, 3)`` uint8 top-down frame: the balls at
    rest, with the paths of the last shot drawn as trails, so ``RecordVideo`` shows each
    shot as one frame (``render_fps`` is 2: half a second per shot). ``"rgb_array_list"``:
    ``render()`` returns every frame since the last call: the layout at reset, then each shot
    sampled from its exact trajectories at ``render_fps`` 30 (twice real time, at most 4 s,
    at least 20 frames a shot; :data:`pool_env.render.LIST_PLAYBACK`). Gymnasium's
    ``RecordVideo`` keeps one frame per step of a list; :class:`pool_env.record.RecordShots`
    keeps them all, and ``gymnasium.utils.save_video.save_video(env.render(), ...)`` writes
    them too. ``"human"``: a pygame window (``pip install "pool_env[render]"``) that animates
    each shot (off screen, silently, on a machine without a display). With a render mode,
    shots keep their trajectories: ``shot_frames()`` samples the last shot for an animation
    and ``save_shot(path)`` writes it as GIF or MP4.

    ## Attributes

    Of the unwrapped environment (``env.unwrapped``), for agents and tools:
    ``table`` (the :class:`~pool_env.sim.table.Table`), ``positions`` (``(N, 2)`` ball centres in
    metres, cue first; a copy), ``on_table`` (``(N,)`` booleans), ``cue`` (0), ``aim``,
    ``aim_range``, ``speed_range``, ``noise``, ``n_object_balls``, ``end_on_miss``,
    ``max_shots``, ``reward_weights`` (pot, scratch, no contact, shaping), ``shots`` (this
    episode), ``last_shot`` (the :class:`~pool_env.sim.result.ShotResult`, rows in the order of
    ``last_shot_balls``).

    Physics note: rolling resistance is low (``mu_roll = 0.01``: a ball at 3 m/s rolls 46 m
    if nothing stops it), but the pockets have jaws: a ball drops only through a pocket's
    opening at an angle the jaws accept (about 8.5 cm straight into a side pocket, nothing
    beyond ~70 degrees), so aiming and speed control are what pot balls.

    ## Version History

    * v0: Initial version.
    """

    metadata: ClassVar[dict[str, Any]] = {
        "render_modes": ["human", "rgb_array", "rgb_array_list"],
        "render_fps": 2,  # rgb_array's; an instance carries its mode's (render.RENDER_FPS)
    }

    def __init__(
        self,
        table: Table | dict[str, Any] | None = None,
        scene: scenes.SceneSpec = "random",
        n_balls: int | None = None,
        aim: AimMode = "cut",
        aim_range: tuple[float, float] | None = None,
        speed_range: tuple[float, float] = DEFAULT_SPEED_RANGE,
        noise: tuple[float, float] | None = None,
        end_on_miss: bool = False,
        max_shots: int | None = None,
        reward_pot: float = 1.0,
        reward_scratch: float = -1.0,
        reward_no_contact: float = 0.0,
        reward_shaping: float = 0.0,
        render_mode: str | None = None,
        render_width: int = 800,
    ) -> None:
        self.table = checks.parse_table(table)
        if aim not in AIM_MODES:
            raise ValueError(f"aim must be one of {list(AIM_MODES)}, got {aim!r}")
        self.aim: AimMode = aim
        self._aim_code = AIM_MODES.index(aim)
        self.aim_range = checks.parse_range("aim_range", aim_range or DEFAULT_AIM_RANGE[aim], None)
        self.speed_range = checks.parse_range("speed_range", speed_range, 0.0)
        self.noise = checks.parse_noise(noise)
        self.end_on_miss = checks.parse_bool("end_on_miss", end_on_miss)
        self.max_shots = checks.parse_count("max_shots", max_shots)
        self.reward_weights = tuple(
            checks.parse_float(name, value)
            for name, value in (
                ("reward_pot", reward_pot),
                ("reward_scratch", reward_scratch),
                ("reward_no_contact", reward_no_contact),
                ("reward_shaping", reward_shaping),
            )
        )
        if render_mode is not None and render_mode not in self.metadata["render_modes"]:
            modes = self.metadata["render_modes"]
            raise ValueError(f"render_mode must be one of {modes} or None, got {render_mode!r}")
        self.render_mode = render_mode
        if render_mode is not None:
            from pool_env.render import RENDER_FPS

            self.metadata = {**self.metadata, "render_fps": RENDER_FPS[render_mode]}
        self.render_width = checks.parse_count("render_width", render_width) or 800
        if self.render_width < 64:
            raise ValueError(f"render_width must be at least 64 pixels, got {render_width!r}")
        self._sample, self.n_object_balls = scenes.make_sampler(scene, self.table, n_balls)

        n = self.n_object_balls + 1
        self.observation_space = gym.spaces.Box(-1.0, 1.0, (3 * n,), np.float32)
        self.action_space = gym.spaces.Box(-1.0, 1.0, (2,), np.float32)
        self.cue = 0
        self._record = render_mode is not None  # trajectories only when something draws them
        self._diagonal = math.hypot(self.table.length, self.table.width)
        self._positions: NDArray[np.float64] | None = None
        self._on_table = np.ones(n, dtype=bool)
        self._rows = np.arange(n)  # balls on the table, cue first: the rows the simulator sees
        self._n_left = n - 1
        self._shots = 0
        self._last_shot: ShotResult | None = None
        self._shot_rows = self._rows
        self._renderer: Any = None
        self._window: Any = None
        self._frames: list[NDArray[np.uint8]] = []  # rgb_array_list: since the last render()

    # -- Gymnasium API --------------------------------------------------------------------

    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[NDArray[np.float32], dict[str, Any]]:
        """Start an episode: a new layout from the scene, or ``options["positions"]``."""
        super().reset(seed=seed)
        n = self.n_object_balls + 1
        on_table = np.ones(n, dtype=bool)
        if options:
            unknown = set(options) - {"positions", "on_table"}
            if unknown:
                raise ValueError(
                    f"unknown reset options {sorted(unknown)}: use 'positions', 'on_table'"
                )
        if options and "positions" in options:
            positions = np.array(options["positions"], dtype=np.float64)
            if positions.shape != (n, 2):
                raise ValueError(
                    f"options['positions'] must have shape ({n}, 2), got {positions.shape}"
                )
            if options.get("on_table") is not None:
                on_table = np.array(options["on_table"], dtype=bool)
                if on_table.shape != (n,) or not on_table[0]:
                    raise ValueError(
                        f"options['on_table'] must be ({n},) booleans with the cue (0) True"
                    )
            scenes.check_layout(self.table, positions[on_table])
        elif options and "on_table" in options:
            raise ValueError("options['on_table'] needs options['positions']")
        else:
            positions = self._sample(self.np_random)
        self._set_state(positions, on_table)
        self._shots = 0
        self._last_shot = None
        if self.render_mode == "human":
            self.render()
        elif self.render_mode == "rgb_array_list":
            self._frames = [self._frame()]
        return self._observation(), {}

    def step(
        self, action: ArrayLike
    ) -> tuple[NDArray[np.float32], float, bool, bool, dict[str, Any]]:
        """Play one shot to rest; see the class docstring for the action, reward and end."""
        positions = self._positions
        if positions is None:
            raise RuntimeError("call reset() before step()")
        angles, speeds = decode_shots(
            check_action(action)[None],
            positions[None],
            self._on_table[None],
            self.cue,
            self._aim_code,
            self.table.ball_radius,
            self.aim_range,
            self.speed_range,
        )
        angle, speed = float(angles[0]), float(speeds[0])
        if self.noise is not None:
            angle += self.noise[0] * float(self.np_random.standard_normal())
            speed = max(0.0, speed + self.noise[1] * float(self.np_random.standard_normal()))

        rows = self._rows
        all_on = rows.shape[0] == positions.shape[0]
        shaping = self.reward_weights[3] != 0.0
        phi_before = self._potential() if shaping else 0.0
        result = shoot(
            self.table, positions if all_on else positions[rows], angle, speed, record=self._record
        )
        # The state never aliases an array that a ShotResult (or a caller) may hold.
        if all_on:
            new = result.positions  # a fresh array from the simulator
        else:
            new = positions.copy()
            new[rows] = result.positions
        self._last_shot, self._shot_rows = result, rows
        self._shots += 1

        # Plain lists: for a handful of balls they beat numpy's per-call overhead.
        pocketed = result.pocketed.tolist()
        potted: tuple[int, ...] = ()
        scratch = False
        if max(pocketed) >= 0:
            balls = [b for b, k in zip(rows.tolist(), pocketed, strict=True) if k >= 0]
            on_table = self._on_table = self._on_table.copy()
            on_table[balls] = False
            scratch = balls[0] == self.cue
            potted = tuple(balls[1:] if scratch else balls)
            self._n_left -= len(potted)
            if scratch:  # back on the head spot, or the free point nearest to it
                if new is result.positions:
                    new = new.copy()
                new[self.cue] = scenes.free_spot(self.table, new, on_table)
                on_table[self.cue] = True
            self._rows = on_table.nonzero()[0]
        self._positions = new
        contact = result.first_contact
        first = -1 if contact is None else int(rows[contact[1] if contact[0] == 0 else contact[0]])
        phi_change = self._potential() - phi_before if shaping else 0.0
        reward = float(
            shot_rewards(len(potted), scratch, first < 0, phi_change, self.reward_weights)
        )

        cleared = self._n_left == 0
        terminated = cleared or (self.end_on_miss and (not potted or scratch))
        truncated = self.max_shots is not None and self._shots >= self.max_shots
        info = {
            "potted": potted,
            "scratch": scratch,
            "first_contact": first,
            "n_events": result.n_events,
            "hit_event_cap": result.hit_event_cap,
            "angle": angle,
            "speed": speed,
            "is_success": cleared,
        }
        if self.render_mode == "human":
            self.render()
        elif self.render_mode == "rgb_array_list":
            from pool_env.render import LIST_PLAYBACK, RENDER_FPS

            self._frames += self.shot_frames(RENDER_FPS["rgb_array_list"], **LIST_PLAYBACK)
        return self._observation(), reward, terminated, truncated, info

    # -- state ----------------------------------------------------------------------------

    def _set_state(self, positions: NDArray[np.float64], on_table: NDArray[np.bool_]) -> None:
        self._positions = np.ascontiguousarray(positions, dtype=np.float64)
        self._on_table = on_table
        self._rows = on_table.nonzero()[0]
        self._n_left = len(self._rows) - 1  # object balls on the table

    def _observation(self) -> NDArray[np.float32]:
        table = self.table
        return encode_observations(
            self._positions[None], self._on_table[None], table.length, table.width
        )[0]

    def _potential(self) -> float:
        pos, on = self._positions[None], self._on_table[None]
        return float(pocket_potentials(pos, on, self.table.pockets, self._diagonal)[0])

    @property
    def positions(self) -> NDArray[np.float64]:
        """``(N, 2)`` ball centres in metres, cue first (a potted ball: where it was captured)."""
        if self._positions is None:
            raise RuntimeError("call reset() first")
        return self._positions.copy()

    @property
    def on_table(self) -> NDArray[np.bool_]:
        """``(N,)`` booleans: which balls are on the table, cue first."""
        return self._on_table.copy()

    @property
    def shots(self) -> int:
        """Shots played in this episode."""
        return self._shots

    @property
    def last_shot(self) -> ShotResult | None:
        """The :class:`~pool_env.ShotResult` of the last step (rows: ``last_shot_balls``)."""
        return self._last_shot

    @property
    def last_shot_balls(self) -> NDArray[np.int64]:
        """Ball numbers of the rows of :attr:`last_shot` (the balls that were on the table)."""
        return self._shot_rows.copy()

    # -- rendering ------------------------------------------------------------------------

    def _get_renderer(self) -> Any:
        if self._renderer is None:
            from pool_env.render import Renderer

            self._renderer = Renderer(self.table, self.render_width)
        return self._renderer

    def _frame(self) -> NDArray[np.uint8]:
        renderer = self._get_renderer()
        trails = None
        if self._last_shot is not None and self._last_shot.recorded:
            trails = renderer.trails(self._last_shot, self._shot_rows)
        return renderer.frame(self.positions, self._on_table, trails=trails)

    def render(self) -> NDArray[np.uint8] | list[NDArray[np.uint8]] | None:
        """The frame(s) of the render mode (see the class docstring, Rendering).

        ``rgb_array``: the current frame with the last shot's trails; ``rgb_array_list``:
        every frame since the last call (the shots animated); ``human``: animate the shot.
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
        self, fps: int = 30, speed: float = 1.0, max_seconds: float = 8.0, min_frames: int = 2
    ) -> list[NDArray[np.uint8]]:
        """Frames of the last shot sampled from its exact trajectories.

        Args:
            fps: Frames per second of playback.
            speed: Playback speed (1 is real time).
            max_seconds: Longer shots are sped up to fit in this playback time.
            min_frames: At least this many frames (shorter shots are slowed down).

        Returns:
            Frames from the strike until everything rests (the last frame shows a scratched
            cue ball in the pocket; :meth:`render` shows it re-spotted).

        Raises:
            ValueError: Without a render mode (no trajectories were kept) or before a shot.
        """
        from pool_env.render import shot_frames

        shot = self._last_shot
        if shot is None or not shot.recorded:
            raise ValueError("no recorded shot: create the env with a render_mode and step() first")
        renderer = self._get_renderer()
        return shot_frames(renderer, shot, self._shot_rows, fps, speed, max_seconds, min_frames)

    def save_shot(
        self, path: str, fps: int = 30, speed: float = 1.0, max_seconds: float = 8.0
    ) -> None:
        """Write the animation of the last shot to ``path`` (``.gif`` or ``.mp4``)."""
        from pool_env.render import save_animation

        save_animation(self.shot_frames(fps, speed, max_seconds), path, fps)

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
