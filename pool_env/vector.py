"""PoolVectorEnv: many pool tables stepped together, one compiled batch of shots per step.

The decision process is :class:`pool_env.env.PoolEnv`'s, reused rather than rewritten: the
arguments are parsed by a ``PoolEnv`` (so spaces, defaults and errors are its own), actions,
observations and rewards are the batched functions of :mod:`pool_env.mdp`, and the physics
is :func:`pool_env.sim.batch.simulate_batch`. What ``PoolEnv`` does per table in Python (layout
sampling, noise, applying a shot's outcome) runs here in kernels over the whole batch
(:mod:`pool_env.game.kernels.vector`), drawing from each table's own ``numpy`` generator.
"""

from __future__ import annotations

import math
from typing import Any, ClassVar

import gymnasium as gym
import numpy as np
from gymnasium.utils import seeding
from gymnasium.vector import AutoresetMode, VectorEnv
from gymnasium.vector.utils import batch_space
from numpy.typing import ArrayLike, NDArray

from pool_env import checks, scenes
from pool_env.env import PoolEnv
from pool_env.game.kernels import vector as kv
from pool_env.mdp import AIM_MODES, decode_shots, encode_observations, pocket_potentials
from pool_env.mdp import shot_rewards as _shot_rewards
from pool_env.sim.batch import (
    PARALLEL_FROM,
    BatchResult,
    available_cpus,
    simulate_batch,
    simulate_batch_threads,
)
from pool_env.vector_info import StepInfo, potted_lookup, step_infos
from pool_env.vector_util import (
    TWO,
    as_actions,
    check_reset_mask,
    generator_addresses,
    object_rows,
    option_layouts,
    scene_kernel,
    seed_list,
)


class PoolVectorEnv(VectorEnv[NDArray[np.float32], NDArray[np.float32], NDArray[Any]]):
    r"""``num_envs`` independent pool tables, each a :class:`~pool_env.env.PoolEnv`, in one env.

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
    ``action_space`` ``Box(-1, 1, (num_envs, 2), float32)`` (``batch_space``).

    ## Autoreset

    ``autoreset_mode`` (``metadata["autoreset_mode"]``), as Gymnasium's vector envs:

    * ``NEXT_STEP`` (default, Gymnasium's): a table that ends an episode is reset by the
      next ``step()``, which ignores its action and returns its first observation with
      reward 0, not terminated, not truncated, and no info for it.
    * ``SAME_STEP``: a finished table is reset within the step that ends it; its final
      observation is ``info["final_obs"][i]`` and its step info ``info["final_info"]``
      (Stable-Baselines3's convention; ``agents.native_vec`` uses this mode).
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
    ``PoolEnv`` argument (``scene``, ``aim``, ``noise``, ``end_on_miss``, ...).
    ``reset(options=...)`` takes ``positions`` (``(N, 2)`` for every table reset, or
    ``(num_envs, N, 2)``) with an optional ``on_table``, and ``reset_mask``.

    ## Rendering

    ``render_mode="rgb_array"``: ``render()`` returns a tuple of frames, the tables at rest
    (without the shot trails of ``PoolEnv``, since batched shots keep no trajectories).

    Registered as the ``vector_entry_point`` of every id:
    ``gym.make_vec("pool_env/OneBall-v0", num_envs=256)`` returns one.
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
        **env_kwargs: Any,
    ) -> None:
        if num_envs is None or checks.parse_count("num_envs", num_envs) is None:
            raise ValueError(f"num_envs must be a positive integer, got {num_envs!r}")
        if render_mode not in (None, "rgb_array"):
            raise ValueError(f"render_mode must be 'rgb_array' or None, got {render_mode!r}")
        self.autoreset_mode = AutoresetMode(autoreset_mode)
        self.metadata = {**type(self).metadata, "autoreset_mode": self.autoreset_mode}
        self.render_mode = render_mode
        self.parallel = parallel
        self._threads = available_cpus()
        self.max_episode_steps = checks.parse_count("max_episode_steps", max_episode_steps)

        # A PoolEnv parses and checks the arguments; its settings are the tables' settings.
        config = PoolEnv(**env_kwargs)
        self.table = config.table
        self.aim, self.aim_range = config.aim, config.aim_range
        self.speed_range, self.noise = config.speed_range, config.noise
        self.end_on_miss, self.max_shots = config.end_on_miss, config.max_shots
        self.reward_weights = config.reward_weights
        self.n_object_balls = config.n_object_balls
        self.render_width = config.render_width
        self.cue = 0
        self._aim_code = AIM_MODES.index(config.aim)
        self._sampler: scenes.SceneSampler = config._sample
        limits = [x for x in (self.max_shots, self.max_episode_steps) if x is not None]
        self._shot_limit = min(limits) if limits else None

        self.num_envs = int(num_envs)
        self.single_observation_space = config.observation_space
        self.single_action_space = config.action_space
        self.observation_space = batch_space(self.single_observation_space, self.num_envs)
        self.action_space = batch_space(self.single_action_space, self.num_envs)

        b, n = self.num_envs, self.n_object_balls + 1
        self._pos = np.zeros((b, n, 2))
        self._on = np.ones((b, n), dtype=np.bool_)
        self._n_left = np.zeros(b, dtype=np.int64)
        self._shots = np.zeros(b, dtype=np.int64)
        self._done = np.zeros(b, dtype=np.bool_)  # finished, awaiting its (auto)reset
        self._unset = np.ones(b, dtype=np.bool_)  # never reset: no layout yet
        self._all = np.arange(b)
        self._rngs: list[np.random.Generator | None] = [None] * b
        self._rng_seeds: list[int | None] = [None] * b
        self._ptrs = np.zeros((b, 3), dtype=np.uintp)
        self._potted_lut = potted_lookup(self.n_object_balls)
        self._renderer: Any = None
        self._scene = scene_kernel(self.table, self._sampler.scene, self.n_object_balls)
        self._diagonal = math.hypot(self.table.length, self.table.width)

    # -- seeding --------------------------------------------------------------------------

    def _seed_table(self, i: int, seed: int | None) -> None:
        rng, used = seeding.np_random(seed)
        self._rngs[i], self._rng_seeds[i] = rng, used
        self._ptrs[i] = generator_addresses(rng)

    def _generators(self) -> list[np.random.Generator]:
        for i, rng in enumerate(self._rngs):
            if rng is None:
                self._seed_table(i, None)
        return self._rngs  # type: ignore[return-value]

    @property
    def np_random(self) -> tuple[np.random.Generator, ...]:  # type: ignore[override]
        """Each table's generator (layouts and noise), as ``PoolEnv.np_random``."""
        return tuple(self._generators())

    @property
    def np_random_seed(self) -> tuple[int, ...]:  # type: ignore[override]
        """Each table's seed (``-1`` where a generator was not made from an int seed)."""
        self._generators()
        return tuple(int(s) if s is not None else -1 for s in self._rng_seeds)

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
        seeds = seed_list(seed, self.num_envs)
        options = dict(options or {})
        mask = options.pop("reset_mask", None)
        tables = self._all if mask is None else check_reset_mask(mask, self.num_envs)
        for i in tables.tolist():
            if seeds[i] is not None or self._rngs[i] is None:
                self._seed_table(i, seeds[i])
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
        acts = as_actions(actions, self.num_envs)
        mode = self.autoreset_mode
        resetting = self._done.copy() if mode == AutoresetMode.NEXT_STEP else None
        if mode == AutoresetMode.DISABLED and self._done.any():
            raise RuntimeError(
                f"tables {np.flatnonzero(self._done).tolist()} have finished: with autoreset "
                "disabled, reset them with reset(options={'reset_mask': mask}) first"
            )
        shooting = self._all if resetting is None else np.flatnonzero(~resetting)
        if shooting.size != self.num_envs:
            acts = acts[shooting]
        bad = np.flatnonzero(np.isnan(acts).any(axis=1))
        if bad.size:
            raise ValueError(
                f"the action of table {int(shooting[bad[0]])} contains NaN: "
                f"{acts[bad[0]].tolist()}; nothing was changed"
            )
        b = self.num_envs
        rewards, terminated, truncated = np.zeros(b), np.zeros(b, np.bool_), np.zeros(b, np.bool_)
        shot = self._shoot(shooting, acts) if shooting.size else None
        if shot is not None:
            rewards[shooting], terminated[shooting], truncated[shooting] = shot.rewards, *shot.ends
        if resetting is not None and resetting.any():
            self._reset_tables(np.flatnonzero(resetting), {})
        done = terminated | truncated
        if mode == AutoresetMode.SAME_STEP and done.any():
            final_obs = self._observations()
            tables = np.flatnonzero(done)
            self._reset_tables(tables, {})
            info = step_infos(shot, b, ~done, self._potted_lut)
            info["final_obs"] = object_rows(final_obs, tables, b)
            info["_final_obs"] = done
            info["final_info"] = step_infos(shot, b, done, self._potted_lut)
            info["_final_info"] = done.copy()
        else:
            info = {} if shot is None else step_infos(shot, b, None, self._potted_lut)
            self._done = done
        return self._observations(), rewards, terminated, truncated, info

    def render(self) -> tuple[NDArray[np.uint8], ...] | None:
        """``rgb_array``: one frame per table, the balls at rest (no shot trails)."""
        if self.render_mode is None:
            gym.logger.warn("render() called without a render_mode; pass render_mode='rgb_array'")
            return None
        if self._renderer is None:
            from pool_env.render import Renderer

            self._renderer = Renderer(self.table, self.render_width)
        return tuple(self._renderer.frame(p, o) for p, o in zip(self._pos, self._on, strict=True))

    # -- attributes for agents and tools --------------------------------------------------

    @property
    def positions(self) -> NDArray[np.float64]:
        """``(num_envs, N, 2)`` ball centres in metres, cue first (a copy)."""
        return self._pos.copy()

    @property
    def on_table(self) -> NDArray[np.bool_]:
        """``(num_envs, N)`` which balls are on each table (a copy)."""
        return self._on.copy()

    @property
    def shots(self) -> NDArray[np.int64]:
        """``(num_envs,)`` shots played in each table's episode (a copy)."""
        return self._shots.copy()

    # -- the batch ------------------------------------------------------------------------

    def _observations(self) -> NDArray[np.float32]:
        return encode_observations(self._pos, self._on, self.table.length, self.table.width)

    def _reset_tables(self, tables: NDArray[np.intp], options: dict[str, Any]) -> None:
        """New layouts for ``tables``, from the options, the scene's kernel, or its sampler."""
        if options:
            self._pos[tables], self._on[tables] = option_layouts(
                self.table, options, tables, self._pos.shape[1], self.num_envs
            )
        else:
            self._on[tables] = True
            if self._scene.fixed is not None:
                self._pos[tables] = self._scene.fixed
            elif self._scene.n_new:
                self._scene.lay_out(tables, self._pos, self._ptrs)
            else:  # a callable scene: Python, one table at a time
                rngs = self._generators()
                for i in tables.tolist():
                    self._pos[i] = self._sampler(rngs[i])
        self._n_left[tables] = self._on[tables].sum(axis=1) - 1
        self._shots[tables] = 0
        self._done[tables] = False

    def _shoot(self, tables: NDArray[np.intp], actions: NDArray[np.floating]) -> StepInfo:
        """Play one shot on each of ``tables`` and apply the outcomes to the state."""
        every = tables.shape[0] == self.num_envs
        pos = self._pos if every else self._pos[tables]
        on = self._on if every else self._on[tables]
        table = self.table
        angles, speeds = decode_shots(
            actions, pos, on, self.cue, self._aim_code, table.ball_radius, self.aim_range,
            self.speed_range,
        )  # fmt: skip
        if self.noise is not None:
            kv.add_noise(tables, angles, speeds, self._ptrs, self.noise[0], self.noise[1])
        shaping = self.reward_weights[3] != 0.0
        if shaping:
            phi_before = pocket_potentials(pos, on, table.pockets, self._diagonal)
        velocities = kv.cue_velocities(angles, speeds, pos.shape[1], self.cue)
        result = self._simulate(pos, velocities, on)
        sk = self._scene
        n_potted, bits, scratch, first, spot_taken = kv.settle(
            tables, self._pos, self._on, self._n_left, result.positions, result.pocketed,
            result.first_contact, sk.spot, sk.circles, sk.reach2, sk.bounds, TWO,
        )  # fmt: skip
        for k in np.flatnonzero(spot_taken).tolist():  # rare: the head spot is taken
            i = int(tables[k])
            occupied = self._on[i].copy()
            occupied[self.cue] = False
            self._pos[i, self.cue] = scenes.free_spot(table, self._pos[i], occupied)
        phi_change = 0.0
        if shaping:
            pos, on = (self._pos, self._on) if every else (self._pos[tables], self._on[tables])
            phi_change = pocket_potentials(pos, on, table.pockets, self._diagonal) - phi_before
        rewards = _shot_rewards(n_potted, scratch, first < 0, phi_change, self.reward_weights)
        self._shots[tables] += 1
        cleared = self._n_left[tables] == 0
        terminated = cleared | (self.end_on_miss & ((n_potted == 0) | scratch))
        limit = self._shot_limit
        truncated = self._shots[tables] >= limit if limit is not None else np.zeros_like(cleared)
        pocketed = None if self._potted_lut is not None else result.pocketed
        return StepInfo(
            tables, np.asarray(rewards, dtype=np.float64), (terminated, truncated), bits,
            pocketed, scratch, first, result.n_events, result.hit_event_cap, angles, speeds,
            cleared,
        )  # fmt: skip

    def _simulate(
        self, pos: NDArray[np.float64], velocities: NDArray[np.float64], on: NDArray[np.bool_]
    ) -> BatchResult:
        """The batch of shots, on one thread or split over the CPUs (see ``parallel``)."""
        parallel = self.parallel
        if parallel is None:
            parallel = pos.shape[0] >= PARALLEL_FROM
        if parallel and self._threads > 1:
            return simulate_batch_threads(self.table, pos, velocities, on, self._threads)
        return simulate_batch(self.table, pos, velocities, active=on, parallel=False)

    def __getstate__(self) -> dict[str, Any]:
        state = self.__dict__.copy()
        state["_renderer"] = None
        return state

    def __setstate__(self, state: dict[str, Any]) -> None:
        self.__dict__.update(state)
        for i, rng in enumerate(self._rngs):  # addresses are per process
            if rng is not None:
                self._ptrs[i] = generator_addresses(rng)
