"""The specification of :class:`pool_env.PoolEnv`, kept here for its length.

``PoolEnv``'s docstring is :func:`with_spec` of its own (a summary and its examples, which
run as doctests): ``help(pool_env.PoolEnv)`` shows the whole, and the docs build reads it
at run time (``docs/griffe_runtime_docs.py``). The class stays a short module of code.
"""

from __future__ import annotations

import inspect

#: The specification: what an episode is, the spaces, rewards, ends, info, arguments, the
#: rules of the game ids, rendering, attributes and the version history.
SPEC = r"""## Description

A cue ball and ``n`` object balls lie on a pool table (a 9-ft table with six pockets by
default). Each step is one shot: the action is decoded to a direction and a speed, the
cue ball is struck, and the simulator runs the shot exactly to rest (rolling resistance,
ball-ball and cushion impacts, pockets with jaws cut to the WPA specifications). The
spin ids (``pool_env/<Task>-v1``, ``model="spin"``) play the spin level
(:class:`~pool_env.Table` ``model="spin"``: sliding, draw, follow, english, throw and
squirt) and add the cue tip to the action; the roll ids (``pool_env/<Task>Roll-v1``,
``model="roll"``) play the roll level (balls roll, no spin). The table's defaults are
measured figures (:class:`~pool_env.Table`: ``mu_roll = 0.01``, ``e_ball = 0.95``,
``e_cushion = 0.65``), and so is the speed range
(0.45 to 4.5 m/s, a slow shot to a power shot). ``table={"pockets": "circles"}`` gives
the cheaper, far more generous capture circles. The goal is to pot every object ball.
Ball ``0`` is the cue ball; object balls are numbered ``1..n``.

## Action Space

``Box(-1, 1, (2,), float32)``, or ``Box(-1, 1, (4,), float32)`` on a spin table
(``model="spin"``, the spin ids), each component mapped linearly onto a range:

| Num | Action | -1 maps to | +1 maps to | default range |
|-----|--------|------------|------------|---------------|
| 0   | aim    | ``aim_range[0]`` | ``aim_range[1]`` | by ``aim``, below |
| 1   | speed  | ``speed_range[0]`` | ``speed_range[1]`` | 0.45 .. 4.5 m/s |
| 2   | tip side (spin only) | ``-tip_limit`` | ``+tip_limit`` | +-0.685 R |
| 3   | tip vertical (spin only) | ``-tip_limit`` | ``+tip_limit`` | +-0.685 R |

The speed is the cue ball's, from a slow shot to a power shot (the speeds real play uses). The
aim is relative to the nearest object ball on the table, or absolute, by ``aim``:

* ``"cut"`` (default): where the cue ball meets the nearest object ball, as the offset
  of its path from that ball's centre in ball diameters; default -1 .. 1 (0 is a full
  hit, +-1 a grazing one; +1 passes on the counter-clockwise side). The object ball
  leaves at ``asin(offset)`` from the cue ball's line whatever the distance, so the
  best action is a smooth function of the layout, and every action in (-1, 1) hits the
  ball (unless another ball is in the way).
* ``"relative"``: radians, counter-clockwise, from the line joining the cue ball to the
  nearest object ball; default +-10 degrees. Action 0 hits that ball full too, but the
  angle a cut needs shrinks with the distance (``~2R sin(cut) / d``), so the best
  action is a steep function of the layout.
* ``"absolute"``: radians from the table's +x axis (its length); default +-pi.

Why ``cut`` is the default: the best action is a smooth function of the layout, and
learners do better with it. On ``OneBallRoll-v1`` (1000 episodes on seeds 10000+,
``results/agents.md``), PPO (300k steps, seed 0, the ghost-ball features) pots 63.4% of
its shots with ``cut`` aim and 61.4% with ``relative`` (500 episodes); SAC (100k steps)
90.1% and 81.4%. For scale: random actions pot 15.6%, a constant full hit at the top
speed 26.7% (26.3% without a scratch), the best of 36 constant actions 27.5%, the
geometric ghost-ball agent 95.3%.

The cue tip (spin table only): the offset ``(a, b)`` of the cue's axis from the ball's
centre, in fractions of the radius ``R``, seen from behind the cue: ``a`` side (+ right
english: the ball spins counter-clockwise seen from above and squirts a little to the
left), ``b`` vertical (+ follow, - draw, 0 a centre-ball hit). Each component ``c`` maps to
``c * tip_limit``. The tip limit is the miscue limit: real tips (and pooltool) miscue
beyond a contact offset of about half a radius, and the contact point lies
``1 / (1 + r_tip / R)`` of the axis offset off centre, so the default ``tip_limit`` is
``0.5 (1 + cue_tip_radius / R)``, 0.685 for the default 10.6 mm tip
(:func:`pool_env.game.config.default_tip_limit`; ``GameConfig.tip_limit``). An offset
outside the circle of radius ``tip_limit`` (the corners of the action square) is scaled
back onto it along its direction: clipped, never a miscue. The strike is pooltool's
instantaneous point strike (:mod:`pool_env.sim.kernels.spin.strike`): the speed stays
the cue ball's speed, the ball leaves along the aim plus the squirt, with spin
``(5 v / 2R)`` times the contact offset (a centre-line hit at contact offset 2/5 leaves
rolling). The cue is level (no elevation: no masse, no jump).

Out-of-range actions (infinities included) are clipped to ``[-1, 1]``. An action with a
NaN raises ``ValueError`` and changes nothing. With ``noise=(sigma_angle, sigma_speed)``
Gaussian execution noise (radians, m/s; from ``self.np_random``) is added to the shot's
direction and speed (the speed is then clipped at 0). A spin table also takes
``noise=(sigma_angle, sigma_speed, sigma_tip)``: the tip's two offsets each get noise of
``sigma_tip`` (fractions of R), drawn after the angle and the speed (so the draws of a
roll table's shot are unchanged), and the noisy tip is scaled back onto the tip limit's
circle as above. :func:`pool_env.encode_action` and :func:`pool_env.decode_action` map a
shot to its action and back.

## Observation Space

``Box(-1, 1, (3 (n + 1),), float32)``: for each ball, in the fixed order cue, 1, ..., n:

| Num       | Observation                     | Min | Max | potted ball |
|-----------|---------------------------------|-----|-----|-------------|
| 3 k       | ball k: x scaled, 2 x / L - 1    | -1  | 1   | 0           |
| 3 k + 1   | ball k: y scaled, 2 y / W - 1    | -1  | 1   | 0           |
| 3 k + 2   | ball k on the table (1) or not (0) | 0 | 1   | 0           |

``L``, ``W`` are the table's length and width; the origin is a corner of the playing
surface. Exact positions in metres are ``env.unwrapped.positions``.

## Rewards

``reward_pot`` (+1) for each object ball the shot pots and ``reward_scratch`` (-1) when the
cue ball is potted (a scratch: the cue ball is put back on the head spot, or the free
point nearest to it). Optional shaping, off by default: ``reward_no_contact`` when the
cue ball touches no ball, and ``reward_shaping`` times the change of the potential
``-sum(distance of each object ball to its nearest pocket) / table diagonal`` (potential
based, so it does not change which policies are optimal for an undiscounted return).

## Starting State

Set by ``scene`` (see :mod:`pool_env.game.scenes`): ``"one_ball"`` (cue and one object ball
uniformly at random), ``"random"`` (cue and ``n_balls`` object balls uniformly at random,
3 by default), ``"nine_ball"`` / ``"eight_ball"`` (the rack on the foot spot, the cue
ball anywhere in the kitchen: the first shot is the break), a fixed ``(N, 2)`` layout, or
a callable ``(table, np_random) -> (N, 2)``. Random layouts never overlap and keep out of
the pockets. ``reset(options={"positions": ..., "on_table": ...})`` starts one episode
from a given layout (``on_table`` optional; the cue ball must be on the table; every
row must be finite, a ball off the table included: its row is kept as its position, so
NaN is refused rather than handed back through ``positions``). ``options`` must be a
dict (or ``None``); a seed is a non-negative Python or numpy integer, of any size.

## Episode End

1. Termination: every object ball is potted (``info["is_success"]``).
2. Termination, with ``end_on_miss=True``: the shot pots no object ball, or scratches
   (the turn passes).
3. Truncation: ``max_episode_steps`` of the registered id (``TimeLimit``), or
   ``max_shots`` shots when given (the raw environment's own limit).

## Info

``potted`` (tuple of object balls potted by the shot), ``scratch`` (bool),
``first_contact`` (first ball the cue ball hit, -1 for none; under the rules, the one
they read of balls met at the same instant), ``n_events`` (simulator
events), ``hit_event_cap`` (bool), ``angle`` and ``speed`` (the executed shot, radians
from +x and m/s: the cue's aim and the cue ball's speed), ``is_success`` (the table is
cleared); on a spin table ``tip`` (the executed tip offset ``(a, b)``, after noise and
the tip limit). ``reset`` returns ``{}``.

## Arguments

| Parameter | Type | Default | Description |
|---|---|---|---|
| ``table`` | Table, dict or None | ``Table()`` | the table, or ``Table`` keyword arguments |
| ``scene`` | str, array or callable | ``"random"`` | starting layout (above) |
| ``n_balls`` | int or None | scene's | object balls (``"random"``: 1..15, default 3) |
| ``aim`` | str | ``"cut"`` | ``"cut"``, ``"relative"`` or ``"absolute"`` |
| ``aim_range`` | (float, float) | by ``aim`` | what action[0] = -1 and +1 map to |
| ``speed_range`` | (float, float) | (0.45, 4.5) | m/s for action -1 and +1 |
| ``noise`` | tuple or None | None | execution noise sigmas (rad, m/s[, tip: R]) |
| ``end_on_miss`` | bool | False | a shot that pots nothing ends the episode |
| ``max_shots`` | int or None | None | truncate the raw env after this many shots |
| ``reward_pot`` | float | 1.0 | per object ball potted |
| ``reward_scratch`` | float | -1.0 | when the cue ball is potted |
| ``reward_no_contact`` | float | 0.0 | when the cue ball hits no ball |
| ``reward_shaping`` | float | 0.0 | weight of the pocket-distance potential |
| ``game`` | str | ``"solitaire"`` | ``"nine"`` or ``"eight"``: the rules (above) |
| ``end_on_foul`` | bool | False | rules: a foul or a lost turn ends the episode |
| ``break_speed_range`` | (float, float) | (8.0, 12.0) | rules: m/s of the break |
| ``reward_foul`` | float | -1.0 | rules: for a foul |
| ``reward_win`` | float | 1.0 | rules: for a won rack (minus for a lost one) |
| ``render_mode`` | str or None | None | ``"rgb_array"``, ``"rgb_array_list"``, ``"human"`` |
| ``render_width`` | int | 800 | frame width in pixels |
| ``model`` | str or None | None | ``"spin"``: the spin table and the tip (the table's) |
| ``tip_limit`` | float or None | None | spin: the tip's largest offset (R; the miscue limit) |

Registered ids (``import pool_env``), each task on the spin table and on the roll table:
``pool_env/Pool-v1`` / ``pool_env/PoolRoll-v1`` (these defaults, 50 shots),
``pool_env/OneBall-v1`` / ``pool_env/OneBallRoll-v1`` (``scene="one_ball"``,
``end_on_miss=True``: one shot per episode, since a pot clears the table and a miss ends
the turn; 10 shots with ``end_on_miss=False``), ``pool_env/NineBall-v1`` /
``pool_env/NineBallRoll-v1`` (break, 50 shots) and ``pool_env/EightBall-v1`` /
``pool_env/EightBallRoll-v1`` (break, 80 shots), all solitaire; ``pool_env/NineBallGame-v1``
/ ``pool_env/NineBallGameRoll-v1`` and ``pool_env/EightBallGame-v1`` /
``pool_env/EightBallGameRoll-v1`` under the rules (below). The old names of the roll ids,
``pool_env/<Task>-v0``, still work (Gymnasium reports them out of date). In
``SubprocVecEnv`` workers use the id ``"pool_env:pool_env/OneBallRoll-v1"`` (or import
``pool_env`` in the main script), so that each worker imports the package that
registers the ids.

## Rules: the game ids

``pool_env/NineBallGame-v1`` and ``pool_env/EightBallGame-v1`` (or ``game=`` with the
``nine_ball`` / ``eight_ball`` scene, or any layout of 9 / 15 object balls) play one rack
under the WPA rules, compiled in :mod:`pool_env.game.kernels.wpa` (its docstring states
every rule). One agent shoots every shot: a foul gives ball in hand to its next shot
(practice mode, ``end_on_foul=False``), or ends the episode (run-out mode,
``end_on_foul=True``: so does a legal shot that does not keep the table). A rack scene
starts with the break: the cue ball in hand behind the head string, the speed mapped
onto ``break_speed_range`` (8 .. 12 m/s; a pro breaks at 11-13). Without ``noise`` a
break from the same spot at the same speed is the same every episode.

Enforced besides the fouls below: with the cue ball in hand behind the head string
(the break, and after a scratch on the 8-ball break) the cue ball may not first meet a
ball whose base lies behind the head string (``x < L / 4``; on the line it is
playable) unless it crossed the line first (foul ``"kitchen_ball_first"``); a cue ball
that meets several balls within 1e-9 s of its first contact gives the shooter the
benefit (legal if any of them may be hit first, whatever their numbers); the 8 potted
on a legal 8-ball break is re-spotted and the breaker continues.

Simplifications that remain, all deliberate:

* No push-out (9-ball), no called shots but the 8's pocket (any object ball potted
  counts), no called safeties, no warning before a third foul, no jump, masse or
  "bad cue ball" fouls (the cue is level and its tip clipped to the miscue limit; the
  roll ids have no spin), no stalemate rule, no three-foul rule in 8-ball (WPA has none
  either).
* An illegal break is a foul with ball in hand on the table as it lies (no re-rack or
  re-break choice); the 8 on a legal break is always re-spotted (no re-break choice).
* Balls potted on a foul stay down, except the 9 (re-spotted) and the 8 (the rack is
  lost, or re-spotted on the break); a re-spotted ball goes on the foot spot or the
  free point nearest to it (WPA: on the long string behind it).
* A pocket jaw counts as a cushion for "a ball touched a rail".
* One foul reason per shot (the first in the order scratch, kitchen_ball_first,
  no_contact, wrong_ball_first, no_rail; on a break scratch, kitchen_ball_first,
  illegal_break).
* One player: the agent is also the incoming player after its own fouls; a lost rack
  is a win of the absent opponent.
* Reset's ``options["rules"]`` may only give racks the rules can finish: the 9 (the
  8) on the table, an open 8-ball table with a ball besides the 8, no groups on the
  break, fouls 0-2.

Action ``Box(-1, 1, (5,), float32)`` (``Box(7)`` on a spin table), each component
mapped linearly:

| Num | Action | -1 .. +1 maps to | used |
|-----|--------|------------------|------|
| 0 | aim | ``aim_range``, from the nearest legal ball (below) | always |
| 1 | speed | ``speed_range``; on a break ``break_speed_range`` | always |
| 2 | cue ball x | ``R .. L - R``; behind the head string ``R .. L / 4`` | cue ball in hand |
| 3 | cue ball y | ``R .. W - R`` | cue ball in hand |
| 4 | called pocket | six equal bins, pockets in ``table.pockets`` order | shooting at the 8 |
| 5 | tip side (spin only) | ``-tip_limit .. +tip_limit`` (as above) | always |
| 6 | tip vertical (spin only) | ``-tip_limit .. +tip_limit`` (as above) | always |

Cut and relative aim refer to the nearest ball the rules let the cue ball hit first
(not to the nearest ball). A placement on or next to a ball (closer than ``2R``) or in
a pocket is moved to the free point nearest to it (:func:`pool_env.free_spot`),
deterministically; the ball in hand is behind the head string on a break and after a
scratch on the 8-ball break.

Observation ``Box(-1, 1, (4 N - 1 + 7,), float32)`` (``N`` balls, cue included): the
``3 N`` ball entries above; then ``N - 1`` flags, one per object ball ``1..N-1``: the
agent may hit it first (9-ball: the ball on; 8-ball: its group, any ball but the 8 on an
open table, the 8 once the group is cleared, any ball on the break); then 7 entries:
cue ball in hand, behind the head string only, the next shot is a break, open table
(8-ball), the agent's successive fouls / 2, the opponent's / 2 (0 with one player),
the agent shoots next (1 with one player). With these the game is Markov.

Reward: ``reward_pot`` (+1) per object ball potted on a legal shot (a re-spotted ball
and the 8 of 8-ball not counted), ``reward_foul`` (-1) for a foul, ``reward_win`` (+1)
for winning the rack and ``-reward_win`` for losing it (three fouls in a row in
9-ball; the 8 early, in an uncalled pocket, or on a foul). The episode terminates when
the rack is decided (``info["is_success"]``: the agent won) and is truncated at the
time limit (100 shots 9-ball, 150 8-ball).

Info adds ``foul`` (``None`` or ``"scratch"``, ``"wrong_ball_first"``, ``"no_rail"``,
``"no_contact"``, ``"illegal_break"``, ``"kitchen_ball_first"``), ``legal``,
``ball_on`` (the ball on before the shot; -1 in 8-ball before the group is cleared),
``winner`` (-1 while undecided, 0 the agent, 1 its absent opponent: a lost rack; an
integer rather than ``None`` so that vector envs keep one dtype per key), ``loss``
(``None`` or ``"three_fouls"``, ``"eight_early"``, ``"eight_wrong_pocket"``,
``"eight_on_foul"``) and ``turn_over`` (a foul, or a shot that would pass the table to
an opponent). ``env.unwrapped.rack``
is the rack state; ``reset(options={"positions": ..., "on_table": ..., "rules":
{...}})`` sets it (keys ``break``, ``ball_in_hand``, ``behind_head_string``,
``groups`` (``"open"``, ``"solids"``, ``"stripes"`` per player), ``fouls``; by default
a given layout is not a break, with the cue ball where it lies and an open table).
Two players: :mod:`pool_env.multiagent`.

## Rendering

``"rgb_array"``: ``render()`` returns an ``(H, W, 3)`` uint8 top-down frame: the balls at
rest, with the paths of the last shot drawn as trails, so ``RecordVideo`` shows each
shot as one frame (``render_fps`` is 2: half a second per shot). ``"rgb_array_list"``:
``render()`` returns every frame since the last call: the layout at reset, then each shot:
0.6 s of the cue stick at ``last_strike``'s aim (on a spin table with a ball face
showing where the tip hits), then the shot sampled from its exact trajectories, sliding
curves included, at ``render_fps`` 30 (twice real time, at most 4 s, at least 20 frames a
shot; :data:`pool_env.render.LIST_PLAYBACK`). Gymnasium's
``RecordVideo`` keeps one frame per step of a list; :class:`pool_env.record.RecordShots`
keeps them all, and ``gymnasium.utils.save_video.save_video(env.render(), ...)`` writes
them too. ``"human"``: a pygame window (``pip install "pool_env[render]"``) that animates
each shot (off screen, silently, on a machine without a display). With a render mode,
shots keep their trajectories: ``shot_frames()`` samples the last shot for an animation
and ``save_shot(path)`` writes it as GIF or MP4.

## Attributes

Of the unwrapped environment (``env.unwrapped``), for agents and tools:
``config`` (the parsed :class:`~pool_env.game.config.GameConfig`), ``table`` (the
:class:`~pool_env.Table`), ``positions`` (``(N, 2)`` ball centres in
metres, cue first; a copy), ``on_table`` (``(N,)`` booleans), ``cue`` (0), ``aim``,
``aim_range``, ``speed_range``, ``noise``, ``n_object_balls``, ``end_on_miss``,
``max_shots``, ``reward_weights`` (pot, scratch, no contact, shaping), ``shots`` (this
episode), ``last_shot`` (the :class:`~pool_env.sim.result.ShotResult`, rows in the order of
``last_shot_balls``), ``last_strike`` (the last shot as executed: ``(angle, speed,
tip_side, tip_vertical)``, the tip ``0.0, 0.0`` on a roll table; ``None`` before the
first shot of an episode).

Physics note: rolling resistance is low (``mu_roll = 0.01``: a ball at 3 m/s rolls 46 m
if nothing stops it), but the pockets have jaws: a ball drops only through a pocket's
opening at an angle the jaws accept (about 8.5 cm straight into a side pocket, nothing
beyond ~70 degrees), so aiming and speed control are what pot balls.

## Version History

* v1: the spin table (``model="spin"``): sliding, draw, follow, english, throw and
  squirt; the action gains the cue tip's side and vertical offsets at its end
  (``Box(4)``, rules ``Box(7)``), clipped to the miscue limit; ``noise`` takes a tip
  sigma; ``info["tip"]``. Scenes, rules, rewards, observations and time limits are
  v0's. The roll table's ids are ``<Task>Roll-v1``: v0 under a name of its own, bit for
  bit, since the two tables are two models of one task, not a version and its successor
  (the ``-v0`` names remain as aliases).
* v0: Initial version (the roll level: balls roll without spin).
"""


def with_spec(docstring: str | None) -> str:
    """``docstring`` (a summary line, then the rest) with :data:`SPEC` after its summary."""
    summary, _, rest = inspect.cleandoc(docstring or "").partition("\n\n")
    return f"{summary}\n\n{SPEC.strip()}\n\n{rest}".rstrip() + "\n"
