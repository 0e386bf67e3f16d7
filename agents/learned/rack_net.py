"""A 9-ball player whose shot is a network's pick among cheap candidates (no search).

:class:`RackNetPlayer` plays the spin 9-ball id (``pool_env/NineBallGame-v2``) in a few
milliseconds a shot. On every shot it:

1. lists candidates (:meth:`RackNetPlayer.candidate_table`): the next-shot pots of the
   search's deeper plies (:func:`agents.learned.next_shots.next_shot_table`: the two most
   forgiving clear pockets of the ball on, five aims across the mouth, three arrival
   speeds, stun/follow/draw; 90 at most) and the lookahead's grid of centre-ball hits
   across the ball on's face (:meth:`~agents.learned.lookahead.LookaheadAgent.grid_shots`:
   combinations, kisses, the 9 off the ball on);
2. plays each once on the game's own step **without noise** (one batch on the exact
   model): whether it keeps the table, fouls or wins, and the layout it leaves, valued by
   the search player's leaf value (the set network) and described by the logistic's
   layout features; and counts how many aims of its fan (the same pocket, speed and tip)
   also keep the table, and whether the pot still keeps it with the aim tilted by
   :data:`TILTS` sigmas of the aim noise either way (two more exact plays): a cheap
   robustness to the aim error;
3. describes each candidate by :data:`FEATURES` (its geometry: the pot chance under the
   aim noise, the cut, distances, speed, tip; the outcome above; the rack) and scores them
   with a small MLP in numpy (:class:`agents.learned.rack_play.ValueNet`); it plays the
   argmax among the candidates whose exact play keeps the table (:func:`eligible`; all
   of them when none does).

The network is distilled from the search player (:mod:`agents.training.distill_rack`):
fitted by cross-entropy to the search's first-ply values of the same candidates (each
played ``samples`` times with the env's noise and valued by the search's leaf), on layouts
the search player (and then the network itself) reached.

The break is the search player's searched break (its file's ``break_*`` settings); with
the cue ball in hand the player tries the search's straight-in spots behind every pocket
of the ball on (:meth:`~agents.learned.search_player.SearchPlayer._spots`, no random
ones) and places the cue ball where the network's best candidate scores highest. The
option and the push-out are the rules agents' (:mod:`agents.baselines.rule_play`). When
no candidate is playable it falls back on the ghost-ball agent's safe full hit.

A model is an ``.npz`` of the :class:`ValueNet` weights beside ``<stem>_config.yaml``
(``kind: rack_net``, ``player:`` the search player file whose break and leaf it takes,
relative to the model's folder); :func:`load_rack_net` reads both.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any, NamedTuple

import numpy as np
from numpy.typing import NDArray

from agents.baselines.rule_play import may_push, rule_action
from agents.learned.game_model import GameModel
from agents.learned.layout_value import aim_chances, layout_features, observed_rack
from agents.learned.leaf_value import SetLeaf
from agents.learned.next_shots import OFFSETS, TIPS, next_shot_table
from agents.learned.player_file import read_player_file
from agents.learned.rack_play import ValueNet, rack_model_config
from agents.learned.search_player import SearchPlayer
from pool_env import obs_layout, shot_constraints
from pool_env.game.codec import encode_shots
from pool_env.game.config import make_config
from pool_env.game.games.wpa import rack_row
from pool_env.game.games.wpa.judge import FOUL, KEEPS, WINNER
from pool_env.game.geometry import ANGLE, APPROACH, BALL_DIST, CUE_DIST, CUT, TOLERANCE

#: A candidate's feature columns (:meth:`RackNetPlayer.candidate_table`); the outcome
#: columns are the candidate's one play without noise.
FEATURES = (
    "pot",  # a next-shot pot (1) or a grid hit (0)
    "p_aim",  # the pot's chance under the aim noise (the ghost-ball tolerance; grid: 0)
    "tolerance_rad_x100",
    "cut_over_90deg",
    "cue_distance_m",
    "ball_distance_m",  # the object ball to its pocket
    "approach_cos",  # its path against the mouth's normal
    "mouth_offset",  # the aim's place across the mouth, in half-widths
    "pocket_rank",  # 0: the most forgiving pocket, 1: the second
    "arrival_m_s",  # the object ball's speed at the pocket
    "tip_vertical",  # follow (+) or draw (-), in fractions of the next shots' tip
    "speed_over_top",  # the cue ball's speed over the top of the range
    "grid_offset",  # a grid hit's place across the ball's face (diameters)
    "keeps",  # the exact play keeps the table (a legal pot, no foul)
    "fouls",
    "wins",  # the 9 made legally
    "potted",  # object balls made
    "fan_keeps",  # share of the fan's five aims whose exact play keeps the table
    "fan_left",  # the next aim on either side keeps it
    "fan_right",
    "tilt_keeps",  # share of the aims tilted by TILTS sigmas whose exact play keeps the table
    "tilt_inner",  # both aims tilted by the smaller TILTS keep it
    "tilt_outer",  # both aims tilted by the larger TILTS keep it
    "leave_value",  # the leaf value of the layout left (1 if won, 0 if the table is lost)
    "leave_p_best",  # the logistic's features of the layout left (0 if the table is lost)
    "leave_p_second",
    "leave_last_ball",
    "leave_balls_left_over_9",
    "balls_left_over_9",  # the rack now
    "last_ball_now",
)
#: Aim errors, in the aim noise's sigmas, at which each pot is also played without noise:
#: how far the aim may stray at the scale of the noise (the fan's aims are wider apart).
TILTS = (-2.0, -1.0, 1.0, 2.0)
#: The layout features of the leave kept (:data:`agents.learned.layout_value.LAYOUT_FEATURES`).
_LEAVE_COLUMNS = (1, 2, 3, 4)
#: The next shots' largest vertical tip, the scale of ``tip_vertical``.
_TIP_SCALE = max(abs(v) for _, v in TIPS)


class Candidates(NamedTuple):
    """One layout's candidates.

    Attributes:
        actions: ``(C, A)`` full env actions (no placement: the cue ball lies where it is).
        features: ``(C, F)`` their :data:`FEATURES`.
        kinds: ``(C,)`` ``"pot"`` or ``"grid"``.
    """

    actions: NDArray[np.float64]
    features: NDArray[np.float64]
    kinds: NDArray[np.str_]


def eligible(features: NDArray[np.float64]) -> NDArray[np.bool_]:
    """``(C,)`` the candidates the player may choose: those whose exact play keeps the table.

    In run-out mode a shot that loses the table ends the rack, so when any candidate keeps
    it (or wins) only those may be chosen; otherwise all may. The network was fitted
    on the same choice (:mod:`agents.training.distill_rack`): without it, a grid hit the
    network had few examples of was played where it fouls even without noise.
    """
    keeps = features[:, FEATURES.index("keeps")] > 0.5
    return keeps if keeps.any() else np.ones_like(keeps)


class RackNetPlayer(SearchPlayer):
    """The network's pick among cheap candidates (module doc).

    Args:
        env: ``pool_env/NineBallGame-v2``, wrapped or not.
        player_file: The search player file (``models/search_player_net.yaml``) whose
            break settings and leaf value the player takes; it must name ``set_value``.
        net: The candidate scorer; ``None`` scores by ``p_aim`` times ``leave_value``
            (the trivial policy of these features, and what collection may run with).
        samples: The noisy plays of each candidate when the teacher values them
            (:meth:`teacher_values`).
        seed: Seed of the noise samples.
        players: As :class:`~agents.baselines.game_agents.GameGhostBallAgent`.

    Raises:
        ValueError: On another game, a player file without ``set_value``, or a network
            that does not take :data:`FEATURES`.
    """

    KIND = "rack_net"
    #: 9-ball only: its leaf is the set network (9-ball's) and its candidates the ball on's.
    GAMES = ("nine",)

    def __init__(
        self,
        env: Any,
        player_file: str | Path,
        net: ValueNet | None = None,
        samples: int = 16,
        seed: int = 0,
        players: int | None = None,
    ) -> None:
        config = env.unwrapped.config
        file = read_player_file(player_file, config.table)
        if file.set_value is None:
            raise ValueError(f"player file {str(player_file)!r} names no set_value (the leaf)")
        settings = file.settings
        super().__init__(env, file.layout_value, "runout", settings, seed=seed, players=players)
        self.leaf = SetLeaf(file.set_value, self.config.table, self.mouths, self.sigma)
        if net is not None and net.mean.shape != (len(FEATURES),):
            raise ValueError(f"the network takes {net.mean.shape[0]} features, not the "
                             f"{len(FEATURES)} of agents.learned.rack_net.FEATURES")  # fmt: skip
        if samples < 1:
            raise ValueError(f"samples must be >= 1, got {samples}")
        self.net = net
        self.teacher_samples = samples
        if self.config.source is None:
            raise ValueError("RackNetPlayer needs an env made from a sectioned config")
        exact = make_config(self.config.source, players=self.config.players, noise=None)
        #: The game without noise: each candidate's one exact play.
        self.exact = GameModel(exact, seed)
        #: The last shot's candidates and the index played (``None``: no candidate).
        self.last_candidates: tuple[Candidates, int] | None = None

    # -- the candidates --------------------------------------------------------------------

    def candidate_table(
        self, positions: NDArray[np.float64], on: NDArray[np.bool_], reference: NDArray[np.bool_]
    ) -> Candidates:
        """The layout's candidates and their :data:`FEATURES` (module doc, items 1-2).

        ``self._targets`` and ``self._fouls`` must be the layout's (as :meth:`_plan` sets
        them); the cue ball lies at ``positions[0]``.
        """
        config, table = self.config, self.config.table
        shots = next_shot_table(config, self.mouths, positions[None], on[None])
        pots = np.flatnonzero(shots.ok[0])
        grid, grid_offsets, grid_speeds = self.grid_shots(positions, on, reference)
        ball = self._ball_on()
        grid_actions = [rule_action(config, g, pocket=-1, ball=ball) for g in grid]
        actions = np.concatenate(
            [shots.actions[0, pots], np.asarray(grid_actions).reshape(-1, config.action_size)]
        )
        n_pot, n = pots.size, actions.shape[0]
        f = np.zeros((n, len(FEATURES)))
        if not n:
            return Candidates(actions, f, np.zeros(0, dtype="<U4"))
        col = {name: k for k, name in enumerate(FEATURES)}
        top = config.speed_range[1]
        rows = shots.rows[0, pots]
        f[:n_pot, col["pot"]] = 1.0
        f[:n_pot, col["p_aim"]] = aim_chances(rows[:, TOLERANCE], self.sigma)
        f[:n_pot, col["tolerance_rad_x100"]] = rows[:, TOLERANCE] * 100.0
        f[:n_pot, col["cut_over_90deg"]] = np.abs(rows[:, CUT]) / (math.pi / 2)
        f[:n_pot, col["cue_distance_m"]] = rows[:, CUE_DIST]
        f[:n_pot, col["ball_distance_m"]] = rows[:, BALL_DIST]
        f[:n_pot, col["approach_cos"]] = rows[:, APPROACH]
        f[:n_pot, col["mouth_offset"]] = shots.offsets[pots]
        f[:n_pot, col["pocket_rank"]] = shots.ranks[pots]
        f[:n_pot, col["arrival_m_s"]] = shots.arrivals[pots]
        f[:n_pot, col["tip_vertical"]] = shots.tips[0, pots, 1] / _TIP_SCALE
        f[:n_pot, col["speed_over_top"]] = shots.speeds[0, pots] / top
        f[n_pot:, col["speed_over_top"]] = grid_speeds / top
        f[n_pot:, col["grid_offset"]] = grid_offsets
        # The exact plays, the pots' tilted aims after them: one batch, no noise.
        tilted, tilt_ok = [], []
        for k in TILTS:
            parts, playable = encode_shots(
                config, positions[None], reference[None], rows[None, :, ANGLE] + k * self.sigma,
                shots.speeds[:, pots], shots.tips[:, pots],
            )  # fmt: skip
            acts = actions[:n_pot].copy()
            acts[:, 0:2] = parts[0, :, 0:2]
            acts[:, list(config.tip_columns)] = parts[0, :, 2:4]  # type: ignore[arg-type]
            tilted.append(acts)
            tilt_ok.append(playable[0])
        rack = rack_row({"fouls": tuple(min(int(x), 2) for x in self._fouls)})
        result, after_all, left_all = self.exact.play(
            positions, on, rack, np.concatenate([actions, *tilted]), 1
        )
        after, left = after_all[:n], left_all[:n]
        all_keeps = (result.hits[:, FOUL] == 0) & (
            (result.hits[:, KEEPS] != 0) | (result.hits[:, WINNER] == 0)
        )
        tilt_keeps = np.stack(
            [all_keeps[n + j * n_pot : n + (j + 1) * n_pot] & tilt_ok[j] for j in range(len(TILTS))]
        )  # (len(TILTS), n_pot)
        hits = result.hits[:n]
        foul = hits[:, FOUL] != 0
        wins = hits[:, WINNER] == 0
        keeps = ~foul & (hits[:, KEEPS] != 0) & ~wins
        f[:, col["keeps"]] = keeps | wins
        f[:, col["fouls"]] = foul
        f[:, col["wins"]] = wins
        f[:, col["potted"]] = on[1:].sum() - left[:, 1:].sum(axis=1)
        fan = np.zeros(shots.ok.shape[1], dtype=np.float64)
        fan[pots] = keeps[:n_pot] | wins[:n_pot]
        fan = fan.reshape(len(OFFSETS), -1)  # (O, P*S*T): candidate m = o * (P*S*T) + rest
        left_keep = np.vstack([np.zeros((1, fan.shape[1])), fan[:-1]]).ravel()[pots]
        right_keep = np.vstack([fan[1:], np.zeros((1, fan.shape[1]))]).ravel()[pots]
        f[:n_pot, col["fan_keeps"]] = np.broadcast_to(fan.mean(axis=0), fan.shape).ravel()[pots]
        f[:n_pot, col["fan_left"]] = left_keep
        f[:n_pot, col["fan_right"]] = right_keep
        f[:n_pot, col["tilt_keeps"]] = tilt_keeps.mean(axis=0)
        f[:n_pot, col["tilt_inner"]] = tilt_keeps[[1, 2]].all(axis=0)
        f[:n_pot, col["tilt_outer"]] = tilt_keeps[[0, 3]].all(axis=0)
        for name in ("tilt_keeps", "tilt_inner", "tilt_outer"):  # a grid hit is not tilted
            f[n_pot:, col[name]] = f[n_pot:, col["keeps"]]
        f[:, col["leave_value"]] = wins.astype(np.float64)
        kept = np.flatnonzero(keeps)
        if kept.size:
            hand = np.zeros(kept.size, dtype=np.bool_)
            zero_fouls = np.zeros((kept.size, 2), dtype=np.int64)
            leave = (after[kept], left[kept], hand, zero_fouls)
            f[kept, col["leave_value"]] = self.leaf(*leave)
            feats = layout_features(table, self.mouths, *leave, self.sigma)
            start = col["leave_p_best"]
            f[kept, start : start + len(_LEAVE_COLUMNS)] = feats[:, list(_LEAVE_COLUMNS)]
        f[:, col["balls_left_over_9"]] = on[1:].sum() / 9.0
        f[:, col["last_ball_now"]] = float(on[1:].sum() == 1)
        kinds = np.array(["pot"] * n_pot + ["grid"] * (n - n_pot))
        return Candidates(actions, f, kinds)

    def scores(self, features: NDArray[np.float64]) -> NDArray[np.float64]:
        """``(C,)`` each candidate's score: the network's (the trivial rule without one).

        ``-inf`` for the candidates that are not :func:`eligible`.
        """
        if self.net is None:
            col = {name: k for k, name in enumerate(FEATURES)}
            out = (
                features[:, col["p_aim"]] * features[:, col["leave_value"]]
                + features[:, col["wins"]]
            )
        else:
            out = self.net(features)
        return np.where(eligible(features), out, -np.inf)

    def teacher_values(
        self, positions: NDArray[np.float64], on: NDArray[np.bool_], actions: NDArray[np.float64]
    ) -> NDArray[np.float64]:
        """``(C,)`` the search's first-ply value of each action (the distillation's target).

        Each action played :attr:`teacher_samples` times with the env's noise (common noise
        across actions) and its outcomes valued by the search's leaf, in run-out mode.
        """
        return self._values(positions, on, actions, self.teacher_samples)

    def observe(self, obs: NDArray[np.floating]) -> tuple[NDArray[np.float64], NDArray[np.bool_],
                                                           NDArray[np.bool_]] | None:  # fmt: skip
        """The layout to shoot from, ``(positions, on, reference)``, or ``None``.

        ``None`` on a break, with the cue ball in hand, or with the option or a push-out
        to decide (a push-out only against an opponent, as the rules agents decide it):
        the decisions the network does not make from the layout as it lies.
        Sets the rules' legal balls and the fouls as :meth:`_plan` does.
        """
        rules = shot_constraints(self.config, obs)
        pushing = rules.push_out and may_push(self.config, self.players)
        if rules.breaking or rules.ball_in_hand or rules.option or pushing:
            return None
        balls = obs_layout(self.config)["balls"]
        positions, on = self.ghost.source.layouts(np.ascontiguousarray(obs[None, balls]))[0]
        self._targets = list(rules.first_balls)
        self._fouls = observed_rack(obs, self.config)[2]
        reference = np.zeros_like(on)
        reference[0] = on[0]
        reference[self._targets] = on[self._targets]
        return positions, on, reference

    # -- the shot and the cue ball in hand -------------------------------------------------

    def _choose(
        self, positions: NDArray[np.float64], on: NDArray[np.bool_], reference: NDArray[np.bool_]
    ) -> tuple[int, NDArray[np.float32] | None]:
        """The candidate of the highest score; ``None`` when there is none."""
        found = self.candidate_table(positions, on, reference)
        if not len(found.actions):
            self.last_candidates = None
            return -1, None
        pick = int(np.argmax(self.scores(found.features)))
        self.last_candidates = (found, pick)
        self._chosen = str(found.kinds[pick])
        strike = found.actions[pick, [0, 1, *self.config.tip_columns]]  # type: ignore[misc]
        return -1, strike.astype(np.float32)

    def _place(
        self,
        positions: NDArray[np.float64],
        on: NDArray[np.bool_],
        reference: NDArray[np.bool_],
        behind: bool,
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """The straight-in spot where the network's best candidate scores highest."""
        spots = self._spots(positions, on, behind)
        best, best_score = None, -np.inf
        trial = positions.copy()
        for spot in spots:
            trial[0] = spot
            found = self.candidate_table(trial, on, reference)
            if len(found.actions):
                score = float(self.scores(found.features).max())
                if score > best_score:
                    best, best_score = spot, score
        if best is None:
            return super(SearchPlayer, self)._place(positions, on, reference, behind)
        placed = positions.copy()
        placed[0] = best
        return placed, self._place_action(best, behind)


def load_rack_net(path: str | Path, env: Any, players: int | None = None) -> RackNetPlayer:
    """The :class:`RackNetPlayer` saved at ``path`` (``.npz``) with its ``<stem>_config.yaml``.

    The config's ``player`` (the search player file) is read relative to the model's folder.

    Raises:
        FileNotFoundError: If the model or its config is missing.
        ValueError: If the config names no player file, names features other than
            :data:`FEATURES` (their order too), or as :class:`RackNetPlayer`.
    """
    path = Path(path)
    config = rack_model_config(path)
    if not path.is_file() or not config:
        raise FileNotFoundError(f"no model {path} with its config {path.stem}_config.yaml")
    if not isinstance(config.get("player"), str):
        raise ValueError(f"{path.stem}_config.yaml must name the search player file (player:)")
    named = config.get("features")
    if named is not None and list(named) != list(FEATURES):
        raise ValueError(
            f"{path.stem}_config.yaml: the network was fitted on other features "
            f"({len(named)} named) than agents.learned.rack_net.FEATURES ({len(FEATURES)})"
        )
    with np.load(path) as data:
        net = ValueNet({k: data[k] for k in data.files}, n_features=len(FEATURES))
    return RackNetPlayer(env, path.parent / config["player"], net, players=players)
