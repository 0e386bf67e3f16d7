"""The spin share of the robustness fuzz (``python -m tools.fuzz --model spin``).

Random spin parameters for a table and a random way to set a scene's balls spinning, drawn
after the roll fuzz's scene (:func:`tools.fuzz.random_case`), so that the scene kinds are
the roll fuzz's: touching layouts, breaks, lumps driven into rails, masses spread over a
million to one, jaw, capture-circle and pocketless tables, tables scaled to the numeric
limits. What the spin level refuses: batches (``simulate_batch``: spin tables are simulated
one shot at a time), so the fuzz runs single shots only.

Spin draws (each documented range of :class:`pool_env.Table`, its edges included):

* ``mu_slide``: 0.2 (default) or log-uniform over 0.01-1;
* ``spin_decel``: the default, or log-uniform over 0.1-1000 rad/s^2;
* ``ball_friction``: Alciatore's fit (with this level's impulse or pooltool's), a constant
  in [0, 0.3], or 0 (frictionless);
* ``cushion_friction``: 0.2, uniform in [0, 1], or 0;
* ``cushion_height``: the WPA default, ``R`` (contact at the equator), or uniform in
  ``[R, 2R)`` (up to a hair below the top of the ball);
* ``cushion_model``: Han's (default) or Stronge's (one table in two), Stronge's with
  ``cushion_omega_ratio`` 1.8 (default) or uniform in ``(1, 2)``; on a Stronge table the
  drawn ``e_cushion`` and ``e_jaw`` are mapped affinely from ``[0, 1]`` onto the model's
  range ``[1 / cushion_omega_ratio, 1]`` (:func:`model_restitution`), so elastic stays 1;
* ``ball_model``: the frictional impulse (default) or Mathavan's (one table in two), with
  ``mathavan_steps`` 1000 (default, one in two), log-uniform over 1-10^4 (45%) or
  10^4-10^5 (5%; the cost of an impact grows with it, so the tail stops below the accepted
  10^6);
* elastic tables come from the roll fuzz's draws (``e_ball = 1`` one table in four,
  ``e_cushion = 1`` one in four, both one in sixteen), on every model;
* a single struck ball (four shots in five): half by :func:`pool_env.shoot` with a tip
  ``(a, b)`` inside the safe range (contact offset up to half a radius) or anywhere in
  ``[-1, 1]^2`` (one time in three), and an elevation of 0, uniform in ``[0, pi/2)``, or
  close to vertical; half by :func:`pool_env.simulate` with random angular velocities;
* several balls moving: random angular velocities for each (zero, natural roll, pure side
  spin about ``z``, or random with a surface speed up to twice the ball's speed, rarely up
  to the speed limit).

Every draw is a shot the simulator accepts: where a draw's energy, spin included, could
speed a ball past the limits (:func:`~pool_env.sim.spin_inputs.reachable_spin_speed`
against :func:`~pool_env.sim.inputs.max_speed`), or a ball's surface speed ``R |w|`` passes
``MAX_SPEED`` (a near-vertical cue), one factor scales its speeds and spins down to 0.999
of the bound (:func:`admitted`), keeping their directions and ratios; the random stream
is the same, so the scenes are the ones drawn before the scaling.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from pool_env import Table, shoot, simulate
from pool_env.sim.constants import MAX_SPEED
from pool_env.sim.inputs import max_speed
from pool_env.sim.result import ShotResult
from pool_env.sim.spin_inputs import reachable_spin_speed, strike, tip_touches_ball

DEFAULT = Table()


def random_spin_parameters(rng: np.random.Generator) -> dict[str, object]:
    """Keyword arguments of a random spin :class:`Table`.

    ``cushion_height`` comes back as a fraction of ``R`` (or ``None``):
    :func:`spin_table_kwargs` turns it into metres once the table's radius is known.
    """
    u = rng.random()
    friction: str | float = (
        "alciatore"
        if u < 0.4
        else ("pooltool" if u < 0.5 else (float(rng.uniform(0, 0.3)) if u < 0.8 else 0.0))
    )
    height = rng.random()
    stronge, ratio, mathavan = rng.random() < 0.5, rng.random(), rng.random() < 0.5
    u = rng.random()
    steps = (
        1000 if u < 0.5 else int(10 ** rng.uniform(0, 4) if u < 0.95 else 10 ** rng.uniform(4, 5))
    )
    return {
        "model": "spin",
        "mu_slide": 0.2 if rng.random() < 0.5 else float(10 ** rng.uniform(-2, 0)),
        "spin_decel": None if rng.random() < 0.5 else float(10 ** rng.uniform(-1, 3)),
        "ball_friction": friction,
        "cushion_friction": float(rng.choice([0.2, rng.uniform(0, 1), 0.0])),
        "cushion_height": None if height < 0.5 else (1.0 if height < 0.6 else rng.uniform(1, 2)),
        "cushion_model": "stronge" if stronge else "han",
        "cushion_omega_ratio": 1.8 if ratio < 0.5 else float(rng.uniform(1.0, 2.0)),
        "ball_model": "mathavan" if mathavan else "frictional",
        "mathavan_steps": steps,
    }


def model_restitution(spin: dict[str, object], e: float) -> float:
    """A drawn cushion or jaw restitution ``e`` in ``[0, 1]``, within the cushion model's range.

    Stronge's model needs ``e >= 1 / cushion_omega_ratio``: ``[0, 1]`` maps affinely onto
    ``[1 / ratio, 1]`` (elastic stays elastic); Han's takes ``e`` as drawn.
    """
    if spin.get("cushion_model") != "stronge":
        return e
    floor = 1.0 / float(spin["cushion_omega_ratio"])  # type: ignore[arg-type]
    return min(1.0, floor + (1.0 - floor) * e)


def spin_table_kwargs(spin: dict[str, object], radius: float) -> dict[str, object]:
    """``spin`` with the cushion height in metres for a ball of ``radius``."""
    out = dict(spin)
    fraction = out.pop("cushion_height")
    out["cushion_height"] = (
        None
        if fraction is None
        else min(float(fraction) * radius, math.nextafter(2.0 * radius, 0.0))
    )
    return out


def _random_tip(rng: np.random.Generator, table: Table) -> tuple[float, float]:
    """A tip axis offset: inside the safe range (contact offset <= R / 2) or anywhere on the ball.

    "Anywhere" draws in the API's box [-1, 1]^2 and scales a draw whose contact point would
    lie off the ball onto the ball's outline (``spin_inputs.tip_touches_ball``), so the
    random stream is the same draw for draw.
    """
    if rng.random() < 1 / 3:
        a, b = float(rng.uniform(-1, 1)), float(rng.uniform(-1, 1))
        if not tip_touches_ball(table, a, b):
            reach = 1.0 + table.cue_tip_radius / table.ball_radius
            scale = reach / math.hypot(a, b) * (1.0 - 1e-12)
            a, b = a * scale, b * scale
        return a, b
    reach = 0.5 * (1.0 + table.cue_tip_radius / table.ball_radius)  # axis offset, safe
    rho = reach * math.sqrt(rng.random())
    phi = rng.uniform(0, 2 * math.pi)
    # A scaled table keeps the regulation tip: its safe reach can pass the API's [-1, 1].
    return float(np.clip(rho * math.cos(phi), -1, 1)), float(np.clip(rho * math.sin(phi), -1, 1))


def _random_elevation(rng: np.random.Generator) -> float:
    u = rng.random()
    if u < 0.5:
        return 0.0
    if u < 0.9:
        return float(rng.uniform(0, 0.5 * math.pi))
    return float(0.5 * math.pi - 10 ** rng.uniform(-6, -1))  # close to vertical


def random_angular(rng: np.random.Generator, table: Table, velocities: np.ndarray) -> np.ndarray:
    """Random ``(N, 3)`` angular velocities for balls moving at ``velocities``."""
    r = table.ball_radius
    n = velocities.shape[0]
    w = np.zeros((n, 3))
    fastest = max_speed(table)
    for i in range(n):
        v = velocities[i]
        speed = float(np.hypot(*v))
        u = rng.random()
        if u < 0.2:
            continue  # no spin: a moving ball starts sliding
        if u < 0.4:
            w[i] = (-v[1] / r, v[0] / r, 0.0)  # natural roll
        elif u < 0.5:
            w[i, 2] = rng.normal(0, 1) * max(speed, 0.1) / r  # side spin only
        else:
            limit = fastest if rng.random() < 0.05 else min(2.0 * speed + 1e-3, fastest)
            direction = rng.normal(0, 1, 3)
            direction /= np.linalg.norm(direction)
            w[i] = direction * float(rng.uniform(0, 0.999 * limit)) / r
    return w


def admitted(
    table: Table, velocities: np.ndarray, angular: np.ndarray, masses: np.ndarray | None
) -> float:
    """The factor (at most 1) that brings a spin scene's speeds and spins within the limits.

    Both bounds are linear in one common factor: the energy bound
    (:func:`~pool_env.sim.spin_inputs.reachable_spin_speed`) below 0.999 of
    :func:`~pool_env.sim.inputs.max_speed`, and every surface speed ``R |w|`` below 0.999 of
    ``MAX_SPEED``.
    """
    reach = reachable_spin_speed(table, velocities, angular, masses)
    surface = table.ball_radius * float(np.max(np.linalg.norm(angular, axis=1), initial=0.0))
    factor = 1.0
    if reach > 0.999 * max_speed(table):
        factor = 0.999 * max_speed(table) / reach
    if surface > 0.999 * MAX_SPEED:
        factor = min(factor, 0.999 * MAX_SPEED / surface)
    return factor


def spin_shot(
    rng: np.random.Generator,
    table: Table,
    positions: np.ndarray,
    velocities: np.ndarray,
    masses: np.ndarray,
) -> Callable[[], ShotResult]:
    """A random spin shot of the scene, as a call that runs it (for the rerun check)."""
    movers = np.flatnonzero(np.any(velocities != 0.0, axis=1))
    if movers.size == 1 and movers[0] == 0 and rng.random() < 0.5:
        v = velocities[0]
        speed = float(np.hypot(*v))
        angle = float(np.arctan2(v[1], v[0]))
        tip = _random_tip(rng, table)
        elevation = _random_elevation(rng)
        struck_v, struck_w = np.zeros_like(velocities), np.zeros((velocities.shape[0], 3))
        # The strike's velocity and spin are linear in the speed: scale the speed.
        struck_v[0], struck_w[0] = strike(table, speed, angle, tip[0], tip[1], elevation)
        speed *= admitted(table, struck_v, struck_w, masses)

        def struck() -> ShotResult:
            return shoot(table, positions, angle, speed, 0, masses, tip=tip, elevation=elevation)

        return struck
    angular = random_angular(rng, table, velocities)
    factor = admitted(table, velocities, angular, masses)
    velocities, angular = velocities * factor, angular * factor

    def rolled() -> ShotResult:
        return simulate(table, positions, velocities, masses, angular_velocities=angular)

    return rolled
