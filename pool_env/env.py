"""PoolEnv: the Gymnasium environment. One step is one shot, simulated exactly to rest.

The class is a front: the decision process is :mod:`pool_env.game` (its config, state and
``step``), run here on one table (B = 1); :class:`pool_env.PoolVectorEnv` runs the same on
many. What stays here is Gymnasium's API, the generator, and rendering.
"""

from __future__ import annotations

from typing import Any, ClassVar

import gymnasium as gym
import numpy as np
from numpy.typing import ArrayLike, NDArray

from pool_env.game import step as game
from pool_env.game.checks import check_actions, check_render, check_seed
from pool_env.game.config import (
    CUE,
    DEFAULT_BREAK_SPEED_RANGE,
    DEFAULT_SPEED_RANGE,
    AimMode,
    GameConfig,
    make_config,
)
from pool_env.game.info import potted_lookup, table_info
from pool_env.game.rack import rack_dict
from pool_env.game.rules import TERMINATED, TRUNCATED
from pool_env.game.scenes import SceneSpec
from pool_env.game.state import GameState, new_state
from pool_env.sim.result import ShotResult
from pool_env.sim.table import Table

_ONE = np.zeros(1, dtype=np.intp)  # the rows of the single table


class PoolEnv(gym.Env[NDArray[np.float32], NDArray[np.float32]]):
    r"""Pool: pot the object balls, one shot per step, on an exact event-based table simulator.

    ## Description

    A cue ball and ``n`` object balls lie on a pool table (a 9-ft table with six pockets by
    default). Each step is one shot: the action is decoded to a direction and a speed, the
    cue ball is struck, and the simulator runs the shot exactly to rest (rolling resistance,
    ball-ball and cushion impacts, pockets with jaws cut to the WPA specifications; no
    spin). The table's defaults are measured figures (:class:`~pool_env.Table`:
    ``mu_roll = 0.01``, ``e_ball = 0.95``, ``e_cushion = 0.65``), and so is the speed range
    (0.45 to 4.5 m/s, a slow shot to a power shot). ``table={"pockets": "circles"}`` gives
    the cheaper, far more generous capture circles. The goal is to pot every object ball.
    Ball ``0`` is the cue ball; object balls are numbered ``1..n``.

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

    Why ``cut`` is the default: the best action is a smooth function of the layout, and
    learners do better with it. On ``OneBall-v0`` (1000 episodes on seeds 10000+,
    ``results/agents.md``), PPO (300k steps, seed 0, the ghost-ball features) pots 63.4% of
    its shots with ``cut`` aim and 61.4% with ``relative`` (500 episodes); SAC (100k steps)
    90.1% and 81.4%. For scale: random actions pot 15.6%, a constant full hit at the top
    speed 26.7% (26.3% without a scratch), the best of 36 constant actions 27.5%, the
    geometric ghost-ball agent 95.3%.

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

    Set by ``scene`` (see :mod:`pool_env.game.scenes`): ``"one_ball"`` (cue and one object ball
    uniformly at random), ``"random"`` (cue and ``n_balls`` object balls uniformly at random,
    3 by default), ``"nine_ball"`` / ``"eight_ball"`` (the rack on the foot spot, the cue
    ball anywhere in the kitchen: the first shot is the break), a fixed ``(N, 2)`` layout, or
    a callable ``(table, np_random) -> (N, 2)``. Random layouts never overlap and keep out of
    the pockets. ``reset(options={"positions": ..., "on_table": ...})`` starts one episode
    from a given layout (``on_table`` optional; the cue ball must be on the table; every
    row must be finite, a ball off the table included: its row is kept as its position, so
    NaN is refused rather than handed back through ``positions``). ``options`` must be a
    dict (or ``None``); a seed is a non-negative Python or numpy integer, of any size.

    ## Episode End

    1. Termination: every object ball is potted (``info["is_success"]``).
    2. Termination, with ``end_on_miss=True``: the shot pots no object ball, or scratches
       (the turn passes).
    3. Truncation: ``max_episode_steps`` of the registered id (``TimeLimit``), or
       ``max_shots`` shots when given (the raw environment's own limit).

    ## Info

    ``potted`` (tuple of object balls potted by the shot), ``scratch`` (bool),
    ``first_contact`` (first ball the cue ball hit, -1 for none; under the rules, the one
    they read of balls met at the same instant), ``n_events`` (simulator
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
    | ``game`` | str | ``"solitaire"`` | ``"nine"`` or ``"eight"``: the rules (above) |
    | ``end_on_foul`` | bool | False | rules: a foul or a lost turn ends the episode |
    | ``break_speed_range`` | (float, float) | (8.0, 12.0) | rules: m/s of the break |
    | ``reward_foul`` | float | -1.0 | rules: for a foul |
    | ``reward_win`` | float | 1.0 | rules: for a won rack (minus for a lost one) |
    | ``render_mode`` | str or None | None | ``"rgb_array"``, ``"rgb_array_list"``, ``"human"`` |
    | ``render_width`` | int | 800 | frame width in pixels |

    Registered ids (``import pool_env``): ``pool_env/Pool-v0`` (these defaults, 50 shots),
    ``pool_env/OneBall-v0`` (``scene="one_ball"``, ``end_on_miss=True``: one shot per
    episode, since a pot clears the table and a miss ends the turn; 10 shots with
    ``end_on_miss=False``), ``pool_env/NineBall-v0`` (break, 50 shots) and
    ``pool_env/EightBall-v0`` (break, 80 shots), all solitaire;
    ``pool_env/NineBallGame-v0`` and ``pool_env/EightBallGame-v0`` under the rules (below).
    In ``SubprocVecEnv`` workers use the id ``"pool_env:pool_env/OneBall-v0"`` (or import
    ``pool_env`` in the main script), so that each worker imports the package that
    registers the ids.

    ## Rules: the game ids

    ``pool_env/NineBallGame-v0`` and ``pool_env/EightBallGame-v0`` (or ``game=`` with the
    ``nine_ball`` / ``eight_ball`` scene, or any layout of 9 / 15 object balls) play one rack
    under the WPA rules, compiled in :mod:`pool_env.game.kernels.wpa` (its docstring states
    every rule). One agent shoots every shot: a foul gives ball in hand to its next shot
    (practice mode, ``end_on_foul=False``), or ends the episode (run-out mode,
    ``end_on_foul=True``: so does a legal shot that does not keep the table). A rack scene
    starts with the break: the cue ball in hand behind the head string, the speed mapped
    onto ``break_speed_range`` (8 .. 12 m/s; a pro breaks at 11-13). Without ``noise`` a
    break from the same spot at the same speed is the same every episode.

    Enforced besides the fouls below: with the cue ball in hand behind the head string
    (the break, and after a scratch on the 8-ball break) the cue ball may not first meet a
    ball whose base lies behind the head string (``x < L / 4``; on the line it is
    playable) unless it crossed the line first (foul ``"kitchen_ball_first"``); a cue ball
    that meets several balls within 1e-9 s of its first contact gives the shooter the
    benefit (legal if any of them may be hit first, whatever their numbers); the 8 potted
    on a legal 8-ball break is re-spotted and the breaker continues.

    Simplifications that remain, all deliberate:

    * No push-out (9-ball), no called shots but the 8's pocket (any object ball potted
      counts), no called safeties, no warning before a third foul, no jump, masse or
      "bad cue ball" fouls (the simulator has no spin and no cue), no stalemate rule, no
      three-foul rule in 8-ball (WPA has none either).
    * An illegal break is a foul with ball in hand on the table as it lies (no re-rack or
      re-break choice); the 8 on a legal break is always re-spotted (no re-break choice).
    * Balls potted on a foul stay down, except the 9 (re-spotted) and the 8 (the rack is
      lost, or re-spotted on the break); a re-spotted ball goes on the foot spot or the
      free point nearest to it (WPA: on the long string behind it).
    * A pocket jaw counts as a cushion for "a ball touched a rail".
    * One foul reason per shot (the first in the order scratch, kitchen_ball_first,
      no_contact, wrong_ball_first, no_rail; on a break scratch, kitchen_ball_first,
      illegal_break).
    * One player: the agent is also the incoming player after its own fouls; a lost rack
      is a win of the absent opponent.
    * Reset's ``options["rules"]`` may only give racks the rules can finish: the 9 (the
      8) on the table, an open 8-ball table with a ball besides the 8, no groups on the
      break, fouls 0-2.

    Action ``Box(-1, 1, (5,), float32)``, each component mapped linearly:

    | Num | Action | -1 .. +1 maps to | used |
    |-----|--------|------------------|------|
    | 0 | aim | ``aim_range``, from the nearest legal ball (below) | always |
    | 1 | speed | ``speed_range``; on a break ``break_speed_range`` | always |
    | 2 | cue ball x | ``R .. L - R``; behind the head string ``R .. L / 4`` | cue ball in hand |
    | 3 | cue ball y | ``R .. W - R`` | cue ball in hand |
    | 4 | called pocket | six equal bins, pockets in ``table.pockets`` order | shooting at the 8 |

    Cut and relative aim refer to the nearest ball the rules let the cue ball hit first
    (not to the nearest ball). A placement on or next to a ball (closer than ``2R``) or in
    a pocket is moved to the free point nearest to it (:func:`pool_env.free_spot`),
    deterministically; the ball in hand is behind the head string on a break and after a
    scratch on the 8-ball break.

    Observation ``Box(-1, 1, (4 N - 1 + 7,), float32)`` (``N`` balls, cue included): the
    ``3 N`` ball entries above; then ``N - 1`` flags, one per object ball ``1..N-1``: the
    agent may hit it first (9-ball: the ball on; 8-ball: its group, any ball but the 8 on an
    open table, the 8 once the group is cleared, any ball on the break); then 7 entries:
    cue ball in hand, behind the head string only, the next shot is a break, open table
    (8-ball), the agent's successive fouls / 2, the opponent's / 2 (0 with one player),
    the agent shoots next (1 with one player). With these the game is Markov.

    Reward: ``reward_pot`` (+1) per object ball potted on a legal shot (a re-spotted ball
    and the 8 of 8-ball not counted), ``reward_foul`` (-1) for a foul, ``reward_win`` (+1)
    for winning the rack and ``-reward_win`` for losing it (three fouls in a row in
    9-ball; the 8 early, in an uncalled pocket, or on a foul). The episode terminates when
    the rack is decided (``info["is_success"]``: the agent won) and is truncated at the
    time limit (100 shots 9-ball, 150 8-ball).

    Info adds ``foul`` (``None`` or ``"scratch"``, ``"wrong_ball_first"``, ``"no_rail"``,
    ``"no_contact"``, ``"illegal_break"``, ``"kitchen_ball_first"``), ``legal``,
    ``ball_on`` (the ball on before the shot; -1 in 8-ball before the group is cleared),
    ``winner`` (-1 while undecided, 0 the agent, 1 its absent opponent: a lost rack; an
    integer rather than ``None`` so that vector envs keep one dtype per key), ``loss``
    (``None`` or ``"three_fouls"``, ``"eight_early"``, ``"eight_wrong_pocket"``,
    ``"eight_on_foul"``) and ``turn_over`` (a foul, or a shot that would pass the table to
    an opponent). ``env.unwrapped.rack``
    is the rack state; ``reset(options={"positions": ..., "on_table": ..., "rules":
    {...}})`` sets it (keys ``break``, ``ball_in_hand``, ``behind_head_string``,
    ``groups`` (``"open"``, ``"solids"``, ``"stripes"`` per player), ``fouls``; by default
    a given layout is not a break, with the cue ball where it lies and an open table).
    Two players: :mod:`pool_env.multiagent`.

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
    ``config`` (the parsed :class:`~pool_env.game.config.GameConfig`), ``table`` (the
    :class:`~pool_env.Table`), ``positions`` (``(N, 2)`` ball centres in
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

    Examples:
        >>> import numpy as np
        >>> from pool_env import PoolEnv
        >>> env = PoolEnv(scene="one_ball", end_on_miss=True)
        >>> obs, info = env.reset(seed=0)
        >>> obs.shape  # x, y and on-table flag of the cue ball and ball 1
        (6,)
        >>> obs, reward, terminated, truncated, info = env.step(np.array([0.0, 1.0]))
        >>> reward, info["potted"], info["first_contact"], terminated  # a full hit, hard
        (1.0, (1,), 1, True)
    """

    metadata: ClassVar[dict[str, Any]] = {
        "render_modes": ["human", "rgb_array", "rgb_array_list"],
        "render_fps": 2,  # rgb_array's; an instance carries its mode's (render.RENDER_FPS)
    }

    def __init__(
        self,
        table: Table | dict[str, Any] | None = None,
        scene: SceneSpec = "random",
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
        game: str = "solitaire",
        end_on_foul: bool = False,
        break_speed_range: tuple[float, float] = DEFAULT_BREAK_SPEED_RANGE,
        reward_foul: float = -1.0,
        reward_win: float = 1.0,
        render_mode: str | None = None,
        render_width: int = 800,
        model: str | None = None,
        tip_limit: float | None = None,
    ) -> None:
        self.render_width = check_render(render_mode, self.metadata["render_modes"], render_width)
        self.render_mode = render_mode
        if render_mode is not None:
            from pool_env.render import RENDER_FPS

            self.metadata = {**self.metadata, "render_fps": RENDER_FPS[render_mode]}
        self.config: GameConfig = make_config(
            table, scene, n_balls, aim, aim_range, speed_range, noise, end_on_miss, max_shots,
            reward_pot, reward_scratch, reward_no_contact, reward_shaping, game, 1, end_on_foul,
            break_speed_range, reward_foul, reward_win, model, tip_limit,
        )  # fmt: skip
        config = self.config
        self.game, self.end_on_foul = config.game, config.end_on_foul
        self.table = config.table
        self.aim: AimMode = config.aim
        self.aim_range, self.speed_range = config.aim_range, config.speed_range
        self.noise, self.end_on_miss = config.noise, config.end_on_miss
        self.max_shots, self.reward_weights = config.max_shots, config.reward_weights
        self.n_object_balls = config.n_object_balls
        self.cue = CUE
        n = config.n_balls
        self.observation_space = gym.spaces.Box(-1.0, 1.0, (config.observation_size,), np.float32)
        self.action_space = gym.spaces.Box(-1.0, 1.0, (config.action_size,), np.float32)
        self._record = render_mode is not None  # trajectories only when something draws them
        self._state: GameState = new_state(1, n)
        self._started = False
        self._potted_lut = potted_lookup(config.n_object_balls)
        self._last_shot: ShotResult | None = None
        self._last_strike: tuple[float, float, float, float] | None = None
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
        self._last_strike = None
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
        strike = result.shots[0].tolist()
        self._last_strike = (strike[0], strike[1], *(strike[2:] or (0.0, 0.0)))
        info = table_info(result, self._potted_lut)
        reward = result.rewards.item()
        flags = result.flags[0].tolist()
        terminated, truncated = flags[TERMINATED], flags[TRUNCATED]
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
        """Under rules: the rack state (:func:`pool_env.game.rack.rack_dict`), a new dict."""
        return rack_dict(self.config, self._state.rack[0])

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
        return self._last_strike

    @property
    def last_shot_balls(self) -> NDArray[np.int64]:
        """Ball numbers of the rows of :attr:`last_shot` (the balls that were on the table)."""
        return self._shot_balls.copy()

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
            trails = renderer.trails(self._last_shot, self._shot_balls)
        return renderer.frame(self.positions, self.on_table, trails=trails)

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
        return shot_frames(renderer, shot, self._shot_balls, fps, speed, max_seconds, min_frames)

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
