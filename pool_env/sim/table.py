"""The table: frozen, validated geometry and physics parameters, and its pockets.

Frame: the origin is one corner of the playing surface at the cushion noses; x runs along the
length, y along the width. A ball centre lives in ``[R, L - R] x [R, W - R]``.
"""

from __future__ import annotations

from dataclasses import dataclass, field, fields

import numpy as np
from numpy.typing import NDArray

from pool_env.sim.kernels import limits
from pool_env.sim.kernels.params import (
    N_PARAMS,
    P_DECEL,
    P_E_BALL,
    P_E_CUSHION,
    P_E_JAW,
    P_LENGTH,
    P_MASS,
    P_RADIUS,
    P_WIDTH,
)
from pool_env.sim.kernels.spin.params import (
    ALCIATORE_FRICTION,
    CONSTANT_FRICTION,
    FRICTIONLESS,
    N_SPIN_PARAMS,
    POOLTOOL_FRICTION,
    S_BALL_MODEL,
    S_CUSHION_FRICTION,
    S_CUSHION_HEIGHT,
    S_CUSHION_MODEL,
    S_END_MASS,
    S_FRICTION_MODE,
    S_MATHAVAN_STEPS,
    S_MU_BALL,
    S_MU_SLIDE,
    S_OMEGA_RATIO,
    S_SLIDE_DECEL,
    S_SPIN_DECEL,
    S_TIP_RADIUS,
)
from pool_env.sim.pocket_spec import parse_pockets, standard_pockets
from pool_env.sim.pockets import (
    CORNER_MOUTH,
    SIDE_MOUTH,
    JawSpec,
    PocketJaws,
    kernel_rows,
    rail_segments,
)
from pool_env.sim.presets import PRESETS, ROLL_ALLOWED
from pool_env.sim.scalars import positive, real_number, within
from pool_env.sim.spin_models import BALL_MODELS, CUSHION_MODELS, check_models

__all__ = ["CORNER_MOUTH", "SIDE_MOUTH", "JawSpec", "PocketJaws", "Table", "standard_pockets"]

#: The model levels: "roll" (balls roll without spin, the cheap level) and "spin".
MODELS = ("roll", "spin")
#: The model levels whose balls carry spin (angular velocities, a cue tip, elevation).
SPIN_MODELS = ("spin",)
#: The parameters only the spin level reads. A roll table keeps each at its default: a
#: value set there would change nothing, so ``Table`` refuses it.
SPIN_ONLY = (
    "mu_slide",
    "spin_decel",
    "ball_friction",
    "cushion_friction",
    "cushion_height",
    "cue_tip_radius",
    "cue_end_mass",
    "cushion_model",
    "cushion_omega_ratio",
    "ball_model",
    "mathavan_steps",
)
#: ``u_sp / R`` of the default spin deceleration, 0.444: pooltool 0.6.0's ``4/9`` to three
#: digits (its code has ``10 * 2 / 5 / 9``; ``Table.preset("pooltool-0.6")`` takes that).
SPIN_FRICTION_RATIO = 0.444
#: Cushion nose height as a fraction of the ball diameter (WPA equipment specifications:
#: 63.5% of the ball's height, 62.5-64.5%); pooltool 0.6.0 uses 0.64 x 2R.
NOSE_HEIGHT_FRACTION = 0.635


def roll_keywords(keywords: dict[str, object]) -> dict[str, object]:
    """``Table`` keywords less those only the spin level reads (:data:`SPIN_ONLY`).

    What a table of these keywords keeps on the roll level, which refuses spin-only values
    set away from their defaults (``Table.preset("snooker", model="roll")``, and the roll
    twin of an id registered with a preset's table).
    """
    return {k: v for k, v in keywords.items() if k not in SPIN_ONLY}


def _non_negative(name: str, value: object) -> float:
    value = real_number(name, value)
    if value < 0.0:
        raise ValueError(f"{name} must be a non-negative finite number, got {value!r}")
    return value


def _check_restitution(name: str, value: object) -> float:
    value = real_number(name, value)
    if not (0.0 <= value <= 1.0):
        raise ValueError(f"{name} must lie in [0, 1], got {value!r}")
    return value


@dataclass(frozen=True, eq=False)
class Table:
    """A pool table: geometry, ball properties and the rolling/impact model parameters.

    All values are SI units. The defaults describe a regulation 9-ft table, each measured
    figure from the sources in ``docs/sources.md`` ("Real tables"):

    Every parameter as pooltool 0.6.0 ships it, models included: ``Table.preset(
    "pooltool-0.6")`` (:mod:`pool_env.sim.presets`).

    * ``mu_roll = 0.01``: rolling resistance of a pool ball on cloth, 0.005-0.015 (Dr. Dave
      Alciatore's FAQ "physical properties"; pooltool 0.6 also uses 0.01).
    * ``e_ball = 0.95``: ball-ball restitution, 0.92-0.98 (same FAQ).
    * ``e_cushion = 0.65``: ball-rail restitution, 0.6-0.9 (same FAQ); "at steep angles a
      ball typically loses about half its speed" in a cushion (FAQ "cushion efficiency"),
      part of which is the sliding after the impact that this model leaves out, so we sit
      near the low end of the range.
    * pockets: the WPA regulation jaws (see :mod:`pool_env.sim.pockets`).

    Args:
        length: Playing length ``L`` between the cushion noses (m).
        width: Playing width ``W`` between the cushion noses (m).
        ball_radius: Radius ``R`` of every ball (m).
        ball_mass: Default ball mass (kg); ``simulate`` accepts per-ball masses.
        mu_roll: Coefficient of rolling resistance; balls decelerate at ``mu_roll * g``.
        g: Gravitational acceleration (m/s^2).
        e_ball: Ball-ball coefficient of restitution, in [0, 1].
        e_cushion: Ball-rail coefficient of restitution, in [0, 1].
        pockets: ``"jaws"`` (default; ``"standard"`` is the same): six regulation pockets
            with jaws; a :class:`~pool_env.sim.pockets.JawSpec` for other jaw shapes;
            ``"circles"``: the six pockets as capture circles with full-length rails (the
            cheap model); ``"none"``: a carom table; or a sequence of ``(x, y, radius)``
            capture circles.
        e_jaw: Restitution of the jaw facings and points, in [0, 1]; ``None`` (default)
            takes ``e_cushion``.
        model: ``"roll"`` (default): balls roll without spin and the parameters below are
            ignored (bit for bit the original model); ``"spin"``: the spin level (sliding,
            rolling, spinning, english, throw, cushion spin), see
            :mod:`pool_env.sim.kernels.spin.level`; every pocket model.
        mu_slide: Sliding friction ball-cloth, 0.2 (Alciatore's physical-properties table:
            0.15-0.4, typical 0.2; pooltool 0.6.0's default). A sliding ball decelerates at
            ``mu_slide * g`` against its contact point's slip.
        spin_decel: Deceleration of the vertical-axis spin (rad/s^2); ``None`` (default)
            takes ``(5 / 2) * 0.444 * g`` = 10.8891 rad/s^2 (Alciatore's table: 5-15
            rad/s^2). Not pooltool's to the last digit: pooltool 0.6.0's
            ``u_sp = (4/9) R`` gives 10.9; the default keeps 0.444 so that the figures
            measured with it stay reproducible, and ``Table.preset("pooltool-0.6")`` has
            10.9.
        ball_friction: Ball-ball friction: ``"alciatore"`` (default) for Alciatore's fit
            to Marlow's data ``0.00995 + 0.108 exp(-1.088 v_rel)`` (pooltool 0.6.0's
            default), ``"pooltool"`` for the same fit with pooltool 0.6.0's friction impulse
            ``mu e_b c`` (its exact model, for comparisons; see
            :mod:`~pool_env.sim.kernels.spin.collide`), a constant ``>= 0``, or 0 for
            frictionless balls.
        cushion_friction: Ball-cushion friction, 0.2 (pooltool 0.6.0's default).
        cushion_height: Height of the cushion nose's contact above the cloth (m), in
            ``[R, 2R)``; ``None`` (default) takes the WPA nose height, 63.5% of the ball
            diameter (``1.27 R``; pooltool uses 0.64 x 2R).
        cue_tip_radius: Radius of the cue tip (m), 0.0106 (pooltool 0.6.0; a 14 mm tip's
            dome is flatter than its width suggests).
        cue_end_mass: The cue's effective end mass for squirt (kg); ``None`` (default)
            takes ``ball_mass / 30`` (pooltool 0.6.0, after Alciatore's TP A-31).
        cushion_model: ``"han"`` (default): Han 2005's rigid impulse
            (:mod:`~pool_env.sim.kernels.spin.cushion`); ``"stronge"``: Stronge's compliant
            model, pooltool 0.6.0's default (:mod:`~pool_env.sim.kernels.spin.stronge`),
            for rails, jaw facings and jaw points alike.
        cushion_omega_ratio: Stronge's ratio ``omega_t / omega_n`` of the contact's
            tangential and normal frequencies, in ``(1, 2)``; 1.8 (pooltool 0.6.0's default
            resolver). With Stronge's model ``e_cushion`` and ``e_jaw`` must be at least
            ``1 / cushion_omega_ratio`` (0.556 at 1.8), the model's range.
        ball_model: ``"frictional"`` (default): the frictional inelastic impulse with throw
            (:mod:`~pool_env.sim.kernels.spin.collide`); ``"mathavan"``: Mathavan et al.
            2014, friction at the balls' and the table's contacts integrated over the
            impact (:mod:`~pool_env.sim.kernels.spin.mathavan`).
        mathavan_steps: Mathavan's ``N``, the impulse steps of one impact, 1000 (pooltool's
            ``num_iterations``), an integer in ``[1, 1e6]``.

    Attributes:
        pockets: ``(K, 3)`` the pockets as ``(x, y, radius)`` capture circles. With
            capture circles these pot; on a jaw table they are the same six circles as a
            summary of where the pockets are (aim points), not used for potting.
        pocket_model: ``"jaws"``, ``"circles"`` or ``"none"``.
        jaws: One :class:`~pool_env.sim.pockets.PocketJaws` per pocket on a jaw table
            (points, rail ends, tips, facings, fall line), empty otherwise.
        rails: ``(M, 2, 2)`` the straight cushion noses as ``(start, end)`` segments: six
            between the pockets of a jaw table, else the four full sides.
        pocket_geometry: The array the compiled kernels read: the capture circles, or the
            jaws offset by ``R`` (``(K, JAW_COLS)``, see
            :func:`pool_env.sim.pockets.kernel_rows`).

    Raises:
        ValueError: On a size, radius, mass or deceleration ``mu_roll * g`` outside the
            numeric limits of :mod:`pool_env.sim.kernels.limits` (or not a finite real
            number); a non-positive ``mu_roll`` or ``g``; a restitution outside [0, 1]; a
            table too small for one ball or for its pockets; or an unknown or malformed
            pocket specification; an unknown ``model``; a spin parameter that is not a
            finite real number in its range (``mu_slide``, ``spin_decel``, ``cue_tip_radius``
            and ``cue_end_mass`` positive, ``ball_friction`` and ``cushion_friction``
            non-negative, ``cushion_height`` in ``[R, 2R)``); an unknown ``cushion_model``
            or ``ball_model``, ``cushion_omega_ratio`` outside ``(1, 2)``, a restitution
            below Stronge's range, or ``mathavan_steps`` not an integer in range; on the
            roll table (``model="roll"``), a spin-only parameter (:data:`SPIN_ONLY`) away
            from its default.

    Examples:
        >>> from pool_env import Table
        >>> table = Table()  # a 9-ft table, six pockets with jaws, measured defaults
        >>> table.length, table.width, table.mu_roll, table.e_ball, table.e_cushion
        (2.54, 1.27, 0.01, 0.95, 0.65)
        >>> len(table.jaws), table.pocket_model
        (6, 'jaws')
        >>> Table(e_ball=1.5)
        Traceback (most recent call last):
        ...
        ValueError: e_ball must lie in [0, 1], got 1.5
    """

    length: float = 2.54
    width: float = 1.27
    ball_radius: float = 0.028575
    ball_mass: float = 0.17
    mu_roll: float = 0.01
    g: float = 9.81
    e_ball: float = 0.95
    e_cushion: float = 0.65
    pockets: NDArray[np.float64] = field(default="jaws")  # type: ignore[assignment]
    e_jaw: float | None = None
    model: str = "roll"
    mu_slide: float = 0.2
    spin_decel: float | None = None
    ball_friction: str | float = "alciatore"
    cushion_friction: float = 0.2
    cushion_height: float | None = None
    cue_tip_radius: float = 0.0106
    cue_end_mass: float | None = None
    cushion_model: str = "han"
    cushion_omega_ratio: float = 1.8
    ball_model: str = "frictional"
    mathavan_steps: int = 1000
    params: NDArray[np.float64] = field(init=False, repr=False)
    pocket_model: str = field(init=False, repr=False)
    jaws: tuple[PocketJaws, ...] = field(init=False, repr=False)
    rails: NDArray[np.float64] = field(init=False, repr=False)
    pocket_geometry: NDArray[np.float64] = field(init=False, repr=False)
    spin_params: NDArray[np.float64] = field(init=False, repr=False)

    def __post_init__(self) -> None:
        setter = object.__setattr__  # frozen dataclass: set validated values once
        for name in ("length", "width", "ball_radius"):
            value = within(name, getattr(self, name), limits.MIN_LENGTH, limits.MAX_LENGTH, "m")
            setter(self, name, value)
        mass = within("ball_mass", self.ball_mass, limits.MIN_MASS, limits.MAX_MASS, "kg")
        setter(self, "ball_mass", mass)
        for name in ("mu_roll", "g"):
            setter(self, name, positive(name, getattr(self, name)))
        low, high = limits.MIN_DECELERATION, limits.MAX_DECELERATION
        within("the rolling deceleration mu_roll * g", self.mu_roll * self.g, low, high, "m/s^2")
        for name in ("e_ball", "e_cushion"):
            setter(self, name, _check_restitution(name, getattr(self, name)))
        e_jaw = self.e_cushion if self.e_jaw is None else self.e_jaw
        setter(self, "e_jaw", _check_restitution("e_jaw", e_jaw))
        if min(self.length, self.width) <= 2.0 * self.ball_radius:
            raise ValueError(
                f"a {self.length} x {self.width} m table cannot hold a ball of radius "
                f"{self.ball_radius} m"
            )
        model, pockets, jaws = parse_pockets(
            self.pockets, self.length, self.width, self.ball_radius
        )
        pockets.setflags(write=False)
        setter(self, "pockets", pockets)
        setter(self, "pocket_model", model)
        setter(self, "jaws", jaws)
        setter(self, "rails", rail_segments(self.length, self.width, jaws))
        geometry = kernel_rows(jaws, self.ball_radius) if jaws else pockets
        setter(self, "pocket_geometry", geometry)
        params = np.empty(N_PARAMS, dtype=np.float64)  # the layout the kernels read
        params[P_LENGTH] = self.length
        params[P_WIDTH] = self.width
        params[P_RADIUS] = self.ball_radius
        params[P_DECEL] = self.mu_roll * self.g
        params[P_E_BALL] = self.e_ball
        params[P_E_CUSHION] = self.e_cushion
        params[P_MASS] = self.ball_mass
        params[P_E_JAW] = self.e_jaw
        params.setflags(write=False)
        setter(self, "params", params)
        self._set_spin_parameters(params)

    def _set_spin_parameters(self, params: NDArray[np.float64]) -> None:
        """Validate the model level and the spin parameters; build ``spin_params``."""
        setter = object.__setattr__
        if not isinstance(self.model, str) or self.model not in MODELS:
            raise ValueError(f"model must be 'roll' or 'spin', got {self.model!r}")
        r, g = self.ball_radius, self.g
        defaults = self._spin_defaults()
        low, high = limits.MIN_DECELERATION, limits.MAX_DECELERATION
        setter(self, "mu_slide", positive("mu_slide", self.mu_slide))
        within("the sliding deceleration mu_slide * g", self.mu_slide * g, low, high, "m/s^2")
        spin_decel = defaults["spin_decel"] if self.spin_decel is None else self.spin_decel
        setter(self, "spin_decel", within("spin_decel", spin_decel, low, high, "rad/s^2"))
        friction = self.ball_friction
        if isinstance(friction, str):
            modes = {"alciatore": ALCIATORE_FRICTION, "pooltool": POOLTOOL_FRICTION}
            if friction not in modes:
                raise ValueError(
                    "ball_friction must be 'alciatore', 'pooltool' or a number >= 0, got "
                    f"{friction!r}"
                )
            mode, mu_ball = modes[friction], 0.0
        else:
            mu_ball = _non_negative("ball_friction", friction)
            setter(self, "ball_friction", mu_ball)
            mode = CONSTANT_FRICTION if mu_ball > 0.0 else FRICTIONLESS
        setter(self, "cushion_friction", _non_negative("cushion_friction", self.cushion_friction))
        height = defaults["cushion_height"] if self.cushion_height is None else self.cushion_height
        height = real_number("cushion_height", height)
        if not r <= height < 2.0 * r:
            raise ValueError(f"cushion_height must lie in [R, 2R) = [{r}, {2 * r}), got {height!r}")
        setter(self, "cushion_height", height)
        tip = within(
            "cue_tip_radius", self.cue_tip_radius, limits.MIN_LENGTH, limits.MAX_LENGTH, "m"
        )
        setter(self, "cue_tip_radius", tip)
        end_mass = defaults["cue_end_mass"] if self.cue_end_mass is None else self.cue_end_mass
        setter(
            self,
            "cue_end_mass",
            within("cue_end_mass", end_mass, limits.MIN_MASS, limits.MAX_MASS, "kg"),
        )
        for name, value in check_models(self).items():
            setter(self, name, value)
        if not self.has_spin:
            meaningless = [n for n in SPIN_ONLY if getattr(self, n) != defaults[n]]
            if meaningless:
                given = ", ".join(f"{n}={getattr(self, n)!r}" for n in meaningless)
                raise ValueError(
                    f"{given}: spin parameters apply to model='spin' only; the roll table "
                    f"(model={self.model!r}, the default) does not read them. Pass "
                    "model='spin', or leave them at their defaults"
                )
        spin = np.empty(N_SPIN_PARAMS, dtype=np.float64)
        spin[: params.shape[0]] = params
        spin[S_SLIDE_DECEL] = self.mu_slide * g
        spin[S_SPIN_DECEL] = self.spin_decel
        spin[S_FRICTION_MODE] = mode
        spin[S_MU_BALL] = mu_ball
        spin[S_CUSHION_FRICTION] = self.cushion_friction
        spin[S_CUSHION_HEIGHT] = self.cushion_height
        spin[S_TIP_RADIUS] = self.cue_tip_radius
        spin[S_END_MASS] = self.cue_end_mass
        spin[S_CUSHION_MODEL] = CUSHION_MODELS[self.cushion_model]
        spin[S_OMEGA_RATIO] = self.cushion_omega_ratio
        spin[S_BALL_MODEL] = BALL_MODELS[self.ball_model]
        spin[S_MATHAVAN_STEPS] = self.mathavan_steps
        spin[S_MU_SLIDE] = self.mu_slide
        spin.setflags(write=False)
        setter(self, "spin_params", spin)

    def _spin_defaults(self) -> dict[str, object]:
        """Each spin-only parameter's default on this table (some follow ``g``, ``R``, mass)."""
        out: dict[str, object] = {f.name: f.default for f in fields(self) if f.name in SPIN_ONLY}
        out["spin_decel"] = 2.5 * SPIN_FRICTION_RATIO * self.g
        out["cushion_height"] = 2.0 * NOSE_HEIGHT_FRACTION * self.ball_radius
        out["cue_end_mass"] = self.ball_mass / 30.0
        return out

    @classmethod
    def preset(cls, name: str, **overrides: object) -> Table:
        """A table with a named preset's parameters (:data:`pool_env.sim.presets.PRESETS`).

        ``Table.preset("pooltool-0.6")`` is pooltool 0.6.0 as it ships: its 7-ft table,
        ball, cushion, cue and friction parameters and its default models (Stronge's
        cushions, the frictional inelastic ball-ball impulse with its friction rule), on
        the spin level (see :mod:`pool_env.sim.presets` for each value and its source).

        The preset is a spin table: ``model="roll"`` over it is refused, as its spin-only
        values (Stronge's cushions, pooltool's friction rule, ...) would mean nothing there;
        a roll table of pooltool's size is ``Table(length=1.9812, width=0.9906, ...)``.
        The presets of :data:`~pool_env.sim.presets.ROLL_ALLOWED` (``"snooker"``) make a
        roll table too: ``model="roll"`` drops their spin-only values (:data:`SPIN_ONLY`).

        Args:
            name: The preset's name.
            **overrides: ``Table`` keywords over the preset's (e.g. ``pockets="none"``).

        Raises:
            ValueError: An unknown preset or keyword (each named, with the valid ones), or a
                value ``Table`` refuses.
        """
        if name not in PRESETS:
            raise ValueError(f"unknown preset {name!r}; the presets are {sorted(PRESETS)}")
        keywords = sorted(f.name for f in fields(cls) if f.init)
        unknown = sorted(set(overrides) - set(keywords))
        if unknown:
            raise ValueError(
                f"unknown Table keyword(s) {unknown} for preset {name!r}; the keywords are "
                f"{keywords}"
            )
        values = dict(PRESETS[name])
        if name in ROLL_ALLOWED and overrides.get("model") == "roll":
            values = roll_keywords(values)
        return cls(**{**values, **overrides})  # type: ignore[arg-type]

    @property
    def deceleration(self) -> float:
        """Rolling deceleration ``mu_roll * g`` (m/s^2)."""
        return self.mu_roll * self.g

    @property
    def n_pockets(self) -> int:
        """Number of pockets (0 on a carom table)."""
        return int(self.pockets.shape[0])

    @property
    def has_spin(self) -> bool:
        """Whether this table's model level has spin (angular velocities, tip, elevation)."""
        return self.model in SPIN_MODELS

    def stop_distance(self, speed: float) -> float:
        """Distance a free ball rolls from ``speed`` to rest: ``v^2 / (2 mu g)``."""
        return speed * speed / (2.0 * self.deceleration)

    def stop_time(self, speed: float) -> float:
        """Time a free ball takes to roll from ``speed`` to rest: ``v / (mu g)``."""
        return speed / self.deceleration

    def _spin_repr(self) -> str:
        if not self.has_spin:
            return ""
        return ", model='spin', " + ", ".join(f"{n}={getattr(self, n)!r}" for n in SPIN_ONLY)

    def __repr__(self) -> str:
        return (
            f"Table(length={self.length}, width={self.width}, ball_radius={self.ball_radius}, "
            f"ball_mass={self.ball_mass}, mu_roll={self.mu_roll}, g={self.g}, "
            f"e_ball={self.e_ball}, e_cushion={self.e_cushion}, e_jaw={self.e_jaw}, "
            f"pockets=<{self.n_pockets} {self.pocket_model}>{self._spin_repr()})"
        )
