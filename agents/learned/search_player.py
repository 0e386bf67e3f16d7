"""A WPA player (9-ball, 10-ball, 8-ball) that searches its shots within a time budget, two deep.

:class:`SearchPlayer` is :class:`agents.learned.lookahead.LookaheadAgent` given a clock and
a second ply. On every shot, within ``budget`` seconds of wall time:

1. **Candidates**: the lookahead's (the spin planner's pots by pocket, tip and speed, the
   ghost-ball agent's choice with its banks and kicks, and the grid of centre-ball hits
   across the ball on's face at four speeds: safeties, combinations, kisses).
2. **First ply**: each candidate is played ``samples`` times on the game's own step with
   the env's execution noise (common noise across candidates) and its outcomes valued by
   the leaf value (:mod:`agents.learned.leaf_value`); the ``finalists`` best go on.
3. **Second ply, anytime**: in rounds of ``round_samples`` more plays of every finalist,
   each outcome that keeps the table is valued by the best next shot searched from it
   (:func:`agents.learned.next_shots.best_next_values`: ghost-ball pots across the mouth,
   three speeds, three tips, ``next_samples`` noisy plays each, valued by the leaf value).
   Against an opponent, an outcome that hands over the table is worth one minus the
   opponent's best reply found the same way (the fast policy of the reply), or one minus
   the leaf value with ball in hand after a foul. After each round the finalists whose mean
   is below the leader's by more than ``prune_z`` standard errors drop out. Rounds go on
   until the budget is spent; the finalist of the best two-ply mean is played.
4. **Ball in hand**: placements are searched too: straight-in spots behind every pocket of
   the ball on and random free spots, each valued by its best shot searched
   (:func:`best_next_values`); the cue ball goes on the best, and the search above
   plays from there.
5. **The break**: a fixed, searched break (:mod:`agents.training.break_search`): where on
   the head string to place the cue ball, its aim off a full hit on the apex ball (on the
   foot spot: the 1 in 9-ball and 10-ball, any ball but the 8 in 8-ball), the speed and
   the tip; saved in the player's config (``models/search_player.yaml``).

**The games**: every step above follows the rules' legal balls, not "the lowest ball": the
candidates, the second ply's next shots and the ball-in-hand spots go on the shooter's legal
balls (8-ball: its group, every ball but the 8 on an open table, the 8 once the group is
cleared), and each simulated outcome is valued with the legal balls of whoever shoots next,
read from the rack row the rules leave (:mod:`agents.learned.legal_sets`: a shot on an open
table decides the groups). The calls are the rules': 10-ball calls the ball on and its
pocket on every shot, 8-ball the pocket (the 8's call: the 8 in another pocket loses). The
push-out and the option are the ghost-ball agent's (:mod:`agents.baselines.rule_play`).
The leaf values are per game (``models/search_player_ten.yaml``: 9-ball's, whose features
read the same in 10-ball; ``models/search_player_eight.yaml``: values fitted on 8-ball
layouts); the set network is 9-ball's only.

**The lookahead is its cheap setting** (``depth=1``): one ply, no clock, the
finalists played ``final_samples`` times more, the planner's ball-in-hand spot and break
arm; a lookahead file (``kind: lookahead``) loads as this player at depth 1
(:func:`agents.learned.player_file.load_lookahead_agent`).

The leaf value is the logistic layout value or the set network
(:mod:`agents.learned.set_value`), named in the player file
(:mod:`agents.learned.player_file`, which checks it). The numba kernels split large
batches over both cores (the step's own threshold).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, fields
from typing import Any

import numpy as np
from numpy.typing import NDArray

from agents.baselines.aiming import shot_to_action
from agents.baselines.rule_play import rule_action
from agents.baselines.spin_play import traced_pots
from agents.learned.layout_value import LayoutValue
from agents.learned.leaf_value import LeafValue, SetLeaf
from agents.learned.legal_sets import shooter_racks
from agents.learned.lookahead import LookaheadAgent
from agents.learned.next_shots import best_next_values
from agents.learned.rack_play import BREAK_ARMS
from agents.learned.shot_fans import AimWindows
from pool_env.game.checks import is_integer, parse_float
from pool_env.game.geometry import points_free
from pool_env.sim import Table
from pool_env.sim.layouts import foot_spot


@dataclass(frozen=True)
class SearchSettings:
    """The search's knobs (their reasons are in ``models/search_player.yaml``).

    Each is checked when the settings are made (:func:`check_setting`: counts are integers
    within their bounds, :data:`COUNTS`; numbers finite, each within its range); the
    break's spot and aim are checked against the table when a player takes them
    (:func:`check_break`).

    Attributes:
        budget: Wall-clock seconds per shot.
        samples: First-ply plays of every candidate.
        finalists: Candidates searched at the second ply.
        round_samples: Plays of every finalist per second-ply round.
        next_samples: Noisy plays of each next-shot candidate at the second ply.
        prune_z: A finalist drops out when its mean is this many standard errors below
            the leader's.
        min_rounds: Second-ply rounds played whatever the clock says (so that a slow
            first ply still gets a second).
        hand_spots: Random free spots tried with the cue ball in hand (beside the
            straight-in spots).
        hand_samples: Noisy plays of each candidate when valuing a spot.
        break_y: The break's cue ball, metres off the head spot along the head string.
        break_cut: The break's aim off a full hit on the 1 (radians, counter-clockwise).
        break_speed: The break's speed action in ``[-1, 1]`` (the break speed range).
        break_tip: The break's tip ``(side, vertical)`` in fractions of the tip limit.
        fans: Aims tried either side of every planned pot on the noiseless model, to aim
            it at the middle of its pot window (:mod:`agents.learned.shot_fans`; 0: the
            planned aims as they are).
        banks: Bank and kick pots kept among the candidates (the most forgiving first,
            one per pocket: :func:`~agents.baselines.spin_play.traced_pots`); 0: none
            beyond the ghost-ball agent's own choice.
        depth: 2, the search (the settings above); 1, the lookahead, its cheap setting:
            one ply, no clock, ``samples`` plays of every candidate and ``final_samples``
            more of the ``finalists`` best, the planner's ball-in-hand spot (``fans``,
            ``banks`` and ``safeties`` apply to the search only).
        pots: The spin planner's pots kept among the candidates, best by its score first.
        final_samples: Depth 1: the finalists' extra plays.
        break_arm: -1 breaks as ``break_y`` .. ``break_tip`` say (the searched break);
            ``k >= 0`` as the rack planner's arm ``k``
            (:data:`agents.learned.rack_play.BREAK_ARMS`: the head spot, a full hit).
        safeties: Keep the grid of centre-ball hits across the ball on (safeties,
            combinations, kisses) among the candidates; ``False`` plays pots only (the
            ablation of the safeties).

    Raises:
        ValueError: Naming the first setting that is not of its type or out of its range.
    """

    budget: float = 1.0
    samples: int = 8
    finalists: int = 5
    round_samples: int = 8
    next_samples: int = 4
    prune_z: float = 3.0
    min_rounds: int = 1
    hand_spots: int = 24
    hand_samples: int = 3
    break_y: float = 0.0
    break_cut: float = 0.0
    break_speed: float = 1.0
    break_tip: tuple[float, float] = (0.0, 0.0)
    fans: int = 0
    banks: int = 0
    safeties: bool = True
    depth: int = 2
    pots: int = 8
    final_samples: int = 24
    break_arm: int = -1

    def __post_init__(self) -> None:
        for name in SETTINGS:  # frozen: the checked values (a tuple for the tip) set back
            object.__setattr__(self, name, check_setting(name, getattr(self, name), name))


#: The config keys of :class:`SearchSettings`.
SETTINGS = tuple(f.name for f in fields(SearchSettings))
_SECOND = "second ply: finalists x round_samples x 90 x next_samples tables"
_HAND = "ball in hand: (18 + hand_spots) x 90 x hand_samples tables"
#: The counts among the settings: their least and greatest values, and why the greatest.
#: A shot plays batches of simulated tables, each about 5 KB of arrays (4.8 KB measured:
#: the model's state and the step's arrays); the greatest value of each count, the others
#: at their defaults, keeps a batch under about 60,000 tables (~0.3 GB, well under 1 GB).
#: The counts multiply: raising several together multiplies the batch. A next-shot search
#: plays at most 90 candidates per layout (:mod:`agents.learned.next_shots`); a shot has
#: about 45 candidates (100 taken as the most).
COUNTS: dict[str, tuple[int, int, str]] = {
    "samples": (1, 512, "first ply: ~100 candidates x samples tables"),
    "finalists": (1, 16, _SECOND),
    "round_samples": (1, 32, _SECOND),
    "next_samples": (1, 16, _SECOND),
    "min_rounds": (0, 100, "rounds played whatever the budget: a bound on time"),
    "hand_spots": (0, 200, _HAND),
    "hand_samples": (1, 16, _HAND),
    "banks": (0, 16, "first ply: ~45 candidates + banks, x samples tables"),
    "depth": (1, 2, "1: the lookahead, 2: the search"),
    "pots": (1, 32, "first ply: the planner's pots among ~45 candidates x samples tables"),
    "final_samples": (0, 512, "depth 1: finalists x final_samples tables"),
    "break_arm": (-1, len(BREAK_ARMS) - 1, "-1: the searched break; k: the planner's arm k"),
    "fans": (
        0,
        32,
        "aims either side of each pot, one noiseless play each: ~10 pots x (2 fans + 1) tables",
    ),
}
#: The numbers among the settings: whether a finite value is in range, and the range said.
#: The break's spot and aim are bounded by the table (:func:`check_break`).
NUMBERS: dict[str, tuple[Callable[[float], bool], str]] = {
    "budget": (lambda x: x > 0.0, "> 0 (seconds)"),
    "prune_z": (lambda x: x >= 0.0, ">= 0 (standard errors)"),
    "break_y": (lambda x: True, "(metres; the table bounds it)"),
    "break_cut": (lambda x: True, "(radians; the table bounds it)"),
    "break_speed": (lambda x: -1.0 <= x <= 1.0, "in [-1, 1]"),
}


def check_setting(name: str, value: object, label: str) -> int | float | bool | tuple[float, float]:
    """A setting's value of its type (an ``int``, a ``float`` or the tip's pair), checked.

    Args:
        name: The setting (:data:`SETTINGS`).
        value: Its value as given.
        label: What the message calls it (``"samples"``; a player file's
            ``"settings.samples"``).

    Raises:
        ValueError: Naming ``label``, its type and range, and ``value``: a count that is not
            an integer (``2.7``, ``True``) or out of its range (:data:`COUNTS`: a bound that
            keeps a shot's arrays well under 1 GB), a number that is not
            finite, a bool or a string, or out of range.
    """
    if name in COUNTS:
        least, most, why = COUNTS[name]
        plain = name in ("min_rounds", "depth", "break_arm")  # no batch of tables
        memory = "" if plain else ", ~5 KB each: a shot well under 1 GB"
        if not is_integer(value) or not least <= value <= most:  # type: ignore[operator]
            raise ValueError(
                f"{label} must be an integer in [{least}, {most}] ({why}{memory}), got {value!r}"
            )
        return int(value)  # type: ignore[arg-type]
    if name == "safeties":
        if not isinstance(value, bool):
            raise ValueError(f"{label} must be true or false, got {value!r}")
        return value
    if name == "break_tip":
        what = f"{label} must be two finite numbers (side, vertical) in [-1, 1], got {value!r}"
        if isinstance(value, str | bytes) or not isinstance(value, Sequence) or len(value) != 2:
            raise ValueError(what)
        try:
            side, vertical = (parse_float(label, v) for v in value)
        except ValueError:
            raise ValueError(what) from None
        if max(abs(side), abs(vertical)) > 1.0:
            raise ValueError(what)
        return side, vertical
    in_range, said = NUMBERS[name]
    try:
        number = parse_float(label, value)
    except ValueError:
        number = math.nan
    if not (math.isfinite(number) and in_range(number)):
        raise ValueError(f"{label} must be a finite number {said}, got {value!r}")
    return number


def break_bounds(table: Table, break_y: float) -> tuple[float, float]:
    """How far off the head spot the break may place the cue ball, and aim off a full hit.

    The cue ball's centre stays a radius off the side rails; from that spot the aim keeps
    the apex ball (on the foot spot) in the cue ball's path: its centre within two radii of
    the line.

    Returns:
        ``(y_max, cut_max)``: ``|break_y| <= y_max`` (m), ``|break_cut| <= cut_max`` (rad).
    """
    r = table.ball_radius
    spot = np.array([table.length / 4.0, table.width / 2.0 + break_y])
    distance = float(np.hypot(*(foot_spot(table) - spot)))
    return table.width / 2.0 - r, math.asin(min(2.0 * r / distance, 1.0))


def check_break(settings: SearchSettings, table: Table, prefix: str = "") -> None:
    """Refuse a break that leaves the table or misses the apex ball (:func:`break_bounds`).

    Args:
        settings: The settings.
        table: The table the player plays on.
        prefix: Put before the settings' names in the message (``"settings."``).

    Raises:
        ValueError: Naming ``break_y`` or ``break_cut``, the range on ``table`` and the value.
    """
    y_max, cut_max = break_bounds(table, settings.break_y)
    if abs(settings.break_y) > y_max:
        raise ValueError(
            f"{prefix}break_y must lie in [{-y_max:.4f}, {y_max:.4f}] m on this table (the "
            f"cue ball on the head string, on the cloth), got {settings.break_y!r}"
        )
    if abs(settings.break_cut) > cut_max:
        raise ValueError(
            f"{prefix}break_cut must lie in [{-cut_max:.4f}, {cut_max:.4f}] rad with break_y "
            f"{settings.break_y!r} on this table (the cue ball must meet the apex ball), got "
            f"{settings.break_cut!r}"
        )


#: The spin game ids of the games a search player plays.
GAME_IDS = {
    "nine": "pool_env/NineBallGame-v2",
    "ten": "pool_env/TenBallGame-v1",
    "eight": "pool_env/EightBallGame-v1",
}
#: Straight-in ball-in-hand spots kept with several legal balls: 9-ball's count (six
#: pockets x three distances behind the ball on).
STRAIGHT = 18


class SearchPlayer(LookaheadAgent):
    """The anytime two-ply search player (module doc).

    Args:
        env: A spin WPA game id (``pool_env/NineBallGame-v2``, ``TenBallGame-v1``,
            ``EightBallGame-v1``), wrapped or not.
        value: The logistic layout value (the first ply's leaves; and the second's unless
            ``leaf`` is given).
        objective: ``"runout"`` or ``"duel"``.
        settings: The search's knobs.
        leaf: The leaf value (``None``: the logistic's).
        seed: Seed of the noise samples and of the random spots.
        players: As :class:`~agents.baselines.game_agents.GameGhostBallAgent`.

    Raises:
        ValueError: On a game other than these, a set-network leaf off 9-ball, or a break
            that leaves the table or misses the apex ball (:func:`check_break`).
    """

    KIND = "search"
    GAMES = ("nine", "ten", "eight")

    def __init__(
        self,
        env: Any,
        value: LayoutValue,
        objective: str = "runout",
        settings: SearchSettings | None = None,
        leaf: LeafValue | None = None,
        seed: int = 0,
        players: int | None = None,
    ) -> None:
        s = settings or SearchSettings()
        config = env.unwrapped.config
        if config.game not in self.GAMES:
            ids = ", ".join(GAME_IDS[g] for g in self.GAMES)
            raise ValueError(
                f"{type(self).__name__} plays the spin WPA game ids ({ids}), got "
                f"game={config.game!r}"
            )
        lookahead = s.depth == 1
        super().__init__(
            env, value, objective, pots=s.pots, samples=s.samples, finalists=s.finalists,
            final_samples=s.final_samples if lookahead else 0,
            break_arm=s.break_arm if s.break_arm >= 0 else None, seed=seed, players=players,
        )  # fmt: skip
        if lookahead:  # what last_plan["kind"] says of a shot: the plies that chose it
            self.KIND = LookaheadAgent.KIND
        check_break(s, self.config.table)
        self.settings = s
        if isinstance(leaf, SetLeaf) and config.game != "nine":
            raise ValueError(
                f"the set network (SetLeaf) values 9-ball layouts only, not game="
                f"{config.game!r}: give the logistic layout value fitted for the game"
            )
        if leaf is not None:
            self.leaf = leaf
        self.spot_rng = np.random.default_rng(seed)
        #: The pot windows' fans, built for ``settings.fans`` when first needed.
        self.windows: AimWindows | None = None
        self._start = 0.0
        #: What the last decision did: candidates, rounds, plays, seconds.
        self.last_search: dict[str, Any] = {}

    # -- the clock and the plan ------------------------------------------------------------

    def _plan(
        self, obs: NDArray[np.floating], positions: NDArray[np.float64], on: NDArray[np.bool_]
    ) -> NDArray[np.float32]:
        self._start = time.perf_counter()
        self.last_search = {}
        action = super()._plan(obs, positions, on)
        if self.last_plan.get("kind") == "break" and self.settings.break_arm < 0:
            action = self.break_action(positions, on)
        self.last_search["seconds"] = time.perf_counter() - self._start
        return action

    def _left(self) -> float:
        """Seconds of the budget left."""
        return self.settings.budget - (time.perf_counter() - self._start)

    # -- the break -------------------------------------------------------------------------

    def break_action(
        self, positions: NDArray[np.float64], on: NDArray[np.bool_]
    ) -> NDArray[np.float64]:
        """The settings' break: the cue ball on the head string, aimed at the apex, speed, tip.

        The apex is the object ball nearest the foot spot (the 1 of a 9-ball or 10-ball
        rack; in 8-ball whichever ball the rack put there).
        """
        s, table = self.settings, self.config.table
        spot = np.array([table.length / 4.0, table.width / 2.0 + s.break_y])
        placed = positions.copy()
        placed[0] = spot
        balls = np.flatnonzero(on[1:]) + 1
        gaps = np.hypot(*(positions[balls] - foot_spot(table)).T)
        apex = int(balls[int(np.argmin(gaps))])
        d = placed[apex] - spot
        reference = np.zeros_like(on)
        reference[[0, apex]] = True
        angle = math.atan2(d[1], d[0]) + s.break_cut
        strike = shot_to_action(angle, 1.0, placed, reference, self.ghost.spec, tip=(0.0, 0.0))
        if strike is None:
            raise ValueError(f"the break's aim {angle:.4f} rad cannot be played in this aim mode")
        limit = float(self.ghost.spec.tip_limit or 1.0)
        part = np.array([strike[0], s.break_speed, *(np.asarray(s.break_tip) * limit)])
        self.last_plan = {"kind": "break", "spot": spot.tolist()}
        place = self._place_action(spot, True)
        return rule_action(self.config, part, place, ball=self._ball_on())

    # -- ball in hand ----------------------------------------------------------------------

    def _place(
        self,
        positions: NDArray[np.float64],
        on: NDArray[np.bool_],
        reference: NDArray[np.bool_],
        behind: bool,
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """The spot whose best searched shot is worth the most (module doc, item 4).

        At depth 1 (the lookahead), the planner's straight-in spot.
        """
        spots = self._spots(positions, on, behind) if self.settings.depth == 2 else []
        if not len(spots):
            return super()._place(positions, on, reference, behind)
        layouts = np.repeat(positions[None], len(spots), axis=0)
        layouts[:, 0] = spots
        flags = np.repeat(on[None], len(spots), axis=0)
        values = best_next_values(
            self.model, self.mouths, self.leaf, self.objective == "runout", layouts, flags,
            self._fouls, self.settings.hand_samples,
            np.broadcast_to(self._rack, (len(spots), self._rack.size)),
        )  # fmt: skip
        best = spots[int(np.argmax(values))]
        placed = positions.copy()
        placed[0] = best
        self.last_search["hand_spots"] = len(spots)
        return placed, self._place_action(best, behind)

    def _spots(
        self, positions: NDArray[np.float64], on: NDArray[np.bool_], behind: bool
    ) -> NDArray[np.float64]:
        """Free spots for the cue ball: straight-in behind each pocket of the legal balls, random.

        With several legal balls (8-ball) the straight-in spots of the :data:`STRAIGHT`
        closest ball-to-pocket pairs that are free are kept (the easier pots; and the
        batch stays 9-ball's size, :data:`COUNTS`).
        """
        table = self.config.table
        r = table.ball_radius
        others = positions[[j for j in range(1, on.shape[0]) if on[j]]]
        dists = np.array([0.15, 0.3, 0.5])
        straight_sets, reach = [], []
        for ball in self._legal(positions, on):
            target = positions[ball]
            away = target[None] - table.pockets[:, :2]
            length = np.maximum(np.hypot(away[:, 0], away[:, 1]), 1e-12)
            away /= length[:, None]
            spots = target[None, None] + (2.0 * r + dists[None, :, None]) * away[:, None]
            straight_sets.append(spots.reshape(-1, 2))
            reach.append(np.repeat(length, len(dists)))
        straight = np.vstack(straight_sets) if straight_sets else np.zeros((0, 2))
        x_high = table.length / 4.0 if behind else table.length
        low = np.array([r, r])
        high = np.array([x_high - r, table.width - r])
        scattered = self.spot_rng.uniform(low, high, size=(self.settings.hand_spots, 2))
        spots = np.vstack([straight, scattered])
        free = points_free(table, spots, others, behind)
        # The agent's own margin, wider than the rule's: no cue ball frozen to a ball.
        gaps = np.hypot(*(spots[:, None] - others[None]).transpose(2, 0, 1))
        free &= gaps.min(axis=1) >= 2.2 * r
        if len(straight_sets) > 1:  # several legal balls: the closest pairs' free spots
            lengths = np.concatenate(reach)
            usable = np.flatnonzero(free[: len(straight)])
            drop = usable[np.argsort(lengths[usable], kind="stable")[STRAIGHT:]]
            free[drop] = False
        return spots[free]

    # -- the shot --------------------------------------------------------------------------

    def _choose(
        self, positions: NDArray[np.float64], on: NDArray[np.bool_], reference: NDArray[np.bool_]
    ) -> tuple[int, NDArray[np.float32] | None]:
        """The finalist of the best two-ply mean (module doc, items 1-3).

        At depth 1 (the lookahead), the candidate of the best one-ply mean.
        """
        s = self.settings
        if s.depth == 1:
            return super()._choose(positions, on, reference)
        actions, pockets, kinds = self._candidates(positions, on, reference)
        for action, pocket in self._banks(positions, on, reference):
            actions.append(action)
            pockets.append(pocket)
            kinds.append("bank")
        if not s.safeties:
            keep = [k for k, kind in enumerate(kinds) if kind != "grid"]
            actions, pockets, kinds = ([x[k] for k in keep] for x in (actions, pockets, kinds))
        if not actions:
            self.last_values = None
            return -1, None
        acts = np.stack(actions)
        if s.fans:
            acts = self._centred(positions, on, reference, acts, kinds)
        first = self._values(positions, on, acts, s.samples)
        finalists = np.argsort(-first, kind="stable")[: s.finalists]
        total = np.zeros(len(finalists))
        squares = np.zeros(len(finalists))
        counts = np.zeros(len(finalists))
        alive = np.ones(len(finalists), dtype=np.bool_)
        rounds, round_time = 0, 0.0
        while alive.sum() > 1 and (rounds < s.min_rounds or self._left() > round_time):
            started = time.perf_counter()
            live = np.flatnonzero(alive)
            values = self._sample_values(
                positions, on, acts[finalists[live]], s.round_samples, self._searched_leaf, None
            )
            per = values.reshape(len(live), s.round_samples)
            total[live] += per.sum(axis=1)
            squares[live] += (per**2).sum(axis=1)
            counts[live] += s.round_samples
            rounds += 1
            mean = total[live] / counts[live]
            se = np.sqrt(np.maximum(squares[live] / counts[live] - mean**2, 1e-6) / counts[live])
            lead = int(np.argmax(mean))
            if rounds >= 2:  # one round's spread is too rough to prune on
                alive[live] = mean + s.prune_z * np.hypot(se, se[lead]) >= mean[lead]
            round_time = time.perf_counter() - started  # the next round costs about as much
        scores = np.where(counts > 0, total / np.maximum(counts, 1), -np.inf)
        if not np.isfinite(scores).any():
            scores = first[finalists]
        pick = int(finalists[int(np.argmax(scores))])
        values = np.full(len(actions), -np.inf)
        values[finalists] = scores
        self.last_values = values
        self.last_search.update(
            candidates=len(actions), rounds=rounds, plays=int(counts.sum()),
            value=float(scores.max()),
        )  # fmt: skip
        self._chosen = kinds[pick]
        strike = acts[pick, [0, 1, *self.config.tip_columns]]  # type: ignore[misc]
        return pockets[pick], strike.astype(np.float32)

    def _banks(
        self, positions: NDArray[np.float64], on: NDArray[np.bool_], reference: NDArray[np.bool_]
    ) -> list[tuple[NDArray[np.float64], int]]:
        """Up to ``settings.banks`` bank and kick pots, one per pocket, most forgiving first."""
        if not self.settings.banks:
            return []
        spec = self.ghost.spec
        lo, top = spec.speed_range
        targets = self._legal(positions, on)
        found: list[tuple[NDArray[np.float64], int]] = []
        pockets: set[int] = set()
        for pot in traced_pots(spec.table, self.ghost.mouths, positions, on, targets, top):
            if len(found) == self.settings.banks:
                break
            if pot.pocket in pockets or pot.speed < lo:
                continue
            strike = shot_to_action(pot.aim, pot.speed, positions, reference, spec)
            if strike is None:
                continue
            pockets.add(pot.pocket)
            call = rule_action(self.config, strike, pocket=pot.pocket, ball=self._ball_on())
            found.append((call, pot.pocket))
        self.last_search["banks"] = len(found)
        return found

    def _centred(
        self,
        positions: NDArray[np.float64],
        on: NDArray[np.bool_],
        reference: NDArray[np.bool_],
        acts: NDArray[np.float64],
        kinds: list[str],
    ) -> NDArray[np.float64]:
        """The planned pots (the planner's, the ghost-ball agent's, the banks) re-aimed."""
        if self.windows is None or self.windows.steps != self.settings.fans:
            self.windows = AimWindows(self.config, self.settings.fans)
        pots = np.flatnonzero([kind in ("pot", "ghost", "bank") for kind in kinds])
        if not pots.size:
            return acts
        out = acts.copy()
        out[pots], shifts = self.windows.centre(positions, on, reference, self._rack, acts[pots])
        self.last_search["re_aimed"] = int(np.count_nonzero(shifts))
        return out

    def _searched_leaf(
        self,
        positions: NDArray[np.float64],
        on_table: NDArray[np.bool_],
        in_hand: NDArray[np.bool_],
        fouls: NDArray[np.int64],
        targets: NDArray[np.int64] | None = None,
    ) -> NDArray[np.float64]:
        """A leaf value one shot deeper: the best next shot searched (ball in hand: the leaf).

        ``targets``: the shooter's legal balls (off 9-ball); its rack row is rebuilt from
        them (:func:`~agents.learned.legal_sets.shooter_racks`: 8-ball's groups).
        """
        if targets is None:
            out = self.leaf(positions, on_table, in_hand, fouls)
        else:
            out = self.leaf(positions, on_table, in_hand, fouls, targets)
        searched = ~np.asarray(in_hand, dtype=np.bool_)
        groups = {tuple(int(f) for f in row) for row in np.asarray(fouls)[searched]}
        runout = self.objective == "runout"
        for group in groups:
            rows = np.flatnonzero(searched & (np.asarray(fouls) == group).all(axis=1))
            racks = None
            if targets is not None:
                racks = shooter_racks(self.config.game, on_table[rows], targets[rows], group)
            out[rows] = best_next_values(
                self.model, self.mouths, self.leaf, runout, positions[rows], on_table[rows],
                group, self.settings.next_samples, racks,
            )  # fmt: skip
        return out
