"""The game ids under the 9-ball, 10-ball and 8-ball rules, through the environment.

A table of rule cases plays each constructed layout through ``gym.make(id)``:
``reset(options={"positions", "on_table", "rules"})`` then one ``step``, and checks the
``info`` verdict, the reward, the episode end and the rack after the shot. The layouts and
shots are those of ``tests/game/test_wpa.py`` (which asserts their physical premises on the
same table); a property test checks the compiled rules against the plain-Python reference
on random outcomes.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Any

import gymnasium as gym
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import pool_env  # noqa: F401  (registers the ids)
from pool_env import decode_action, free_spot, shot_constraints
from pool_env.envs.multiagent import PoolDuelEnv
from pool_env.game.scenes import CLEARANCE
from pool_env.sim.layouts import break_scene, foot_spot
from tests.game.test_wpa import (
    TABLE,
    TOWARD_CORNER,
    R,
    _graze_into_corner,
    diag,
    parked,
    straight_in,
)
from tests.profiles import examples
from tests.rules_harness import compiled_judge, same_verdict
from tests.wpa_reference import (
    N_BALLS,
    OPEN,
    SOLIDS,
    STRIPES,
    RackState,
    ShotOutcome,
    judge,
    run_out_ends,
)

IDS = {
    "nine": "pool_env/NineBallGameRoll-v2",
    "ten": "pool_env/TenBallGameRoll-v1",
    "eight": "pool_env/EightBallGameRoll-v1",
}
W = TABLE.width
MID = W / 2
# Absolute aim and 0-10 m/s for every shot, the break included: action = (angle / pi,
# speed / 5 - 1, ...).
KWARGS = {
    "aim": "absolute",
    "speed_range": (0.0, 10.0),
    "break_speed_range": (0.0, 10.0),
    "table": {"pockets": "circles", "e_cushion": 0.85},
}


def make(game: str, **kwargs: Any) -> gym.Env:
    return gym.make(IDS[game], **{**KWARGS, **kwargs})


def action(angle: float, speed: float, place=(0.0, 0.0), pocket: float = -1.0) -> np.ndarray:
    """The rules' first five components; :func:`fit` adds a game's own (option off)."""
    return np.array([angle / math.pi, speed / 5.0 - 1.0, *place, pocket], dtype=np.float64)


def fit(env: Any, act: np.ndarray) -> np.ndarray:
    """``act`` (rows of five components) padded to the env's action with -1.

    The option off (no push-out, no hand-back), 10-ball's ball 1 called.
    """
    width = env.unwrapped.config.action_size
    pad = np.full((*act.shape[:-1], width - act.shape[-1]), -1.0)
    return np.concatenate([act, pad], axis=-1)


def layout(game: str, balls: dict[int, tuple[float, float]]) -> dict[str, Any]:
    n = N_BALLS[game]
    pos = np.zeros((n, 2))
    on = np.zeros(n, dtype=bool)
    for b, p in balls.items():
        pos[b], on[b] = p, True
    return {"positions": pos, "on_table": on}


def play(game: str, balls: dict, angle: float, speed: float, rules: dict | None = None,
         pocket: float = -1.0, place=(0.0, 0.0), **kwargs: Any):  # fmt: skip
    env = make(game, **kwargs)
    env.reset(seed=0, options={**layout(game, balls), "rules": rules or {}})
    obs, reward, terminated, truncated, info = env.step(
        fit(env, action(angle, speed, place, pocket))
    )
    return env, obs, reward, terminated, truncated, info


def rack_balls(game: str) -> dict[int, tuple[float, float]]:
    return {k: tuple(p) for k, p in enumerate(break_scene(TABLE, game))}


def break_angle(game: str) -> float:
    pos = break_scene(TABLE, game)
    d = pos[1] - pos[0]
    return math.atan2(d[1], d[0])


SOLID_STRIPE = {"groups": ("solids", "stripes")}
NINE_MISS = {0: (0.9, MID), 1: parked(0), 9: parked(1)}  # straight up the table: no contact
SOFT = {0: (0.8, MID), 1: (1.0, MID), 9: parked(3)}  # the 1 straight ahead, mid-table
EIGHT_EARLY = {0: diag(0.55), 3: diag(0.4), 8: diag(0.25), 5: parked(0), 11: parked(1)}
FOUL_EIGHT = {0: diag(0.2 + 2 * R), 8: diag(0.095), 11: parked(1)}
ON_EIGHT = {**straight_in(8), 11: parked(1)}

# (name, game, balls, angle, speed, rules option, pocket action, expected info, reward,
# terminated). Expected info: only the keys given are checked.
CASES: list[tuple] = [
    ("nine-legal-pot", "nine", {**straight_in(1), 2: parked(0), 9: parked(1)}, TOWARD_CORNER,
     1.5, None, -1.0, {"foul": None, "legal": True, "ball_on": 1, "potted": (1,),
                       "winner": -1}, 1.0, False),
    ("nine-wrong-ball", "nine", {**straight_in(2), 1: parked(0), 9: parked(1)}, TOWARD_CORNER,
     1.5, None, -1.0, {"foul": "wrong_ball_first", "legal": False, "potted": (2,)}, -1.0,
     False),
    ("nine-no-contact", "nine", NINE_MISS, math.pi / 2, 0.3, None, -1.0,
     {"foul": "no_contact", "first_contact": -1}, -1.0, False),
    ("nine-no-rail", "nine", SOFT, 0.0, 0.4, None, -1.0,
     {"foul": "no_rail", "first_contact": 1}, -1.0, False),
    ("nine-rail-legal", "nine", SOFT, 0.0, 1.0, None, -1.0,
     {"foul": None, "legal": True, "potted": ()}, 0.0, False),
    ("nine-rail-first-then-ball", "nine", {0: (1.0, 0.3), 1: (1.0, 0.75), 9: parked(3)},
     -math.pi / 2, 0.55, None, -1.0, {"foul": "no_rail"}, -1.0, False),
    ("nine-scratch-after-contact", "nine", {**_graze_into_corner(1), 9: parked(1)},
     TOWARD_CORNER, 1.5, None, -1.0, {"foul": "scratch", "scratch": True,
                                      "first_contact": 1}, -1.0, False),
    ("nine-scratch-no-contact", "nine", {0: diag(0.4), 1: parked(0), 9: parked(1)},
     TOWARD_CORNER, 1.0, None, -1.0, {"foul": "scratch", "first_contact": -1}, -1.0, False),
    ("nine-combination-wins", "nine", {0: diag(0.55), 1: diag(0.4), 9: diag(0.25),
                                       3: parked(0)}, TOWARD_CORNER, 2.0, None, -1.0,
     {"foul": None, "winner": 0, "potted": (9,), "is_success": True}, 2.0, True),
    ("nine-ball-on-nine-wins", "nine", straight_in(9), TOWARD_CORNER, 1.5, None, -1.0,
     {"ball_on": 9, "winner": 0, "is_success": True}, 2.0, True),
    ("nine-combination-keeps-table", "nine", {0: diag(0.55), 1: diag(0.4), 4: diag(0.25),
                                              9: parked(0)}, TOWARD_CORNER, 2.0, None, -1.0,
     {"foul": None, "potted": (4,), "winner": -1}, 1.0, False),
    ("nine-nine-on-foul-respotted", "nine", {**straight_in(9), 1: parked(0)}, TOWARD_CORNER,
     1.5, None, -1.0, {"foul": "wrong_ball_first", "potted": (9,), "winner": -1}, -1.0,
     False),
    ("nine-nine-with-scratch-respotted", "nine", {0: diag(0.2 + 2 * R), 9: diag(0.095)},
     TOWARD_CORNER, 6.0, None, -1.0, {"foul": "scratch", "winner": -1}, -1.0, False),
    ("nine-third-foul-loses", "nine", NINE_MISS, math.pi / 2, 0.3, {"fouls": (2, 0)}, -1.0,
     {"foul": "no_contact", "loss": "three_fouls", "winner": 1, "is_success": False}, -2.0,
     True),
    ("nine-second-foul-does-not", "nine", NINE_MISS, math.pi / 2, 0.3, {"fouls": (1, 0)},
     -1.0, {"foul": "no_contact", "loss": None, "winner": -1}, -1.0, False),
    ("nine-break-hard-legal", "nine", rack_balls("nine"), break_angle("nine"), 9.0,
     {"break": True}, -1.0, {"foul": None, "legal": True, "first_contact": 1}, None, None),
    ("nine-break-soft-illegal", "nine", rack_balls("nine"), break_angle("nine"), 0.8,
     {"break": True}, -1.0, {"foul": "illegal_break", "potted": ()}, -1.0, False),
    ("eight-break-legal-open", "eight", rack_balls("eight"), break_angle("eight"), 8.0,
     {"break": True}, -1.0, {"foul": None, "legal": True}, None, None),
    ("eight-on-break-respotted", "eight",
     {**straight_in(8), **{b: parked(b) for b in range(1, 16) if b != 8}}, TOWARD_CORNER, 1.5,
     {"break": True}, -1.0, {"foul": None, "potted": (8,), "winner": -1}, 0.0, False),
    ("eight-solids-assigned", "eight", {**straight_in(3), 8: parked(0), 5: parked(1),
                                        10: parked(2)}, TOWARD_CORNER, 1.5, None, -1.0,
     {"foul": None, "potted": (3,), "ball_on": -1}, 1.0, False),
    ("eight-stripes-assigned", "eight", {**straight_in(12), 8: parked(0), 5: parked(1),
                                         10: parked(2)}, TOWARD_CORNER, 1.5, None, -1.0,
     {"foul": None, "potted": (12,)}, 1.0, False),
    ("eight-open-table-eight-first", "eight", {0: (0.8, MID), 8: (1.0, MID), 3: parked(0),
                                               11: parked(1)}, 0.0, 1.0, None, -1.0,
     {"foul": "wrong_ball_first", "first_contact": 8}, -1.0, False),
    ("eight-opponents-group-first", "eight", {**straight_in(12), 3: parked(0), 8: parked(1)},
     TOWARD_CORNER, 1.5, SOLID_STRIPE, -1.0, {"foul": "wrong_ball_first"}, -1.0, False),
    ("eight-carom-opponents-ball", "eight", {0: diag(0.55), 3: diag(0.4), 10: diag(0.25),
                                             8: parked(0), 11: parked(1)}, TOWARD_CORNER,
     2.0, SOLID_STRIPE, -1.0, {"foul": None, "potted": (10,)}, 1.0, False),
    ("eight-early-loses", "eight", EIGHT_EARLY, TOWARD_CORNER, 2.0, SOLID_STRIPE, -1.0,
     {"foul": None, "loss": "eight_early", "winner": 1}, -1.0, True),
    ("eight-called-pocket-wins", "eight", ON_EIGHT, TOWARD_CORNER, 1.5, SOLID_STRIPE, -1.0,
     {"foul": None, "ball_on": 8, "winner": 0, "is_success": True}, 1.0, True),
    ("eight-wrong-pocket-loses", "eight", ON_EIGHT, TOWARD_CORNER, 1.5, SOLID_STRIPE, 1.0,
     {"loss": "eight_wrong_pocket", "winner": 1}, -1.0, True),
    ("eight-with-scratch-loses", "eight", FOUL_EIGHT, TOWARD_CORNER, 6.0, SOLID_STRIPE, -1.0,
     {"foul": "scratch", "loss": "eight_on_foul", "winner": 1}, -2.0, True),
    # 10-ball: fit() calls ball 1; pocket -1.0 calls pocket 0 (the corner it drops in).
    ("ten-call-made", "ten", {**straight_in(1), 2: parked(0), 10: parked(1)}, TOWARD_CORNER,
     1.5, None, -1.0, {"foul": None, "turn_over": False, "potted": (1,)}, 1.0, False),
    ("ten-wrong-pocket", "ten", {**straight_in(1), 2: parked(0), 10: parked(1)}, TOWARD_CORNER,
     1.5, None, 1.0, {"foul": None, "turn_over": True, "potted": (1,)}, 0.0, False),
    ("ten-wrong-ball-first", "ten", {**straight_in(2), 1: parked(0), 10: parked(1)},
     TOWARD_CORNER, 1.5, None, -1.0, {"foul": "wrong_ball_first", "potted": (2,)}, -1.0, False),
    ("eight-group-cleared", "eight", {**straight_in(7), 8: parked(0), 11: parked(1)},
     TOWARD_CORNER, 1.5, SOLID_STRIPE, -1.0, {"foul": None, "ball_on": -1, "potted": (7,)},
     1.0, False),
]  # fmt: skip


@pytest.mark.parametrize("case", CASES, ids=[c[0] for c in CASES])
def test_rule_cases_through_the_env(case: tuple) -> None:
    name, game, balls, angle, speed, rules, pocket, want, reward, terminated = case
    env, obs, got_reward, got_terminated, truncated, info = play(
        game, balls, angle, speed, rules, pocket
    )
    assert {k: info[k] for k in want} == want, f"{name}: {info}"
    assert info["legal"] == (info["foul"] is None)
    if reward is not None:
        assert got_reward == reward
    if terminated is not None:
        assert got_terminated == terminated and not truncated
    rack = env.unwrapped.rack
    assert rack["ball_in_hand"] == (info["foul"] is not None)
    assert rack["shooter"] == 0 and not rack["break"]  # one player: never the turn passes
    assert rack["winner"] == info["winner"]
    assert env.observation_space.contains(obs)


def test_the_nine_potted_on_a_foul_is_back_on_the_foot_spot() -> None:
    env, obs, *_, info = play("nine", {**straight_in(9), 1: parked(0)}, TOWARD_CORNER, 1.5)
    assert info["potted"] == (9,) and info["foul"] == "wrong_ball_first"
    raw = env.unwrapped
    assert raw.on_table[9]
    np.testing.assert_array_equal(raw.positions[9], foot_spot(TABLE))
    assert obs[3 * 9 + 2] == 1.0


def test_group_assignment_and_the_ball_on_are_in_the_rack_and_the_observation() -> None:
    balls = {**straight_in(3), 8: parked(0), 5: parked(1), 10: parked(2)}
    env, obs, *_ = play("eight", balls, TOWARD_CORNER, 1.5)
    assert env.unwrapped.rack["groups"] == ("solids", "stripes")
    n = 16
    legal = obs[3 * n : 3 * n + 15]
    assert legal.tolist() == [1.0 if b == 5 else 0.0 for b in range(1, 16)]  # the 3 is down
    flags = obs[4 * n - 1 :]
    assert flags.tolist() == [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0]  # group assigned: not open
    env, obs, *_ = play("eight", {**straight_in(7), 8: parked(0), 11: parked(1)},
                        TOWARD_CORNER, 1.5, SOLID_STRIPE)  # fmt: skip
    assert obs[3 * n : 3 * n + 15].tolist() == [1.0 if b == 8 else 0.0 for b in range(1, 16)]


def test_a_foul_gives_ball_in_hand_placed_by_the_action() -> None:
    env = make("nine")
    env.reset(seed=0, options={**layout("nine", NINE_MISS), "rules": {"ball_in_hand": True}})
    x, y = 0.6, 0.4
    u = (x - R) / (TABLE.length - 2 * R) * 2 - 1
    v = (y - R) / (W - 2 * R) * 2 - 1
    *_, info = env.step(fit(env, action(0.0, 0.0, (u, v))))  # speed 0: the cue ball stays put
    np.testing.assert_allclose(env.unwrapped.positions[0], [x, y], rtol=0, atol=1e-12)
    assert info["foul"] == "no_contact"


def test_ball_in_hand_on_an_occupied_spot_goes_to_the_nearest_free_point() -> None:
    balls = {0: (0.3, 0.3), 1: (1.0, 0.6), 9: parked(1)}
    env = make("nine")
    env.reset(seed=0, options={**layout("nine", balls), "rules": {"ball_in_hand": True}})
    target = np.array([1.0 + 0.01, 0.6])  # just right of the 1
    u = (target[0] - R) / (TABLE.length - 2 * R) * 2 - 1
    v = (target[1] - R) / (W - 2 * R) * 2 - 1
    env.step(fit(env, action(0.0, 0.0, (u, v))))
    got = env.unwrapped.positions[0]
    # the 1's circle of radius 2R + clearance, on the line from its centre to the target
    np.testing.assert_allclose(got, [1.0 + 2 * R + CLEARANCE, 0.6], rtol=0, atol=1e-9)
    others = env.unwrapped.on_table.copy()
    others[0] = False
    want = free_spot(env.unwrapped.config.table, env.unwrapped.positions, others, target)
    np.testing.assert_array_equal(got, want)  # the one placement search, deterministic


def test_an_eight_ball_break_scratch_puts_the_ball_in_hand_behind_the_head_string() -> None:
    balls = rack_balls("eight")
    balls[0] = (TABLE.length - 0.4, 0.3)
    corner = TABLE.pockets[2, :2]
    angle = math.atan2(corner[1] - 0.3, corner[0] - balls[0][0])
    env, obs, reward, *_, info = play("eight", balls, angle, 1.5, {"break": True})
    assert info["foul"] == "scratch" and reward == -1.0
    rack = env.unwrapped.rack
    assert rack["ball_in_hand"] and rack["behind_head_string"]
    assert obs[4 * 16 - 1 : 4 * 16 + 1].tolist() == [1.0, 1.0]
    # the placement maps onto the kitchen: +1 is the head string
    env.step(fit(env, action(0.0, 0.0, (1.0, 0.0))))
    np.testing.assert_allclose(env.unwrapped.positions[0], [TABLE.length / 4, MID], atol=1e-12)


EIGHT_ON_BREAK = {**straight_in(8), **{b: parked(b) for b in range(1, 16) if b != 8}}


def test_the_eight_on_a_legal_break_is_respotted_and_the_breaker_continues() -> None:
    # WPA 8-ball 3.3(e): re-spot the 8 and continue (the rules always take that choice).
    # In run-out mode the episode goes on; in a duel the breaker stays at the table.
    env, _, reward, terminated, _, info = play(
        "eight", EIGHT_ON_BREAK, TOWARD_CORNER, 1.5, {"break": True}, end_on_foul=True
    )
    assert info["foul"] is None and info["potted"] == (8,) and info["winner"] == -1
    assert not info["turn_over"] and not terminated and reward == 0.0
    np.testing.assert_array_equal(env.unwrapped.positions[8], foot_spot(TABLE))
    rack = env.unwrapped.rack
    assert not rack["ball_in_hand"] and not rack["break"] and rack["groups"] == ("open", "open")
    duel = PoolDuelEnv("eight", aim="absolute", speed_range=(0.0, 10.0),
                       break_speed_range=(0.0, 10.0), table=KWARGS["table"])  # fmt: skip
    duel.reset(seed=0, options={**layout("eight", EIGHT_ON_BREAK), "rules": {"break": True}})
    duel.step(fit(duel, action(TOWARD_CORNER, 1.5)).astype(np.float32))
    assert duel.infos["player_0"]["potted"] == (8,) and duel.agent_selection == "player_0"


def test_run_out_mode_ends_at_the_first_foul_or_missed_turn() -> None:
    *_, terminated, _, info = play("nine", SOFT, 0.0, 1.0, end_on_foul=True)
    assert info["legal"] and info["potted"] == () and terminated  # legal, but the turn ends
    *_, terminated, _, info = play("nine", NINE_MISS, math.pi / 2, 0.3, end_on_foul=True)
    assert info["foul"] == "no_contact" and terminated
    balls = {**straight_in(1), 2: parked(0), 9: parked(1)}
    *_, terminated, _, info = play("nine", balls, TOWARD_CORNER, 1.5, end_on_foul=True)
    assert info["legal"] and info["potted"] == (1,) and not terminated  # the run goes on


def test_the_break_of_a_racked_episode_uses_the_break_speed_range() -> None:
    env = gym.make(IDS["nine"])
    env.reset(seed=3)
    assert env.unwrapped.rack["break"] and env.unwrapped.rack["behind_head_string"]
    *_, info = env.step(fit(env, np.array([0.0, -1.0, 0.0, 0.0, 0.0])))
    assert info["speed"] == 8.0  # break_speed_range (8, 12), action -1
    *_, info = env.step(fit(env, np.array([0.0, -1.0, 0.0, 0.0, 0.0])))
    assert info["speed"] == 0.45  # after the break: speed_range


def test_bad_rule_options_and_arguments_raise() -> None:
    env = make("eight")
    balls = layout("eight", ON_EIGHT)
    for rules, match in [
        ({"groups": ("solids", "solids")}, "groups"),
        ({"fouls": (3, 0)}, "fouls"),
        ({"shooter": 1}, "shooter"),
        ({"behind_head_string": True}, "needs ball_in_hand"),
        ({"push_out": True}, "game='eight' has no push-out"),
        ({"option": True}, "game='eight' has no push-out"),
        ({"jump": True}, "unknown"),
        ({"break": 1}, "bool"),
    ]:
        with pytest.raises(ValueError, match=match):
            env.reset(options={**balls, "rules": rules})
    with pytest.raises(ValueError, match="rules"):
        gym.make("pool_env/NineBallRoll-v1").reset(options={**layout("nine", SOFT), "rules": {}})
    with pytest.raises(ValueError, match="9 object balls"):
        gym.make("pool_env/PoolRoll-v1", game="nine")
    with pytest.raises(ValueError, match="end_on_foul"):
        gym.make("pool_env/PoolRoll-v1", end_on_foul=True)
    with pytest.raises(ValueError, match="players"):
        gym.make_vec(IDS["nine"], 2, vectorization_mode="vector_entry_point", players=2)
    env = make("nine")
    env.reset(seed=0)
    with pytest.raises(ValueError, match=r"shape \(6,\)"):
        env.step(np.zeros(2))


# --- the compiled rules against the reference on random outcomes ------------------------


@st.composite
def outcomes(draw: st.DrawFn) -> tuple:
    game = draw(st.sampled_from(["nine", "ten", "eight"]))
    n = N_BALLS[game]
    on = [True] + [draw(st.booleans()) for _ in range(1, n)]
    if not any(on[1:]):
        on[draw(st.integers(1, n - 1))] = True
    numbers = [b for b in range(n) if on[b]]
    m = len(numbers)
    groups = draw(st.sampled_from([(OPEN, OPEN), (SOLIDS, STRIPES), (STRIPES, SOLIDS)]))
    if game != "eight":
        groups = (OPEN, OPEN)
    in_hand = draw(st.booleans())
    breaking = draw(st.booleans())
    # The push-out and the option (9-ball, 10-ball): the shot after the break, no ball in hand.
    offer = "none"
    # push_out=False plays 9-ball without them (NineBallGame-v1)
    offers = game == "ten" or (game == "nine" and draw(st.booleans()))
    if offers and not breaking and not in_hand:
        offer = draw(st.sampled_from(["none", "push_out", "option"]))
    state = RackState(
        game=game, on_table=tuple(on), shooter=draw(st.integers(0, 1)),
        breaking=breaking, fouls=(draw(st.integers(0, 2)), draw(st.integers(0, 2))),
        groups=groups, ball_in_hand=in_hand, behind_head_string=in_hand and draw(st.booleans()),
        push_out=offer == "push_out", option=offer == "option",
        offers_push_out=offers or game == "eight",
    )  # fmt: skip
    first_row = draw(st.integers(-1, m - 1))
    first = None if first_row <= 0 else (0, first_row)
    # Balls met at the first contact's instant, and whether the cue ball crossed the head
    # string first; rows 1-3 lie behind the head string (x = 0.3 + 0.1 row < L / 4).
    others = [r for r in range(1, m) if r != first_row]
    rows = draw(st.lists(st.sampled_from(others), unique=True, max_size=2)) if others else []
    simultaneous = () if first is None else tuple(numbers[r] for r in rows)
    crossed = draw(st.booleans())
    dropped = draw(st.lists(st.integers(0, m - 1), unique=True, max_size=m))
    money = {"nine": 9, "ten": 10, "eight": 8}[game]
    if on[money] and numbers.index(money) not in dropped and draw(st.booleans()):
        dropped.append(numbers.index(money))  # the ball that decides the rack, more often
    pocketed = [-1] * m
    order = [-1] * m
    for k, row in enumerate(dropped):
        pocketed[row] = draw(st.integers(0, 5))
        order[row] = k
    cushions = [draw(st.integers(0, 2)) for _ in range(m)]
    if first is None:
        cushions = [0] * m  # nothing counts before the first contact
    called = draw(st.none() | st.integers(0, 5))
    # 10-ball's call: often a ball that dropped, so that calls are made as often as missed.
    potted_balls = [numbers[r] for r in dropped if numbers[r] != 0]
    ball_choices = st.integers(1, n - 1) | st.none()
    if potted_balls:
        ball_choices = ball_choices | st.sampled_from(potted_balls)
    called_ball = draw(ball_choices) if game == "ten" else None
    if called_ball is not None and called_ball in potted_balls and draw(st.booleans()):
        called = pocketed[numbers.index(called_ball)]  # the called pocket, made
    declared = draw(st.booleans())  # a push-out or the option, where offered (else ignored)
    calls = {"called_ball": called_ball, "push_out": declared, "hand_back": declared}
    return (state, numbers, first, cushions, pocketed, order, called, simultaneous, crossed,
            calls)  # fmt: skip


@settings(max_examples=examples(600), deadline=None)
@given(outcomes())
def test_compiled_rules_equal_the_reference_on_random_outcomes(case: tuple) -> None:
    state, numbers, first, cushions, pocketed, order, called, simultaneous, crossed, calls = case
    nb = np.array(numbers)
    hit = np.full(len(numbers), -1)
    if first is not None:
        hit[0] = first[1]
    positions = [(0.3 + 0.1 * k, 0.3) for k in range(len(numbers))]
    shot = ShotOutcome.from_arrays(hit, cushions, pocketed, order, nb)
    met = () if first is None else (numbers[first[1]], *simultaneous)
    kitchen = tuple(b for b in met if positions[numbers.index(b)][0] < TABLE.length / 4)
    shot = replace(shot, simultaneous=simultaneous, kitchen=kitchen, crossed_head_string=crossed)
    verdict, after = judge(state, shot, called, **calls)
    extra = {"simultaneous": simultaneous, "crossed": crossed, **calls}
    got, got_after = compiled_judge(
        TABLE, state, positions, numbers, first, cushions, pocketed, order, called, **extra
    )
    same_verdict(verdict, after, got, got_after)
    if state.option:
        return  # one player never has the option (the reference plays two)
    one, one_after = compiled_judge(
        TABLE,
        state,
        positions,
        numbers,
        first,
        cushions,
        pocketed,
        order,
        called,
        players=1,
        end_on_foul=True,
        **extra,
    )  # one player: the same verdict, the shooter kept, never the option
    assert {k: one[k] for k in ("foul", "winner", "loss", "push_out")} == {
        k: got[k] for k in ("foul", "winner", "loss", "push_out")
    }
    assert one_after.shooter == state.shooter and not one_after.option
    assert one["terminated"] == run_out_ends(verdict)  # run-out mode ends as the reference


def _eight_state(on: set[int], groups: tuple[int, int]) -> RackState:
    """An 8-ball rack after the break, player 0 to shoot, with the balls ``on`` the table."""
    return RackState(
        game="eight", on_table=tuple(b == 0 or b in on for b in range(16)), shooter=0,
        breaking=False, fouls=(0, 0), groups=groups, ball_in_hand=False,
        behind_head_string=False,
    )  # fmt: skip


# Rare outcomes that the random property test above reaches only by luck (three mutants
# of the rules survived a run when its draws changed): each stated with its verdict.
# Rows: the cue ball, then the balls in ``numbers``; ``drops`` maps a row to
# (pocket, drop order).
RARE_OUTCOMES = [
    # On the 8, the 8 dropped in the called pocket, but a stripe was hit first: the 8 on a
    # foul loses (WPA 8-ball: pocketing the 8 on a foul), whichever pocket was called.
    (
        "eight on a foul loses",
        {8, 9},
        (SOLIDS, STRIPES),
        [0, 8, 9],
        2,
        {1: (2, 0)},
        2,
        {"foul": "wrong_ball_first", "winner": 1, "loss": "eight_on_foul"},
        None,
    ),
    # Open table, a solid dropped before a stripe: the shooter takes the solids.
    (
        "open table takes the first ball's group",
        {3, 8, 12},
        (OPEN, OPEN),
        [0, 3, 8, 12],
        1,
        {1: (0, 0), 3: (5, 1)},
        None,
        {"foul": None, "winner": None, "loss": None},
        (SOLIDS, STRIPES),
    ),
    # The same, the stripe first: the drop order decides, not the ball numbers.
    (
        "drop order, not ball number",
        {3, 8, 12},
        (OPEN, OPEN),
        [0, 3, 8, 12],
        1,
        {1: (0, 1), 3: (5, 0)},
        None,
        {"foul": None, "winner": None, "loss": None},
        (STRIPES, SOLIDS),
    ),
]


@pytest.mark.parametrize(
    ("on", "groups", "numbers", "first_row", "drops", "called", "verdict", "groups_after"),
    [case[1:] for case in RARE_OUTCOMES],
    ids=[case[0] for case in RARE_OUTCOMES],
)
def test_rare_outcomes_have_their_verdicts(
    on: set[int],
    groups: tuple[int, int],
    numbers: list[int],
    first_row: int,
    drops: dict[int, tuple[int, int]],
    called: int | None,
    verdict: dict[str, Any],
    groups_after: tuple[int, int] | None,
) -> None:
    state = _eight_state(on, groups)
    m = len(numbers)
    pocketed, order = [-1] * m, [-1] * m
    for row, (pocket, k) in drops.items():
        pocketed[row], order[row] = pocket, k
    cushions = [1] * m
    positions = [(1.5 + 0.1 * row, 0.6) for row in range(m)]  # all beyond the head string
    got, after = compiled_judge(
        TABLE, state, positions, numbers, (0, first_row), cushions, pocketed, order, called
    )
    assert {key: got[key] for key in verdict} == verdict
    hit = np.full(m, -1)
    hit[0] = first_row
    shot = ShotOutcome.from_arrays(hit, cushions, pocketed, order, np.array(numbers))
    ref, ref_after = judge(state, shot, called)
    assert (ref.foul, ref.winner, ref.loss) == (verdict["foul"], verdict["winner"], verdict["loss"])
    if groups_after is not None:
        assert after.groups == ref_after.groups == groups_after


# Rotation outcomes at the push-out's and 10-ball's edges, each judged by the compiled rules
# and the reference alike (the random property test reaches them rarely): (name, state,
# potted balls with their pockets, first ball, calls, expected verdict).
ROTATION_EDGES: list[tuple] = [
    ("nine: the 9 on a push-out is spotted", RackState("nine", (True,) * 10, push_out=True,
     breaking=False), {3: 0, 9: 1}, 5, {"push_out": True},
     {"winner": None, "respot": (9,), "continues": False, "push_out": True}),
    ("ten: the 10 on a push-out is spotted", RackState("ten", (True,) * 11, push_out=True,
     breaking=False), {10: 1}, 1, {"push_out": True, "called_ball": 10, "called": 1},
     {"winner": None, "respot": (10,), "continues": False, "push_out": True}),
    ("ten: the 10 beside a made call is spotted", RackState("ten", (True,) * 11,
     breaking=False), {1: 0, 10: 2}, 1, {"called_ball": 1, "called": 0},
     {"winner": None, "respot": (10,), "continues": True}),
    ("ten: the called 10 made wins", RackState("ten", (True,) * 11, breaking=False),
     {10: 2}, 1, {"called_ball": 10, "called": 2},
     {"winner": 0, "respot": (), "continues": False}),
    ("ten: the called 10 on the break is spotted", RackState.new_rack("ten"), {10: 2, 4: 3},
     1, {"called_ball": 10, "called": 2}, {"winner": None, "respot": (10,), "continues": True}),
    ("ten: the called 10 in another pocket is spotted", RackState("ten", (True,) * 11,
     breaking=False), {10: 2}, 1, {"called_ball": 10, "called": 4},
     {"winner": None, "respot": (10,), "continues": False}),
]  # fmt: skip


@pytest.mark.parametrize("case", ROTATION_EDGES, ids=[c[0] for c in ROTATION_EDGES])
def test_rotation_edges_have_their_verdicts(case: tuple) -> None:
    _, state, drops, first, calls, want = case
    numbers = list(range(len(state.on_table)))
    m = len(numbers)
    pocketed, order = [-1] * m, [-1] * m
    for k, (ball, pocket) in enumerate(drops.items()):
        pocketed[ball], order[ball] = pocket, k
    cushions = [1] * m
    positions = [(1.5 + 0.01 * row, 0.6) for row in range(m)]
    called = calls.pop("called", None)
    got, after = compiled_judge(
        TABLE, state, positions, numbers, (0, first), cushions, pocketed, order, called, **calls
    )
    hit = np.full(m, -1)
    hit[0] = first
    shot = ShotOutcome.from_arrays(hit, cushions, pocketed, order, np.array(numbers))
    ref, ref_after = judge(state, shot, called, **calls)
    same_verdict(ref, ref_after, got, after)
    have = {**got, "continues": got["keeps"] and got["winner"] is None}
    assert {key: have[key] for key in want} == want


def test_the_vector_env_plays_the_rules_alike_threaded_and_with_rule_options() -> None:
    from gymnasium.utils.env_checker import data_equivalence

    envs = [
        gym.make_vec(IDS["nine"], 4, vectorization_mode="vector_entry_point", parallel=p)
        for p in (False, True)
    ]
    rng = np.random.default_rng(4)
    out = [env.reset(seed=7) for env in envs]
    for _ in range(25):
        actions = rng.uniform(-1, 1, (4, 6))  # the option's column too
        out = [env.step(actions) for env in envs]
        assert data_equivalence(out[0], out[1], exact=True)
    # options["rules"] reaches every table reset; the rack state is per table
    env = gym.make_vec(IDS["nine"], 4, vectorization_mode="vector_entry_point", **KWARGS)
    env.reset(options={**layout("nine", NINE_MISS), "rules": {"fouls": (2, 0)}})
    assert [r["fouls"] for r in env.unwrapped.rack] == [(2, 0)] * 4
    *_, terminated, _, info = env.step(fit(env, np.tile(action(math.pi / 2, 0.3), (4, 1))))
    assert terminated.all() and (info["winner"] == 1).all()
    assert list(info["foul"]) == ["no_contact"] * 4
    assert list(info["loss"]) == ["three_fouls"] * 4


# --- ball in hand, the called pocket and the break speed: the action's other components ---


@pytest.mark.parametrize("bin_", range(6))
def test_the_called_pocket_is_one_of_six_equal_bins_of_the_last_action(bin_: int) -> None:
    # Action 4 calls pocket floor(6 (a + 1) / 2): the 8 goes straight into pocket 0, so
    # only a call from bin 0 wins; every other bin's call loses the rack (WPA 8-ball 3.x:
    # the 8 in the called pocket). Bin centres and both edges of bin 0.
    pocket = -1.0 + (2 * bin_ + 1) / 6.0
    *_, reward, terminated, _, info = play("eight", ON_EIGHT, TOWARD_CORNER, 1.5, SOLID_STRIPE,
                                           pocket)  # fmt: skip
    assert info["potted"] == (8,) and info["foul"] is None and terminated
    if bin_ == 0:
        assert info["winner"] == 0 and info["loss"] is None and reward == 1.0
    else:
        assert info["winner"] == 1 and info["loss"] == "eight_wrong_pocket" and reward == -1.0


@pytest.mark.parametrize("pocket", [-1.0, -1.0 + 2.0 / 6.0 - 1e-9])
def test_both_edges_of_the_first_bin_call_pocket_0(pocket: float) -> None:
    *_, info = play("eight", ON_EIGHT, TOWARD_CORNER, 1.5, SOLID_STRIPE, pocket)
    assert info["winner"] == 0 and info["loss"] is None


def test_ball_in_hand_behind_the_head_string_on_a_covered_point_stays_behind_it() -> None:
    # The kitchen's +1 placement is the head string itself (x = L / 4); a ball just in
    # front of it covers that point. The nearest free point behind the head string lies on
    # that ball's 2R circle where it meets the head string (WPA 8-ball: ball in hand behind
    # the head string after a break scratch); the free point just past the ball is not
    # allowed.
    head = TABLE.length / 4
    gap = 0.01
    balls = {0: (0.3, 0.3), 3: (head - gap, MID), 8: parked(0), 11: parked(1)}
    env = make("eight")
    rules = {"ball_in_hand": True, "behind_head_string": True, **SOLID_STRIPE}
    env.reset(seed=0, options={**layout("eight", balls), "rules": rules})
    env.step(fit(env, action(0.0, 0.0, (1.0, 0.0))))  # speed 0: the cue ball stays where it is put
    cue = env.unwrapped.positions[0]
    assert cue[0] <= head
    assert math.dist(cue, (head - gap, MID)) >= 2 * R


def test_ball_in_hand_that_is_not_a_break_uses_the_shot_speed_range() -> None:
    env = make("nine", break_speed_range=(8.0, 12.0))
    env.reset(seed=0, options={**layout("nine", NINE_MISS), "rules": {"ball_in_hand": True}})
    *_, info = env.step(fit(env, action(math.pi / 2, 0.3)))
    assert info["speed"] == pytest.approx(0.3, abs=1e-12)  # speed_range (0, 10), not (8, 12)
    assert info["foul"] == "no_contact"


def test_the_eight_potted_without_a_call_loses_the_rack() -> None:
    # The env always calls a pocket (action 4); the compiled rules also take "no call"
    # (-1). WPA 8-ball: the 8 wins only in the called pocket, so without a call, potting it
    # on the 8 loses like any other pocket. No physics: a legal shot that drops the 8.
    on = tuple(b in (0, 8, 11) for b in range(16))
    state = RackState(game="eight", on_table=on, breaking=False, groups=(SOLIDS, STRIPES))
    args = ([(0.3, 0.3), (0.0, 0.0), (1.0, 0.6)], [0, 8, 11], (0, 1), [0, 0, 0])
    for called, loss, winner in [(None, "eight_wrong_pocket", 1), (0, None, 0),
                                 (3, "eight_wrong_pocket", 1)]:  # fmt: skip
        got, after = compiled_judge(TABLE, state, *args, [-1, 0, -1], [-1, 0, -1], called)
        assert got["foul"] is None and got["ball_on"] == 8
        assert (got["loss"], got["winner"], after.winner) == (loss, winner, winner)


# --- the push-out, the option and 10-ball's called ball: the action's own columns ------------


def test_a_push_out_through_the_env_needs_no_contact_and_the_agent_shoots_on() -> None:
    env = make("nine", end_on_foul=True)
    env.reset(seed=0, options={**layout("nine", NINE_MISS), "rules": {"push_out": True}})
    push = fit(env, action(math.pi / 2, 0.3))
    push[env.unwrapped.config.ruleset.option_column] = 1.0  # declared
    _, reward, terminated, _, info = env.step(push)
    assert info["push_out"] and info["legal"] and info["foul"] is None and info["turn_over"]
    # Run-out mode: the turn is over as two players count it, but one agent shoots on (the
    # option needs an opponent): the episode goes on, the agent to shoot, no ball in hand.
    assert reward == 0.0 and not terminated
    rack = env.unwrapped.rack
    assert not rack["option"] and not rack["push_out"] and not rack["ball_in_hand"]
    assert rack["shooter"] == 0 and rack["fouls"] == (0, 0)
    *_, terminated, _, info = env.step(fit(env, action(math.pi / 2, 0.3)))  # shoots on
    assert info["foul"] == "no_contact" and not info["push_out"] and terminated
    # One player: no option; the same shot, not declared, is the no-contact foul.
    env.reset(seed=0, options={**layout("nine", NINE_MISS), "rules": {"push_out": True}})
    *_, info = env.step(fit(env, action(math.pi / 2, 0.3)))
    assert info["foul"] == "no_contact" and not info["push_out"]


@pytest.mark.parametrize("game", ["nine", "ten"])
def test_the_duel_opponent_hands_the_table_back_after_a_push_out(game: str) -> None:
    duel = PoolDuelEnv(game, **KWARGS, model="roll")
    balls = {**NINE_MISS, 10: parked(2)} if game == "ten" else NINE_MISS
    duel.reset(seed=0, options={**layout(game, balls), "rules": {"push_out": True}})
    option = duel.config.ruleset.option_column
    push = fit(duel, action(math.pi / 2, 0.3))
    push[option] = 1.0
    duel.step(push.astype(np.float32))
    info = duel.infos["player_0"]
    assert info["push_out"] and duel.agent_selection == "player_1"
    assert duel.rack["option"] and duel.rack["shooter"] == 1
    assert shot_constraints(duel.config, duel.observe("player_1")).option
    assert not shot_constraints(duel.config, duel.observe("player_0")).option
    before, shots = duel.positions, duel.shots
    back = np.zeros(duel.config.action_size, np.float32)
    back[option] = 1.0
    duel.step(back)
    info = duel.infos["player_1"]
    assert info["handed_back"] and not info["push_out"] and info["foul"] is None
    assert info["speed"] == 0.0 and info["angle"] == 0.0  # no shot struck
    assert duel.agent_selection == "player_0" and not duel.rack["option"]
    np.testing.assert_array_equal(duel.positions, before)  # nothing was struck
    assert duel.shots == shots + 1
    # The pusher must shoot now: the option column is ignored and a shot is played.
    duel.step(back)
    assert not duel.infos["player_0"]["handed_back"]
    assert duel.infos["player_0"]["foul"] == "no_contact"


@pytest.mark.parametrize("ball", range(1, 11))
def test_the_called_ball_is_one_of_ten_equal_bins_of_its_column(ball: int) -> None:
    config = make("ten").unwrapped.config
    pos = break_scene(config.table, "ten")
    column = config.ruleset.ball_column
    for edge in (-1.0 + 0.2 * (ball - 1) + 1e-9, -1.0 + 0.2 * ball - 1e-9):
        act = np.zeros(config.action_size)
        act[column] = edge
        assert decode_action(config, act, pos).ball == ball
