"""The cue strike of either model level, for compiled code above the simulator.

The game layer's kernels decode an action into a strike on every table of a batch; which
model level the table has is the simulator's business. :func:`level_strike` is the one
compiled place above the levels that picks a level's strike, so the game layer names no
level (the Python side picks a level in :mod:`pool_env.sim.levels`).
"""

from __future__ import annotations

from pool_env.sim.jit import kernel
from pool_env.sim.kernels.roll.motion import struck_velocity
from pool_env.sim.kernels.spin.strike import cue_strike


@kernel
def level_strike(spin, speed, angle, a, b, radius, mass, end_mass, tip_radius, out):
    """The struck cue ball's state: ``out[:2]`` (roll level) or ``out[:5]`` (spin level).

    Args:
        spin: Whether the table is the spin level.
        speed: The ball's speed after the strike (m/s).
        angle: The cue's aim (radians from +x).
        a: Side offset of the cue's axis, fraction of ``R`` (spin level only).
        b: Vertical offset of the cue's axis, fraction of ``R`` (spin level only).
        radius: Ball radius (m). mass: the ball's mass (kg), spin level only.
        end_mass: The cue's end mass for squirt (kg), spin level only.
        tip_radius: The cue tip's radius (m), spin level only.
        out: Written: the velocity ``(vx, vy)``, and on the spin level the angular velocity
            ``(wx, wy, wz)`` after it (:mod:`pool_env.sim.kernels.spin.strike`, a level cue).
    """
    if spin:
        cue_strike(speed, angle, a, b, 0.0, radius, mass, end_mass, tip_radius, out)
    else:
        struck_velocity(speed, angle, out)
