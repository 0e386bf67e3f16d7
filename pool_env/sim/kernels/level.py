"""What a model level is (compiled): the parts the one event loop calls, as a strategy.

A model level is a motion law and its resolution models: how a ball moves in each of its
motion states, when it changes state, when it can meet a rail, a jaw, a pocket or another
ball, and what an impact does. The event loop (:mod:`~pool_env.sim.kernels.loop`), the
batch (:mod:`~pool_env.sim.kernels.batch`) and the rollout
(:mod:`~pool_env.sim.kernels.rollout_kernel`) are written once, against the functions below, and
import no level. Each level lives in its own package and registers its implementation of
every function here for its marker type (:func:`pool_env.sim.jit.level_method`):

* :mod:`pool_env.sim.kernels.roll`: the seed's model, every moving ball rolling with
  constant deceleration on a straight line; anchors ``(N, 9)``
  (:mod:`~pool_env.sim.kernels.roll.motion`), states rest, moving, potted.
* :mod:`pool_env.sim.kernels.spin`: sliding, rolling, spinning, english and throw
  (pooltool's model); anchors ``(N, 11)`` (:mod:`~pool_env.sim.kernels.spin.state`).

A caller passes the level's marker (``ROLL`` or ``SPIN``) as the first argument; numba
compiles one specialised loop per marker type, calling the level's parts directly (no
dispatch at run time: the marker is a type, not a value). A third level (an airborne ball, say)
is a new package beside these two that defines a marker and implements every function here;
the loop, the batch, the rollout, recording, validation and the Python API stay as they are
(:mod:`pool_env.sim.levels` names it for the Python side).

The functions below are the interface: compiled, a call is the level's implementation;
called from Python (with numba's JIT disabled, ``NUMBA_DISABLE_JIT=1``, the loop itself
runs as Python), a function looks up the marker's implementation and runs it, and a
value that is no level's marker raises ``TypeError``. ``st`` is the
level's anchor array and ``ms`` its per-ball motion states (``int8``); ``prm`` the level's
flat parameter array (``Table.params`` or ``Table.spin_params``); ``own`` and ``boxes`` the
loop's ``(N, 4)`` next-own-event rows (columns of :mod:`~pool_env.sim.kernels.kinds`) and
the level's per-ball reach bounds used to cull pair tests.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

#: Each level's implementations, by the interface function's name and the marker's type
#: (filled by :func:`pool_env.sim.jit.level_method`), for calls from plain Python.
IMPLEMENTATIONS: dict[tuple[str, type], Callable[..., Any]] = {}


def _implementation(name: str, level: Any) -> Callable[..., Any]:
    impl = IMPLEMENTATIONS.get((name, type(level)))
    if impl is None:
        raise TypeError(
            f"pool_env.sim.kernels.level.{name} needs a model level's marker (ROLL or SPIN) "
            f"first, got {level!r}"
        )
    return impl


def start(level: Any, positions: Any, velocities: Any, angular: Any, prm: Any) -> Any:
    """The anchors of a shot's balls at time 0: ``(st, ms)``.

    ``positions``, ``velocities`` ``(N, 2)`` and ``angular`` ``(N, 3)`` are validated (a
    level without spin is given zeros, and ignores them).
    """
    return _implementation("start", level)(level, positions, velocities, angular, prm)


def predict_own(
    level: Any, st: Any, ms: Any, i: int, prm: Any, pockets: Any, own: Any, boxes: Any
) -> None:
    """Write ball ``i``'s next own event (rail, jaw, pocket, transition) into ``own[i]``.

    Also writes ``boxes[i]``, the bound on where the ball can be until then, for
    :func:`predict_pair`.
    """
    return _implementation("predict_own", level)(level, st, ms, i, prm, pockets, own, boxes)


def predict_pair(
    level: Any, st: Any, ms: Any, i: int, j: int, now: float, prm: Any, own: Any, boxes: Any
) -> float:
    """The time balls ``i < j`` next meet before either's own event (``inf`` if never)."""
    return _implementation("predict_pair", level)(level, st, ms, i, j, now, prm, own, boxes)


def impact(
    level: Any,
    st: Any,
    ms: Any,
    masses: Any,
    i: int,
    j: int,
    now: float,
    repeats: int,
    prm: Any,
    pockets: Any,
    changed: Any,
    out: Any,
) -> int:
    """Resolve the impact of balls ``i < j`` at ``now``: re-anchor the balls it changes.

    ``repeats`` counts the pair's impacts in a row within ``ZENO_WINDOW`` (the Zeno rules
    are the level's); ``out`` is scratch space of 10 floats.

    Returns:
        The number of balls re-anchored (two, or a stuck cluster), listed in ``changed``:
        the loop re-predicts their own events and pairs and logs a segment for each.
    """
    return _implementation("impact", level)(
        level, st, ms, masses, i, j, now, repeats, prm, pockets, changed, out
    )


def cushion(
    level: Any,
    st: Any,
    ms: Any,
    kind: int,
    i: int,
    j: int,
    now: float,
    repeats: int,
    prm: Any,
    pockets: Any,
    out: Any,
) -> None:
    """Resolve ball ``i`` meeting rail, jaw facing or jaw point ``j`` (``kind``) at ``now``.

    ``repeats`` counts the ball's cushion impacts in a row within ``ZENO_WINDOW``.
    """
    return _implementation("cushion", level)(
        level, st, ms, kind, i, j, now, repeats, prm, pockets, out
    )


def capture(level: Any, st: Any, ms: Any, i: int, now: float, prm: Any) -> None:
    """Ball ``i`` drops into a pocket at ``now``: it stays where it was captured, still."""
    return _implementation("capture", level)(level, st, ms, i, now, prm)


def settle(level: Any, st: Any, ms: Any, kind: int, i: int, now: float, prm: Any) -> bool:
    """Ball ``i`` changes its motion state at ``now`` (a stop, or a transition of ``kind``).

    Returns:
        Whether the ball's pair predictions still hold (a roll-level stop: each pair's
        prediction already includes both balls' rest): the loop then re-predicts only the
        ball's own event and logs no segment.
    """
    return _implementation("settle", level)(level, st, ms, kind, i, now, prm)


def moving(level: Any, ms: Any, i: int) -> bool:
    """Whether ball ``i`` is in motion (what the event cap stops)."""
    return _implementation("moving", level)(level, ms, i)


def halt(level: Any, st: Any, ms: Any, i: int, now: float, prm: Any) -> None:
    """Stop moving ball ``i`` where it is at ``now`` (the event cap's end of a shot)."""
    return _implementation("halt", level)(level, st, ms, i, now, prm)


def new_segments(level: Any, capacity: int) -> Any:
    """An empty ``SegmentLog`` (:mod:`~pool_env.sim.kernels.record`) of the level's width."""
    return _implementation("new_segments", level)(level, capacity)


def log_segment(level: Any, log: Any, row: int, k: int, now: float, st: Any, ms: Any) -> None:
    """Write segment ``row`` (below the capacity): ball ``k`` re-anchored at ``now``."""
    return _implementation("log_segment", level)(level, log, row, k, now, st, ms)


def check_scene(
    level: Any, positions: Any, velocities: Any, angular: Any, masses: Any, prm: Any, pockets: Any
) -> Any:
    """Validate a scene: ``(code, i, j)`` naming its first problem (``OK`` if none).

    Codes of :mod:`~pool_env.sim.kernels.validation`.
    """
    return _implementation("check_scene", level)(
        level, positions, velocities, angular, masses, prm, pockets
    )


def strike(
    level: Any,
    speed: float,
    angle: float,
    a: float,
    b: float,
    elevation: float,
    prm: Any,
    out: Any,
) -> None:
    """The cue ball's velocity and spin just after a strike: ``out[:5]`` = vx, vy, wx, wy, wz.

    ``speed`` and ``angle`` are the ball's speed in the table plane and the cue's aim;
    ``a``, ``b`` the tip offsets and ``elevation`` the cue's (zero on a level without spin).
    """
    return _implementation("strike", level)(level, speed, angle, a, b, elevation, prm, out)


def tail_sizes(level: Any) -> Any:
    """``(floats, ints)`` per ball that the level adds to a packed shot's buffer."""
    return _implementation("tail_sizes", level)(level)


def write_tails(
    level: Any, floats: Any, ints: Any, f: int, k: int, st: Any, ms: Any, now: float, prm: Any
) -> None:
    """Write the level's per-ball tails into a packed buffer from ``floats[f]``, ``ints[k]``."""
    return _implementation("write_tails", level)(level, floats, ints, f, k, st, ms, now, prm)
