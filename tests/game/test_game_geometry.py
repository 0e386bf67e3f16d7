"""The game's compiled geometry and batched codec: closed forms, and batched equals one by one.

:mod:`pool_env.game.geometry` answers the players' questions (ghost-ball shots, clear paths,
speeds, where a ball may be) and :func:`pool_env.game.codec.encode_shots` encodes many
shots at once; both are checked against hand geometry and against the one-shot codec.
"""

from __future__ import annotations

import math

import gymnasium as gym
import numpy as np
import pytest

import pool_env
from pool_env import Shot, Table, decode_action, encode_action, encode_observations, free_spot
from pool_env.game import geometry as geo
from pool_env.game.codec import (
    decode_observations,
    encode_placement,
    encode_pocket,
    encode_shots,
    reference_balls,
)
from pool_env.sim.table import standard_pockets

TABLE = Table()
R = TABLE.ball_radius
CIRCLES = Table(pockets=standard_pockets(2.54, 1.27, 0.028575))


def _one(positions: list, on: list | None = None, targets: tuple = (1,), table=TABLE):
    """Ghost-shot rows ``(T, K, NG)`` of one layout."""
    pos = np.array(positions, dtype=np.float64)[None]
    on_table = np.ones(pos.shape[:2], bool) if on is None else np.array(on)[None]
    mouths = geo.pocket_mouths(table)
    return geo.ghost_shots(table, mouths, pos, on_table, [list(targets)])[0], mouths


@pytest.mark.parametrize("table", [TABLE, CIRCLES], ids=["jaws", "circles"])
def test_a_straight_in_shot_has_no_cut_and_the_ghost_point_behind_the_ball(table) -> None:
    mouths = geo.pocket_mouths(table)
    k = 1  # the bottom side pocket: mouth at (L/2, ~R), straight down
    target = mouths.targets[k]
    ball = target + np.array([0.0, 0.5])
    cue = ball + np.array([0.0, 0.4])
    rows, _ = _one([cue, ball], table=table)
    shot = rows[0, k]
    u = (target - ball) / np.hypot(*(target - ball))
    assert shot[geo.VALID] == 1.0 and shot[geo.CLEAR_PATH] == 1.0
    assert shot[geo.CUT] == pytest.approx(0.0, abs=1e-12)
    assert shot[geo.COS_CUT] == pytest.approx(1.0, abs=1e-15)
    np.testing.assert_allclose(shot[[geo.GX, geo.GY]], ball - 2.0 * R * u, atol=1e-15)
    assert shot[geo.CUE_DIST] == pytest.approx(0.4 - 2.0 * R, abs=1e-15)
    assert shot[geo.ANGLE] == pytest.approx(-math.pi / 2.0, abs=1e-12)
    assert shot[geo.BALL_DIST] == pytest.approx(0.5, abs=1e-15)
    assert shot[geo.APPROACH] == pytest.approx(1.0, abs=1e-12)
    half = mouths.half_tolerance(k, u)
    expected = 2.0 * R * half / ((0.4 - 2.0 * R) * 0.5)  # 2R cos(cut) h / (d_cue d_ball)
    assert shot[geo.TOLERANCE] == pytest.approx(expected, rel=1e-12)


@pytest.mark.parametrize("cut_deg", [-60.0, -30.0, 15.0, 45.0])
def test_the_cut_is_the_angle_between_the_cue_path_and_the_ball_path(cut_deg: float) -> None:
    mouths = geo.pocket_mouths(TABLE)
    k = 1
    ball = mouths.targets[k] + np.array([0.0, 0.5])
    u = np.array([0.0, -1.0])
    ghost = ball - 2.0 * R * u
    # The cue ball sits 0.3 m behind the ghost point, its path turned by the cut.
    phi = -math.pi / 2.0 - math.radians(cut_deg)
    cue = ghost - 0.3 * np.array([math.cos(phi), math.sin(phi)])
    shot = _one([cue, ball])[0][0, k]
    assert shot[geo.VALID] == 1.0
    assert math.degrees(shot[geo.CUT]) == pytest.approx(cut_deg, abs=1e-9)
    assert shot[geo.COS_CUT] == pytest.approx(math.cos(math.radians(cut_deg)), abs=1e-12)
    assert shot[geo.CUE_DIST] == pytest.approx(0.3, abs=1e-12)
    assert shot[geo.ANGLE] == pytest.approx(phi, abs=1e-12)


def test_shots_too_thin_behind_the_ball_or_off_the_cloth_are_not_kept() -> None:
    mouths = geo.pocket_mouths(TABLE)
    k = 1
    ball = mouths.targets[k] + np.array([0.0, 0.5])
    beside = ball + np.array([0.3, -0.05])  # a cut of about 90 degrees to the side pocket
    assert _one([beside, ball])[0][0, k, geo.VALID] == 0.0
    on_rail = np.array([TABLE.length / 2.0, TABLE.width - R])  # the ghost point beyond the rail
    to_pocket = mouths.targets[k] - on_rail
    assert geo.ghost_contact(TABLE, on_rail, to_pocket / np.hypot(*to_pocket), ball) is None


def test_a_ball_in_the_path_is_reported_not_hidden() -> None:
    mouths = geo.pocket_mouths(TABLE)
    k = 1
    ball = mouths.targets[k] + np.array([0.0, 0.5])
    cue = ball + np.array([0.0, 0.4])
    blocker = ball + np.array([0.0, -0.25])  # on the object ball's path to the pocket
    rows, _ = _one([cue, ball, blocker])
    assert rows[0, k, geo.VALID] == 1.0 and rows[0, k, geo.CLEAR_PATH] == 0.0
    rows, _ = _one([cue, ball, blocker], on=[True, True, False])  # potted: no obstacle
    assert rows[0, k, geo.CLEAR_PATH] == 1.0


@pytest.mark.parametrize(
    ("ball", "clear"),
    [
        ((0.5, 0.1), False),  # exactly 2R = 0.1 from the path: touching is blocked
        ((0.5, 0.1 + 1e-9), True),
        ((-0.0999, 0.0), False),  # behind the start, within reach
        ((1.0 + 0.1 + 1e-9, 0.0), True),  # beyond the end, out of reach
    ],
)
def test_path_clear_measures_the_gap_to_the_segment(ball: tuple, clear: bool) -> None:
    assert geo.path_clear((0.0, 0.0), (1.0, 0.0), [ball], 0.1) is clear
    assert geo.path_clear((0.0, 0.0), (1.0, 0.0), np.empty((0, 2)), 0.1)


def test_cue_speed_is_the_rolling_and_collision_model_backwards() -> None:
    mouths = geo.pocket_mouths(TABLE)
    k = 1
    ball = mouths.targets[k] + np.array([0.0, 0.5])
    cue = ball + np.array([0.2, 0.4])
    rows = _one([cue, ball])[0]
    shot = rows[0, k]
    a, e = TABLE.deceleration, TABLE.e_ball
    v_ball = math.sqrt(0.3**2 + 2.0 * a * shot[geo.TRAVEL])
    v_contact = v_ball / ((1.0 + e) / 2.0 * math.cos(shot[geo.CUT]))
    expected = math.sqrt(v_contact**2 + 2.0 * a * shot[geo.CUE_DIST])
    speeds = geo.cue_speeds(TABLE, rows, 0.3)
    assert speeds.shape == rows.shape[:2]
    assert speeds[0, k] == pytest.approx(expected, rel=1e-14)
    assert (speeds[rows[..., geo.VALID] == 0.0] == 0.0).all()


def test_a_batch_is_its_layouts_one_by_one() -> None:
    rng = np.random.default_rng(3)
    mouths = geo.pocket_mouths(TABLE)
    pos = np.stack(
        [rng.uniform(R, TABLE.length - R, (40, 5)), rng.uniform(R, TABLE.width - R, (40, 5))], -1
    )
    on = rng.random((40, 5)) < 0.8
    targets = np.array([[1, 2, -1]] * 40)
    batch = geo.ghost_shots(TABLE, mouths, pos, on, targets)
    assert batch[:, 2, :, geo.VALID].sum() == 0.0  # the empty slot
    assert 0 < batch[..., geo.VALID].sum() < batch[..., geo.VALID].size
    for i in range(40):
        one = geo.ghost_shots(TABLE, mouths, pos[i : i + 1], on[i : i + 1], targets[i : i + 1])
        np.testing.assert_array_equal(one[0], batch[i])


def test_bad_shapes_are_refused() -> None:
    mouths = geo.pocket_mouths(TABLE)
    pos, on = np.zeros((2, 3, 2)), np.ones((2, 3), bool)
    with pytest.raises(ValueError, match="targets"):
        geo.ghost_shots(TABLE, mouths, pos, on, [[1]])
    with pytest.raises(ValueError, match="ball indices"):
        geo.ghost_shots(TABLE, mouths, pos, on, [[3], [1]])
    with pytest.raises(ValueError, match="on_table"):
        geo.ghost_shots(TABLE, mouths, pos, on[:, :2], [[1], [1]])


def test_points_free_is_the_games_placement_rule() -> None:
    balls = np.array([[1.0, 0.6]])
    spot = free_spot(TABLE, balls, np.array([True]), target=(1.0, 0.6))  # covered: moved
    pocket = TABLE.pockets[0, :2]
    points = [spot, (1.0, 0.6), tuple(pocket), (TABLE.length / 2.0 + 0.3, 0.6)]
    np.testing.assert_array_equal(geo.points_free(TABLE, points, balls), [True, False, False, True])
    kitchen = geo.points_free(TABLE, [(0.5, 0.6), (2.0, 0.6)], balls, behind_head_string=True)
    np.testing.assert_array_equal(kitchen, [True, False])


@pytest.mark.parametrize("aim", ["cut", "relative", "absolute"])
@pytest.mark.parametrize("env_id", ["pool_env/PoolRoll-v1", "pool_env/Pool-v1"])
def test_encode_shots_is_encode_action_for_many_shots(env_id: str, aim: str) -> None:
    env = gym.make(env_id, aim=aim).unwrapped
    config = env.config
    rng = np.random.default_rng(5)
    angles, speeds = rng.uniform(-4.0, 4.0, (6, 20)), rng.uniform(0.0, 9.0, (6, 20))
    tips = None
    if config.spin:  # inside the miscue circle
        radius = config.tip_limit * np.sqrt(rng.uniform(0.0, 1.0, (6, 20)))
        phi = rng.uniform(-math.pi, math.pi, (6, 20))
        tips = np.stack([radius * np.cos(phi), radius * np.sin(phi)], -1)
    layouts = []
    for k in range(6):
        env.reset(seed=k)
        layouts.append((env.positions, env.on_table))
    pos = np.stack([p for p, _ in layouts])
    on = np.stack([o for _, o in layouts])
    actions, playable = encode_shots(config, pos, on, angles, speeds, tips)
    assert actions.shape == (6, 20, 4 if config.spin else 2)
    assert playable.any() and (aim == "absolute" or not playable.all())
    lo, hi = config.speed_range
    for i in range(6):
        for m in range(20):
            tip = (0.0, 0.0) if tips is None else tuple(tips[i, m])
            shot = Shot(angles[i, m], min(max(speeds[i, m], lo), hi), tip)
            if playable[i, m]:
                one = encode_action(config, shot, pos[i], on[i])
                np.testing.assert_allclose(actions[i, m], one, rtol=0, atol=1e-12)
                back = decode_action(config, one, pos[i], on[i])
                assert math.remainder(back.angle - angles[i, m], 2 * math.pi) == pytest.approx(
                    0.0, abs=1e-9
                )
            else:
                with pytest.raises(ValueError, match=r"angle|cut"):
                    encode_action(config, shot, pos[i], on[i])


def test_encode_shots_refuses_tips_it_cannot_play() -> None:
    pos, on = np.array([[[0.5, 0.5], [1.0, 0.5]]]), np.ones((1, 2), bool)
    roll = gym.make("pool_env/OneBallRoll-v1").unwrapped.config
    with pytest.raises(ValueError, match="spin table"):
        encode_shots(roll, pos, on, [[0.0]], [[1.0]], [[(0.1, 0.0)]])
    spin = gym.make("pool_env/OneBall-v1").unwrapped.config
    with pytest.raises(ValueError, match="tip limit"):
        encode_shots(spin, pos, on, [[0.0]], [[1.0]], [[(spin.tip_limit, 0.1)]])


def test_reference_balls_are_the_nearest_on_the_table() -> None:
    pos = np.array([[[0.5, 0.5], [1.0, 0.5], [0.7, 0.5]], [[0.5, 0.5], [1.0, 0.5], [0.7, 0.5]]])
    on = np.array([[True, True, True], [True, True, False]])
    np.testing.assert_array_equal(reference_balls(pos, on), [2, 1])
    np.testing.assert_array_equal(reference_balls(pos, on & [True, False, False]), [-1, -1])


def test_decode_observations_inverts_the_env_encoding() -> None:
    rng = np.random.default_rng(9)
    pos = np.stack(
        [rng.uniform(R, TABLE.length - R, (50, 4)), rng.uniform(R, TABLE.width - R, (50, 4))], -1
    )
    on = rng.random((50, 4)) < 0.7
    obs = encode_observations(pos, on, TABLE.length, TABLE.width)
    back, back_on = decode_observations(TABLE, obs)
    np.testing.assert_array_equal(back_on, on)
    np.testing.assert_allclose(back[on], pos[on], rtol=0, atol=3e-7)  # float32 of 2.54 m
    with pytest.raises(ValueError, match="3 N"):
        decode_observations(TABLE, obs[:, :-1])


def test_the_geometry_module_is_public() -> None:
    assert pool_env.encode_shots is encode_shots
    assert pool_env.decode_observations is decode_observations


def test_placement_and_pocket_components_decode_to_what_was_asked() -> None:
    env = gym.make("pool_env/NineBallGame-v2").unwrapped
    env.reset(seed=2)
    rack = {**env.rack, "break": False, "ball_in_hand": True, "behind_head_string": False}
    config = env.config
    want = (1.7, 0.4)
    action = np.zeros(config.action_size)
    action[2:4] = encode_placement(config, want)
    action[4] = encode_pocket(config, 4)
    action[1] = -1.0
    shot = decode_action(config, action, env.positions, env.on_table, rack)
    np.testing.assert_allclose(shot.cue, want, rtol=0, atol=1e-12)
    assert shot.pocket == 4
    kitchen = encode_placement(config, (TABLE.length / 4.0, 0.4), behind=True)
    assert kitchen[0] == pytest.approx(1.0, abs=1e-12)  # the head string is the box's edge
    with pytest.raises(ValueError, match="outside"):
        encode_placement(config, (TABLE.length / 2.0, 0.4), behind=True)
    with pytest.raises(ValueError, match="pocket"):
        encode_pocket(config, 6)
    with pytest.raises(ValueError, match="rules"):
        encode_placement(gym.make("pool_env/OneBall-v1").unwrapped.config, want)
