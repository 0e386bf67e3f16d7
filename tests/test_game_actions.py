"""The decision process's pure functions: decoding, aiming, observations, potential, rules."""

from __future__ import annotations

import math

import numpy as np
import pytest

from pool_env import AIM_MODES, Table, decode_shots, encode_observations, nearest_object_ball
from pool_env.game.checks import check_actions
from pool_env.game.kernels.actions import aim_angles, decode_actions
from pool_env.game.kernels.observe import pocket_potentials
from pool_env.game.rules import judge
from pool_env.game.scenes import placement

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
    ONE = np.zeros(1, np.intp)
    phi = pocket_potentials(ONE, pos[None], on[None], TABLE.pockets, 2.0)[0]
    assert phi == pytest.approx(-0.25)
    on[1] = False
    assert pocket_potentials(ONE, pos[None], on[None], TABLE.pockets, 2.0)[0] == 0.0  # cleared
    no_pockets = np.zeros((0, 3))
    assert pocket_potentials(ONE, pos[None], np.ones((1, 3), bool), no_pockets, 2.0)[0] == 0.0


def _judge(n_potted, scratch, first, phi, weights, n_left=1, shots=1, end_on_miss=False,
           limit=0, positions=None):  # fmt: skip
    k = len(n_potted)
    pos = np.tile([[0.1, 0.1], [1.5, 0.5]], (k, 1, 1)) if positions is None else positions
    on = np.ones((k, 2), bool)
    on[:, 0] = ~np.asarray(scratch)  # settle took a scratched cue ball off the table
    place = placement(TABLE)
    out = judge(
        np.arange(k), pos, on, np.full(k, n_left), np.full(k, shots), np.asarray(n_potted),
        np.asarray(scratch), np.asarray(first), np.asarray(phi, float), np.asarray(weights),
        end_on_miss, limit, 0, place.spot, place.bounds, place.circles, place.reach**2,
    )  # fmt: skip
    return (*out, pos, on)


def test_rule_rewards_pots_scratches_misses_and_shaping() -> None:
    w = (1.0, -1.0, -0.25, 2.0)
    rewards, *_ = _judge([2], [True], [3], [0.1], w)
    assert rewards[0] == pytest.approx(1.2)
    rewards, *_ = _judge([0, 1], [False, True], [-1, 2], [0.0, 0.0], w)
    np.testing.assert_allclose(rewards, [-0.25, 0.0])


def test_rule_puts_a_scratched_cue_ball_on_the_head_spot_when_free() -> None:
    _, _, _, _, taken, pos, on = _judge([0], [True], [1], [0.0], (1.0, -1.0, 0.0, 0.0))
    assert on[0, 0] and not taken[0]
    np.testing.assert_array_equal(pos[0, 0], placement(TABLE).spot)
    covered = np.array([[[0.1, 0.1], placement(TABLE).spot + [0.01, 0.0]]])
    *_, taken, pos, on = _judge([0], [True], [1], [0.0], (1, -1, 0, 0), positions=covered)
    assert on[0, 0] and taken[0]  # back on the table; free_spot places it
    np.testing.assert_array_equal(pos[0, 0], [0.1, 0.1])


@pytest.mark.parametrize(
    ("n_potted", "scratch", "n_left", "end_on_miss", "shots", "limit", "ends"),
    [
        (1, False, 0, False, 1, 0, (True, False, True)),  # cleared
        (1, False, 2, False, 1, 0, (False, False, False)),
        (0, False, 2, False, 1, 0, (False, False, False)),
        (0, False, 2, True, 1, 0, (True, False, False)),  # a miss ends it
        (1, True, 2, True, 1, 0, (True, False, False)),  # a pot with a scratch too
        (1, False, 2, True, 1, 0, (False, False, False)),
        (0, False, 2, False, 3, 3, (False, True, False)),  # the shot limit
        (1, False, 0, False, 3, 3, (True, True, True)),
    ],
)
def test_rule_episode_ends(n_potted, scratch, n_left, end_on_miss, shots, limit, ends) -> None:
    _, terminated, truncated, cleared, *_ = _judge(
        [n_potted], [scratch], [1], [0.0], (1.0, -1.0, 0.0, 0.0), n_left=n_left,
        shots=shots, end_on_miss=end_on_miss, limit=limit,
    )  # fmt: skip
    assert (bool(terminated[0]), bool(truncated[0]), bool(cleared[0])) == ends


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
