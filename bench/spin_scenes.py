"""Seeded spin-level shots for the pooltool comparison: a cue strike on a pocketless table.

Each shot strikes the cue ball (row 0) with side and vertical tip offsets and sometimes an
elevated cue, aimed at an object ball with a random cut; shots are kept when the 50-digit
reference (:mod:`pool_env.testing.spin_reference`) counts 1 to 3 collisions (ball-ball plus
cushion impacts). The same shot is handed to pooltool in its own terms
(:func:`pooltool_strike`) and to pool_env's ``shoot``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from types import SimpleNamespace
from typing import Any

import numpy as np
from mpmath import mp, mpf
from numpy.typing import NDArray

from pool_env import Table
from pool_env.interop.pooltool import POOLTOOL_CUE_MASS, cue_to_pooltool
from pool_env.testing import spin_physics_mp as ph
from pool_env.testing.scenes_random import random_layout
from pool_env.testing.spin_reference import params_from

#: Alciatore's ball-ball friction fit ``a + b exp(-c v)``: pooltool 0.6.0's coefficients,
#: which pool_env's spin level and the reference use too.
ALCIATORE = (0.009951, 0.108, 1.088)


def spin_table() -> Any:
    """The spin table: pool_env's ``Table(model="spin", pockets="none")`` once it exists.

    Before the spin level is merged, a stand-in with the contract's defaults
    (``docs/sources.md``, "The spin model").
    """
    try:
        return Table(model="spin", pockets="none")  # type: ignore[call-arg]
    except TypeError:
        base = Table(pockets="none")
        r, m = base.ball_radius, base.ball_mass
        return SimpleNamespace(
            length=base.length, width=base.width, ball_radius=r, ball_mass=m,
            g=base.g, mu_roll=base.mu_roll, e_ball=base.e_ball, e_cushion=base.e_cushion,
            mu_slide=0.2, spin_decel=2.5 * 0.444 * base.g, ball_friction="alciatore",
            cushion_friction=0.2, cushion_height=0.635 * 2 * r, cue_tip_radius=0.0106,
            cue_end_mass=m / 30, model="spin", pockets="none",
        )  # fmt: skip


@dataclass(frozen=True, eq=False)
class SpinShot:
    """One struck shot.

    Attributes:
        name: Label.
        positions: ``(N, 2)`` centres.
        angle: Cue aim (radians).
        speed: Cue ball's in-plane speed after the strike (m/s).
        tip: Side (+ right) and vertical (+ top) tip offsets, fractions of R.
        elevation: Cue elevation (radians).
        velocities: ``(N, 2)`` after the strike (the reference's strike, rounded).
        angular_velocities: ``(N, 3)`` after the strike.
        ref_positions: ``(N, 2)`` the reference's final centres (rounded to float64).
        ref_events: The reference's ``(kind, i, j)`` sequence.
    """

    name: str
    positions: NDArray[np.float64]
    angle: float
    speed: float
    tip: tuple[float, float]
    elevation: float
    velocities: NDArray[np.float64]
    angular_velocities: NDArray[np.float64]
    ref_positions: NDArray[np.float64] | None = None
    ref_events: tuple[tuple[str, int, int], ...] = ()


def strike_state(table: Any, angle: float, speed: float, tip: tuple[float, float],
                 elevation: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:  # fmt: skip
    """The cue ball's ``(v, w)`` after the strike, from the reference's strike at 50 digits."""
    with mp.workdps(50):
        prm = params_from(table)
        v, w = ph.cue_strike(
            mpf(speed), mpf(angle), (mpf(tip[0]), mpf(tip[1])), mpf(elevation), prm,
            mpf(float(table.ball_mass)),
        )  # fmt: skip
        return np.array([float(x) for x in v]), np.array([float(x) for x in w])


def pooltool_strike(table: Any, shot: SpinShot) -> dict[str, float]:
    """The shot in pooltool's cue terms and frame (``a`` > 0 is left english there).

    pooltool's instantaneous-point strike gives the ball ``V = 2 V0 / (1 + m/M + (5/2)(a^2
    + b^2))`` along the cue (contact offsets ``a, b``) and keeps ``V cos(theta)`` in the
    plane; its frame is ours turned by +90 degrees (the mapping:
    :func:`pool_env.interop.pooltool.cue_to_pooltool`).
    """
    cue = cue_to_pooltool(
        table, shot.angle, shot.speed, shot.tip, shot.elevation, cue_mass=POOLTOOL_CUE_MASS
    )
    return {**cue._asdict(), "M": POOLTOOL_CUE_MASS, "end_mass": table.cue_end_mass}


def _draw(rng: np.random.Generator, table: Any, k: int) -> SpinShot:
    n = int(rng.integers(2, 5))
    pos = random_layout(Table(pockets="none"), n, rng, min_gap=2e-3)
    target = pos[int(rng.integers(1, n))]
    angle = math.atan2(*(target - pos[0])[::-1]) + float(rng.normal(0.0, 0.15))
    speed = float(rng.uniform(0.4, 3.0))
    tip = (float(rng.uniform(-0.5, 0.5)), float(rng.uniform(-0.6, 0.6)))
    elevation = 0.0 if rng.random() < 0.6 else float(rng.uniform(0.02, 0.3))
    vel, ang = np.zeros((n, 2)), np.zeros((n, 3))
    vel[0], ang[0] = strike_state(table, angle, speed, tip, elevation)
    return SpinShot(f"shot{k}", pos, angle, speed, tip, elevation, vel, ang)


def spin_shots(n: int, seed: int = 19, table: Any = None) -> list[SpinShot]:
    """``n`` seeded shots with 1-3 collisions (ball-ball plus cushion) in the reference."""
    from pool_env.testing.spin_reference import spin_reference_simulate

    table = spin_table() if table is None else table
    rng = np.random.default_rng(seed)
    shots: list[SpinShot] = []
    k = 0
    while len(shots) < n:
        shot = _draw(rng, table, k)
        k += 1
        ref = spin_reference_simulate(
            table, shot.positions, shot.velocities, shot.angular_velocities, max_events=400
        )
        impacts = sum(kind in ("ball", "cushion") for _, kind, _, _ in ref.events)
        if 1 <= impacts <= 3:
            final = np.array([[float(x), float(y)] for x, y in ref.positions])
            events = tuple((kind, i, j) for _, kind, i, j in ref.events)
            shots.append(replace(shot, ref_positions=final, ref_events=events))
    return shots


def worker_scene(
    table: Any, shot: SpinShot, strike: bool = True, throw: str = "coulomb"
) -> dict[str, Any]:
    """The pooltool worker's description of a spin shot (see ``pooltool_worker``).

    Args:
        table: The spin table.
        shot: The shot.
        strike: Let pooltool strike the cue ball (else start from the shot's state).
        throw: ``"coulomb"`` configures pooltool to the spin level's friction impulse
            ``mu (1 + e) / 2 |du_n|`` (per unit mass) by scaling its friction by
            ``(1 + e) / (2 e)``, since pooltool applies ``mu e |du_n|`` (exact for equal
            masses, which these shots have); ``"pooltool"`` leaves pooltool's own.
    """
    n = shot.positions.shape[0]
    e = table.e_ball
    k = (1.0 + e) / (2.0 * e) if throw == "coulomb" else 1.0
    friction = table.ball_friction
    if friction != "alciatore":
        friction = k * float(friction)
    scene: dict[str, Any] = {
        "table": {
            "model": "spin", "pockets": False, "length": table.length, "width": table.width,
            "ball_radius": table.ball_radius, "ball_mass": table.ball_mass,
            "mu_roll": table.mu_roll, "g": table.g, "e_ball": table.e_ball,
            "e_cushion": table.e_cushion, "mu_slide": table.mu_slide,
            "spin_decel": table.spin_decel, "ball_friction": friction,
            "alciatore": [k * ALCIATORE[0], k * ALCIATORE[1], ALCIATORE[2]],
            "cushion_friction": table.cushion_friction,
            "cushion_height": table.cushion_height,
        },
        "positions": shot.positions.tolist(),
        "obj": 1,
        "masses": None,
    }  # fmt: skip
    if strike:
        scene["velocities"] = [[0.0, 0.0]] * n
        scene["angular_velocities"] = [[0.0, 0.0, 0.0]] * n
        scene["strike"] = pooltool_strike(table, shot)
    else:
        scene["velocities"] = shot.velocities.tolist()
        scene["angular_velocities"] = shot.angular_velocities.tolist()
    return scene
