"""Run the compiled WPA rules (:mod:`pool_env.game.games.wpa.judge`) on one shot's outcome.

The tests judge each outcome twice, with the plain-Python reference
(:mod:`tests.wpa_reference`) and with the product's compiled rules, and compare; this file
converts between the reference's :class:`RackState` and the compiled rack-state row.
"""

from __future__ import annotations

from functools import cache
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from pool_env.game.config import GameConfig, make_config
from pool_env.game.games.wpa import rack_state as cw
from pool_env.game.games.wpa.first_contact import shooters_benefit
from pool_env.game.games.wpa.judge import (
    BALL_ON,
    FOUL,
    KEEPS,
    LOSS,
    PLAY,
    RESPOT,
    WINNER,
    judge_rules,
)
from pool_env.game.games.wpa.params import VARIANT as GAME_CODE
from pool_env.game.games.wpa.shots import (
    CALL_BALL,
    CALL_HAND_BACK,
    CALL_POCKET,
    CALL_PUSH_OUT,
    N_CALLS,
)
from pool_env.game.kernels.outcome import TERMINATED
from pool_env.sim.table import Table
from tests.wpa_reference import RackState

SCENES = {"nine": "nine_ball", "ten": "ten_ball", "eight": "eight_ball"}


@cache
def rules_config(
    game: str, players: int, table: Table, push_out: bool = True, end_on_foul: bool = False
) -> GameConfig:
    """A rules config on ``table`` (absolute aim, speeds 0-10 m/s for easy actions).

    ``push_out=False`` plays 9-ball without the push-out (``NineBallGame-v1``);
    ``end_on_foul`` is run-out mode.
    """
    return make_config(
        table=table, scene=SCENES[game], game=game, players=players, aim="absolute",
        speed_range=(0.0, 10.0), push_out=None if push_out else False, end_on_foul=end_on_foul,
    )  # fmt: skip


def rack_row(state: RackState) -> np.ndarray:
    """The compiled rack-state row of a reference state."""
    row = np.zeros(cw.N_RACK, dtype=np.int64)
    row[cw.SHOOTER] = state.shooter
    row[cw.IN_HAND], row[cw.BEHIND] = state.ball_in_hand, state.behind_head_string
    row[cw.BREAKING] = state.breaking
    row[cw.GROUP_0], row[cw.GROUP_1] = state.groups
    row[cw.FOULS_0], row[cw.FOULS_1] = state.fouls
    row[cw.WINNER] = -1 if state.winner is None else state.winner
    row[cw.PUSH_OUT], row[cw.OPTION] = state.push_out, state.option
    return row


def rules_option(state: RackState) -> dict[str, Any]:
    """``options["rules"]`` for a reference state (shooter 0's seat)."""
    names = ("open", "solids", "stripes")
    out: dict[str, Any] = {
        "break": state.breaking,
        "ball_in_hand": state.ball_in_hand,
        "behind_head_string": state.behind_head_string,
        "fouls": state.fouls,
        "shooter": state.shooter,
    }
    if state.game == "eight":
        out["groups"] = tuple(names[g] for g in state.groups)
    if state.push_out or state.option:
        out["push_out"], out["option"] = state.push_out, state.option
    return out


def compiled_judge(
    table: Table,
    state: RackState,
    positions: ArrayLike,
    numbers: ArrayLike,
    first_contact: tuple[int, int] | None,
    cushions: ArrayLike,
    pocketed: ArrayLike,
    order: ArrayLike,
    called: int | None,
    players: int = 2,
    simultaneous: tuple[int, ...] = (),
    crossed: bool = True,
    start: ArrayLike | None = None,
    called_ball: int | None = None,
    push_out: bool = False,
    hand_back: bool = False,
    end_on_foul: bool = False,
) -> tuple[dict[str, Any], RackState]:
    """Judge a shot with the compiled rules from a reference state.

    Args:
        table: The table.
        state: The rack before the shot.
        positions: ``(M, 2)`` final positions of the simulated rows.
        numbers: ``(M,)`` the ball number of each row (cue first).
        first_contact: Rows of the first ball-ball impact, or None.
        cushions: ``(M,)`` cushion impacts after the first contact per row.
        pocketed: ``(M,)`` pocket per row, -1 none.
        order: ``(M,)`` the order the rows dropped, -1 none.
        called: The called pocket (None: none).
        players: 1 or 2.
        simultaneous: Other balls (numbers) the cue ball met at its first contact's
            instant: the first ball is then read as the product reads it
            (:func:`pool_env.game.games.wpa.first_contact.shooters_benefit`).
        crossed: The cue ball crossed the head string before its first contact.
        start: ``(M, 2)`` positions before the shot (default: ``positions``); the kitchen
            rule reads the first ball's.
        called_ball: 10-ball: the called ball (None: none).
        push_out: A push-out declared (the rules read it only where the rack offers one).
        hand_back: The option used (the rules read it only where the rack offers it).
        end_on_foul: Run-out mode (the episode's end is ``terminated``).

    Returns:
        The verdict as a dict (``foul``, ``legal``, ``ball_on`` (None for -1), ``respot``
        (a tuple), ``winner``, ``loss``, ``keeps``, ``terminated``) and the rack after the
        shot.
    """
    config = rules_config(state.game, players, table, state.offers_push_out, end_on_foul)
    balls = np.asarray(numbers, dtype=np.int64)
    n = config.n_balls
    final = np.asarray(positions, dtype=np.float64).reshape(1, -1, 2)
    pos = np.zeros((1, n, 2))
    pos[0, balls] = final[0] if start is None else np.asarray(start, dtype=np.float64)
    on = np.array([state.on_table], dtype=np.bool_)
    rack = rack_row(state)[None].copy()
    first = np.array([first_contact if first_contact is not None else (-1, -1)], np.int64)
    if first_contact is not None and simultaneous:
        met = [int(balls[first_contact[1]]), *simultaneous]
        chosen = shooters_benefit(int(config.params[GAME_CODE]), rack[0], on[0], met)
        first[0, 1] = int(np.flatnonzero(balls == chosen)[0])
    _, flags, hits = judge_rules(
        config.params, table.pockets, np.zeros(1, np.intp), balls, pos, on,
        np.zeros(1, np.int64), rack, final, np.array([pocketed], np.int64), first,
        np.array([cushions], np.int64), np.array([order], np.int64),
        _calls(called, called_ball, push_out, hand_back), np.array([crossed]),
    )  # fmt: skip
    h = hits[0]
    verdict = {
        "foul": cw.FOUL_NAMES[h[FOUL]],
        "legal": h[FOUL] == 0,
        "ball_on": None if h[BALL_ON] < 0 else int(h[BALL_ON]),
        "respot": () if h[RESPOT] < 0 else (int(h[RESPOT]),),
        "winner": None if h[WINNER] < 0 else int(h[WINNER]),
        "loss": cw.LOSS_NAMES[h[LOSS]],
        "keeps": bool(h[KEEPS]),
        "push_out": h[PLAY] == cw.PUSHED_OUT,
        "handed_back": h[PLAY] == cw.HANDED_BACK,
        "terminated": bool(flags[0, TERMINATED]),
    }
    row = rack[0]
    after = RackState(
        game=state.game,
        on_table=tuple(bool(v) for v in on[0]),
        shooter=int(row[cw.SHOOTER]),
        breaking=bool(row[cw.BREAKING]),
        fouls=(int(row[cw.FOULS_0]), int(row[cw.FOULS_1])),
        groups=(int(row[cw.GROUP_0]), int(row[cw.GROUP_1])),
        ball_in_hand=bool(row[cw.IN_HAND]),
        behind_head_string=bool(row[cw.BEHIND]),
        winner=None if row[cw.WINNER] < 0 else int(row[cw.WINNER]),
        push_out=bool(row[cw.PUSH_OUT]),
        option=bool(row[cw.OPTION]),
        offers_push_out=state.offers_push_out,
    )
    return verdict, after


def _calls(pocket: int | None, ball: int | None, push_out: bool, hand_back: bool) -> np.ndarray:
    """The calls row the rules read, as the action's decoding leaves it (raw declarations)."""
    calls = np.full((1, N_CALLS), -1, dtype=np.int64)
    calls[0, CALL_POCKET] = -1 if pocket is None else pocket
    calls[0, CALL_BALL] = -1 if ball is None else ball
    calls[0, CALL_PUSH_OUT], calls[0, CALL_HAND_BACK] = push_out, hand_back
    return calls


def same_verdict(ref: Any, ref_after: RackState, got: dict[str, Any], after: RackState) -> None:
    """Assert the compiled verdict and rack equal the reference's."""
    want = {
        "foul": ref.foul, "legal": ref.legal, "ball_on": ref.ball_on, "respot": ref.respot,
        "winner": ref.winner, "loss": ref.loss, "continues": ref.shooter_continues,
        "push_out": ref.push_out, "handed_back": ref.handed_back,
    }  # fmt: skip
    have = {**got, "continues": got["keeps"] and got["winner"] is None}
    assert {k: have[k] for k in want} == want, (have, want)
    assert after == ref_after, (after, ref_after)
