"""The base of every baseline agent (SB3's ``predict``) and what it knows of its environment.

The table, the action decoding and the layout:

Baselines are built from an environment (a Gymnasium env, wrapped or not, or an SB3
``VecEnv``) and then called like an SB3 model, with observations only. The observation holds
the layout in float32 (about 0.1 um on a 9-ft table), which is plenty to aim, but touching
balls (a rack) decode as overlapping and chaotic shots (a break) amplify the rounding. So when
the environment's exact state matches the observation it is used; otherwise the layout is
decoded from the observation.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from pool_env import GameConfig, Table, encode_observations
from pool_env.game.codec import decode_observations

Layout = tuple[NDArray[np.float64], NDArray[np.bool_]]


@dataclass(frozen=True)
class EnvSpec:
    """The static facts of an environment that a planner needs, read from its config.

    The config is the decision process's own (:class:`pool_env.GameConfig`): its codec
    encodes the planners' shots (:func:`pool_env.encode_shots`), and the properties below
    read it.

    Attributes:
        config: The env's config.
    """

    config: GameConfig

    @property
    def n_balls(self) -> int:
        """Balls in the layout, cue included."""
        return int(self.config.n_balls)

    @property
    def table(self) -> Table:
        """The table."""
        return self.config.table

    @property
    def aim(self) -> str:
        """Aim mode (``"cut"``, ``"relative"`` or ``"absolute"``)."""
        return str(self.config.aim)

    @property
    def aim_range(self) -> tuple[float, float]:
        """What action[0] = -1 and +1 map to."""
        return self.config.aim_range

    @property
    def speed_range(self) -> tuple[float, float]:
        """Speeds (m/s) that action[1] = -1 and +1 map to."""
        return self.config.speed_range

    @property
    def noise(self) -> tuple[float, ...] | None:
        """Execution noise sigmas (rad, m/s, and on a spin env the tip's) or ``None``."""
        return self.config.noise

    @property
    def tip_limit(self) -> float | None:
        """The tip components' reach (fraction of ``R``); ``None`` on a roll env."""
        return self.config.tip_limit

    @property
    def spin(self) -> bool:
        """Whether the action ends with the two tip components (a spin env)."""
        return self.tip_limit is not None


def is_vec_env(env: Any) -> bool:
    """Whether ``env`` is an SB3 ``VecEnv`` (duck-typed: SB3 is an optional dependency)."""
    return hasattr(env, "num_envs") and hasattr(env, "get_attr") and hasattr(env, "env_method")


def env_spec(env: Any) -> EnvSpec:
    """Read the :class:`EnvSpec` of a (wrapped) ``PoolEnv`` or of an SB3 ``VecEnv`` of them.

    Raises:
        ValueError: If the env has no decision-process config (not a ``PoolEnv``).
    """
    if is_vec_env(env):
        config = env.get_attr("config", indices=[0])[0]
    else:
        config = getattr(env.unwrapped, "config", None)
    if not isinstance(config, GameConfig):
        raise ValueError(f"{env!r} is no PoolEnv: it has no GameConfig to plan with")
    return EnvSpec(config=config)


def decode_observation(obs: NDArray[np.floating], table: Table) -> Layout:
    """Invert :func:`pool_env.encode_observations` for one observation (float32 precision).

    The env's inverse (:func:`pool_env.game.codec.decode_observations`, which keeps every
    centre within ``R`` of the rails); balls that decode closer than ``2R`` (touching in
    the real layout, or a ball resting in a pocket's throat brought back onto the rail line
    next to one frozen to it) are then pushed apart along their line of centres, each kept
    within the rails too, so that the simulator accepts the layout.
    """
    decoded, on = decode_observations(table, np.asarray(obs, dtype=np.float64)[None])
    positions, on_table = decoded[0], on[0]
    r = table.ball_radius
    box = (np.array([r, r]), np.array([table.length - r, table.width - r]))
    _separate(positions, on_table, 2.0 * r * (1.0 + 1e-9), box)
    return positions, on_table


def _separate(
    positions: NDArray[np.float64],
    on_table: NDArray[np.bool_],
    reach: float,
    box: tuple[NDArray[np.float64], NDArray[np.float64]],
) -> None:
    """Push overlapping balls apart in place, a few sweeps, keeping centres inside ``box``.

    A ball the box stops (on a rail line) leaves the rest of the push to the other one:
    pushed past a rail line, a centre could land in a pocket's jaw, which the simulator
    refuses.
    """
    low, high = box
    rows = on_table.nonzero()[0]
    for _ in range(8):
        moved = False
        for a_i, a in enumerate(rows):
            for b in rows[a_i + 1 :]:
                d = positions[b] - positions[a]
                dist = float(np.hypot(d[0], d[1]))
                if 0.0 < dist < reach:
                    push = (reach - dist) / 2.0 * d / dist
                    want_a, want_b = positions[a] - push, positions[b] + push
                    got_a, got_b = np.clip(want_a, low, high), np.clip(want_b, low, high)
                    # Each also moves whatever part of the other's push the box stopped.
                    positions[a] = np.clip(got_a - (want_b - got_b), low, high)
                    positions[b] = np.clip(got_b - (want_a - got_a), low, high)
                    moved = True
        if not moved:
            return


class LayoutSource:
    """Turns a batch of observations into exact layouts, from the environment when it can.

    Args:
        env: The environment the agent plays (``gym.Env`` or SB3 ``VecEnv``), or ``None``
            to always decode observations.
        table: The table (to decode and to check observations).
        n_balls: Balls of a layout: the observation's first ``3 n_balls`` entries are
            theirs (what follows, such as the ``"shots"`` features, is not read).
    """

    def __init__(self, env: Any, table: Table, n_balls: int) -> None:
        self.env = env
        self.table = table
        self.n_balls = n_balls

    def layouts(self, obs: NDArray[np.floating]) -> list[Layout]:
        """One ``(positions, on_table)`` per row of the ``(B, D)`` observations."""
        obs = obs[:, : 3 * self.n_balls]
        exact = self._exact(obs.shape[0])
        out = []
        for k in range(obs.shape[0]):
            if exact is not None and self._matches(obs[k], *exact[k]):
                out.append((exact[k][0].copy(), exact[k][1].copy()))
            else:
                out.append(decode_observation(obs[k], self.table))
        return out

    def _exact(self, batch: int) -> list[Layout] | None:
        env = self.env
        if env is None:
            return None
        try:
            if is_vec_env(env):
                if env.num_envs != batch:
                    return None
                pos, on = env.get_attr("positions"), env.get_attr("on_table")
                return list(zip(pos, on, strict=True))
            if batch != 1:
                return None
            unwrapped = env.unwrapped
            return [(unwrapped.positions, unwrapped.on_table)]
        except (RuntimeError, AttributeError):  # not reset yet, or not a PoolEnv
            return None

    def _matches(
        self, obs: NDArray[np.floating], positions: NDArray[np.float64], on: NDArray[np.bool_]
    ) -> bool:
        if positions.shape[0] * 3 != obs.shape[0]:
            return False
        t = self.table
        expected = encode_observations(positions[None], on[None], t.length, t.width)[0]
        return bool(np.array_equal(expected, np.asarray(obs, dtype=np.float32)))


def batch_obs(observation: Any) -> tuple[NDArray[np.floating], bool]:
    """``(B, D)`` observations and whether the input was a single unbatched one."""
    obs = np.asarray(observation)
    if obs.ndim == 1:
        return obs[None, :], True
    if obs.ndim != 2:
        raise ValueError(f"observations must have shape (D,) or (B, D), got {obs.shape}")
    return obs, False


class BaselineAgent:
    """SB3's ``predict`` for the baselines, so ``evaluate_policy`` takes them unchanged.

    Subclasses implement :meth:`act` on a batch; ``predict`` batches a single observation
    and unbatches the answer.
    """

    def act(self, observations: NDArray[np.floating]) -> NDArray[np.float32]:
        """``(B, 2)`` float32 actions for ``(B, D)`` observations."""
        raise NotImplementedError

    def predict(
        self,
        observation: Any,
        state: tuple[NDArray[Any], ...] | None = None,
        episode_start: NDArray[np.bool_] | None = None,
        deterministic: bool = True,
    ) -> tuple[NDArray[np.float32], tuple[NDArray[Any], ...] | None]:
        """Actions for one observation ``(D,)`` or a batch ``(B, D)`` (SB3's signature).

        Args:
            observation: One observation ``(D,)`` or a batch ``(B, D)``.
            state: Recurrent state (unused, returned as is).
            episode_start: Unused.
            deterministic: Unused: each baseline is what it is.

        Returns:
            ``(actions, state)``: ``(2,)`` or ``(B, 2)`` float32 actions.
        """
        obs, single = batch_obs(observation)
        actions = self.act(obs)
        return (actions[0] if single else actions), state
