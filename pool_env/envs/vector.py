"""PoolVectorEnv: many pool tables stepped together, one compiled batch of shots per step.

A front, as :class:`pool_env.PoolEnv` is: the decision process is :mod:`pool_env.game`
(config, state, ``step``), run here on ``num_envs`` tables at once. What stays here is
Gymnasium's vector API: autoreset, per-table seeding, the batched info layout, rendering.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any, ClassVar

import gymnasium as gym
import numpy as np
from gymnasium.vector import AutoresetMode, VectorEnv
from gymnasium.vector.utils import batch_space
from numpy.typing import ArrayLike, NDArray

from pool_env.envs.checks import check_render, check_reset_mask, check_seeds
from pool_env.envs.seeding import seed_table, seeded_generators
from pool_env.game import step as game
from pool_env.game.checks import check_actions, check_options, parse_count
from pool_env.game.config import GameConfig, PoolConfig, make_config
from pool_env.game.info import batch_info, potted_lookup
from pool_env.game.sections import resolve
from pool_env.game.state import GameState

_OPTIONS = ("positions", "on_table", "reset_mask")


class PoolVectorEnv(VectorEnv[NDArray[np.float32], NDArray[np.float32], NDArray[Any]]):
    r"""``num_envs`` independent pool tables, each a :class:`~pool_env.PoolEnv`, in one env.

    ## Description

    Table ``i`` behaves exactly as ``gym.make(id)`` (a ``PoolEnv`` in its ``TimeLimit``)
    reset with seed ``seed + i``: same spaces, observations, rewards, terminations,
    truncations and info for the same actions, bit for bit; a ``SyncVectorEnv`` of those
    environments returns the very same arrays (tested). Only the speed differs: each
    ``step()`` decodes every action, simulates every shot to rest and applies every outcome
    in a handful of compiled calls over the batch, with no Python loop over tables.

    ## Spaces

    ``single_observation_space`` and ``single_action_space`` are ``PoolEnv``'s;
    ``observation_space`` is ``Box(-1, 1, (num_envs, 3 (n + 1)), float32)`` and
    ``action_space`` ``Box(-1, 1, (num_envs, 4), float32)`` on the default table, the spin
    table (``(num_envs, 2)`` with ``model="roll"``; ``batch_space``).

    ## Autoreset

    ``autoreset_mode`` (``metadata["autoreset_mode"]``), as Gymnasium's vector envs:

    * ``NEXT_STEP`` (default, Gymnasium's): a table that ends an episode is reset by the
      next ``step()``, which ignores its action and returns its first observation with
      reward 0, not terminated, not truncated, and no info for it.
    * ``SAME_STEP``: a finished table is reset within the step that ends it; its final
      observation is ``info["final_obs"][i]`` and its step info ``info["final_info"]``
      (Stable-Baselines3's convention; ``agents.vec.native_vec`` uses this mode).
    * ``DISABLED``: finished tables wait for ``reset(options={"reset_mask": mask})``.

    ## Seeding

    ``reset(seed=s)`` seeds table ``i`` with ``s + i`` (a list seeds each table; ``None``
    keeps the tables' generators, creating random ones the first time). Each table owns a
    ``numpy.random.Generator`` made by ``gymnasium.utils.seeding.np_random``, as
    ``PoolEnv.np_random``; layouts and execution noise draw from it in the same order as
    ``PoolEnv``, inside compiled code (:mod:`pool_env.game.kernels.rng`). ``np_random`` and
    ``np_random_seed`` are tuples over the tables.

    ## Info

    Gymnasium's vector layout: for each of ``PoolEnv``'s keys (``potted``, ``scratch``,
    ``first_contact``, ``n_events``, ``hit_event_cap``, ``angle``, ``speed``,
    ``is_success``) an array over the tables, with a boolean mask ``info["_key"]`` of the
    tables it holds; ``potted`` is an object array of tuples. ``reset`` returns ``{}``.

    ## Arguments

    ``num_envs`` (tables), ``max_episode_steps`` (``TimeLimit``'s; ``make_vec`` passes the
    id's), ``autoreset_mode``, ``parallel`` (split each batch of shots over the CPUs, one
    Python thread each running the GIL-free compiled loop,
    :func:`pool_env.sim.batch.simulate_batch_threads`; ``None``: from 64 tables on), and every
    ``PoolEnv`` argument (``config``, ``id_defaults``, ``scene``, ``aim``, ``noise``,
    ``end_on_miss``, ...), by ``PoolEnv``'s precedence: the caller's keywords over the
    caller's config, which replaces the id's defaults.
    ``reset(options=...)`` takes ``positions`` (``(N, 2)`` for every table reset, or
    ``(num_envs, N, 2)``) with an optional ``on_table``, and ``reset_mask``.

    ## Rendering

    ``render_mode="rgb_array"``: ``render()`` returns a tuple of frames, the tables at rest
    (without the shot trails of ``PoolEnv``, since batched shots keep no trajectories).

    Registered as the ``vector_entry_point`` of every id:
    ``gym.make_vec("pool_env/OneBallRoll-v1", num_envs=256)`` returns one.

    Examples:
        >>> import numpy as np
        >>> from pool_env import PoolVectorEnv
        >>> envs = PoolVectorEnv(4, scene="one_ball", end_on_miss=True)  # the spin table
        >>> obs, info = envs.reset(seed=0)  # table i is seeded with 0 + i
        >>> obs.shape
        (4, 6)
        >>> actions = np.zeros((4, 4), dtype=np.float32)  # aim, speed, tip side and height
        >>> actions[:, 1], actions[:, 3] = 0.5, -1.0  # full hits at 3.5 m/s, with draw
        >>> obs, rewards, terminated, truncated, info = envs.step(actions)
        >>> rewards  # pot, scratch, pot, miss
        array([ 1., -1.,  1.,  0.])
        >>> bool(terminated.all())  # one shot ends a one-ball episode
        True
    """

    metadata: ClassVar[dict[str, Any]] = {
        "render_modes": ["rgb_array"],
        "render_fps": 2,
        "autoreset_mode": AutoresetMode.NEXT_STEP,
    }

    def __init__(
        self,
        num_envs: int = 1,
        max_episode_steps: int | None = None,
        autoreset_mode: AutoresetMode | str = AutoresetMode.NEXT_STEP,
        parallel: bool | None = None,
        render_mode: str | None = None,
        render_width: int = 800,
        config: PoolConfig | None = None,
        id_defaults: Mapping[str, Any] | None = None,
        **overrides: Any,
    ) -> None:
        if num_envs is None or parse_count("num_envs", num_envs) is None:
            raise ValueError(f"num_envs must be a positive integer, got {num_envs!r}")
        self.render_width = check_render(render_mode, self.metadata["render_modes"], render_width)
        self.render_mode = render_mode
        self.autoreset_mode = AutoresetMode(autoreset_mode)
        self.metadata = {**type(self).metadata, "autoreset_mode": self.autoreset_mode}
        self.parallel = parallel
        self.max_episode_steps = parse_count("max_episode_steps", max_episode_steps)
        source = resolve(config, overrides, id_defaults)
        self.config: GameConfig = make_config(source, 1).with_shot_limit(self.max_episode_steps)
        config = self.config

        self.num_envs = int(num_envs)
        self.single_observation_space = gym.spaces.Box(
            -1.0, 1.0, (config.observation_size,), np.float32
        )
        self.single_action_space = gym.spaces.Box(-1.0, 1.0, (config.action_size,), np.float32)
        self.observation_space = batch_space(self.single_observation_space, self.num_envs)
        self.action_space = batch_space(self.single_action_space, self.num_envs)

        self._state: GameState = self.config.new_state(self.num_envs)
        self._done = np.zeros(self.num_envs, dtype=np.bool_)  # finished, awaiting a reset
        self._unset = np.ones(self.num_envs, dtype=np.bool_)  # never reset: no layout yet
        self._all = np.arange(self.num_envs)
        self._potted_lut = potted_lookup(config.n_object_balls)
        self._renderer: Any = None

    # -- seeding --------------------------------------------------------------------------

    @property
    def np_random(self) -> tuple[np.random.Generator, ...]:  # type: ignore[override]
        """Each table's generator (layouts and noise), as ``PoolEnv.np_random``."""
        return tuple(seeded_generators(self._state))

    @property
    def np_random_seed(self) -> tuple[int, ...]:  # type: ignore[override]
        """Each table's seed (``-1`` where a generator was not made from an int seed)."""
        seeded_generators(self._state)
        return tuple(int(s) if s is not None else -1 for s in self._state.seeds)

    # -- Gymnasium API --------------------------------------------------------------------

    def reset(
        self,
        *,
        seed: int | list[int | None] | None = None,
        options: dict[str, Any] | None = None,
    ) -> tuple[NDArray[np.float32], dict[str, Any]]:
        """Reset every table (or those of ``options["reset_mask"]``) to a new layout.

        Args:
            seed: ``None``, an int (table ``i`` gets ``seed + i``) or one seed per table.
            options: ``positions`` / ``on_table`` (a given layout) and ``reset_mask``.

        Returns:
            The observations of all tables and ``{}``.
        """
        seeds = check_seeds(seed, self.num_envs)
        options = check_options(options)
        mask = options.pop("reset_mask", None)
        tables = self._all if mask is None else check_reset_mask(mask, self.num_envs)
        state = self._state
        for i in tables.tolist():
            if seeds[i] is not None or state.generators[i] is None:
                seed_table(state, i, seeds[i])
        self._reset_tables(tables, options)
        self._unset[tables] = False
        return self._observations(), {}

    def step(
        self, actions: ArrayLike
    ) -> tuple[
        NDArray[np.float32], NDArray[np.float64], NDArray[np.bool_], NDArray[np.bool_], dict
    ]:
        """One shot on every table (or an autoreset); see the class docstring."""
        if self._unset.any():
            raise RuntimeError(
                f"call reset() before step(): tables {np.flatnonzero(self._unset).tolist()} "
                "were never reset"
            )
        mode = self.autoreset_mode
        if mode == AutoresetMode.DISABLED and self._done.any():
            raise RuntimeError(
                f"tables {np.flatnonzero(self._done).tolist()} have finished: with autoreset "
                "disabled, reset them with reset(options={'reset_mask': mask}) first"
            )
        resetting = self._done.copy() if mode == AutoresetMode.NEXT_STEP else None
        shooting = self._all if resetting is None else np.flatnonzero(~resetting)
        acts = check_actions(
            actions, self.num_envs, single=False,
            tables=None if shooting.size == self.num_envs else shooting,
            width=self.config.action_size,
        )  # fmt: skip
        b = self.num_envs
        rewards, terminated, truncated = np.zeros(b), np.zeros(b, np.bool_), np.zeros(b, np.bool_)
        shot = None
        if shooting.size:
            shot = game.step(self.config, self._state, shooting, acts, parallel=self.parallel)
            rewards[shooting], terminated[shooting] = shot.rewards, shot.terminated
            truncated[shooting] = shot.truncated
        if resetting is not None and resetting.any():
            self._reset_tables(np.flatnonzero(resetting), {})
        done = terminated | truncated
        lut = self._potted_lut
        if mode == AutoresetMode.SAME_STEP and done.any():
            final_obs = self._observations()
            tables = np.flatnonzero(done)
            self._reset_tables(tables, {})
            info = batch_info(shot, b, ~done, lut)  # type: ignore[arg-type]
            info["final_obs"] = _object_rows(final_obs, tables, b)
            info["_final_obs"] = done
            info["final_info"] = batch_info(shot, b, done, lut)  # type: ignore[arg-type]
            info["_final_info"] = done.copy()
        else:
            info = {} if shot is None else batch_info(shot, b, None, lut)
            self._done = done
        return self._observations(), rewards, terminated, truncated, info

    def render(self) -> tuple[NDArray[np.uint8], ...] | None:
        """``rgb_array``: one frame per table, the balls at rest (no shot trails)."""
        if self.render_mode is None:
            gym.logger.warn("render() called without a render_mode; pass render_mode='rgb_array'")
            return None
        if self._renderer is None:
            from pool_env.render import Renderer

            self._renderer = Renderer.for_config(self.config, self.render_width)
        state = self._state
        return tuple(
            self._renderer.frame(p, o) for p, o in zip(state.positions, state.on_table, strict=True)
        )

    # -- attributes for agents and tools --------------------------------------------------

    @property
    def positions(self) -> NDArray[np.float64]:
        """``(num_envs, N, 2)`` ball centres in metres, cue first (a copy)."""
        return self._state.positions.copy()

    @property
    def on_table(self) -> NDArray[np.bool_]:
        """``(num_envs, N)`` which balls are on each table (a copy)."""
        return self._state.on_table.copy()

    @property
    def rack(self) -> tuple[dict[str, Any], ...]:
        """Under rules: each table's rack state (as ``PoolEnv.rack``)."""
        return tuple(self.config.ruleset.state_dict(row) for row in self._state.rack)

    @property
    def shots(self) -> NDArray[np.int64]:
        """``(num_envs,)`` shots played in each table's episode (a copy)."""
        return self._state.shots.copy()

    # -- the batch ------------------------------------------------------------------------

    def _observations(self) -> NDArray[np.float32]:
        return game.observe(self.config, self._state)

    def _reset_tables(self, tables: NDArray[np.intp], options: dict[str, Any]) -> None:
        game.reset(self.config, self._state, tables, options, _OPTIONS)
        self._done[tables] = False

    def __getstate__(self) -> dict[str, Any]:
        state = self.__dict__.copy()
        state["_renderer"] = None
        return state


def _object_rows(rows: NDArray[Any], tables: NDArray[np.intp], n: int) -> NDArray[np.object_]:
    """An object array holding ``rows[i]`` for each table ``i`` (``None`` elsewhere)."""
    out = np.full(n, None, dtype=object)
    # Assigning a list of arrays would broadcast them into a 2-D block; fromiter keeps each
    # row as one object, without a Python loop.
    out[tables] = np.fromiter(iter(rows[tables]), dtype=object, count=tables.size)
    return out
