"""The rules on played racks: every step of random two-player racks judged again by the reference.

The property test of ``tests/game/test_games.py`` judges hand-built outcomes; here the
outcomes are the simulator's. Two players play random actions (the option column drawn
too, so push-outs and hand-backs happen) through :class:`pool_env.envs.multiagent.PoolDuelEnv`
on the roll table with execution noise. For each step the executed shot (``info["angle"]``,
``info["speed"]``, the placement :func:`pool_env.decode_action` reads) is shot again with
:func:`pool_env.shoot`, recorded, its outcome read by the plain-Python reference
(:func:`tests.wpa_reference.outcome_of`, simultaneous hits and the head string from the
trajectory) and judged (:func:`tests.wpa_reference.judge`): the env's ``info`` verdict and
rack after the step must be the reference's. ``HYPOTHESIS_PROFILE=deep`` plays 200 times as
many steps (the scale of :func:`tests.profiles.examples`): 34,000 a game, 102,000 in all.
"""

from __future__ import annotations

import numpy as np
import pytest

from pool_env import decode_action, shoot
from pool_env.envs.multiagent import PoolDuelEnv
from tests.profiles import examples
from tests.wpa_reference import GROUPS_BY_NAME, RackState, judge, outcome_of

SPEEDS = (0.45, 4.5)


def _state(duel: PoolDuelEnv) -> RackState:
    """The reference's rack state of the duel's table."""
    rack = duel.rack
    on = tuple(bool(v) for v in duel._state.on_table[0])
    return RackState(
        game=duel.config.game, on_table=(True, *on[1:]), shooter=rack["shooter"],
        breaking=rack["break"], fouls=rack["fouls"],
        groups=tuple(GROUPS_BY_NAME[g] for g in rack["groups"]),  # type: ignore[arg-type]
        ball_in_hand=rack["ball_in_hand"], behind_head_string=rack["behind_head_string"],
        push_out=rack["push_out"], option=rack["option"],
    )  # fmt: skip


def play_and_judge(game: str, steps: int, seed: int) -> dict[str, int]:
    """Play ``steps`` random steps of ``game`` racks and check each against the reference.

    Returns:
        Counts of what was played: steps, racks, push-outs, hand-backs, fouls, pots.
    """
    # The roll table: the reference replays each shot with shoot(angle, speed), no tip.
    duel = PoolDuelEnv(game, noise=(0.003, 0.05), model="roll")
    config, table = duel.config, duel.config.table
    head_x = table.length / 4.0
    rng = np.random.default_rng(seed)
    counts = dict.fromkeys(("steps", "racks", "push_outs", "hand_backs", "fouls", "pots"), 0)
    duel.reset(seed=seed)
    while counts["steps"] < steps:
        if any(duel.terminations.values()) or any(duel.truncations.values()):
            counts["racks"] += 1
            duel.reset(seed=int(rng.integers(2**31)))
            continue
        state, before = _state(duel), duel.positions
        # float32 as the env takes it: a break is chaotic, 1e-8 m of placement changes it
        action = rng.uniform(-1.0, 1.0, config.action_size).astype(np.float32)
        shot = decode_action(config, action, before, duel._state.on_table[0], duel.rack)
        agent = duel.agent_selection
        duel.step(action)
        info = duel.infos[agent]
        counts["steps"] += 1
        if info.get("handed_back"):
            verdict, after = judge(state, None, hand_back=True)  # type: ignore[arg-type]
            counts["hand_backs"] += 1
        else:
            layout = before.copy()
            if shot.cue is not None:
                layout[0] = shot.cue
            numbers = [b for b in range(config.n_balls) if state.on_table[b]]
            result = shoot(table, layout[numbers], info["angle"], info["speed"])
            outcome = outcome_of(result, numbers, head_x)
            called_ball = shot.ball if config.game == "ten" else None
            verdict, after = judge(state, outcome, shot.pocket, called_ball, shot.push_out)
            assert info["potted"] == tuple(sorted(outcome.potted)), (info, outcome)
        winner = None if info["winner"] is None else int(info["winner"][-1])
        got = (info["foul"], info["loss"], winner, info.get("push_out", False),
               info.get("handed_back", False))  # fmt: skip
        want = (verdict.foul, verdict.loss, verdict.winner, verdict.push_out,
                verdict.handed_back)  # fmt: skip
        assert got == want, (game, counts["steps"], state, got, want)
        if verdict.winner is None:
            assert _state(duel) == after, (game, counts["steps"], state, _state(duel), after)
        counts["push_outs"] += int(verdict.push_out)
        counts["fouls"] += int(verdict.foul is not None)
        counts["pots"] += len(info["potted"])
    return counts


@pytest.mark.parametrize("game", ["nine", "ten", "eight"])
def test_played_racks_are_judged_as_the_reference_judges_them(game: str) -> None:
    counts = play_and_judge(game, examples(170), seed={"nine": 1, "ten": 2, "eight": 3}[game])
    print(game, counts)  # the deep run's tallies (pytest -s)
    assert counts["racks"] >= 1 and counts["fouls"] >= 1 and counts["pots"] >= 1
    if game != "eight":
        assert counts["push_outs"] >= 1 and counts["hand_backs"] >= 1
