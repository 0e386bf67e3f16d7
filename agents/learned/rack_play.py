"""Learned rack play on the 9-ball spin ids: a value learned over the planner's candidate shots.

The ghost-ball planner (:class:`agents.baselines.game_agents.GameGhostBallAgent` on a spin
env) already works out, for the ball on, every pocket x cue tip x arrival speed as an exact
strike (throw, squirt, slide; :func:`agents.baselines.spin_play.plan_contact`), and ranks
them by a hand-made score (this pot's chance times the next one's). :class:`RackAgent`
keeps the planner's candidates and its rules (which ball is on, ball in hand, the break,
the fallback when nothing is planned) but lets a learned action value choose among them
(optionally among the planner's ``top_k`` best only): ``Q(candidate) = r + gamma V(next
shot)``, fitted on played racks (:mod:`agents.training.racks`). Its break is a learned
choice too: one of :data:`BREAK_ARMS` (speed in the 8 .. 12 m/s break range,
follow/stun/draw), the arm whose racks scored best (legal pots of the break plus ``gamma``
times the fitted value after it).

A candidate's features (:data:`FEATURES`) follow the rules' ball on: the planner only
plans shots on the legal ball, and the next-shot chance is taken for the ball on after it.
The model is a small MLP evaluated in numpy (:class:`ValueNet`), saved as ``.npz`` beside a
``<stem>_config.yaml`` (env id, env kwargs, ``gamma``, the break arm), which
:func:`load_rack_agent` reads; ``python -m agents.evaluate --agent models/rack_value.npz``
plays it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from agents.baselines.aiming import shot_to_action
from agents.baselines.game_agents import GameGhostBallAgent
from agents.baselines.rule_play import ROTATION
from agents.baselines.spin_play import ARRIVAL_SPEEDS, plan_contact, pot_chance

#: The clear shots (most forgiving first) whose tips and speeds become candidates.
CANDIDATE_SHOTS = 4
#: The names of a candidate's feature columns (:meth:`RackAgent.candidates`).
FEATURES = (
    "p_now",  # this pot's chance under the aim noise
    "p_next",  # the best next shot's chance from the cue ball's rest (1 if none is needed)
    "planner_score",  # the ghost planner's score: p_now (0.1 + 0.9 p_next)
    "tolerance_mrad_over_10",  # the aim error the pot forgives
    "cut_over_90deg",  # |cut angle| / 90 degrees
    "cue_distance_m",
    "object_travel_m",
    "strike_speed_over_top",
    "tip_side",  # fractions of the tip limit
    "tip_vertical",
    "arrival_speed_m_s",
    "last_ball",  # 1 if this pot wins the rack
    "balls_left_over_9",
)
#: Break choices: ``(speed action in [-1, 1] over 8 .. 12 m/s, vertical tip in fractions of
#: the tip limit)``; the cue ball on the head spot, a full hit on the 1 (the planner's).
BREAK_ARMS: tuple[tuple[float, float], ...] = tuple(
    (s, v) for s in (-1.0, -0.5, 0.0, 0.5, 1.0) for v in (-1.0, -0.5, 0.0, 0.5)
)


@dataclass(frozen=True)
class Candidate:
    """One planned strike: the env action (tip included), the strike it encodes, its features.

    Attributes:
        action: The strike's part of the env action, ``(aim, speed, tip side, tip
            vertical)``; the planner adds the placement and called pocket when it plays it.
        ball: The object ball (the ball on).
        pocket: The pocket it is planned into.
        aim: The cue's aim (rad from +x) the action encodes.
        speed: The cue ball's speed (m/s) the action encodes.
        tip: The tip offset ``(side, vertical)`` in fractions of ``R``.
        features: The :data:`FEATURES` row.
    """

    action: NDArray[np.float32]
    ball: int
    pocket: int
    aim: float
    speed: float
    tip: tuple[float, float]
    features: NDArray[np.float64]


class ValueNet:
    """A ReLU MLP in numpy: ``(B, F)`` features to ``(B,)`` values (inputs standardised).

    Args:
        weights: ``W0, b0, W1, b1, ...`` (``W_k`` of shape ``(in, out)``), the last layer
            of width 1, plus ``mean`` and ``scale`` of the inputs.
        n_features: The inputs' width (the rack agent's :data:`FEATURES`; the rack
            network's :data:`agents.learned.rack_net.FEATURES`).

    Raises:
        ValueError: If the weights do not take ``n_features`` inputs.
    """

    def __init__(
        self, weights: dict[str, NDArray[np.float64]], n_features: int = len(FEATURES)
    ) -> None:
        self.mean = np.asarray(weights["mean"], dtype=np.float64)
        self.scale = np.asarray(weights["scale"], dtype=np.float64)
        n = sum(1 for k in weights if k.startswith("W"))
        self.layers = [
            (np.asarray(weights[f"W{k}"], np.float64), np.asarray(weights[f"b{k}"], np.float64))
            for k in range(n)
        ]
        if self.mean.shape != (n_features,) or self.layers[0][0].shape[0] != n_features:
            raise ValueError(f"the net does not take the {n_features} candidate features")

    def __call__(self, features: NDArray[np.floating]) -> NDArray[np.float64]:
        """The values of ``(B, F)`` candidate features."""
        h = (np.asarray(features, dtype=np.float64) - self.mean) / self.scale
        for k, (w, b) in enumerate(self.layers):
            h = h @ w + b
            if k < len(self.layers) - 1:
                h = np.maximum(h, 0.0)
        return h[:, 0]

    def weights(self) -> dict[str, NDArray[np.float64]]:
        """The arrays to save (``np.savez``)."""
        out = {"mean": self.mean, "scale": self.scale}
        for k, (w, b) in enumerate(self.layers):
            out[f"W{k}"], out[f"b{k}"] = w, b
        return out


class RackAgent(GameGhostBallAgent):
    """9-ball (and 10-ball) on the spin ids: the planner's candidates, chosen by a learned value.

    Args:
        env: A spin rotation game id (``pool_env/NineBallGame-v2``; ``TenBallGame-v1``, where
            a value fitted on 9-ball sees its features off their training range: up to ten
            balls left), wrapped or not.
        value: The learned value; ``None`` ranks by the planner's own score (the trivial
            policy of this action space: its first row).
        break_arm: Index into :data:`BREAK_ARMS`; ``None`` keeps the planner's break (the
            top of the range, centre ball).
        explore: Chance of a uniformly random candidate instead of the best (data collection).
        seed: Seed of the exploration.
        top_k: Choose among the planner's ``top_k`` best candidates only (``None``: all):
            the value is surest where the data has it (the planner's picks).
        players: As :class:`~agents.baselines.game_agents.GameGhostBallAgent`.

    Raises:
        ValueError: On an env that is not a spin rotation game id, or a bad ``break_arm``.
    """

    KIND = "learned"
    #: The games it plays (a subclass that follows the legal balls may play more).
    GAMES: tuple[str, ...] = ROTATION

    def __init__(
        self,
        env: Any,
        value: ValueNet | None = None,
        break_arm: int | None = None,
        explore: float = 0.0,
        seed: int | None = 0,
        top_k: int | None = None,
        players: int | None = None,
    ) -> None:
        super().__init__(env, spin=True, players=players)
        if self.config.game not in self.GAMES or self.ghost.spec.tip_limit is None:
            kind = "rotation" if self.GAMES == ROTATION else "game"
            raise ValueError(
                f"{type(self).__name__} plays the spin {kind} ids ({', '.join(self.GAMES)}: "
                f"pool_env/NineBallGame-v2, ...), got game={self.config.game!r} on a "
                f"{'roll' if self.ghost.spec.tip_limit is None else 'spin'} table"
            )
        if break_arm is not None and not 0 <= break_arm < len(BREAK_ARMS):
            raise ValueError(f"break_arm must index BREAK_ARMS (0..{len(BREAK_ARMS) - 1})")
        if top_k is not None and top_k < 1:
            raise ValueError(f"top_k must be >= 1 or None, got {top_k}")
        self.value = value
        self.break_arm = break_arm
        self.top_k = top_k
        self.explore = float(explore)
        self.rng = np.random.default_rng(seed)
        #: The last shot's candidates' features and the index played (``None``: no candidate).
        self.last_candidates: tuple[NDArray[np.float64], int] | None = None
        #: The last shot's candidates themselves.
        self.last_found: list[Candidate] = []

    def _plan(
        self, obs: NDArray[np.floating], positions: NDArray[np.float64], on: NDArray[np.bool_]
    ) -> NDArray[np.float64]:
        action = super()._plan(obs, positions, on)
        if self.last_plan.get("kind") == "break" and self.break_arm is not None:
            speed, vertical = BREAK_ARMS[self.break_arm]
            side_column, vertical_column = self.config.tip_columns  # type: ignore[misc]
            action[1] = speed
            action[side_column], action[vertical_column] = 0.0, vertical
            self.last_plan["arm"] = self.break_arm
        return action

    def candidates(
        self, positions: NDArray[np.float64], on: NDArray[np.bool_], reference: NDArray[np.bool_]
    ) -> list[Candidate]:
        """Every planned strike on the legal ball whose cue ball stays out of the pockets.

        The :data:`CANDIDATE_SHOTS` most forgiving clear shots, each with the planner's
        tips and arrival speeds, as :meth:`GhostBallAgent.position_shot` plans them (but
        all kept, not only the best by its score).
        """
        ghost, table = self.ghost, self.config.table
        spec = ghost.spec
        lo, top = spec.speed_range
        limit = float(spec.tip_limit or 1.0)
        targets = self._legal(positions, on)
        shots, sigma, scorer = ghost.forgiving_shots(positions, on, targets, CANDIDATE_SHOTS)
        left = int(on[1:].sum())
        out: list[Candidate] = []
        for shot in shots:
            p_now = pot_chance(shot.tolerance, sigma)
            after = on.copy()
            after[shot.ball] = False
            nexts = ghost.next_targets(positions, after, shot.ball)
            for tip in ghost.tips:
                for arrival in ARRIVAL_SPEEDS:
                    contact = plan_contact(table, ghost.mouths, shot, positions, tip, arrival)
                    if contact is None or not lo <= contact.speed <= top:
                        continue
                    if contact.path.pocket >= 0:
                        continue  # the cue ball follows the object ball in
                    action = shot_to_action(
                        contact.aim, contact.speed, positions, reference, spec, tip=tip
                    )  # the env's codec: (aim, speed, tip side, tip vertical)
                    if action is None:
                        continue
                    p_next = scorer.next_chance(contact, positions, after, nexts) if nexts else 1.0
                    score = p_now * (0.1 + 0.9 * p_next) if nexts else p_now
                    tip_part = np.clip(np.array(tip) / limit, -1.0, 1.0)  # a feature
                    row = [
                        p_now, p_next, score, shot.tolerance * 100.0, abs(shot.cut) / (math.pi / 2),
                        shot.cue_distance, shot.travel, contact.speed / top, tip_part[0],
                        tip_part[1], arrival, float(not nexts), left / 9.0,
                    ]  # fmt: skip
                    out.append(
                        Candidate(
                            action, shot.ball, shot.pocket, contact.aim, contact.speed, tip,
                            np.array(row),
                        )
                    )  # fmt: skip
        return out

    def _choose(
        self, positions: NDArray[np.float64], on: NDArray[np.bool_], reference: NDArray[np.bool_]
    ) -> tuple[int, NDArray[np.float32] | None]:
        """The candidate of the highest learned value; the planner's choice if there is none."""
        found = self.last_found = self.candidates(positions, on, reference)
        if not found:
            self.last_candidates = None
            return super()._choose(positions, on, reference)
        features = np.stack([c.features for c in found])
        if self.explore > 0.0 and self.rng.random() < self.explore:
            pick = int(self.rng.integers(len(found)))
        elif self.value is None:
            pick = int(np.argmax(features[:, FEATURES.index("planner_score")]))
        else:
            values = self.value(features)
            if self.top_k is not None and len(found) > self.top_k:
                score = features[:, FEATURES.index("planner_score")]
                values[np.argsort(-score, kind="stable")[self.top_k :]] = -np.inf
            pick = int(np.argmax(values))
        self.last_candidates = (features, pick)
        self._chosen = None
        return found[pick].pocket, found[pick].action


def load_rack_agent(path: str | Path, env: Any, players: int | None = None) -> RackAgent:
    """The :class:`RackAgent` saved at ``path`` (``.npz``) with its ``<stem>_config.yaml``.

    ``players``: as :class:`RackAgent`.

    Raises:
        FileNotFoundError: If the model or its config is missing.
    """
    import yaml

    path = Path(path)
    config_path = path.with_name(f"{path.stem}_config.yaml")
    if not path.is_file() or not config_path.is_file():
        raise FileNotFoundError(f"no model {path} with its config {config_path.name}")
    config = yaml.safe_load(config_path.read_text()) or {}
    with np.load(path) as data:
        net = ValueNet({k: data[k] for k in data.files})
    return RackAgent(env, net, config.get("break_arm"), top_k=config.get("top_k"), players=players)


def rack_model_config(path: str | Path) -> dict[str, Any]:
    """The saved config of a rack model (``<stem>_config.yaml``), empty if none."""
    import yaml

    path = Path(path)
    config_path = path.with_name(f"{path.stem}_config.yaml")
    return (yaml.safe_load(config_path.read_text()) or {}) if config_path.is_file() else {}
