"""The layout of a spin table's flat parameter array (``Table.spin_params``).

It begins with the roll level's :mod:`~pool_env.sim.kernels.params` layout (the same
indices, ``P_LENGTH`` ... ``P_E_JAW``) and appends the spin level's parameters, so the spin
kernels read both by name. The roll level's own ``Table.params`` is untouched.
"""

from __future__ import annotations

from pool_env.sim.kernels.params import N_PARAMS

#: Indices after the roll layout: sliding deceleration ``mu_slide * g`` (m/s^2), spin
#: deceleration (rad/s^2), ball-ball friction mode (0 frictionless, 1 constant, 2 Alciatore's
#: fit, 3 the same with pooltool's impulse), the constant ball-ball friction, cushion
#: friction, cushion contact height (m), cue tip radius (m), cue end mass (kg), the cushion
#: model (:data:`HAN_CUSHION` or :data:`STRONGE_CUSHION`), Stronge's frequency ratio
#: ``omega_t / omega_n``, the ball-ball model (:data:`FRICTIONAL_BALLS` or
#: :data:`MATHAVAN_BALLS`), Mathavan's step count ``N`` and the ball-cloth sliding friction
#: ``mu_slide`` (Mathavan's model reads the coefficient itself, not ``mu_slide * g``).
(
    S_SLIDE_DECEL,
    S_SPIN_DECEL,
    S_FRICTION_MODE,
    S_MU_BALL,
    S_CUSHION_FRICTION,
    S_CUSHION_HEIGHT,
    S_TIP_RADIUS,
    S_END_MASS,
    S_CUSHION_MODEL,
    S_OMEGA_RATIO,
    S_BALL_MODEL,
    S_MATHAVAN_STEPS,
    S_MU_SLIDE,
) = range(N_PARAMS, N_PARAMS + 13)

#: Length of ``Table.spin_params``.
N_SPIN_PARAMS = N_PARAMS + 13

#: Ball-ball friction modes, the one enumeration (``Table.spin_params[S_FRICTION_MODE]``, the
#: ``friction_mode`` argument of the resolution kernel,
#: :mod:`~pool_env.sim.kernels.spin.collide`): none, a constant, Alciatore's fit with
#: Coulomb's impulse, Alciatore's fit with pooltool 0.6.0's impulse.
FRICTIONLESS, CONSTANT_FRICTION, ALCIATORE_FRICTION, POOLTOOL_FRICTION = 0, 1, 2, 3

#: Cushion models (``Table.spin_params[S_CUSHION_MODEL]``): Han 2005
#: (:mod:`~pool_env.sim.kernels.spin.cushion`), Stronge's compliant model
#: (:mod:`~pool_env.sim.kernels.spin.stronge`).
HAN_CUSHION, STRONGE_CUSHION = 0, 1

#: Ball-ball models (``Table.spin_params[S_BALL_MODEL]``): the frictional inelastic impulse
#: (:mod:`~pool_env.sim.kernels.spin.collide`), Mathavan et al. 2014
#: (:mod:`~pool_env.sim.kernels.spin.mathavan`).
FRICTIONAL_BALLS, MATHAVAN_BALLS = 0, 1
