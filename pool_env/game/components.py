"""One action component from the value it stands for: the encoders' shared step.

Every part of a shot that an action carries (aim, speed, placement, tip) is a value in a
range ``[low, high]`` mapped linearly onto ``[-1, 1]``; the codec and each ruleset's
encoder write their parts through :func:`unit_component`, so out-of-range values are
refused (or clipped) by one rule with one message.
"""

from __future__ import annotations

from pool_env.game.checks import is_integer
from pool_env.game.kernels.encode import to_unit


def unit_component(name: str, value: float, low: float, high: float, clip: bool) -> float:
    """``value`` in ``[low, high]`` as an action component in ``[-1, 1]``.

    Args:
        name: The part's name, for the error message.
        value: The value wanted.
        low: What component -1 stands for.
        high: What component +1 stands for.
        clip: Map a value outside the range onto its nearer end instead of raising.

    Raises:
        ValueError: On a value outside the range (more than 1e-12 of the component), or not
            the only value of a zero-width range, without ``clip``.
    """
    if high == low and value != low and not clip:
        raise ValueError(f"{name} {value!r} is not {low!r}, the only value of its range")
    c = to_unit(value, low, high)
    if not -1.0 - 1e-12 <= c <= 1.0 + 1e-12 and not clip:
        raise ValueError(f"{name} {value!r} lies outside its range [{low!r}, {high!r}]")
    return min(max(c, -1.0), 1.0)


def pocket_component(n_pockets: int, pocket: int) -> float:
    """The action component that calls ``pocket`` of ``n_pockets``: the middle of its bin.

    Raises:
        ValueError: If the table has no pocket ``pocket``.
    """
    if not is_integer(pocket) or not 0 <= pocket < n_pockets:
        raise ValueError(f"pocket must be an integer in 0..{n_pockets - 1}, got {pocket!r}")
    return (2.0 * pocket + 1.0) / n_pockets - 1.0


def ball_component(n_objects: int, ball: int) -> float:
    """The action component that calls object ball ``ball`` (10-ball): the middle of its bin.

    Raises:
        ValueError: If ``ball`` is not one of the ``n_objects`` object balls.
    """
    if not is_integer(ball) or not 1 <= ball <= n_objects:
        raise ValueError(f"the called ball must be an integer in 1..{n_objects}, got {ball!r}")
    return (2.0 * (ball - 1) + 1.0) / n_objects - 1.0
