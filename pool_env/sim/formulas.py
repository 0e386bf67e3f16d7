"""The spin level's closed-form pieces, for code that reasons about a shot without simulating it.

A player that plans with spin (``agents/baselines/cue_path.py``) and a comparison with another
simulator's formulas (``bench/spin_kernels_pooltool.py``) reuse the simulator's own
equations instead of re-deriving them. These are the compiled kernels themselves, named here
so that nothing outside :mod:`pool_env` imports :mod:`pool_env.sim.kernels` (the import
contract "agents, bench and tools use public names only" in ``pyproject.toml``):

* :func:`cue_strike`: the ball's velocity and spin right after the instantaneous-point cue
  strike (:mod:`pool_env.sim.kernels.spin.strike`);
* :func:`squirt_angle`: how far side english turns the ball off the aim (TP A-31);
* :func:`ball_ball_spin`: a frictional ball-ball impact with throw
  (:mod:`pool_env.sim.kernels.spin.collide`);
* :func:`cushion_han`: a ball's rebound off a cushion, Han's model, and
  :func:`cushion_spin`, the rebound by the model a table picks (Han's or Stronge's,
  :data:`HAN_CUSHION`, :data:`STRONGE_CUSHION`) (:mod:`pool_env.sim.kernels.spin.cushion`);
* :func:`ball_ball_mathavan`: a ball-ball impact by Mathavan's model
  (:mod:`pool_env.sim.kernels.spin.mathavan`);
* the ball-ball friction models ``ball_ball_spin`` takes, the one enumeration
  (``Table.spin_params``' friction mode): :data:`FRICTIONLESS`, :data:`CONSTANT_FRICTION`,
  :data:`ALCIATORE_FRICTION`, :data:`POOLTOOL_FRICTION`.

The equations are in ``docs/physics.md`` ("Spin").
"""

from __future__ import annotations

from pool_env.sim.kernels.spin.collide import ball_ball_spin
from pool_env.sim.kernels.spin.cushion import cushion_han, cushion_spin
from pool_env.sim.kernels.spin.mathavan import ball_ball_mathavan
from pool_env.sim.kernels.spin.params import (
    ALCIATORE_FRICTION,
    CONSTANT_FRICTION,
    FRICTIONLESS,
    HAN_CUSHION,
    POOLTOOL_FRICTION,
    STRONGE_CUSHION,
)
from pool_env.sim.kernels.spin.strike import cue_strike, squirt_angle

__all__ = [
    "ALCIATORE_FRICTION",
    "CONSTANT_FRICTION",
    "FRICTIONLESS",
    "HAN_CUSHION",
    "POOLTOOL_FRICTION",
    "STRONGE_CUSHION",
    "ball_ball_mathavan",
    "ball_ball_spin",
    "cue_strike",
    "cushion_han",
    "cushion_spin",
    "squirt_angle",
]
