"""The hard cases of docs/physics.md, run on every engine that can set them up.

Each case names the contacts that must happen (a missed one is *tunnelling*) and those that
must not (a reported one is a *phantom* hit). Every run is then checked for:

* ``crash``: the engine raised;
* ``hang``: it hit its step or event cap, or its time limit;
* ``escape``: a ball that was not potted ended off the playing surface (centre outside the
  cushion noses; for pooltool, whose pockets have jaws, not counting the 15 cm around a
  pocket) or at a non-finite position;
* ``overlap``: at rest, two balls overlap or a ball is past a rail line by more than 1e-9 m
  (the G invariant);
* ``tunnel`` / ``phantom``: as above.

The final positions are also compared with the 50-digit reference (or with our simulator
where the reference refuses the case, marked ``*``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from pool_env import Table
from pool_env.sim.layouts import break_scene
from tools.shots import Outcome, Scene

TOL = 1e-9  # m, the G invariant
JAW_ZONE = 0.15  # m around a pocket centre where pooltool's jaws let a ball pass a rail line


@dataclass(frozen=True, eq=False)
class HardCase:
    """A scene and the contacts it must and must not produce."""

    scene: Scene
    must_hit: tuple[tuple[int, int], ...] = ()
    must_miss: tuple[tuple[int, int], ...] = ()
    notes: str = ""
    extra: dict = field(default_factory=dict)


def _case(
    name: str,
    table: Table,
    pos: list,
    vel: list,
    masses: list | None = None,
    hit: tuple = (),
    miss: tuple = (),
) -> HardCase:
    p = np.array(pos, dtype=np.float64)
    v = np.zeros_like(p)
    v[: len(vel)] = np.array(vel, dtype=np.float64)
    m = None if masses is None else np.array(masses, dtype=np.float64)
    return HardCase(Scene(name, "hard", table, p, v, 1 if len(p) > 1 else -1, m), hit, miss)


def hard_cases() -> list[HardCase]:
    """The hard cases, in the order of docs/physics.md."""
    open_t = Table(pockets="none")
    elastic = Table(pockets="none", e_ball=1.0)
    std = Table(pockets="circles")  # the pocket model every engine here shares
    r, cy, length, width = std.ball_radius, std.width / 2.0, std.length, std.width
    cradle = [(0.5, cy)] + [(1.0 + 2.0 * r * k, cy) for k in range(5)]
    rack = break_scene(std, "eight")
    d = rack[1] - rack[0]
    s45 = 2.0 / math.sqrt(2.0)
    s80 = (15.0 * math.cos(math.radians(80.0)), 15.0 * math.sin(math.radians(80.0)))
    return [
        _case("head-on, e = 1", elastic, [(0.5, cy), (1.0, cy)], [(2.0, 0.0)], hit=((0, 1),)),
        _case(
            "oblique, unequal masses",
            open_t,
            [(0.5, cy), (1.0, cy + r)],
            [(2.0, 0.0)],
            [0.17, 0.34],
            hit=((0, 1),),
        ),
        _case(
            "grazing, 1e-9 m inside 2R",
            open_t,
            [(0.5, cy), (1.0, cy + 2 * r - 1e-9)],
            [(2.0, 0.0)],
            hit=((0, 1),),
        ),
        _case(
            "grazing, 1e-9 m outside 2R",
            open_t,
            [(0.5, cy), (1.0, cy + 2 * r + 1e-9)],
            [(2.0, 0.0)],
            miss=((0, 1),),
        ),
        _case(
            "touching, closing", open_t, [(1.0, cy), (1.0 + 2 * r, cy)], [(1.0, 0.0)], hit=((0, 1),)
        ),
        _case(
            "touching, opening",
            open_t,
            [(1.0, cy), (1.0 + 2 * r, cy)],
            [(-0.3, 0.0)],
            miss=((0, 1),),
        ),
        _case("Newton's cradle, e = 1", elastic, cradle, [(1.0, 0.0)], hit=((0, 1), (4, 5))),
        _case("Newton's cradle, e = 0.95", open_t, cradle, [(1.0, 0.0)], hit=((0, 1), (4, 5))),
        _case(
            "16-ball touching rack, 10 m/s",
            std,
            rack.tolist(),
            [tuple(10.0 * d / np.hypot(*d))],
            hit=((0, 1),),
        ),
        _case("along a rail", open_t, [(0.5, r)], [(2.0, 0.0)]),
        _case("a hair off parallel to a rail", open_t, [(0.5, r)], [(2.0, -1e-9)]),
        _case("45 degrees into a corner", open_t, [(length - 0.5, width - 0.5)], [(s45, s45)]),
        _case("touching a rail, moving into it", open_t, [(r, cy)], [(-1.0, 0.0)]),
        _case(
            "same way, catching up",
            open_t,
            [(0.5, cy), (0.7, cy)],
            [(2.0, 0.0), (1.0, 0.0)],
            hit=((0, 1),),
        ),
        _case(
            "same way, same speed",
            open_t,
            [(0.5, cy), (0.7, cy)],
            [(0.5, 0.0), (0.5, 0.0)],
            miss=((0, 1),),
        ),
        _case(
            "side by side, same speed",
            open_t,
            [(0.5, 0.5), (0.5, 0.5 + 2 * r + 1e-6)],
            [(0.5, 0.0), (0.5, 0.0)],
            miss=((0, 1),),
        ),
        _case(
            "wedged between ball and rail",
            open_t,
            [(0.6, cy), (r, cy)],
            [(-1.0, 0.0)],
            hit=((0, 1),),
        ),
        _case(
            "1e-6 m/s shot into a ball 1e-12 m away",
            open_t,
            [(0.5, cy), (0.5 + 2 * r + 1e-12, cy)],
            [(1e-6, 0.0)],
            hit=((0, 1),),
        ),
        _case("15 m/s into a ball", std, [(0.4, cy), (1.2, cy)], [(15.0, 0.0)], hit=((0, 1),)),
        _case("15 m/s at a rail, 80 degrees", open_t, [(1.0, cy)], [s80]),
    ]


def check(case: HardCase, out: Outcome, jaws: bool = False) -> list[str]:
    """The failure tags of one run (empty: it survived).

    Args:
        case: The case.
        out: The engine's outcome.
        jaws: The engine models pocket jaws (pooltool): a ball may rest past a rail line
            within 0.15 m of a pocket without being off the table.
    """
    if out.error is not None:
        if "different mass" in out.error:
            return ["unsupported (equal masses only)"]
        return ["hang" if out.error.startswith("hang") else "crash"]
    tags = []
    if out.capped:
        tags.append("hang")
    table = case.scene.table
    on = out.pocketed < 0
    pts = out.positions[on]
    if jaws and table.n_pockets:
        near = (
            np.min(
                np.hypot(
                    pts[:, None, 0] - table.pockets[None, :, 0],
                    pts[:, None, 1] - table.pockets[None, :, 1],
                ),
                axis=1,
            )
            < JAW_ZONE
        )
        pts = pts[~near]
    if not np.all(np.isfinite(pts)) or np.any(
        (pts[:, 0] < 0.0)
        | (pts[:, 0] > table.length)
        | (pts[:, 1] < 0.0)
        | (pts[:, 1] > table.width)
    ):
        tags.append("escape")
    elif _rest_overlap(pts, table) > TOL:
        tags.append("overlap")
    if any(p not in out.pairs for p in case.must_hit):
        tags.append("tunnel")
    if any(p in out.pairs for p in case.must_miss):
        tags.append("phantom")
    return tags


def _rest_overlap(pts: NDArray[np.float64], table: Table) -> float:
    r = table.ball_radius
    if pts.size == 0:
        return 0.0
    worst = float(
        np.max(
            np.maximum.reduce(
                [
                    r - pts[:, 0],
                    pts[:, 0] - (table.length - r),
                    r - pts[:, 1],
                    pts[:, 1] - (table.width - r),
                ]
            )
        )
    )
    if pts.shape[0] > 1:
        d = np.hypot(*(pts[:, None, :] - pts[None, :, :]).transpose(2, 0, 1))
        d[np.diag_indices_from(d)] = np.inf
        worst = max(worst, float(2.0 * r - d.min()))
    return worst
