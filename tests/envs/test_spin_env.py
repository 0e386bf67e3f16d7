"""The spin table as an environment: the cue tip action, its limit, its noise, the spin ids.

The strike's physics is the simulator's (``tests/sim/test_spin_strike.py``); here the env's
decoding of the two tip components is checked against the closed form of the strike, the
miscue circle, the order of the noise draws, what follow and draw do on a full hit, and
the rules' action layout.
"""

from __future__ import annotations

import math

import gymnasium as gym
import numpy as np
import pytest

import pool_env
from pool_env import PoolEnv, Table, shoot
from pool_env.envs.registration import SPIN_ONLY, TASKS, roll_id, spin_id
from pool_env.game.config import default_tip_limit, make_config
from pool_env.game.games.wpa.shots import executed_rule_shots, place_in_hand
from pool_env.game.kernels.actions import executed_shots
from pool_env.game.state import generator_addresses
from pool_env.sim.table import SPIN_ONLY as SPIN_PARAMS

LAYOUT = np.array([[0.8, 0.635], [1.1, 0.635]])  # a straight shot along +x, 0.3 m apart
R = Table().ball_radius


def _one_shot(
    tip: tuple[float, float],
    angle: float,
    speed: float,
    rng: np.random.Generator | None = None,
    **kwargs: object,
) -> tuple:
    """``executed_shots`` of one spin table: absolute aim at ``angle``, ``speed`` m/s."""
    config = make_config(
        scene=LAYOUT, model="spin", aim="absolute", aim_range=(angle, angle),
        speed_range=(speed, speed), **kwargs,
    )  # fmt: skip
    actions = np.array([[0.0, 0.0, *tip]])
    ptrs = np.zeros((1, 3), dtype=np.uintp)
    if rng is not None:
        ptrs[0] = generator_addresses(rng)
    one = np.zeros(1, dtype=np.intp)
    return config, executed_shots(
        config.params, actions, one, LAYOUT[None].copy(), np.ones((1, 2), bool), ptrs
    )


@pytest.mark.parametrize("tip", [(0.0, 0.0), (0.6, 0.0), (0.0, -1.0), (-0.4, 0.7), (1.0, 1.0)])
def test_a_tip_action_gives_the_closed_form_spin_of_the_strike(tip: tuple[float, float]) -> None:
    angle, speed = 0.7, 2.5
    config, (shots, states) = _one_shot(tip, angle, speed)
    velocities, spins = states[:, :, :2], states[:, :, 2:]
    table, limit = config.table, config.tip_limit
    a, b = tip[0] * limit, tip[1] * limit
    if math.hypot(a, b) > limit:
        a, b = a * limit / math.hypot(a, b), b * limit / math.hypot(a, b)
    np.testing.assert_allclose(shots[0], [angle, speed, a, b], rtol=0, atol=1e-15)
    # Pooltool's point strike (TP A-30, A-31): contact offsets a' = a / (1 + r_tip / R);
    # w = (5 v / 2R) (b' (z x f) + a' z); the ball leaves at angle + squirt (right english
    # squirts it left, counter-clockwise).
    scale = 1.0 / (1.0 + table.cue_tip_radius / R)
    ac, bc = a * scale, b * scale
    w = 2.5 * speed / R
    f = np.array([math.cos(angle), math.sin(angle)])
    np.testing.assert_allclose(spins[0, 0], [-w * bc * f[1], w * bc * f[0], w * ac], atol=1e-12)
    np.testing.assert_array_equal(spins[0, 1], 0.0)  # the object ball rests
    m_ratio = table.ball_mass / table.cue_end_mass
    squirt = math.atan2(2.5 * ac * math.sqrt(1 - ac * ac), 1 + m_ratio + 2.5 * (1 - ac * ac))
    heading = angle + squirt
    np.testing.assert_allclose(
        velocities[0, 0], [speed * math.cos(heading), speed * math.sin(heading)], atol=1e-14
    )
    if tip[0] > 0:
        assert squirt > 0.005  # ~1-2 degrees of squirt for real english
    # The rolling condition: a centre-line strike at contact offset 2/5 leaves rolling.
    if tip == (0.0, 0.0):
        assert not spins.any()


def test_the_env_plays_the_shot_that_shoot_plays_with_that_tip() -> None:
    env = PoolEnv(scene=LAYOUT, model="spin", aim="absolute")
    env.reset(seed=0)
    action = np.array([0.1, -0.2, 0.5, -0.8])
    _, _, _, _, info = env.step(action)
    angle, speed, a, b = env.last_strike
    assert info["tip"] == (a, b) and (info["angle"], info["speed"]) == (angle, speed)
    direct = shoot(Table(model="spin"), LAYOUT, angle, speed, tip=(a, b), record=False)
    on = direct.pocketed < 0
    np.testing.assert_array_equal(env.positions[on], direct.positions[on])  # bit for bit
    assert info["scratch"] == (not on[0]) and info["potted"] == ((1,) if not on[1] else ())
    assert info["n_events"] == direct.n_events


def _cue_after_contact(vertical: float) -> float:
    """How far (m, along +x) the cue ball moves in the 0.5 s after a full hit."""
    env = PoolEnv(
        scene=LAYOUT, model="spin", table={"pockets": "none"}, speed_range=(2.0, 2.0),
        render_mode="rgb_array",
    )  # fmt: skip
    env.reset(seed=0)
    env.step(np.array([0.0, 0.0, 0.0, vertical]))  # cut aim 0: a full hit
    shot = env.last_shot
    t1 = next(e.time for e in shot.events if e.kind == "ball")
    return float(shot.positions_at(t1 + 0.5)[0, 0] - shot.positions_at(t1)[0, 0])


def test_follow_and_draw_on_a_full_hit_move_the_cue_ball_forward_and_back() -> None:
    # After a full hit the cue ball keeps (1 - e) / 2 of its speed and all its spin: cloth
    # friction then drives it along its topspin (follow) or back along its backspin (draw).
    follow, draw = _cue_after_contact(1.0), _cue_after_contact(-1.0)
    assert follow > 0.1 and draw < -0.1
    centre = _cue_after_contact(0.0)  # slid 0.3 m: some topspin already, less than follow
    assert draw < centre < follow


def test_the_tip_is_clipped_onto_the_miscue_circle() -> None:
    env = gym.make("pool_env/OneBall-v1")
    limit = env.unwrapped.config.tip_limit
    assert limit == pytest.approx(0.5 * (1 + 0.0106 / 0.028575))  # contact offset R / 2
    env.reset(seed=0)
    cases = {
        (0.3, -0.5): (0.3 * limit, -0.5 * limit),  # inside: linear
        (1.0, 0.0): (limit, 0.0),
        (5.0, -np.inf): (limit / math.sqrt(2), -limit / math.sqrt(2)),  # clipped, then onto it
        (-1.0, 1.0): (-limit / math.sqrt(2), limit / math.sqrt(2)),
    }
    for tip, want in cases.items():
        env.reset()
        _, _, _, _, info = env.step(np.array([0.0, 0.0, *tip]))
        np.testing.assert_allclose(info["tip"], want, rtol=0, atol=2e-16)
        assert math.hypot(*info["tip"]) <= limit * (1 + 1e-15)
        assert env.unwrapped.last_strike[2:] == info["tip"]


def test_tip_noise_draws_after_angle_and_speed() -> None:
    n = 2000
    ours, theirs = np.random.default_rng(7), np.random.default_rng(7)
    shots = np.array([_one_shot((0.0, 0.0), 0.0, 3.0, noise=(1.0, 2.0, 0.1), rng=ours)[1][0][0]
                      for _ in range(n)])  # fmt: skip
    normals = theirs.standard_normal(4 * n).reshape(n, 4)
    aims = normals[:, 0]  # the reported direction: in [-pi, pi), wrapped when beyond it
    inside = (aims >= -np.pi) & (aims < np.pi)
    np.testing.assert_array_equal(
        shots[:, 0], np.where(inside, aims, (aims + np.pi) % (2 * np.pi) - np.pi)
    )
    np.testing.assert_array_equal(shots[:, 1], np.maximum(0.0, 3.0 + 2.0 * normals[:, 1]))
    tips = 0.1 * normals[:, 2:]
    norm = np.sqrt((tips**2).sum(axis=1))
    limit = default_tip_limit(Table(model="spin"))
    outside = norm > limit
    tips[outside] *= (limit / norm[outside])[:, None]
    np.testing.assert_array_equal(shots[:, 2:], tips)
    # Without a tip sigma a spin table draws exactly as a roll table: angle, speed.
    ours, theirs = np.random.default_rng(8), np.random.default_rng(8)
    spin = [_one_shot((0.2, 0.1), 0.0, 3.0, noise=(1.0, 2.0), rng=ours)[1][0][0] for _ in range(50)]
    normals = theirs.standard_normal(100).reshape(50, 2)
    np.testing.assert_array_equal(np.array(spin)[:, 0], normals[:, 0])


def test_v0_and_v1_streams_agree_up_to_the_tip_draws() -> None:
    v0 = gym.make("pool_env/OneBallRoll-v1", noise=(0.01, 0.05))
    v1 = gym.make("pool_env/OneBall-v1", noise=(0.01, 0.05, 0.05))
    a, b = v0.reset(seed=3), v1.reset(seed=3)
    np.testing.assert_array_equal(a[0], b[0])  # the same layout: the same draws
    i0 = v0.step(np.array([0.2, 0.4]))[4]
    i1 = v1.step(np.array([0.2, 0.4, 0.0, 0.0]))[4]
    assert (i0["angle"], i0["speed"]) == (i1["angle"], i1["speed"])
    assert i1["tip"] != (0.0, 0.0) and "tip" not in i0
    assert v0.unwrapped.last_strike[2:] == (0.0, 0.0)


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"model": "masse"}, "model must be"),
        ({"model": "spin", "table": Table()}, "model='spin' but the table"),
        ({"model": "spin", "table": {"model": "roll"}}, "give one model"),
        ({"model": "spin", "tip_limit": 0.0}, "tip_limit must lie"),
        ({"model": "spin", "tip_limit": 1.2}, "tip_limit must lie"),
        ({"model": "spin", "tip_limit": float("nan")}, "tip_limit must be finite"),
        ({"model": "spin", "tip_limit": "0.5"}, "tip_limit must be a number"),  # float() took it
        ({"model": "spin", "tip_limit": True}, "tip_limit must be a number"),  # as 1.0
        ({"model": "spin", "noise": (True, 0.05)}, r"noise must be \(sigma_angle"),
        ({"speed_range": ("1", 4.0)}, "speed_range must be a pair"),
        ({"model": "roll", "tip_limit": 0.5}, "tip_limit needs a spin table"),
        ({"model": "roll", "noise": (0.0, 0.0, 0.1)}, "roll table has no cue tip"),
        ({"model": "spin", "noise": (0.0, 0.0, -0.1)}, "must be >= 0"),
        ({"model": "spin", "noise": (0.1, 0.1, 0.1, 0.1)}, "sigma_tip"),
    ],
)
def test_bad_spin_arguments_raise(kwargs: dict, match: str) -> None:
    with pytest.raises(ValueError, match=match):
        PoolEnv(scene="one_ball", **kwargs)


def test_bad_tip_actions_raise_and_change_nothing() -> None:
    env = gym.make("pool_env/NineBallGame-v2")
    env.reset(seed=0)
    before = env.unwrapped.positions
    for bad in ([0, 0, 0, 0, 0, 0, np.nan, 0], [0, 0, 0, 0, 0, 0, 0, np.nan], [0.0] * 7,
                [0.0] * 9):  # fmt: skip
        with pytest.raises(ValueError, match=r"NaN|shape"):
            env.step(np.array(bad))
    np.testing.assert_array_equal(env.unwrapped.positions, before)
    assert env.unwrapped.shots == 0
    roll = PoolEnv(scene="one_ball", noise=(0.1, 0.1, 0.0), model="roll")
    assert roll.config.noise == (0.1, 0.1)  # a zero tip sigma on a roll table: fine


@pytest.mark.parametrize(("game", "width"), [("nine", 6), ("ten", 7), ("eight", 5)])
def test_rules_actions_keep_placement_and_pocket_where_they_were(game: str, width: int) -> None:
    scene = f"{game}_ball"
    roll, spin = (
        PoolEnv(scene=scene, game=game, model="roll"),
        PoolEnv(scene=scene, game=game, model="spin"),
    )
    assert roll.action_space.shape == (width,) and spin.action_space.shape == (width + 2,)
    assert spin.config.tip_columns == (width, width + 1)
    roll.reset(seed=4)
    spin.reset(seed=4)
    rng = np.random.default_rng(4)
    actions = rng.uniform(-1.1, 1.1, (200, width + 2))
    out = []
    for env, size in ((roll, width), (spin, width + 2)):
        state = env._state
        positions = np.repeat(state.positions, 200, axis=0)  # one table per action
        on, rack = (np.repeat(a, 200, axis=0) for a in (state.on_table, state.rack))
        ptrs = np.zeros((200, 3), dtype=np.uintp)
        rows = np.arange(200)
        params, pockets = env.config.params, env.config.table.pockets
        unplaced = place_in_hand(params, pockets, actions[:, :size], rows, positions, on, rack)
        shots = executed_rule_shots(params, pockets, actions[:, :size], rows, positions, on,
                                    ptrs, rack, np.zeros(200, np.bool_))  # fmt: skip
        out.append((positions, unplaced, shots[0][:, :2], shots[2]))
    for got, want in zip(out[1], out[0], strict=True):
        np.testing.assert_array_equal(got, want)  # placement, aim, speed, the calls
    assert len(set(out[1][3][:, 0].tolist())) == 6  # every pocket was called


def test_every_spin_id_is_its_roll_id_on_the_spin_table() -> None:
    for task in TASKS:
        if task in SPIN_ONLY:  # no roll twin (tests/envs/test_registration.py)
            assert roll_id(task) not in pool_env.ENV_IDS
            continue
        kwargs, steps = pool_env.ENV_IDS[spin_id(task)]
        roll_kwargs, roll_steps = pool_env.ENV_IDS[roll_id(task)]
        # A game's own table (snooker's preset): its roll twin keeps what the roll level reads.
        own = kwargs.get("table")
        if own is not None:
            assert roll_kwargs["table"] == {k: v for k, v in own.items() if k not in SPIN_PARAMS}
            roll_kwargs = {**roll_kwargs, "table": own}
        assert kwargs == {**roll_kwargs, "model": "spin"} and steps == roll_steps
        roll_kwargs = pool_env.ENV_IDS[roll_id(task)][0]
        spin = gym.make(spin_id(task)).unwrapped
        roll = PoolEnv(**roll_kwargs)
        assert spin.config.table.model == "spin" and roll.config.table.model == "roll"
        assert spin.action_space.shape[0] == roll.action_space.shape[0] + 2
