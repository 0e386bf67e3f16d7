"""The action codec: the shot an action plays, and the action that plays a shot.

:func:`decode_action` runs the decision process's own decoding on one table, noise off:
the game's ruleset places the cue ball in hand and strikes the shot
(:meth:`~pool_env.game.ruleset.Ruleset.shoot`), as a step does. There is one decoder: what
it returns is what a step executes before its noise. :func:`encode_action` inverts it: it
maps each part of a :class:`Shot` back onto its action component (the aim through the
same reference ball, :func:`~pool_env.game.kernels.actions.nearest_object_ball` of the
balls the rules let the cue ball hit first), so ``decode_action(encode_action(shot))`` is
``shot`` up to rounding (tested).
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from pool_env.game.checks import check_actions
from pool_env.game.components import pocket_component, unit_component
from pool_env.game.config import GameConfig, make_config
from pool_env.game.kernels import params as kp
from pool_env.game.kernels.actions import (
    nearest_object_ball,
)
from pool_env.game.kernels.encode import (
    AIM_AWAY,
    AIM_NO_REFERENCE,
    AIM_OUT_OF_RANGE,
    aim_parameter,
    tip_components,
)
from pool_env.game.kernels.encode import encode_shots as kernel_encode_shots
from pool_env.game.kernels.encode import reference_balls as kernel_reference_balls
from pool_env.game.kernels.tips import onto_tip_circle
from pool_env.game.ruleset import Turn
from pool_env.game.sections import PoolConfig
from pool_env.game.shots import Shot, ShotConstraints
from pool_env.game.state import GameState
from pool_env.sim import Table

_ONE = np.zeros(1, dtype=np.intp)


def _check_finite(shot: Shot) -> None:
    """Refuse a shot with a part that is NaN or infinite (clipping cannot place it)."""
    parts = {"angle": shot.angle, "speed": shot.speed, "tip": shot.tip}
    if shot.cue is not None:
        parts["cue"] = shot.cue
    for name, value in parts.items():
        values = np.asarray(value, dtype=np.float64)
        if not np.all(np.isfinite(values)):
            raise ValueError(f"shot {name} {value!r} is not a finite number")


def _table(
    config: GameConfig, positions: ArrayLike, on_table: ArrayLike | None, rack: Any
) -> GameState:
    """A one-table state of these balls (and rack), its generator unused (no noise)."""
    n = config.n_balls
    pos = np.array(positions, dtype=np.float64)
    if pos.shape != (n, 2) or not np.isfinite(pos).all():
        raise ValueError(f"positions must be ({n}, 2) finite numbers, got shape {pos.shape}")
    on = np.ones(n, dtype=np.bool_) if on_table is None else np.array(on_table, dtype=np.bool_)
    if on.shape != (n,):
        raise ValueError(f"on_table must have shape ({n},), got {on.shape}")
    state = config.new_state(1)
    state.positions[0], state.on_table[0] = pos, on
    state.rack[0] = config.ruleset.state_row(config, rack, on)  # the game parses its own state
    return state


def _quiet(config: GameConfig) -> NDArray[np.float64]:
    """The config's kernel parameters with the noise off."""
    params = config.params.copy()
    params[kp.NOISE] = 0.0
    return params


def decode_action(
    config: GameConfig | PoolConfig | Any,
    action: ArrayLike,
    positions: ArrayLike,
    on_table: ArrayLike | None = None,
    rack: Any = None,
) -> Shot:
    """The shot that ``action`` plays from this layout, before execution noise.

    Args:
        config: The env's config (``env.unwrapped.config``).
        action: One action of the env's action space (out-of-range values are clipped).
        positions: ``(N, 2)`` ball centres (``env.unwrapped.positions``).
        on_table: ``(N,)`` which balls are on the table (default: all).
        rack: Rules only: the rack state, as ``env.unwrapped.rack`` gives it (default: no
            break, the cue ball where it lies, an open table).

    Returns:
        The :class:`Shot`; under rules with the cue ball in hand, ``cue`` is where the
        step places it (the free point nearest the requested one, if that is covered);
        ``push_out`` and ``pass_back`` only where the rack offers them (else the step
        plays a shot); ``pass_back``: the angle and speed are 0, no shot is played.

    Raises:
        ValueError: On a malformed action (or NaN), layout or rack.
    """
    config = game_config(config, "decode_action")
    actions = check_actions(action, 1, single=True, width=config.action_size)
    state = _table(config, positions, on_table, rack)
    ruleset = config.ruleset
    quiet = replace(config, params=_quiet(config))
    executed = ruleset.shoot(Turn(quiet, state, _ONE), actions)
    row = executed.shots[0].tolist()
    tip = (row[2], row[3]) if config.spin else (0.0, 0.0)
    return ruleset.decoded_shot(row, executed.calls, tip, ruleset.placed_cue(state))


def _aim(config: GameConfig, state: GameState, angle: float, clip: bool) -> float:
    """The aim component that plays the direction ``angle`` (radians from +x)."""
    params = config.params
    mode, (low, high) = int(params[kp.AIM_MODE]), config.aim_range
    ruleset = config.ruleset
    targets = ruleset.aim_references(state)[0]
    # From the striker's own cue ball (three-cushion's yellow on player 1's turn), as the
    # game's shoot() decodes it.
    cue = int(ruleset.cue_columns(state)[0])
    j, dist, base = nearest_object_ball(state.positions[0], targets, cue)
    param, status = aim_parameter(mode, low, high, params[kp.RADIUS], angle, j, dist, base, 0.0)
    if mode == 0 and status == AIM_OUT_OF_RANGE:
        if not clip:
            raise ValueError(f"angle {angle!r} lies outside aim_range {config.aim_range}")
        param = high if param - high < low + 2.0 * math.pi - param else low
    if status == AIM_NO_REFERENCE:
        return 0.0  # no reference ball: every cut aims along +x
    if status == AIM_AWAY and not clip:
        raise ValueError(
            f"angle {angle!r} turns more than 90 degrees from the reference ball {j}: cut "
            "aim cannot play it (use aim='absolute', or clip=True)"
        )
    name = ("angle", "angle (relative aim)", "cut")[mode]
    return unit_component(name, param, low, high, clip)


def encode_shots(
    config: GameConfig | PoolConfig | Any,
    positions: ArrayLike,
    refer: ArrayLike,
    angles: ArrayLike,
    speeds: ArrayLike,
    tips: ArrayLike | None = None,
) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
    """The aim, speed (and tip) components of many shots on many layouts: one compiled call.

    What :func:`encode_action` writes for the shot's own parts, for every candidate shot of
    a planner or an observation feature, marking rather than refusing what it cannot play.
    (Under rules the cue ball's placement and the called pocket are not parts of the shot:
    :func:`encode_action` writes them.)

    Args:
        config: The env's config (its aim mode, aim and speed ranges, ball radius, tip limit).
        positions: ``(B, N, 2)`` ball centres, cue first.
        refer: ``(B, N)`` the balls the aim may refer to: those on the table (under rules,
            the legal first contacts).
        angles: ``(B, M)`` shot directions (radians from +x).
        speeds: ``(B, M)`` cue speeds (m/s); clipped to the speed range.
        tips: ``(B, M, 2)`` cue tip offsets ``(side, vertical)`` in fractions of R, within
            the tip limit (spin tables; default centre ball).

    Returns:
        ``(actions, playable)``: ``(B, M, 2)`` float64 components ``(aim, speed)`` in
        ``[-1, 1]``, ``(B, M, 4)`` with ``(side, vertical)`` on a spin table, and ``(B, M)``
        whether the aim mode can play each direction (1e-9 rad of slack at the ends).

    Raises:
        ValueError: On shapes that do not fit together, a tip on a roll table, or a tip
            beyond the tip limit.
    """
    config = game_config(config, "encode_shots")
    pos = np.ascontiguousarray(positions, dtype=np.float64)
    ref = np.ascontiguousarray(refer, dtype=np.bool_)
    ang = np.ascontiguousarray(angles, dtype=np.float64)
    spd = np.ascontiguousarray(speeds, dtype=np.float64)
    if pos.ndim != 3 or pos.shape[2] != 2 or ref.shape != pos.shape[:2]:
        raise ValueError(f"positions (B, N, 2) and refer (B, N), got {pos.shape}, {ref.shape}")
    if ang.ndim != 2 or ang.shape[0] != pos.shape[0] or spd.shape != ang.shape:
        raise ValueError(f"angles and speeds must be ({pos.shape[0]}, M), got {ang.shape}")
    tip = np.zeros((*ang.shape, 2)) if tips is None else np.array(tips, dtype=np.float64)
    if tip.shape != (*ang.shape, 2):
        raise ValueError(f"tips must be {(*ang.shape, 2)}, got {tip.shape}")
    limit = 0.0 if config.tip_limit is None else float(config.tip_limit)
    if limit == 0.0 and tip.any():
        raise ValueError("tips need a spin table: a roll table has no tip")
    if limit and (np.hypot(tip[..., 0], tip[..., 1]) > limit * (1.0 + 1e-12)).any():
        raise ValueError(f"tips must lie within the tip limit {limit!r} (miscue)")
    params = config.params
    return kernel_encode_shots(
        int(params[kp.AIM_MODE]), *config.aim_range, *config.speed_range,
        float(params[kp.RADIUS]), limit, pos, ref, ang, spd, tip,
    )  # fmt: skip


def decode_observations(
    table: Table, observations: ArrayLike
) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
    """The layouts that ``(B, 3 N)`` observations show: the inverse of the env's encoding.

    :func:`pool_env.encode_observations` scales each centre onto ``[-1, 1]`` in float32
    (~0.1 um); this scales it back and keeps it where a centre can be (``R`` from the
    rails), so that a decoded layout is a function of the observation alone. Balls that
    decode touching are left touching.

    Args:
        table: The env's table (its size and ball radius).
        observations: ``(B, 3 N)`` observations (or their first ``3 N`` columns).

    Returns:
        ``(positions, on_table)``: ``(B, N, 2)`` float64 centres and ``(B, N)`` flags.
    """
    obs = np.asarray(observations, dtype=np.float64)
    if obs.ndim != 2 or obs.shape[1] % 3:
        raise ValueError(f"observations must be (B, 3 N), got shape {obs.shape}")
    per_ball = obs.reshape(obs.shape[0], -1, 3)
    r = table.ball_radius
    positions = np.empty(per_ball.shape[:2] + (2,))
    for axis, size in enumerate((table.length, table.width)):
        positions[..., axis] = np.clip((per_ball[..., axis] + 1.0) * size / 2.0, r, size - r)
    return positions, per_ball[..., 2] > 0.5


def game_config(source: Any, caller: str) -> GameConfig:
    """The parsed config of ``source``: what :func:`obs_layout` and the like take.

    Args:
        source: A :class:`~pool_env.game.config.GameConfig` (``env.unwrapped.config``), a
            :class:`~pool_env.PoolConfig` (what :func:`pool_env.default_config` returns:
            parsed here, as an env of one agent parses it) or an env, wrapped or not (its
            ``unwrapped.config``: ``PoolEnv``, ``PoolVectorEnv``, the two-player fronts;
            a ``SyncVectorEnv`` of them: its first env's).
        caller: The public function's name, for the message.

    Raises:
        ValueError: On anything else, saying what it takes; on a ``PoolConfig`` that does
            not parse, naming its bad key.
    """
    if isinstance(source, GameConfig):
        return source
    if isinstance(source, PoolConfig):
        return make_config(source)
    config = getattr(getattr(source, "unwrapped", source), "config", None)
    if isinstance(config, GameConfig):
        return config
    envs = getattr(source, "envs", None)  # Gymnasium's SyncVectorEnv: its envs share one
    if isinstance(envs, list | tuple) and envs:
        return game_config(envs[0], caller)
    raise ValueError(
        f"{caller} takes a GameConfig (env.unwrapped.config), a PoolConfig "
        f"(pool_env.default_config()) or a pool_env env, got {type(source).__name__} "
        f"{source!r:.80}"
    )


def obs_layout(config: GameConfig | PoolConfig | Any) -> dict[str, slice]:
    """Where each part of the env's observation lies: a slice per part, by name.

    Every game has ``"balls"`` (``(x, y, on_table)`` per ball, the cue ball first); the
    rule games add ``"legal"`` (object balls ``1..N-1``: may the viewer hit it first) and
    one entry per rule feature (``"ball_in_hand"``, ``"behind_head_string"``, ``"break"``,
    ``"open_table"``, ``"fouls"``, ``"opponent_fouls"``, ``"to_shoot"``; 9-ball and
    10-ball also ``"push_out"`` and ``"option"``): the game's
    :meth:`~pool_env.game.ruleset.Ruleset.obs_layout`. With ``observation="shots"``
    the last part is ``"shots"``: per pocket the
    :data:`~pool_env.game.shot_features.SHOT_FEATURES` row.

    Examples:
        >>> import gymnasium as gym, pool_env
        >>> from pool_env import obs_layout
        >>> env = gym.make("pool_env/NineBallGame-v2")
        >>> layout = obs_layout(env.unwrapped.config)
        >>> layout["balls"], layout["legal"], layout["ball_in_hand"]
        (slice(0, 30, None), slice(30, 39, None), slice(39, 40, None))
        >>> obs_layout(env) == layout  # the env itself, or pool_env.default_config(...)
        True

    Args:
        config: The env's config (``env.unwrapped.config``), a :class:`~pool_env.PoolConfig`
            (:func:`pool_env.default_config`) or the env, wrapped or not.

    Raises:
        ValueError: On anything else (:func:`game_config`).
    """
    config = game_config(config, "obs_layout")
    layout = config.ruleset.obs_layout(config.n_balls)
    if config.shot_features_width:
        end = config.observation_size
        layout["shots"] = slice(end - config.shot_features_width, end)
    return layout


def shot_constraints(
    config: GameConfig | PoolConfig | Any, observation: ArrayLike
) -> ShotConstraints:
    """What the next shot may do, as the observation's viewer sees it (the game's rules).

    The legal first balls, ball in hand and its placement box, the break (and its speed
    range), whether the called pocket counts: the game's
    :meth:`~pool_env.game.ruleset.Ruleset.constraints`. Agents ask this rather than
    restate the rules.

    The observation must be one of this config's game: of its size, every entry in
    ``[-1, 1]``, each ball's ``on_table`` entry 0 or 1 with a potted ball at ``(0, 0)``
    and the cue ball on, and under rules every flag 0 or 1 (the successive fouls 0, 1/2
    or 1), a legal first ball on the table, the push-out and the option for the viewer
    to shoot only. An
    observation of another game of the same size (15-ball solitaire's against 9-ball's)
    fails these in all but contrived layouts.

    Args:
        config: The env's config (``env.unwrapped.config``), a :class:`~pool_env.PoolConfig`
            (:func:`pool_env.default_config`) or the env, wrapped or not.
        observation: One observation of that env.

    Raises:
        ValueError: On another config (:func:`game_config`), or an observation that is
            not one of the config's game, saying which entry.
    """
    config = game_config(config, "shot_constraints")
    obs = np.asarray(observation)
    if obs.shape != (config.observation_size,):
        raise ValueError(
            f"observation must have shape ({config.observation_size},), got {obs.shape}"
        )
    if obs.dtype.kind not in "fiu":
        raise ValueError(f"observation must be real numbers, got dtype {obs.dtype}")
    _check_balls(config, obs)
    return config.ruleset.constraints(config, obs)


def _check_balls(config: GameConfig, obs: NDArray[Any]) -> None:
    """Refuse an observation whose entries, or ball part, no env of ``config`` gives."""
    game = config.rules.game
    if not np.all(np.abs(obs) <= 1.0):  # NaN too
        k = int(np.flatnonzero(~(np.abs(obs) <= 1.0))[0])
        raise ValueError(
            f"observation[{k}] = {float(obs[k])!r} lies outside [-1, 1]: not an observation of "
            f"this env (game={game!r})"
        )
    balls = obs[config.ruleset.obs_layout(config.n_balls)["balls"]].reshape(-1, 3)
    on = balls[:, 2]
    off = on == 0.0
    bad = ~(off | (on == 1.0)) | (off & ((balls[:, 0] != 0.0) | (balls[:, 1] != 0.0)))
    if bad.any() or off[0]:
        j = 0 if off[0] else int(np.flatnonzero(bad)[0])
        raise ValueError(
            f"observation entries {3 * j}..{3 * j + 2} {balls[j].tolist()} are no ball "
            f"{j} of game={game!r} (x, y, on_table: on_table 0 or 1, a potted ball at "
            "(0, 0), the cue ball on): not an observation of this env"
        )


def reference_balls(positions: ArrayLike, refer: ArrayLike) -> NDArray[np.int64]:
    """The ball that relative and cut aim refer to in each of ``B`` layouts (-1: none).

    The nearest ball to the cue ball (ball 0) among ``refer`` (``(B, N)``; the balls on
    the table, or under rules the legal first contacts), ties to the lower index: what
    :func:`decode_action` and :func:`encode_action` aim from.

    Raises:
        ValueError: On shapes that do not fit together.
    """
    pos = np.ascontiguousarray(positions, dtype=np.float64)
    ref = np.ascontiguousarray(refer, dtype=np.bool_)
    if pos.ndim != 3 or pos.shape[2] != 2 or ref.shape != pos.shape[:2]:
        raise ValueError(f"positions (B, N, 2) and refer (B, N), got {pos.shape}, {ref.shape}")
    return kernel_reference_balls(pos, ref)


def encode_action(
    config: GameConfig | PoolConfig | Any,
    shot: Shot,
    positions: ArrayLike,
    on_table: ArrayLike | None = None,
    rack: Any = None,
    clip: bool = False,
) -> NDArray[np.float64]:
    """The action that plays ``shot`` from this layout (the inverse of :func:`decode_action`).

    Args:
        config: The env's config (``env.unwrapped.config``).
        shot: The shot wanted: aim direction, speed, tip (spin), placement and pocket (rules).
        positions: ``(N, 2)`` ball centres.
        on_table: ``(N,)`` which balls are on the table (default: all).
        rack: Rules only: the rack state (``env.unwrapped.rack``); it says whether the cue
            ball is in hand (``shot.cue`` is then its placement; ``None`` keeps it where
            it lies), whether the shot is a break (the break's speed range) and which balls
            cut and relative aim may refer to.
        clip: Map parts outside the action's reach onto its edge instead of raising.

    Returns:
        ``(action_size,)`` float64 in ``[-1, 1]`` (float64 keeps the shot exact; the env
        takes any real dtype).

    Raises:
        ValueError: On a part the action cannot play (without ``clip``): an angle outside
            the aim range (cut aim: more than 90 degrees off its reference ball), a speed
            outside its range, a tip beyond the tip limit or any tip on a roll table, a
            pocket that does not exist; on a part that is not a finite number (with or
            without ``clip``: no edge is nearest to NaN); or a malformed layout or rack.
    """
    config = game_config(config, "encode_action")
    _check_finite(shot)
    state = _table(config, positions, on_table, rack)
    out = np.zeros(config.action_size)
    _tip(config, shot.tip, out, clip)
    speeds = config.ruleset.encode(config, shot, state, out, clip)
    out[0] = _aim(config, state, float(shot.angle), clip)
    out[1] = unit_component("speed", float(shot.speed), *speeds, clip)
    return out


def encode_placement(
    config: GameConfig | PoolConfig | Any, cue: ArrayLike, behind: bool = False, clip: bool = False
) -> tuple[float, float]:
    """The action components (``action[2]``, ``action[3]``) that place the cue ball in hand.

    Args:
        config: A rules env's config.
        cue: ``(x, y)`` where the cue ball should go (m).
        behind: Ball in hand behind the head string (the kitchen, ``x <= L / 4``).
        clip: Map a point outside the placement box onto its edge instead of raising.

    Raises:
        ValueError: On a solitaire config, or a point outside the box (without ``clip``).
    """
    config = game_config(config, "encode_placement")
    return config.ruleset.encode_placement(config, cue, behind, clip)


def encode_pocket(config: GameConfig | PoolConfig | Any, pocket: int) -> float:
    """The action component (``action[4]``) that calls ``pocket``: the middle of its bin.

    Raises:
        ValueError: If the table has no pocket ``pocket``.
    """
    config = game_config(config, "encode_pocket")
    return pocket_component(config.table.n_pockets, pocket)


def encode_ball(config: GameConfig | PoolConfig | Any, ball: int) -> float:
    """The action component that calls object ball ``ball`` (10-ball): the middle of its bin.

    Raises:
        ValueError: On a game that calls no ball, or a ball that is not one of its own.
    """
    config = game_config(config, "encode_ball")
    return config.ruleset.encode_ball(config, ball)


def _tip(
    config: GameConfig, tip: tuple[float, float], out: NDArray[np.float64], clip: bool
) -> None:
    """Write the tip's action components (a spin table's last two) into ``out``."""
    a, b = (float(v) for v in tip)
    if config.tip_columns is None:
        if a != 0.0 or b != 0.0:
            raise ValueError(f"tip {tip!r} needs a spin table: a roll table has no tip")
        return
    limit = float(config.tip_limit)  # type: ignore[arg-type]
    norm = math.sqrt(a * a + b * b)
    if norm > limit * (1.0 + 1e-12):
        if not clip:
            raise ValueError(f"tip {tip!r} lies beyond the tip limit {limit!r} (miscue)")
        a, b = onto_tip_circle(a, b, limit)  # the decoder's own rule
    side, vertical = config.tip_columns
    out[side], out[vertical] = tip_components(a, b, limit)
