"""The rules: what a shot's outcome means. The one place for every rule of the game.

Both fronts (:class:`pool_env.PoolEnv`, :class:`pool_env.PoolVectorEnv`) run these
through :func:`pool_env.game.step.step`, after the simulator and
:func:`pool_env.game.kernels.settle.settle` have said what physically happened (which
balls dropped, the first ball the cue ball hit). A rule is a pure function of that outcome
and the tables' state, compiled, one table at a time inside a loop over the batch.

The rule of the registered ids is *solitaire*: one player pots every object ball in any
order and any pocket.

* Reward: ``reward_pot`` per object ball potted, ``reward_scratch`` when the cue ball
  drops, ``reward_no_contact`` when it hits no ball, and ``reward_shaping`` times the
  change of the pocket-distance potential.
* A potted object ball stays off the table; a potted cue ball goes back on the head spot,
  or (when the spot is taken; the caller finishes that case with
  :func:`pool_env.game.scenes.free_spot`) the free point nearest to it.
* The episode terminates when the table is cleared, and with ``end_on_miss`` after a shot
  that pots nothing or scratches; it is truncated after ``shot_limit`` shots.

Where game rules go (fouls, ball in hand, turns, two players): a new rule beside
:func:`judge`, reading the same outcome arrays (``potted``, ``scratch``, ``first_ball``,
and the events of the shot if it needs them) plus the state it keeps in
:class:`pool_env.game.state.GameState` (e.g. whose turn, ball in hand), chosen by a
:class:`pool_env.game.config.GameConfig` field and called from
:func:`pool_env.game.step.step`; the fronts do not change.
"""

from __future__ import annotations

import numpy as np

from pool_env.game.kernels.layout import point_free
from pool_env.sim.kernels._jit import kernel


@kernel
def judge(tables, positions, on_table, n_left, shots, n_potted, scratch, first_ball,
          phi_change, weights, end_on_miss, shot_limit, cue, spot, bounds, circles,
          reach2):  # fmt: skip
    """The solitaire rule for each table that shot (see the module docstring).

    Args:
        tables: ``(K,)`` tables that shot.
        positions: ``(B, N, 2)`` state after :func:`~pool_env.game.kernels.settle.settle`;
            a scratched cue ball is put back on ``spot`` here when it is free.
        on_table: ``(B, N)`` state, updated in place (the cue ball is always back on).
        n_left: ``(B,)`` object balls on each table.
        shots: ``(B,)`` shots of each episode, this one included.
        n_potted: ``(K,)`` object balls the shot potted.
        scratch: ``(K,)`` whether the cue ball dropped.
        first_ball: ``(K,)`` first ball the cue ball hit, -1 for none.
        phi_change: ``(K,)`` change of the shaping potential (zeros when shaping is off).
        weights: ``(4,)`` ``(reward_pot, reward_scratch, reward_no_contact, reward_shaping)``.
        end_on_miss: Whether a shot without a pot, or with a scratch, ends the episode.
        shot_limit: Shots after which an episode is truncated (0: none).
        cue: Ball number of the cue ball.
        spot: ``(2,)`` where a scratched cue ball goes back (the head spot).
        bounds: ``(4,)`` centres allowed on the table.
        circles: ``(P, 3)`` padded capture circles.
        reach2: Squared distance a re-spotted ball keeps from the others.

    Returns:
        ``(rewards, terminated, truncated, cleared, spot_taken)``, each ``(K,)``;
        ``spot_taken``: tables whose scratched cue ball is back on the table but not yet
        placed, since something covers the spot.
    """
    n_shots, n_balls = tables.shape[0], on_table.shape[1]
    rewards = np.empty(n_shots)
    terminated = np.zeros(n_shots, dtype=np.bool_)
    truncated = np.zeros(n_shots, dtype=np.bool_)
    cleared = np.zeros(n_shots, dtype=np.bool_)
    spot_taken = np.zeros(n_shots, dtype=np.bool_)
    others = np.empty((n_balls, 2))
    for k in range(n_shots):
        b = tables[k]
        no_contact = 1.0 if first_ball[k] < 0 else 0.0
        rewards[k] = (
            weights[0] * n_potted[k]
            + weights[1] * (1.0 if scratch[k] else 0.0)
            + weights[2] * no_contact
            + weights[3] * phi_change[k]
        )
        if scratch[k]:
            on_table[b, cue] = True
            count = 0
            for j in range(n_balls):
                if j != cue and on_table[b, j]:
                    others[count] = positions[b, j]
                    count += 1
            if point_free(spot[0], spot[1], bounds, circles, others, count, reach2):
                positions[b, cue, 0], positions[b, cue, 1] = spot[0], spot[1]
            else:
                spot_taken[k] = True
        cleared[k] = n_left[b] == 0
        missed = n_potted[k] == 0 or scratch[k]
        terminated[k] = cleared[k] or (end_on_miss and missed)
        truncated[k] = shot_limit > 0 and shots[b] >= shot_limit
    return rewards, terminated, truncated, cleared, spot_taken
