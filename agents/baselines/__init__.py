"""The baselines: agents that play from geometry or the simulator, with SB3's ``predict``.

Nothing here needs stable-baselines3 or torch: the core install plays and evaluates them.
``random_agent`` (uniform or one constant action; the best constant of a grid is
:mod:`agents.evaluation.constant_scan`'s), ``ghost_ball`` (the geometric ghost-ball
heuristic), ``search`` (candidate shots checked on the simulator), ``game_agents`` (both
under the rules of the game ids); ``base``, ``aiming``, ``geometry`` and ``trace`` are what
they share (the env's spec and observation, the action codec, the table's shots, the cue
ball's path off the cushions). On the spin ids: ``cue_path`` (the cue ball in closed form:
strike, slide, roll, contact with throw) and ``spin_play`` (the tip and speed for position).
Three-cushion (``ThreeCushion-v1``): ``carom`` (the point, from the rollout's rows and from
an event log; the noise's draws), ``three_cushion_search`` (the anytime search over the
batched rollout, on the raw simulator) and ``three_cushion_agent`` (the same through the
env's action).
"""
