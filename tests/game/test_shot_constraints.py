"""The rules' public views: the observation's layout and what the next shot may do.

:func:`pool_env.obs_layout` names every part of the observation, and
:func:`pool_env.shot_constraints` reads the next shot's constraints from one observation;
both are checked here against the plain-Python reading of the rules
(:class:`tests.wpa_reference.RackState`), over random rack states, through the env's own
observation encoding.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from pool_env import Table, obs_layout, shot_constraints
from pool_env.game.config import make_config
from pool_env.game.games.wpa import params as wp
from pool_env.sim.layouts import break_scene
from tests.profiles import examples
from tests.rules_harness import SCENES, rack_row
from tests.wpa_reference import OPEN, SOLIDS, STRIPES, RackState

_ONE = np.zeros(1, dtype=np.intp)

TABLE = Table()
CONFIGS = {
    game: make_config(table=TABLE, scene=SCENES[game], game=game, players=2)
    for game in ("nine", "ten", "eight")
}
MONEY = {"nine": 9, "ten": 10, "eight": 8}


def _observe(state: RackState) -> np.ndarray:
    """The observation the env shows the shooter of ``state`` (a racked layout)."""
    config = CONFIGS[state.game]
    game_state = config.new_state(1)
    game_state.positions[0] = break_scene(TABLE, state.game)
    game_state.on_table[0] = state.on_table
    game_state.rack[0] = rack_row(state)
    viewers = np.array([state.shooter], dtype=np.int64)
    return config.ruleset.observe(config, game_state, viewers)[0]


@st.composite
def rack_states(draw: st.DrawFn) -> RackState:
    """A rack state the rules can reach: balls off, groups, fouls, ball in hand, the break."""
    game = draw(st.sampled_from(["nine", "ten", "eight"]))
    n = MONEY[game] + 1 if game != "eight" else 16
    on = [True] + [draw(st.booleans()) for _ in range(n - 1)]
    on[MONEY[game]] = True  # the rack is still being played
    breaking = draw(st.booleans())
    if breaking:
        on = [True] * n
    groups = (OPEN, OPEN)
    if game == "eight" and not breaking and draw(st.booleans()):
        groups = draw(st.sampled_from([(SOLIDS, STRIPES), (STRIPES, SOLIDS)]))
    in_hand = breaking or draw(st.booleans())
    offer = "none"  # the push-out or the option: 9-ball and 10-ball, no break, no ball in hand
    if game != "eight" and not in_hand:
        offer = draw(st.sampled_from(["none", "push_out", "option"]))
    return RackState(
        game=game, on_table=tuple(on), shooter=draw(st.sampled_from([0, 1])),
        breaking=breaking, fouls=(draw(st.integers(0, 2)), draw(st.integers(0, 2))),
        groups=groups, ball_in_hand=in_hand,
        behind_head_string=in_hand and (breaking or draw(st.booleans())),
        push_out=offer == "push_out", option=offer == "option",
    )  # fmt: skip


@settings(max_examples=examples(300), deadline=None)
@given(rack_states())
def test_constraints_read_the_rules_from_the_observation(state: RackState) -> None:
    config = CONFIGS[state.game]
    got = shot_constraints(config, _observe(state))
    if state.breaking:  # the break: the 1 in rotation, 8-ball any ball (WPA 8-ball 3.2)
        want = (1,) if state.game != "eight" else tuple(range(1, 16))
    else:
        want = state.legal_first_balls()
    assert got.first_balls == want
    assert got.ball_in_hand == state.ball_in_hand
    assert got.breaking == state.breaking
    speeds = config.rules.break_speed_range if state.breaking else config.speed_range
    assert got.speed_range == speeds
    on_eight = state.game == "eight" and want == (8,)
    assert got.call_pocket == (not state.breaking and (on_eight or state.game == "ten"))
    assert got.call_ball == (state.game == "ten" and not state.breaking)
    assert got.push_out == state.push_out and got.option == state.option
    if not state.ball_in_hand:
        assert got.placement is None
    else:
        (x_low, x_high), (y_low, y_high) = got.placement
        head = TABLE.length / 4.0
        assert (x_low, y_low) == (TABLE.ball_radius, TABLE.ball_radius)
        assert x_high == (head if state.behind_head_string else TABLE.length - TABLE.ball_radius)
        assert y_high == TABLE.width - TABLE.ball_radius


def test_placement_box_is_what_the_step_accepts() -> None:
    """The box's corners encode to the action's edges (the step places the ball there)."""
    config = CONFIGS["nine"]
    state = replace(RackState.new_rack("nine"), ball_in_hand=True, behind_head_string=True)
    box = shot_constraints(config, _observe(state)).placement
    assert box is not None
    (_, x_high), (y_low, _) = box
    assert x_high == config.params[wp.HEAD_X]
    behind = config.ruleset.encode_placement(config, (x_high, y_low), True, False)
    assert behind == (1.0, -1.0)
    with pytest.raises(ValueError, match="cue x"):
        config.ruleset.encode_placement(config, (x_high + 1e-3, y_low), True, False)


@pytest.mark.parametrize("game", ["solitaire", "nine", "ten", "eight"])
def test_layout_partitions_the_observation(game: str) -> None:
    """Every entry belongs to exactly one named part, and the parts are in order."""
    scene = {"solitaire": "random", **SCENES}[game]
    config = make_config(scene=scene, game=game, n_balls=4 if game == "solitaire" else None)
    layout = obs_layout(config)
    covered = np.zeros(config.observation_size, dtype=int)
    for part in layout.values():
        covered[part] += 1
    assert (covered == 1).all()
    assert layout["balls"] == slice(0, 3 * config.n_balls)
    starts = [part.start for part in layout.values()]
    assert starts == sorted(starts)


def test_solitaire_constraints_are_the_balls_on_the_table() -> None:
    config = make_config(scene="random", n_balls=4)
    obs = np.zeros(config.observation_size, dtype=np.float32)
    obs[obs_layout(config)["balls"]][2::3] = 1.0  # a view: writes through
    obs[3 * 2 + 2] = 0.0  # ball 2 potted
    got = shot_constraints(config, obs)
    assert got.first_balls == (1, 3, 4)
    assert got.speed_range == config.speed_range
    assert not (got.ball_in_hand or got.breaking or got.call_pocket)
    with pytest.raises(ValueError, match="observation must have shape"):
        shot_constraints(config, obs[:-1])
