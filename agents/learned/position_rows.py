"""Position play by candidate strikes: the spin ghost-ball agent's options, re-ranked by a policy.

On a spin table (``pool_env/Pool-v1``) the ghost-ball agent weighs, for its most forgiving
shots on every ball and pocket the aim mode can play, every tip and object-ball arrival
speed (:meth:`agents.baselines.ghost_ball.GhostBallAgent.position_options`), and plays the
strike whose pot chance times the next shot's chance from the cue ball's rest scores best.
Its score takes the aim noise only, and looks one shot ahead. :class:`PositionRows`
describes the :data:`N_ROWS` best of those strikes to a policy, one row each (at most
:data:`PER_SHOT_ROWS` per ball and pocket, so that other pockets and balls are seen): the
env action that plays it, the ghost agent's score and its two factors, the shot's
geometry, the tip and speed, and the leave (where the cue ball stops, how far it rolls,
how near a rail it ends). Rows are sorted by the ghost score, so row 0 is the ghost
agent's own choice; when it has no option that keeps the cue ball out of the pockets,
row 0 is its own play (a scratching shot, a bank, a break) and the only valid row.

The action is a preference over the rows' features, weight-shared across rows:
``action = w`` in ``[-1, 1]^len(PREFERENCE_COLUMNS)``, and the row played is the valid row
with the largest ``score_k + PICK_SCALE * (w . f_k)``, with ``f_k`` the row's
:data:`PREFERENCE_COLUMNS`. ``w = 0`` plays the ghost agent's strike exactly, so a policy
starts at the heuristic and learns which strikes succeed more often under the noise (the
leave's travel, the tip, soft or firm) than the ghost score says. Decoding reads the
observation alone (:func:`decode_position`), so the ``gym.Env`` wrapper
(:class:`PositionCandidates`), the native vector env
(:class:`agents.training.vec_features.PositionCandidatesVecEnv`) and a loaded model
(:mod:`agents.learned.pretrained`) decode the same way.

Each observation costs the ghost agent's planning (~0.1 s a shot on 3 balls): the training
budget is counted in thousands of steps, not millions.
"""

from __future__ import annotations

import math
from typing import Any, SupportsFloat

import gymnasium as gym
import numpy as np
from numpy.typing import NDArray

from agents.baselines.base import decode_observation, env_spec
from agents.baselines.ghost_ball import MIN_SIGMA, GhostBallAgent, PositionOption
from agents.baselines.spin_play import Contact, PositionScore, pot_chance
from agents.baselines.trace import Trace
from pool_env import onto_tip_circle, shoot

__all__ = [
    "N_ROWS",
    "PICK_SCALE",
    "PREFERENCE_COLUMNS",
    "PositionCandidates",
    "PositionRowFeatures",
    "decode_position",
    "position_space",
]

#: Candidate strikes described per observation.
N_ROWS = 10
#: At most this many rows per ball and pocket (the rest of the rows go to other shots).
PER_SHOT_ROWS = 6
#: Weight of the policy's preference against the ghost score (a score lies in [0, 1]; the
#: top rows' scores are often a few hundredths apart, and ``|w . f| <~ 3``).
PICK_SCALE = 0.1

#: Noisy replays of each row's strike on the simulator (the same draws for every row of a
#: layout, from :data:`REPLAY_SEED`, so that rows are compared on common noise and the
#: rows are a function of the observation alone).
REPLAYS = 8
REPLAY_SEED = 4747

#: Row columns. ``ACTION`` holds the env action (aim, speed, tip side, tip height).
VALID, KIND, ACTION, SCORE, P_NOW, P_NEXT, COS_CUT, CUE_DIST, OBJ_DIST = 0, 1, 2, 6, 7, 8, 9, 10, 11
ARRIVAL, STRIKE, REST_X, REST_Y, TRAVEL, RAIL, BALL, POCKET, LAST, RANK, SIDE, HEIGHT = range(
    12, 24
)
#: The replays: the share that pot the ball cleanly, the share that scratch, and the next
#: shot's chance from where the noiseless replay leaves the cue ball (-1 if it misses).
SIM_POT, SIM_SCRATCH, SIM_NEXT = 24, 25, 26
PER_ROW = 27
#: The features the policy's preference weighs (one weight each, shared by every row).
PREFERENCE_COLUMNS = (
    P_NOW, P_NEXT, COS_CUT, CUE_DIST, OBJ_DIST, ARRIVAL, STRIKE, TRAVEL, RAIL, SIDE, HEIGHT,
    SIM_POT, SIM_SCRATCH, SIM_NEXT,
)  # fmt: skip


def position_space(n_rows: int = N_ROWS) -> gym.spaces.Box:
    """The action space: one preference weight per :data:`PREFERENCE_COLUMNS` entry."""
    del n_rows  # the weights are shared by the rows: the space does not grow with them
    return gym.spaces.Box(-1.0, 1.0, (len(PREFERENCE_COLUMNS),), np.float32)


def decode_position(
    observations: NDArray[np.floating], actions: NDArray[np.floating], n_rows: int = N_ROWS
) -> tuple[NDArray[np.float32], NDArray[np.int64]]:
    """The env actions ``(B, 4)`` of preference actions, and the rows played ``(B,)``.

    Args:
        observations: ``(B, D + n_rows * PER_ROW)`` observations with the rows last.
        actions: ``(B, len(PREFERENCE_COLUMNS))`` preference weights (clipped to [-1, 1]).
        n_rows: Rows per observation.

    Raises:
        ValueError: On shapes that do not fit, or an observation without a valid row.
    """
    obs = np.asarray(observations, dtype=np.float64)
    act = np.clip(np.asarray(actions, dtype=np.float64), -1.0, 1.0)
    width = len(PREFERENCE_COLUMNS)
    if obs.ndim != 2 or act.shape != (obs.shape[0], width):
        raise ValueError(
            f"expected (B, D) observations and (B, {width}) actions, got {obs.shape} and "
            f"{act.shape}"
        )
    if obs.shape[1] < n_rows * PER_ROW:
        raise ValueError(f"observations of size {obs.shape[1]} hold no {n_rows} position rows")
    rows = obs[:, obs.shape[1] - n_rows * PER_ROW :].reshape(len(obs), n_rows, PER_ROW)
    valid = rows[..., VALID] > 0.5
    if not valid.any(axis=1).all():
        raise ValueError("an observation without a valid position row (not from PositionRows)")
    utility = rows[..., SCORE] + PICK_SCALE * np.einsum(
        "bkf,bf->bk", rows[..., list(PREFERENCE_COLUMNS)], act
    )
    pick = np.argmax(np.where(valid, utility, -np.inf), axis=1)
    chosen = rows[np.arange(len(obs)), pick, ACTION : ACTION + 4]
    return chosen.astype(np.float32), pick.astype(np.int64)


class PositionRowFeatures:
    """The :data:`N_ROWS` candidate strikes of a layout as feature rows (module docstring).

    Args:
        env: The spin env (``gym.Env``, wrapped or not, or an SB3 ``VecEnv``).
        n_rows: Rows per observation.

    Raises:
        ValueError: If the env has no cue tip (the rows are the spin agent's options).
    """

    def __init__(self, env: Any, n_rows: int = N_ROWS) -> None:
        self.spec = env_spec(env)
        if not self.spec.spin:
            raise ValueError(
                "position rows need a spin env (the action's cue tip: e.g. pool_env/Pool-v1)"
            )
        if n_rows < 1:
            raise ValueError(f"n_rows must be at least 1, got {n_rows!r}")
        self.n_rows = int(n_rows)
        self.size = self.n_rows * PER_ROW
        self.ghost = GhostBallAgent(env)
        sigma = max(self.spec.noise[0] if self.spec.noise else 0.0, MIN_SIGMA)
        self.sigma = sigma  # the aim noise the ghost agent's chances assume
        self.scorer = PositionScore(
            self.spec.table, self.ghost.mouths, sigma, self.ghost.next_targets
        )

    def of_observations(self, observations: NDArray[np.floating]) -> NDArray[np.float32]:
        """``(B, n_rows * PER_ROW)`` rows for ``(B, D)`` observations (layouts decoded)."""
        obs = np.asarray(observations)
        out = np.zeros((obs.shape[0], self.size), dtype=np.float32)
        for b in range(obs.shape[0]):
            layout = decode_observation(obs[b, : 3 * self.spec.n_balls], self.spec.table)
            out[b] = self.rows(*layout).ravel()
        return out

    def options(
        self, positions: NDArray[np.float64], on_table: NDArray[np.bool_]
    ) -> list[PositionOption]:
        """The strikes the rows describe, best ghost score first (the rows' order)."""
        options, _, _ = self.ghost.position_options(positions, on_table)
        ranked = sorted((o for o in options if o.score is not None), key=lambda o: -o.score)  # type: ignore[operator]
        kept: list[PositionOption] = []
        per_shot: dict[tuple[int, int], int] = {}
        for option in ranked:
            key = (option.shot.ball, option.shot.pocket)
            if per_shot.get(key, 0) < PER_SHOT_ROWS:
                per_shot[key] = per_shot.get(key, 0) + 1
                kept.append(option)
                if len(kept) == self.n_rows:
                    break
        return kept

    def rows(self, positions: NDArray[np.float64], on_table: NDArray[np.bool_]) -> NDArray:
        """``(n_rows, PER_ROW)`` rows of one layout, in ``[-1, 1]``."""
        rows = np.zeros((self.n_rows, PER_ROW), dtype=np.float64)
        options = self.options(positions, on_table)
        if not options:  # the ghost agent's own play: a scratch, a bank, a break
            rows[0, VALID], rows[0, KIND], rows[0, SCORE] = 1.0, -1.0, 0.0
            rows[0, ACTION : ACTION + 4] = self.ghost.plan(positions, on_table)
            return rows
        draws = np.random.default_rng(REPLAY_SEED).standard_normal((REPLAYS, 4))
        for k, option in enumerate(options):
            rows[k] = self._row(option, k, positions, on_table)
            rows[k, SIM_POT : SIM_NEXT + 1] = self._replays(option, positions, on_table, draws)
        return np.clip(rows, -1.0, 1.0)

    def _replays(
        self,
        option: PositionOption,
        positions: NDArray[np.float64],
        on_table: NDArray[np.bool_],
        draws: NDArray[np.float64],
    ) -> tuple[float, float, float]:
        """``(SIM_POT, SIM_SCRATCH, SIM_NEXT)`` of a strike, from replays on the simulator.

        The replays add the env's noise sigmas times ``draws`` to the strike's angle,
        speed and tip (the tip put back on the miscue circle), as an execution error.
        """
        spec, contact = self.spec, option.contact
        sigmas = tuple(spec.noise or ()) + (0.0, 0.0, 0.0)
        limit = spec.tip_limit or 0.0
        live = on_table.nonzero()[0]
        sub = np.ascontiguousarray(positions[live])
        target = int(np.searchsorted(live, option.shot.ball))
        pots = scratches = 0
        for d in draws:
            tip = onto_tip_circle(
                contact.tip[0] + sigmas[2] * d[2], contact.tip[1] + sigmas[2] * d[3], limit
            )
            result = shoot(
                spec.table,
                sub,
                contact.aim + sigmas[0] * d[0],
                max(contact.speed + sigmas[1] * d[1], 0.0),
                record=False,
                tip=tip,
            )
            scratch = bool(result.pocketed[0] >= 0)
            scratches += scratch
            pots += bool(result.pocketed[target] >= 0) and not scratch
        plain = shoot(spec.table, sub, contact.aim, contact.speed, record=False, tip=contact.tip)
        next_chance = -1.0
        if plain.pocketed[target] >= 0 and plain.pocketed[0] < 0:
            after = on_table.copy()
            after[live] = plain.pocketed < 0
            moved = positions.copy()
            moved[live] = plain.positions
            targets = self.ghost.next_targets(moved, after, option.shot.ball)
            rest = Contact(
                contact.aim, contact.speed, contact.tip, contact.ghost, 0.0,
                Trace(-1, moved[0], ()),
            )  # fmt: skip
            chance = self.scorer.next_chance(rest, moved, after, targets) if targets else 1.0
            next_chance = 2.0 * chance - 1.0
        n = len(draws)
        return 2.0 * pots / n - 1.0, 2.0 * scratches / n - 1.0, next_chance

    def _row(
        self,
        option: PositionOption,
        rank: int,
        positions: NDArray[np.float64],
        on_table: NDArray[np.bool_],
    ) -> NDArray[np.float64]:
        spec, table = self.spec, self.spec.table
        shot, contact = option.shot, option.contact
        p_now = pot_chance(shot.tolerance, self.sigma)
        after = on_table.copy()
        after[shot.ball] = False
        last = not self.ghost.next_targets(positions, after, shot.ball)
        # The score's two factors, apart: the next chance is the ghost agent's own scorer's.
        p_next = (
            1.0
            if last
            else self.scorer.next_chance(
                contact, positions, after, self.ghost.next_targets(positions, after, shot.ball)
            )
        )
        lo, top = spec.speed_range
        half_l, half_w = table.length / 2.0, table.width / 2.0
        rest = contact.path.rest
        travel = sum(float(np.hypot(*(b - a))) for a, b in contact.path.legs)
        rail = min(half_l - abs(rest[0] - half_l), half_w - abs(rest[1] - half_w))
        limit = spec.tip_limit or 1.0
        n_obj = max(spec.n_balls - 1, 1)
        row = np.zeros(PER_ROW, dtype=np.float64)
        row[VALID], row[KIND] = 1.0, 1.0
        row[ACTION : ACTION + 4] = option.action
        row[SCORE] = float(option.score)  # type: ignore[arg-type]
        row[P_NOW], row[P_NEXT] = 2.0 * p_now - 1.0, 2.0 * p_next - 1.0
        row[COS_CUT] = math.cos(shot.cut)
        row[CUE_DIST] = shot.cue_distance / table.length * 2.0 - 1.0
        row[OBJ_DIST] = shot.ball_distance / table.length * 2.0 - 1.0
        row[ARRIVAL] = option.arrival - 1.0
        row[STRIKE] = (contact.speed - lo) / (top - lo) * 2.0 - 1.0
        row[REST_X], row[REST_Y] = rest[0] / half_l - 1.0, rest[1] / half_w - 1.0
        row[TRAVEL] = travel / table.length - 1.0
        row[RAIL] = rail / half_w * 2.0 - 1.0
        row[BALL] = (shot.ball - 1) / n_obj * 2.0 - 1.0
        row[POCKET] = shot.pocket / max(self.ghost.mouths.n - 1, 1) * 2.0 - 1.0
        row[LAST] = 1.0 if last else -1.0
        row[RANK] = rank / max(self.n_rows - 1, 1) * 2.0 - 1.0
        row[SIDE] = abs(contact.tip[0]) / limit * 2.0 - 1.0
        row[HEIGHT] = contact.tip[1] / limit
        return row


class PositionCandidates(gym.Wrapper):
    """A spin ``PoolEnv`` seen through :class:`PositionRowFeatures`, acting by preferences.

    The observation is the env's with the rows appended (``Box(-1, 1)``); the action is a
    preference (module docstring), decoded on the last observation's rows. The env action
    played is in ``info["env_action"]``, the row in ``info["position_row"]``.

    Args:
        env: A (wrapped) spin ``PoolEnv``.
        n_rows: Rows per observation.
    """

    def __init__(self, env: gym.Env, n_rows: int = N_ROWS) -> None:
        super().__init__(env)
        self.position_rows = PositionRowFeatures(env, n_rows)
        self.n_rows = self.position_rows.n_rows
        raw = env.observation_space.shape[0]
        self.observation_space = gym.spaces.Box(
            -1.0, 1.0, (raw + self.position_rows.size,), np.float32
        )
        self.action_space = position_space(self.n_rows)
        self._last: NDArray[np.float32] | None = None

    def _append(self, obs: NDArray[np.floating]) -> NDArray[np.float32]:
        raw = np.asarray(obs, dtype=np.float32)[None]
        return np.concatenate([raw, self.position_rows.of_observations(raw)], axis=1)[0]

    def reset(self, **kwargs: Any) -> tuple[NDArray[np.float32], dict[str, Any]]:
        """Reset; the observation with its rows."""
        obs, info = self.env.reset(**kwargs)
        self._last = self._append(obs)
        return self._last.copy(), info

    def step(
        self, action: NDArray[np.floating]
    ) -> tuple[NDArray[np.float32], SupportsFloat, bool, bool, dict[str, Any]]:
        """Decode the preference on the last observation's rows and play that strike.

        Raises:
            RuntimeError: If called before ``reset``.
        """
        if self._last is None:
            raise RuntimeError("call reset() before step()")
        env_action, pick = decode_position(self._last[None], np.asarray(action)[None], self.n_rows)
        obs, reward, terminated, truncated, info = self.env.step(env_action[0])
        self._last = self._append(obs)
        info = {**info, "env_action": env_action[0], "position_row": int(pick[0])}
        return self._last.copy(), reward, terminated, truncated, info
