"""A plain-Python reference of the decision process for one table: slow and obvious.

It shares no code with :mod:`pool_env.game`: layouts, action decoding, aiming, noise,
settling, rewards, episode ends, observations and info are written out here again, one
table, one ball at a time, in Python floats. What it does borrow is the physics
(:func:`pool_env.shoot`, checked against its own 50-digit reference elsewhere), the
rare nearest-free-point search of a re-spot when the head spot is covered
(:func:`pool_env.free_spot`, with its own tests) and a rack's spots
(:mod:`pool_env.sim.layouts`; the order the rules rack the balls in is written out here).
``tests/game/test_game_reference.py`` plays random episodes of every registered id on this
and on ``gym.make(id)`` and compares them exactly. On a spin table (the spin ids) the
action's last two components are the cue tip, decoded here again (clip, scale by the tip
limit, back onto the miscue circle) and struck through :func:`pool_env.shoot`'s ``tip``.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from pool_env import Table, free_spot, shoot
from pool_env.sim.layouts import break_scene, rack_spots

CLEARANCE = 1e-7  # the documented margin of every placed ball (pool_env.game.scenes)
TRIES = 4096
AIM_RANGES = {
    "absolute": (-math.pi, math.pi),
    "relative": (-math.radians(10), math.radians(10)),
    "cut": (-1.0, 1.0),
}


class ReferenceEnv:
    """One table; ``reset``/``step`` as ``gym.make(id)`` (``TimeLimit`` included)."""

    def __init__(self, max_episode_steps: int, scene: str = "random", n_balls: int | None = None,
                 aim: str = "cut", noise: tuple[float, float] | None = None,
                 end_on_miss: bool = False, speed_range: tuple[float, float] = (0.45, 4.5),
                 reward_shaping: float = 0.0, reward_no_contact: float = 0.0,
                 model: str = "roll", tip_limit: float | None = None,
                 rack_order: str = "random") -> None:  # fmt: skip
        self.table = Table(model=model)
        self.spin = model == "spin"
        # a contact offset of half a radius, as an axis offset: 0.5 (1 + r_tip / R)
        ratio = self.table.cue_tip_radius / self.table.ball_radius
        self.tip_limit = tip_limit if tip_limit is not None else min(1.0, 0.5 * (1.0 + ratio))
        self.scene, self.rack_order = scene, rack_order
        counts = {"one_ball": 1, "nine_ball": 9, "eight_ball": 15}
        self.n = counts.get(scene, 3 if n_balls is None else n_balls)
        self.aim, self.aim_range, self.speed_range = aim, AIM_RANGES[aim], speed_range
        self.noise = noise
        self.end_on_miss = end_on_miss
        self.weights = (1.0, -1.0, reward_no_contact, reward_shaping)
        self.limit = max_episode_steps
        self.rng: np.random.Generator | None = None

    # -- layouts ----------------------------------------------------------------------

    def _free(self, x: float, y: float, balls: list[tuple[float, float]], reach: float) -> bool:
        t, r = self.table, self.table.ball_radius
        if not (r <= x <= t.length - r and r <= y <= t.width - r):
            return False
        for px, py, pr in t.pockets.tolist():
            padded = pr + CLEARANCE
            if (x - px) * (x - px) + (y - py) * (y - py) <= padded * padded:
                return False
        return all((x - bx) * (x - bx) + (y - by) * (y - by) >= reach * reach for bx, by in balls)

    def _draw(self, n: int, box: tuple[float, float, float, float], placed: list) -> list:
        """``n`` balls one after another by rejection, draws in blocks as numpy's random."""
        reach = 2.0 * self.table.ball_radius + CLEARANCE
        balls, failures = list(placed), 0
        while len(balls) < len(placed) + n:
            block = self.rng.random((len(placed) + n - len(balls) + 2, 2)).tolist()
            for u, v in block:
                x = box[0] + u * (box[1] - box[0])
                y = box[2] + v * (box[3] - box[2])
                if self._free(x, y, balls, reach):
                    balls.append((x, y))
                    failures = 0
                    if len(balls) == len(placed) + n:
                        break
                else:
                    failures += 1
            assert failures < TRIES, "the reference does not model the grid fallback"
        return balls[len(placed) :]

    def _wpa_order(self) -> list[list[float]]:
        """The rack as the rules rack it, drawn after the cue ball (``rack_order="random"``).

        Spots in row order (apex first; the simulator's ``rack_spots``). 9-ball: the 1 on
        the apex (spot 0), the 9 in the centre (spot 4); 8-ball: the 8 in the third row's
        middle (spot 4), a solid (``integers(1, 8)``) and a stripe (``integers(9, 16)``) in
        the back corners 10 and 14, the solid's corner by ``integers(2)``; then the other
        balls onto the other spots in the order of ``permutation``.
        """
        assert self.rng is not None
        name = "nine" if self.scene == "nine_ball" else "eight"
        spots = rack_spots(self.table, name).tolist()
        pins = {1: 0, 9: 4} if name == "nine" else {8: 4}
        if name == "eight":
            solid, stripe = int(self.rng.integers(1, 8)), int(self.rng.integers(9, 16))
            corners = (10, 14) if int(self.rng.integers(2)) == 0 else (14, 10)
            pins[solid], pins[stripe] = corners
        free_spots = [k for k in range(self.n) if k not in pins.values()]
        order = self.rng.permutation(free_spots).tolist()
        free_balls = [b for b in range(1, self.n + 1) if b not in pins]
        spot_of = {**pins, **dict(zip(free_balls, order, strict=True))}
        return [spots[spot_of[b]] for b in range(1, self.n + 1)]

    def reset(self, seed: int | None = None) -> tuple[np.ndarray, dict]:
        if seed is not None or self.rng is None:
            self.rng = np.random.Generator(np.random.PCG64(np.random.SeedSequence(seed)))
        t, r = self.table, self.table.ball_radius
        if self.scene in ("nine_ball", "eight_ball"):
            rack = break_scene(t, "nine" if self.scene == "nine_ball" else "eight")[1:].tolist()
            cue = self._draw(1, (r, t.length / 4.0, r, t.width - r), [tuple(b) for b in rack])
            if self.rack_order == "random":  # the rack's spots are the same: only the order
                rack = self._wpa_order()
            self.pos = [list(cue[0])] + [list(b) for b in rack]
        else:
            self.pos = [
                list(b) for b in self._draw(self.n + 1, (r, t.length - r, r, t.width - r), [])
            ]
        self.on = [True] * (self.n + 1)
        self.shots = 0
        return self._obs(), {}

    # -- a shot ---------------------------------------------------------------------------

    def _nearest(self) -> tuple[int, float, float]:
        cx, cy = self.pos[0]
        best, best_j, base = math.inf, -1, 0.0
        for j in range(1, self.n + 1):
            if self.on[j]:
                dx, dy = self.pos[j][0] - cx, self.pos[j][1] - cy
                if dx * dx + dy * dy < best:
                    best, best_j, base = dx * dx + dy * dy, j, math.atan2(dy, dx)
        return best_j, math.sqrt(best), base

    def _potential(self) -> float:
        pockets = self.table.pockets.tolist()
        if not pockets:
            return 0.0
        total = 0.0
        for j in range(1, self.n + 1):
            if self.on[j]:
                x, y = self.pos[j]
                total += min(
                    math.sqrt((x - px) * (x - px) + (y - py) * (y - py)) for px, py, _ in pockets
                )
        return -total / math.hypot(self.table.length, self.table.width)

    def step(self, action: np.ndarray) -> tuple[np.ndarray, float, bool, bool, dict[str, Any]]:
        u, v = ((min(max(float(a), -1.0), 1.0) + 1.0) * 0.5 for a in action[:2])
        lo, hi = self.aim_range
        param = lo + u * (hi - lo)
        speed = self.speed_range[0] + v * (self.speed_range[1] - self.speed_range[0])
        angle = param
        if self.aim != "absolute":
            j, dist, base = self._nearest()
            if self.aim == "relative" or j < 0:
                angle = base + (param if self.aim == "relative" else 0.0)
            else:
                s = param * 2.0 * self.table.ball_radius / dist
                angle = base + math.asin(min(max(s, -1.0), 1.0))
        if self.noise is not None:
            angle = angle + self.noise[0] * float(self.rng.standard_normal())
            speed = max(0.0, speed + self.noise[1] * float(self.rng.standard_normal()))
        tip = (0.0, 0.0)
        if self.spin:
            tip = self._tip([min(max(float(c), -1.0), 1.0) * self.tip_limit for c in action[2:]])
            if self.noise is not None and len(self.noise) > 2 and self.noise[2] > 0.0:
                tip = self._tip(
                    [t + self.noise[2] * float(self.rng.standard_normal()) for t in tip]
                )
        phi_before = self._potential()
        rows = [j for j in range(self.n + 1) if self.on[j]]
        result = shoot(self.table, [self.pos[j] for j in rows], angle, speed, record=False, tip=tip)
        potted, scratch = [], False
        for row, j in enumerate(rows):
            self.pos[j] = result.positions[row].tolist()
            if result.pocketed[row] >= 0:
                self.on[j] = False
                if j == 0:
                    scratch = True
                else:
                    potted.append(j)
        first = -1
        if result.first_contact is not None:
            a, b = (rows[i] for i in result.first_contact)
            first = b if a == 0 else a
        phi_change = self._potential() - phi_before if self.weights[3] else 0.0
        if scratch:
            self.on[0] = True
            spot = (self.table.length / 4.0, self.table.width / 2.0)
            others = [tuple(self.pos[j]) for j in range(1, self.n + 1) if self.on[j]]
            if self._free(*spot, others, 2.0 * self.table.ball_radius + CLEARANCE):
                self.pos[0] = list(spot)
            else:
                occupied = np.array(self.on)
                occupied[0] = False
                self.pos[0] = free_spot(self.table, np.array(self.pos), occupied).tolist()
        w = self.weights
        reward = w[0] * len(potted) + w[1] * (1.0 if scratch else 0.0)
        reward = reward + w[2] * (1.0 if first < 0 else 0.0) + w[3] * phi_change
        self.shots += 1
        cleared = not any(self.on[1:])
        terminated = cleared or (self.end_on_miss and (not potted or scratch))
        truncated = self.shots >= self.limit
        info = {
            "potted": tuple(sorted(potted)), "scratch": scratch, "first_contact": first,
            "n_events": result.n_events, "hit_event_cap": result.hit_event_cap,
            "angle": _wrapped(angle), "speed": speed, "is_success": cleared,
            # each reward term, scaled: 0.0 (not -0.0) where it did not happen
            "reward_pot": w[0] * len(potted) if potted else 0.0,
            "reward_scratch": w[1] if scratch else 0.0,
            "reward_no_contact": w[2] if first < 0 else 0.0,
            "reward_shaping": w[3] * phi_change if w[3] else 0.0,
        }  # fmt: skip
        if self.spin:
            info["tip"] = tip
        return self._obs(), reward, terminated, truncated, info

    def _tip(self, tip: list[float]) -> tuple[float, float]:
        """The tip offset scaled back onto the miscue circle when outside it."""
        a, b = tip
        h = math.sqrt(a * a + b * b)
        if h > self.tip_limit:
            a, b = a * (self.tip_limit / h), b * (self.tip_limit / h)
        return a, b

    def _obs(self) -> np.ndarray:
        t = self.table
        out = []
        for (x, y), on in zip(self.pos, self.on, strict=True):
            if on:
                out += [min(max((2.0 * x - t.length) / t.length, -1.0), 1.0),
                        min(max((2.0 * y - t.width) / t.width, -1.0), 1.0), 1.0]  # fmt: skip
            else:
                out += [0.0, 0.0, 0.0]
        return np.array(out, dtype=np.float32)


def _wrapped(angle: float) -> float:
    """The reported direction: ``angle`` in ``[-pi, pi)`` (the shot is struck as aimed)."""
    if -math.pi <= angle < math.pi:
        return angle
    wrapped = (angle + math.pi) % (2.0 * math.pi) - math.pi
    return wrapped if wrapped < math.pi else -math.pi
