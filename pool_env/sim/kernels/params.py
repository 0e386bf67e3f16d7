"""The layout of the table's flat parameter array (``Table.params``), read by every kernel.

:class:`pool_env.sim.table.Table` writes the array in this layout; the kernels read it by
these names, never by bare positions.
"""

from __future__ import annotations

#: Indices into ``Table.params``: playing length and width (m), ball radius (m), rolling
#: deceleration ``mu_roll * g`` (m/s^2), ball-ball and ball-cushion restitution, ball mass (kg),
#: restitution of the jaw facings and points.
P_LENGTH, P_WIDTH, P_RADIUS, P_DECEL, P_E_BALL, P_E_CUSHION, P_MASS, P_E_JAW = range(8)

#: Length of ``Table.params``.
N_PARAMS = 8
