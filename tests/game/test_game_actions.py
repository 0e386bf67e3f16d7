"""The decision process's pure functions: decoding, aiming, observations, potential, rules."""

from __future__ import annotations

import math

import numpy as np
import pytest

from pool_env import AIM_MODES, Table, decode_shots, encode_observations, nearest_object_ball
from pool_env.game.checks import check_actions
from pool_env.game.config import make_config
from pool_env.game.games.solitaire import REWARD_TERMS
from pool_env.game.games.solitaire.rules import judge
from pool_env.game.kernels.actions import aim_angles, decode_actions
from pool_env.game.kernels.observe import pocket_potentials
from pool_env.game.kernels.outcome import (
    CLEARED,
    FIRST_BALL,
    POTTED_BITS,
    REWARD,
    SCRATCH,
    SPOT_TAKEN,
    TERMINATED,
    TRUNCATED,
)
from pool_env.sim.layouts import head_spot

TABLE = Table()
R = TABLE.ball_radius
ABSOLUTE, RELATIVE, CUT = (AIM_MODES.index(m) for m in ("absolute", "relative", "cut"))


def test_decode_maps_ends_and_middle_linearly() -> None:
    actions = np.array([[-1.0, -1.0], [1.0, 1.0], [0.0, 0.0], [0.5, -0.5]])
    aims, speeds = decode_actions(actions, -0.2, 0.4, 0.5, 10.0)
    np.testing.assert_allclose(aims, [-0.2, 0.4, 0.1, 0.25])
    np.testing.assert_allclose(speeds, [0.5, 10.0, 5.25, 2.875])


def test_decode_clips_out_of_range_and_infinite_actions() -> None:
    actions = np.array([[7.0, -3.0], [np.inf, -np.inf], [1.0, -1.0]], dtype=np.float32)
    aims, speeds = decode_actions(actions, -1.0, 1.0, 0.5, 10.0)
    assert aims.tolist() == [1.0, 1.0, 1.0]
    assert speeds.tolist() == [0.5, 0.5, 0.5]


@pytest.mark.parametrize("bad", [[np.nan, 0.0], [0.0, np.nan], np.array([np.nan, 1], np.float32)])
def test_check_action_rejects_nan(bad: object) -> None:
    with pytest.raises(ValueError, match="NaN"):
        check_actions(bad, 1, single=True)


@pytest.mark.parametrize("bad", [[0.0], [0.0, 0.0, 0.0], [[0.0, 0.0]], "ab", None])
def test_check_action_rejects_bad_shapes(bad: object) -> None:
    with pytest.raises(ValueError, match="action"):
        check_actions(bad, 1, single=True)


def test_check_action_accepts_lists_and_integers() -> None:
    assert check_actions([1, 0], 1, single=True).tolist() == [[1.0, 0.0]]


def _aim(params: list[float], positions: np.ndarray, on: np.ndarray, mode: int) -> np.ndarray:
    return aim_angles(np.array(params), positions[None], on[None], 0, mode, R)


def test_absolute_aim_is_the_parameter() -> None:
    pos = np.array([[0.5, 0.5], [1.0, 0.9]])
    assert _aim([1.25], pos, np.ones(2, bool), ABSOLUTE)[0] == 1.25


def test_relative_aim_is_an_offset_from_the_nearest_object_ball_on_the_table() -> None:
    pos = np.array([[1.0, 0.6], [1.0, 0.9], [1.2, 0.6], [0.9, 0.6]])
    on = np.array([True, True, True, False])  # ball 3 is nearest but potted
    base = math.atan2(0.0, 0.2)  # ball 2, 0.2 m along +x
    assert _aim([0.0], pos, on, RELATIVE)[0] == pytest.approx(base)
    assert _aim([0.1], pos, on, RELATIVE)[0] == pytest.approx(base + 0.1)
    on[2] = False
    assert _aim([0.0], pos, on, RELATIVE)[0] == pytest.approx(math.pi / 2)  # ball 1, above


@pytest.mark.parametrize("offset", [-1.0, -0.6, 0.0, 0.3, 0.95])
@pytest.mark.parametrize("distance", [2 * R + 1e-6, 0.1, 1.3])
def test_cut_aim_passes_offset_diameters_from_the_object_ball_centre(
    offset: float, distance: float
) -> None:
    phi = 0.7  # direction from the cue ball to the object ball
    cue = np.array([0.8, 0.4])
    obj = cue + distance * np.array([math.cos(phi), math.sin(phi)])
    angle = _aim([offset], np.stack([cue, obj]), np.ones(2, bool), CUT)[0]
    u = np.array([math.cos(angle), math.sin(angle)])
    rel = obj - cue
    signed_gap = u[0] * rel[1] - u[1] * rel[0]  # object centre to the left of the path: > 0
    assert -signed_gap == pytest.approx(offset * 2 * R, abs=1e-12)  # +offset passes on the left
    assert u @ rel > 0.0  # aimed towards the ball, not away


def test_with_no_object_ball_left_the_reference_line_is_x() -> None:
    pos = np.array([[0.5, 0.5], [1.0, 0.9]])
    on = np.array([True, False])
    assert _aim([0.3], pos, on, CUT)[0] == 0.0
    assert _aim([0.3], pos, on, RELATIVE)[0] == 0.3


def test_observation_scales_positions_and_zeroes_potted_balls() -> None:
    pos = np.array([[R, TABLE.width - R], [TABLE.length / 2, TABLE.width / 4], [0.1, 0.1]])
    on = np.array([True, True, False])
    obs = encode_observations(pos[None], on[None], TABLE.length, TABLE.width)[0]
    assert obs.dtype == np.float32
    expected = [
        2 * R / TABLE.length - 1,
        1 - 2 * R / TABLE.width,
        1.0,
        0.0,
        -0.5,
        1.0,
        0.0,
        0.0,
        0.0,
    ]
    np.testing.assert_allclose(obs, expected, atol=1e-6)


def test_observation_clamps_a_ball_a_rounding_error_outside_the_rails() -> None:
    pos = np.array([[-1e-12, TABLE.width + 1e-12]])
    obs = encode_observations(pos[None], np.ones((1, 1), bool), TABLE.length, TABLE.width)
    assert obs[0].tolist() == [-1.0, 1.0, 1.0]


def test_batched_calls_equal_row_by_row_calls() -> None:
    rng = np.random.default_rng(0)
    pos = rng.uniform(0.1, 1.2, (5, 4, 2))
    on = rng.random((5, 4)) < 0.7
    on[:, 0] = True
    params = rng.uniform(-1, 1, 5)
    for mode in range(3):
        batch = aim_angles(params, pos, on, 0, mode, R)
        rows = [
            aim_angles(params[k : k + 1], pos[k : k + 1], on[k : k + 1], 0, mode, R)[0]
            for k in range(5)
        ]
        np.testing.assert_array_equal(batch, rows)
    obs = encode_observations(pos, on, 2.54, 1.27)
    for k in range(5):
        np.testing.assert_array_equal(
            obs[k], encode_observations(pos[k : k + 1], on[k : k + 1], 2.54, 1.27)[0]
        )


def test_pocket_potential() -> None:
    corner = TABLE.pockets[0, :2]
    pos = np.array(
        [[1.0, 0.6], corner + np.array([0.3, 0.4]), [1.2, 0.6]]
    )  # ball 1 is 0.5 m from a corner
    on = np.array([True, True, False])
    phi = pocket_potentials(pos[None], on[None], TABLE.pockets, 2.0)[0]
    assert phi == pytest.approx(-0.25)
    on[1] = False
    assert pocket_potentials(pos[None], on[None], TABLE.pockets, 2.0)[0] == 0.0  # cleared
    no_pockets = np.zeros((0, 3))
    assert pocket_potentials(pos[None], np.ones((1, 3), bool), no_pockets, 2.0)[0] == 0.0


LAYOUT = np.array([[0.1, 0.6], [1.5, 0.5], [1.8, 0.9], [2.1, 0.3]])  # cue and balls 1-3


def _judge(
    dropped: list[int],
    first: tuple[int, int] = (0, 1),
    weights: tuple[float, ...] = (1.0, -1.0, -0.25, 0.0),
    shots: int = 0,
    end_on_miss: bool = False,
    limit: int = 0,
    layout: np.ndarray = LAYOUT,
    on: np.ndarray | None = None,
) -> tuple:
    """The rules after a shot that left every ball in place but dropped ``dropped``."""
    scales = {f"reward_{term}": w for term, w in zip(REWARD_TERMS, weights, strict=True)}
    params = make_config(
        table=TABLE, scene="one_ball", speed_range=(0.5, 10.0), end_on_miss=end_on_miss,
        max_shots=limit or None, **scales,
    ).params  # fmt: skip
    n = layout.shape[0]
    pos = layout[None].copy()
    on_table = np.ones((1, n), bool) if on is None else on[None].copy()
    pocketed = np.full((1, n), -1)
    pocketed[0, dropped] = 0
    out = judge(
        params, TABLE.pockets, np.zeros(1, np.intp), np.arange(n), pos, on_table,
        np.array([shots]), layout[None].copy(), pocketed, np.array([first]),
    )  # fmt: skip
    values, flags, hits = out
    f, h = flags[0], hits[0]
    assert values[0, REWARD] == values[0, 1:].sum()  # the terms add up to the reward
    return (
        values[0, REWARD], f[TERMINATED], f[TRUNCATED], f[CLEARED], h[POTTED_BITS], f[SCRATCH],
        h[FIRST_BALL], f[SPOT_TAKEN], pos[0], on_table[0],
    )  # fmt: skip


def test_rule_rewards_pots_scratches_and_misses() -> None:
    assert _judge([1, 2, 0])[0] == 1.0  # two pots and a scratch
    assert _judge([], first=(-1, -1))[0] == -0.25  # no contact
    assert _judge([3, 0], first=(2, 0))[0] == 0.0  # the cue ball hit ball 2 second
    reward, _, _, _, bits, scratch, first_ball, *_ = _judge([1, 3], first=(2, 0))
    assert reward == 2.0 and first_ball == 2 and not scratch
    assert bits == 0b101  # balls 1 and 3


def test_rule_puts_a_scratched_cue_ball_on_the_head_spot_when_free() -> None:
    *_, taken, pos, on = _judge([0])
    assert on[0] and not taken
    np.testing.assert_array_equal(pos[0], head_spot(TABLE))
    covered = LAYOUT.copy()
    covered[2] = head_spot(TABLE) + [0.01, 0.0]
    *_, taken, pos, on = _judge([0], layout=covered)
    assert on[0] and taken  # back on the table; free_spot places it
    np.testing.assert_array_equal(pos[0], LAYOUT[0])


@pytest.mark.parametrize(
    ("dropped", "end_on_miss", "shots", "limit", "ends"),
    [
        ([1, 2, 3], False, 0, 0, (True, False, True)),  # cleared
        ([1], False, 0, 0, (False, False, False)),
        ([], False, 0, 0, (False, False, False)),
        ([], True, 0, 0, (True, False, False)),  # a miss ends it
        ([1, 0], True, 0, 0, (True, False, False)),  # a pot with a scratch too
        ([1], True, 0, 0, (False, False, False)),
        ([], False, 2, 3, (False, True, False)),  # the third shot reaches the limit
        ([], False, 1, 3, (False, False, False)),
        ([1, 2, 3], False, 2, 3, (True, True, True)),
    ],
)
def test_rule_episode_ends(
    dropped: list[int], end_on_miss: bool, shots: int, limit: int, ends: tuple
) -> None:
    _, terminated, truncated, cleared, *_ = _judge(
        dropped, shots=shots, end_on_miss=end_on_miss, limit=limit
    )
    assert (bool(terminated), bool(truncated), bool(cleared)) == ends


def test_nearest_object_ball_ties_go_to_the_lower_number_and_none_is_minus_one() -> None:
    pos = np.array([[1.0, 0.6], [1.3, 0.6], [0.7, 0.6], [1.0, 0.2]])
    on = np.ones(4, bool)
    j, dist, angle = nearest_object_ball(pos, on, 0)
    assert (j, dist) == (1, pytest.approx(0.3)) and angle == 0.0
    on[1] = False
    assert nearest_object_ball(pos, on, 0)[0] == 2
    on[1:] = False
    assert nearest_object_ball(pos, on, 0) == (-1, math.inf, 0.0)


def test_decode_shots_is_decode_then_aim() -> None:
    rng = np.random.default_rng(2)
    actions = rng.uniform(-1.2, 1.2, (6, 2))
    pos = rng.uniform(0.1, 1.2, (6, 3, 2))
    on = np.ones((6, 3), bool)
    for mode in range(3):
        angles, speeds = decode_shots(actions, pos, on, 0, mode, R, (-0.3, 0.5), (0.5, 9.0))
        aims, expected_speeds = decode_actions(actions, -0.3, 0.5, 0.5, 9.0)
        np.testing.assert_array_equal(angles, aim_angles(aims, pos, on, 0, mode, R))
        np.testing.assert_array_equal(speeds, expected_speeds)
