"""A rotation player (9-ball, 10-ball) that looks one shot ahead and values what each shot leaves.

:class:`LookaheadAgent` plays the spin 9-ball ids (``pool_env/NineBallGame-v2``) and the
two-player front (:class:`pool_env.envs.multiagent.PoolDuelEnv`) from the observation alone. On
every shot it:

1. lists candidates: the spin planner's pots on the ball on (the ``pots`` best of
   :meth:`agents.learned.rack_play.RackAgent.candidates` by the planner's score), the ghost-ball
   agent's own choice (so its set always holds the baseline's shot, banks included), and
   a *grid* of centre-ball hits on the ball on, :data:`GRID_OFFSETS` across its face at
   :data:`GRID_SPEEDS`: not aimed at any pocket, they are what the simulation makes of
   them, safeties that leave the opponent nothing, combinations into other balls (the 9
   too), kisses;
2. plays each candidate ``samples`` times on the game's own step with the env's execution
   noise (:class:`agents.learned.game_model.GameModel`: the same decoding, physics and rules;
   common noise across candidates), then the ``finalists`` best ``final_samples`` times
   more;
3. values each outcome by who shoots next and what they face: a won rack is 1, a lost one
   0; a shot that keeps the table is worth :class:`agents.learned.layout_value.LayoutValue` of the
   layout it leaves (the chance that the shooter wins from there); a miss or a foul hands
   the table over and is worth one minus the opponent's chance from what it leaves (ball in
   hand after a foul); and plays the candidate of the highest mean.

In run-out mode (``objective="runout"``: the first miss or foul ends the rack, nobody else
shoots) a miss is worth 0 and a kept table the layout's value, a chance to run out.
The layout value is learned (:mod:`agents.training.fit_layout_value`), the rest is the model and
the rules. The break and ball-in-hand placement are :class:`agents.learned.rack_play.RackAgent`'s,
and so are the option and the push-out (:mod:`agents.baselines.rule_play`).

10-ball (``pool_env/TenBallGame-v1``): the same, every candidate calling the ball on and its
pocket, so that the model judges the calls as the rules do. The layout value is the one fitted
on 9-ball layouts (its features are the ball on's pot chances, the last ball, the balls left
and the fouls: they read the same in 10-ball, up to one more ball left), and a 10-ball miss
that pots a ball is valued as any miss (the opponent's option to hand it back is not modelled).
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from agents.baselines.ghost_ball import MIN_SIGMA
from agents.baselines.rule_play import PUSH_OFFSETS, face_angles, rule_action
from agents.learned.game_model import GameModel
from agents.learned.layout_value import LayoutValue, observed_rack
from agents.learned.leaf_value import LeafValue, LogisticLeaf, outcome_values
from agents.learned.legal_sets import observed_row
from agents.learned.rack_play import FEATURES, RackAgent
from pool_env.game.codec import encode_shots
from pool_env.game.games.wpa import rack_row
from pool_env.game.geometry import pocket_mouths

#: Where the cue ball's centre passes the ball on, in ball diameters across its face.
GRID_OFFSETS = PUSH_OFFSETS
#: Cue speeds (m/s) of the grid: from a touch that barely reaches a rail to a firm hit.
GRID_SPEEDS = (0.9, 1.5, 2.3, 3.3)
#: What the agent optimises: the two-player rack, or a run-out.
OBJECTIVES = ("duel", "runout")
#: The settings a saved model's config carries
#: (:func:`agents.learned.player_file.load_lookahead_agent`).
PLAY_SETTINGS = ("objective", "pots", "samples", "finalists", "final_samples", "break_arm")


class LookaheadAgent(RackAgent):
    """Candidates played out on the true model, chosen by the value of what they leave.

    Args:
        env: A spin rotation game id (``pool_env/NineBallGame-v2``, or ``TenBallGame-v1``
            with a value fitted on 9-ball: see the module doc), wrapped or not.
        value: The learned layout value (the shooter's chance to win, or to run out).
        objective: ``"duel"`` or ``"runout"`` (module doc).
        pots: The planner's pots kept as candidates, best by its score first.
        samples: Noisy plays of every candidate.
        finalists: Candidates played ``final_samples`` times more.
        final_samples: Their extra plays.
        break_arm: The break (:data:`agents.learned.rack_play.BREAK_ARMS`; ``None``: the planner's).
        seed: Seed of the noise samples.
        players: As :class:`~agents.baselines.game_agents.GameGhostBallAgent`.

    Raises:
        ValueError: On an env that is not a spin rotation id (9-ball, 10-ball) or a bad
            setting.
    """

    KIND = "lookahead"

    def __init__(
        self,
        env: Any,
        value: LayoutValue,
        objective: str = "duel",
        pots: int = 8,
        samples: int = 8,
        finalists: int = 6,
        final_samples: int = 24,
        break_arm: int | None = 15,
        seed: int = 0,
        players: int | None = None,
    ) -> None:
        super().__init__(env, break_arm=break_arm, seed=seed, players=players)
        if objective not in OBJECTIVES:
            raise ValueError(f"objective must be one of {OBJECTIVES}, got {objective!r}")
        if min(pots, samples, finalists) < 1 or final_samples < 0:
            raise ValueError("pots, samples and finalists must be >= 1, final_samples >= 0")
        self.layout_value = value
        self.objective = objective
        self.pots, self.samples = pots, samples
        self.finalists, self.final_samples = finalists, final_samples
        self.model = GameModel(self.config, seed)
        self.mouths = pocket_mouths(self.config.table)
        noise = self.config.noise
        self.sigma = max(float(noise[0]) if noise else 0.0, MIN_SIGMA)  # as the planner's
        #: What an outcome's layout is worth (:mod:`agents.learned.leaf_value`).
        self.leaf: LeafValue = LogisticLeaf(
            value, self.config.table, self.mouths, self.sigma, self.config.game
        )
        self._fouls = (0, 0)
        #: The rack row the model shoots from (the viewer in seat 0: its fouls, its group).
        self._rack = rack_row({})
        #: The last shot's candidates' mean values (``-inf``: not among the finalists).
        self.last_values: NDArray[np.float64] | None = None

    def _plan(
        self, obs: NDArray[np.floating], positions: NDArray[np.float64], on: NDArray[np.bool_]
    ) -> NDArray[np.float32]:
        self._fouls = observed_rack(obs, self.config)[2]
        self._rack = observed_row(obs, self.config)
        return super()._plan(obs, positions, on)

    def _choose(
        self, positions: NDArray[np.float64], on: NDArray[np.bool_], reference: NDArray[np.bool_]
    ) -> tuple[int, NDArray[np.float32] | None]:
        """The candidate whose outcomes are worth the most; ``None`` if none is playable."""
        actions, pockets, kinds = self._candidates(positions, on, reference)
        if not actions:
            self.last_values = None
            return -1, None
        acts = np.stack(actions)
        values = self._values(positions, on, acts, self.samples)
        order = np.argsort(-values, kind="stable")
        if self.final_samples and len(actions) > 1:
            best = order[: self.finalists]
            more = self._values(positions, on, acts[best], self.final_samples)
            total = self.samples + self.final_samples
            values[best] = (values[best] * self.samples + more * self.final_samples) / total
            values[order[self.finalists :]] = -np.inf  # too few samples to be chosen
        pick = int(np.argmax(values))
        self.last_values = values
        self._chosen = kinds[pick]  # last_plan["shot"]: "pot", "ghost" or "grid"
        strike = acts[pick, [0, 1, *self.config.tip_columns]]  # type: ignore[misc]
        return pockets[pick], strike.astype(np.float32)

    def _candidates(
        self, positions: NDArray[np.float64], on: NDArray[np.bool_], reference: NDArray[np.bool_]
    ) -> tuple[list[NDArray[np.float64]], list[int], list[str]]:
        """Full env actions (no placement: it is done), their called pockets and kinds.

        In 10-ball each calls the ball on and its pocket (a grid shot pocket 0: the model
        then judges what it pots as the rules do, a call missed).
        """
        actions: list[NDArray[np.float64]] = []
        pockets: list[int] = []
        kinds: list[str] = []
        ball = self._ball_on()

        def add(strike: NDArray[np.floating], pocket: int, kind: str) -> None:
            actions.append(rule_action(self.config, strike, pocket=pocket, ball=ball))
            pockets.append(pocket)
            kinds.append(kind)

        score = FEATURES.index("planner_score")
        found = sorted(self.candidates(positions, on, reference),
                       key=lambda c: -c.features[score])[: self.pots]  # fmt: skip
        for cand in found:
            add(cand.action, cand.pocket, "pot")
        pocket, ghost = super(RackAgent, self)._choose(positions, on, reference)
        if ghost is not None:
            add(ghost, pocket, "ghost")
        for strike in self._grid(positions, on, reference):
            add(strike, -1, "grid")
        return actions, pockets, kinds

    def _grid(
        self, positions: NDArray[np.float64], on: NDArray[np.bool_], reference: NDArray[np.bool_]
    ) -> list[NDArray[np.float64]]:
        """Centre-ball strikes at the ball on across its face (:data:`GRID_OFFSETS`)."""
        return list(self.grid_shots(positions, on, reference)[0])

    def grid_shots(
        self, positions: NDArray[np.float64], on: NDArray[np.bool_], reference: NDArray[np.bool_]
    ) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
        """The grid's playable strikes ``(G, 4)``, with each one's face offset and speed ``(G,)``.

        The offsets are :data:`GRID_OFFSETS` (ball diameters from a full hit), the speeds
        :data:`GRID_SPEEDS` (m/s); none when no legal ball is on or the cue ball touches it.
        The grid's ball is the legal ball nearest the cue ball: the ball on in 9-ball and
        10-ball; in 8-ball the nearest of the group (or the 8), the ball a soft safety or
        a kiss most surely reaches first (one ball keeps the grid's cost 9-ball's).
        """
        none = np.zeros((0, 4)), np.zeros(0), np.zeros(0)
        targets = self._legal(positions, on)
        if not targets:
            return none
        r = self.config.table.ball_radius
        gaps = [float(np.hypot(*(positions[j] - positions[0]))) for j in targets]
        angles = face_angles(positions, targets[int(np.argmin(gaps))], r, GRID_OFFSETS)
        if not angles:
            return none
        grid = [(a, f, s) for a, f in zip(angles, GRID_OFFSETS, strict=True) for s in GRID_SPEEDS]
        acts, ok = encode_shots(
            self.config, positions[None], reference[None], [[a for a, _, _ in grid]],
            [[s for _, _, s in grid]], np.zeros((1, len(grid), 2)),
        )  # fmt: skip
        keep = np.flatnonzero(ok[0])
        offsets = np.array([f for _, f, _ in grid])[keep]
        speeds = np.array([s for _, _, s in grid])[keep]
        return np.asarray(acts[0, keep], dtype=np.float64).reshape(-1, 4), offsets, speeds

    def _values(
        self,
        positions: NDArray[np.float64],
        on: NDArray[np.bool_],
        actions: NDArray[np.float64],
        samples: int,
    ) -> NDArray[np.float64]:
        """``(C,)`` each action's mean outcome value over ``samples`` noisy plays."""
        return self._sample_values(positions, on, actions, samples).reshape(-1, samples).mean(1)

    def _sample_values(
        self,
        positions: NDArray[np.float64],
        on: NDArray[np.bool_],
        actions: NDArray[np.float64],
        samples: int,
        leaf: LeafValue | None = None,
        parallel: bool | None = False,
    ) -> NDArray[np.float64]:
        """``(C * samples,)`` each noisy play's outcome value (action ``c``'s plays in a row).

        ``leaf``: what the outcomes' layouts are worth (the agent's own by default);
        ``parallel``: as :meth:`GameModel.play`.
        """
        acts = np.asarray(actions, dtype=np.float64)
        c = acts.shape[0]
        result, after, left, racks = self.model.play_racks(
            np.broadcast_to(positions, (c, *positions.shape)),
            np.broadcast_to(on, (c, *on.shape)),
            np.broadcast_to(self._rack, (c, self._rack.size)),
            acts, samples, parallel,
        )  # fmt: skip
        runout = self.objective == "runout"
        # 9-ball's leaves read the ball on, as fitted; off 9-ball they are told the legal balls.
        ruleset = None if self.config.game == "nine" else self.config.ruleset
        return outcome_values(
            leaf or self.leaf, runout, result, after, left, self._fouls, racks, ruleset
        )
