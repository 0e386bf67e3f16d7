"""Checks of what the decision process takes: each error is a ``ValueError`` naming it.

The config's values (tables, ranges, noise, counts), actions and reset options, checked
here for every front, so that the same bad input gets the same message from each; what
only a Gymnasium front takes (seeds, reset masks, render modes) is checked in
:mod:`pool_env.envs.checks`.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from pool_env.game.noise import MAX_NORMAL_DRAW, MAX_SIGMA_ANGLE, NOISE_MODELS
from pool_env.sim.constants import MAX_SPEED
from pool_env.sim.inputs import max_speed, speed_limits
from pool_env.sim.levels import level_of
from pool_env.sim.spin_inputs import reachable_spin_speed
from pool_env.sim.table import MODELS, Table


def parse_table(
    table: Table | Mapping[str, Any] | None, model: str | None, default_model: str
) -> Table:
    """A :class:`Table`, the ``Table(**mapping)`` of a dict (a config file), or the default.

    Args:
        table: The table, its keyword arguments, or ``None`` (the default table).
        model: ``"roll"`` or ``"spin"`` (the env's ``model`` keyword, which the ids set),
            or ``None``: a :class:`Table`'s own, else ``default_model``. A dict or ``None``
            gets it as its ``model``; a :class:`Table` (or a dict naming a model) must
            already have it.
        default_model: The model of a table given as ``None`` or as a dict that names no
            model, when ``model`` is ``None`` (the config's
            :data:`~pool_env.game.sections.DEFAULT_MODEL`).

    Raises:
        ValueError: On a bad table, an unknown model, or a table of another model.
    """
    if model is not None and model not in MODELS:
        raise ValueError(f"model must be one of {list(MODELS)} or None, got {model!r}")
    if table is None:
        return Table(model=default_model if model is None else model)
    if isinstance(table, Table):
        if model is not None and table.model != model:
            raise ValueError(
                f"model={model!r} but the table given is Table(model={table.model!r}): pass "
                f"model={table.model!r}, or a Table(model={model!r}, ...)"
            )
        return table
    if isinstance(table, Mapping):
        if model is not None and table.get("model", model) != model:
            raise ValueError(
                f"model={model!r} but table['model'] is {table['model']!r}: give one model"
            )
        try:
            return Table(
                **{"model": default_model, **table, **({} if model is None else {"model": model})}
            )
        except TypeError as exc:
            raise ValueError(f"table: {exc}") from None
    raise ValueError(
        f"table must be a pool_env.Table, a dict of Table arguments or None, got {table!r}"
    )


def parse_float(name: str, value: object) -> float:
    """A finite number: not a string or a bool, which ``float()`` would take (``"0.5"``, 1.0)."""
    if isinstance(value, str | bytes | bool | np.bool_):
        raise ValueError(f"{name} must be a number, got {value!r}")
    try:
        out = float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number, got {value!r}") from None
    if not math.isfinite(out):
        raise ValueError(f"{name} must be finite, got {value!r}")
    return out


def parse_range(name: str, value: object, minimum: float | None) -> tuple[float, float]:
    """A pair ``(low, high)`` of finite numbers with ``low <= high`` (and ``low >= minimum``)."""
    try:
        low, high = (parse_float(name, v) for v in value)  # type: ignore[union-attr]
    except (TypeError, ValueError) as exc:
        raise ValueError(
            f"{name} must be a pair (low, high) of finite numbers, got {value!r}"
        ) from exc
    if not low <= high or (minimum is not None and low < minimum):
        floor = "" if minimum is None else f" and low >= {minimum}"
        raise ValueError(f"{name} must have low <= high{floor}, got {value!r}")
    return low, high


def parse_noise(value: object, table: Table) -> tuple[float, ...] | None:
    """Noise sigmas ``(angle, speed)`` or, on a spin table, ``(angle, speed, tip)``.

    ``value`` is the sigmas themselves (angle in radians, speed in m/s, tip in fractions of
    R; all >= 0), or a noise model by name (:mod:`pool_env.game.noise`): ``"fastfiz"`` or
    ``("fastfiz", k)``, its sigmas times ``k >= 0``. ``None`` when off (or all 0). A roll
    table has no cue tip: there a non-zero tip sigma given as a number is refused (a zero one
    is accepted, so one noise setting serves every id), and a named model has none.
    """
    if value is None:
        return None
    if isinstance(value, str) or (
        isinstance(value, tuple | list) and len(value) > 0 and isinstance(value[0], str)
    ):
        name, multiple = _noise_model(value)
        sigmas = NOISE_MODELS[name](table, multiple)
        if sigmas[0] > MAX_SIGMA_ANGLE:
            k_max = MAX_SIGMA_ANGLE / NOISE_MODELS[name](table, 1.0)[0]
            raise ValueError(
                f"noise={value!r}: k must be at most {k_max:.6g}, where the angle's sigma "
                f"reaches pi rad (beyond, the executed aim is uniform over the circle); the "
                f"speed ranges may allow less (the speed sigma's bound is checked next)"
            )
        return None if not any(sigmas) else sigmas
    try:
        sigmas = tuple(parse_float("noise", v) for v in value)  # type: ignore[union-attr]
    except (TypeError, ValueError) as exc:
        raise ValueError(
            f"noise must be (sigma_angle, sigma_speed), (sigma_angle, sigma_speed, "
            f"sigma_tip), {_NAMED}, got {value!r}"
        ) from exc
    if len(sigmas) not in (2, 3):
        raise ValueError(
            f"noise must be (sigma_angle, sigma_speed), (sigma_angle, sigma_speed, "
            f"sigma_tip), {_NAMED}, got {value!r}"
        )
    if min(sigmas) < 0.0:
        raise ValueError(f"noise sigmas must be >= 0, got {value!r}")
    if sigmas[0] > MAX_SIGMA_ANGLE:
        raise ValueError(
            f"noise={value!r}: the angle's sigma must lie in [0, pi] rad: beyond it the "
            "executed aim is uniform over the circle"
        )
    if len(sigmas) == 3 and sigmas[2] != 0.0 and not table.has_spin:
        raise ValueError(
            f"noise {value!r} has a tip sigma, but a roll table has no cue tip: use "
            "model='spin' (the spin ids) or give (sigma_angle, sigma_speed)"
        )
    if not table.has_spin:
        sigmas = sigmas[:2]
    return None if not any(sigmas) else sigmas


#: The named spellings of ``noise``, for the messages.
_NAMED = " or ".join(f"{name!r} or ({name!r}, k)" for name in NOISE_MODELS)


def _noise_model(value: str | tuple[Any, ...] | list[Any]) -> tuple[str, float]:
    """The model's name and multiple of ``"name"`` or ``("name", k)``, checked."""
    name, rest = (value, ()) if isinstance(value, str) else (value[0], tuple(value[1:]))
    if name not in NOISE_MODELS:
        raise ValueError(
            f"unknown noise model {name!r}: use {_NAMED}, or the sigmas (sigma_angle, "
            "sigma_speed[, sigma_tip])"
        )
    if isinstance(value, str):
        return name, 1.0
    if len(rest) != 1:
        raise ValueError(f"noise ({name!r}, k) takes one multiple k >= 0, got {value!r}")
    multiple = parse_float(f"noise ({name!r}, k): k", rest[0])
    if multiple < 0.0:
        raise ValueError(f"noise ({name!r}, k): k must be >= 0, got {value!r}")
    return name, multiple


def parse_bool(name: str, value: object) -> bool:
    """A real boolean (not a truthy string)."""
    if not isinstance(value, bool | np.bool_):
        raise ValueError(f"{name} must be True or False, got {value!r}")
    return bool(value)


def is_integer(value: object) -> bool:
    """Whether ``value`` is a Python or numpy integer, and not a bool (which is an ``int``)."""
    return isinstance(value, int | np.integer) and not isinstance(value, bool | np.bool_)


def parse_count(name: str, value: object) -> int | None:
    """A positive integer, or ``None``."""
    if value is None:
        return None
    if not is_integer(value) or value < 1:  # type: ignore[operator]
        raise ValueError(f"{name} must be a positive integer or None, got {value!r}")
    return int(value)


def check_actions(
    actions: object,
    n: int,
    single: bool,
    tables: NDArray[np.intp] | None = None,
    width: int = 2,
) -> NDArray[np.float64]:
    """Actions as a ``(n, width)`` float64 array, checked alike for every front.

    Every real dtype is accepted and converted to float64 (exact for float16 and float32;
    long double rounds to the nearest double), whatever its byte order; complex numbers,
    strings and objects are rejected, since their imaginary part or text has no meaning as
    an aim or a speed. Out-of-range values (infinities included) are left to the decoding,
    which clips them; NaN has no direction to clip it to and raises.

    Args:
        actions: ``(2,)`` when ``single`` (one table), else ``(n, 2)``.
        n: Number of tables.
        single: Whether this is the single environment's one action.
        tables: The tables whose actions are played (``None``: all); only their rows are
            returned and checked for NaN (the others are ignored, as an autoreset does).
        width: Action components (2; 5 under rules; spin tables: 2 more).

    Returns:
        ``(K, width)`` float64 for the ``K`` tables, a new array (the caller's is never kept).

    Raises:
        ValueError: On a bad shape, a non-real dtype, or a NaN (naming the table).
    """
    what = "the action" if single else "actions"
    shape = (width,) if single else (n, width)
    arr = actions if isinstance(actions, np.ndarray) else None
    if arr is None:
        try:
            arr = np.asarray(actions)
        except (TypeError, ValueError) as exc:
            raise ValueError(f"{what} must be real numbers of shape {shape}: {exc}") from None
    if arr.dtype.kind not in "fiub":
        raise ValueError(f"{what} must be real numbers of shape {shape}, got dtype {arr.dtype}")
    if arr.shape != shape:
        raise ValueError(f"{what} must have shape {shape}, got {arr.shape}")
    out = np.array(arr, dtype=np.float64, order="C").reshape(n, width)
    if tables is not None:
        out = out[tables]
    if single and width == 2:  # two Python floats test faster than numpy's reductions
        x, y = out[0].tolist()
        nan = x != x or y != y
    elif single:  # and so do the few of a spin or rules action
        nan = any(v != v for v in out[0].tolist())
    else:
        nan = bool(np.isnan(out).any())
    if nan:
        k = int(np.argmax(np.isnan(out).any(axis=1)))
        table = k if tables is None else int(tables[k])
        where = "the action" if single else f"the action of table {table}"
        raise ValueError(f"{where} contains NaN: {out[k].tolist()}; nothing was changed")
    return out


def check_options(options: object) -> dict[str, Any]:
    """Reset options: ``None`` or a mapping, as a new dict (``ValueError`` otherwise)."""
    if options is None:
        return {}
    if not isinstance(options, Mapping):
        raise ValueError(f"options must be a dict or None, got {options!r}")
    return dict(options)


#: The contact offset (fraction of R) beyond which a real tip miscues: about half a radius
#: (pooltool and Dr. Dave's miscue-limit FAQ). The default tip limit is the axis offset
#: that gives it (:func:`default_tip_limit`).
MISCUE_CONTACT_OFFSET = 0.5


def default_tip_limit(table: Table) -> float:
    """The default tip limit of a spin table: the axis offset of a half-radius contact.

    The tip's contact point lies ``1 / (1 + r_tip / R)`` of the axis offset from the ball's
    centre line (:mod:`pool_env.sim.kernels.spin.strike`), so the axis offset of a contact
    offset ``c`` is ``c (1 + r_tip / R)``: 0.685 for the default 10.6 mm tip (capped at 1).
    """
    return min(1.0, MISCUE_CONTACT_OFFSET * (1.0 + table.cue_tip_radius / table.ball_radius))


def parse_tip_limit(table: Table, tip_limit: object) -> float | None:
    """The tip limit of a spin table (``None``: :func:`default_tip_limit`); ``None`` on roll.

    Raises:
        ValueError: Unless a number in ``(0, 1]``, or when given for a roll table.
    """
    if not table.has_spin:
        if tip_limit is not None:
            raise ValueError("tip_limit needs a spin table: model='spin' (the spin ids)")
        return None
    if tip_limit is None:
        return default_tip_limit(table)
    limit = parse_float("tip_limit", tip_limit)
    if not 0.0 < limit <= 1.0:
        raise ValueError(f"tip_limit must lie in (0, 1] (a fraction of R), got {tip_limit!r}")
    return limit


#: Relative margin kept below the speed ceiling: the kernels compute a strike's energy at its
#: own speed, not scaled from a unit strike as :func:`strike_speed_limit` does, a few
#: roundings (~1e-16 each) apart.
_ROUNDING_MARGIN = 1e-12


def strike_speed_limit(table: Table, tip_limit: float | None) -> float:
    """The fastest cue ball speed (m/s) a strike on ``table`` may have at any tip it allows.

    The simulator refuses a shot whose speed, or on a spin table whose energy with the
    spin the tip gives, passes its limits (:func:`pool_env.sim.inputs.max_speed`; the
    spin's surface speed too). A strike scales with its speed, so the limit is the
    table's over the strike of unit speed at the largest tip offset ``tip_limit`` (the
    executed tip never leaves that circle; the spin grows with the offset alone).

    Args:
        table: The table.
        tip_limit: The tip limit (fraction of R), ``None`` on a roll table.
    """
    velocity, angular = level_of(table).strike(table, 1.0, 0.0, tip_limit or 0.0, 0.0, 0.0)
    unit = float(np.hypot(*velocity))
    if table.has_spin:
        unit = reachable_spin_speed(table, velocity[None], angular[None])
    limit = max_speed(table) / unit
    surface = table.ball_radius * float(np.sqrt(angular @ angular))
    if surface > 0.0:
        limit = min(limit, MAX_SPEED / surface)
    return limit * (1.0 - _ROUNDING_MARGIN)


@dataclass(frozen=True)
class SpeedCeiling:
    """What a speed range's top may be: the fastest strike less the noise's largest draw.

    Built once per config (:func:`pool_env.game.config.make_config`), which checks the
    task's ``speed_range`` with it; a game checks its own ranges (the WPA break's) with
    the same, so no step can ask the simulator for a strike it refuses.

    Attributes:
        table: The table.
        tip_limit: The tip limit (fraction of R), ``None`` on a roll table.
        sigma_speed: The noise's speed sigma (m/s; 0 without noise).
        noise: The ``noise`` as the user gave it, for the messages.
        strike: :func:`strike_speed_limit` of the table and tip limit (m/s).
    """

    table: Table
    tip_limit: float | None
    sigma_speed: float
    noise: object
    strike: float = field(init=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "strike", strike_speed_limit(self.table, self.tip_limit))

    @property
    def top(self) -> float:
        """The largest top speed (m/s) a range may have with this noise."""
        return self.strike - MAX_NORMAL_DRAW * self.sigma_speed

    def check(self, name: str, given: object, high: float) -> None:
        """Refuse a range ``name`` (``given`` as written) whose top ``high`` passes :attr:`top`.

        Raises:
            ValueError: Naming the range when it passes the strike limit itself, else the
                noise, with the largest value each may have here.
        """
        spin = (f"; here at the tip limit {self.tip_limit:.6g} R, the spin's energy counted"
                if self.tip_limit else "")  # fmt: skip
        where = f"the simulator takes on this table ({speed_limits(self.table)}{spin})"
        if high > self.strike:
            raise ValueError(
                f"{name}={given!r}: its top speed must be at most {self.strike:.6g} m/s, the "
                f"fastest strike {where}"
            )
        if high > self.top:
            reach = high + MAX_NORMAL_DRAW * self.sigma_speed
            largest = (self.strike - high) / MAX_NORMAL_DRAW
            raise ValueError(
                f"noise={self.noise!r}: its speed sigma {self.sigma_speed:.6g} m/s, whose "
                f"draws reach {MAX_NORMAL_DRAW} sigma, could take {name}'s top speed "
                f"{high:g} m/s to {reach:.6g} m/s, beyond the {self.strike:.6g} m/s "
                f"{where}: the speed sigma must be at most {largest:.6g} m/s here"
                + self._model_bound(largest)
            )

    def _model_bound(self, largest: float) -> str:
        """For a named noise model, the largest multiple ``k`` the speed sigma allows."""
        named = self.noise if isinstance(self.noise, str) else None
        if isinstance(self.noise, tuple | list) and self.noise and isinstance(self.noise[0], str):
            named = self.noise[0]
        if named not in NOISE_MODELS:
            return ""
        unit = NOISE_MODELS[named](self.table, 1.0)[1]
        return f" (({named!r}, k) with k at most {largest / unit:.6g})"
