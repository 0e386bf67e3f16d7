"""What a config refuses, or takes, when it is made: never a step that then fails or lies.

Issue 49 (second round): a bare rules section names its game; a two-player rack refuses the
one-agent run-out mode; a game named twice must be one game; a section of another game is
refused; a config copies what it is given; and the speed ranges and the noise are refused
when the simulator could not strike what they ask.
"""

from __future__ import annotations

import copy
import math
import pickle
import re
from dataclasses import dataclass

import numpy as np
import pytest

from pool_env import PoolEnv, PoolVectorEnv, Table, default_config
from pool_env.game.checks import strike_speed_limit
from pool_env.game.config import make_config
from pool_env.game.games.wpa.section import WpaRules
from pool_env.game.noise import MAX_NORMAL_DRAW, fastfiz_sigmas
from pool_env.game.ruleset import RulesSection
from pool_env.game.sections import PoolConfig
from pool_env.sim.inputs import max_speed

# -- B: a bare rules section names its game ----------------------------------------------


def test_a_bare_rules_section_is_its_games_rules_at_their_defaults() -> None:
    config = default_config(rules=RulesSection(game="nine"), scene="nine_ball", model="roll")
    assert config.rules == WpaRules(game="nine")
    assert PoolConfig(rules=RulesSection(game="eight")).rules == WpaRules(game="eight")
    env = PoolEnv(rules=RulesSection(game="nine"), scene="nine_ball", model="roll")
    assert env.config.game == "nine" and env.config.action_size == 6
    env.reset(seed=0)
    assert env.rack["break"]  # 9-ball's rack state: the break comes first


# -- C: a game named twice, a section of another game, the duel's end_on_foul -----------------


@pytest.mark.parametrize("rules", [{"game": "eight"}, WpaRules(game="eight")])
def test_a_game_and_rules_of_another_game_are_refused_in_either_form(rules: object) -> None:
    with pytest.raises(ValueError, match=r"game='nine' but rules=.* names game 'eight'"):
        default_config(game="nine", rules=rules)
    assert default_config(game="eight", rules=rules).rules.game == "eight"  # one game: fine


def test_a_section_of_another_game_is_refused_not_dropped() -> None:
    with pytest.raises(ValueError, match=r"game='solitaire' takes a RulesSection.*WpaRules"):
        default_config(rules=WpaRules(game="solitaire", end_on_foul=True))

    @dataclass(frozen=True)
    class OtherRules(RulesSection):
        fouls: int = 3

    with pytest.raises(ValueError, match=r"game='nine' takes a WpaRules.*OtherRules is no game"):
        PoolConfig(rules=OtherRules(game="nine"))


@pytest.mark.parametrize("front", ["PoolDuelEnv", "VersusPolicyEnv"])
def test_the_two_player_fronts_refuse_end_on_foul(front: str) -> None:
    multiagent = pytest.importorskip("pool_env.envs.multiagent", reason="needs pettingzoo")
    make = getattr(multiagent, front)
    with pytest.raises(ValueError, match="a foul passes the table to the opponent"):
        make(game="nine", end_on_foul=True)
    with pytest.raises(ValueError, match="end_on_foul=True is the one-agent run-out mode"):
        make(config=default_config(game="eight", scene="eight_ball", end_on_foul=True))
    assert PoolEnv(game="nine", scene="nine_ball", end_on_foul=True).config.rules.end_on_foul


# -- D: a config copies what it is given; a wrong type is named as one -----------------------


def test_a_config_keeps_copies_of_the_callers_arrays_and_dicts() -> None:
    layout = np.array([[0.5, 0.6], [1.5, 0.6]])
    speeds = [0.5, 3.0]
    table = {"length": 2.54, "width": 1.27}
    scales = {"pot": 2.0}
    config = default_config(scene=layout, speed_range=speeds, table=table, rewards=scales)
    layout[1] = (2.0, 1.0)
    speeds[1] = 1e6
    table["length"] = 3.0
    scales["pot"] = -5.0
    env = PoolEnv(config=config)  # made after the caller's changes: none of them reached it
    env.reset(seed=0)
    np.testing.assert_array_equal(env.positions, [[0.5, 0.6], [1.5, 0.6]])
    assert env.config.speed_range == (0.5, 3.0) and env.config.table.length == 2.54
    assert env.config.rewards["pot"] == 2.0
    with pytest.raises(ValueError, match="read-only"):
        config.task.scene[0, 0] = 0.0
    with pytest.raises(TypeError):
        config.table.table["length"] = 3.0  # type: ignore[index]
    with pytest.raises(TypeError):
        env.config.rewards["pot"] = 9.0  # type: ignore[index]
    with pytest.raises(ValueError, match="read-only"):
        env.config.params[0] = 1.0


def test_a_section_given_as_a_mapping_is_copied_too() -> None:
    layout = np.array([[0.5, 0.6], [1.5, 0.6]])
    config = default_config(task={"scene": layout}, rules={"game": "solitaire"})
    layout[0] = (1.0, 1.0)
    assert config.task.scene.tolist() == [[0.5, 0.6], [1.5, 0.6]]
    break_range = [8.0, 11.0]
    rules = WpaRules(game="nine", break_speed_range=break_range)  # type: ignore[arg-type]
    break_range[1] = 1e6
    assert rules.break_speed_range == (8.0, 11.0)


def test_a_frozen_config_survives_gymnasiums_copies_and_pickles() -> None:
    """gym.make deep-copies its keywords, AsyncVectorEnv pickles them."""
    layout = np.array([[0.5, 0.6], [1.5, 0.6]])
    config = default_config(table={"length": 2.54}, rewards={"pot": 2.0}, scene=layout)
    for copied in (copy.deepcopy(config), pickle.loads(pickle.dumps(config))):
        assert copied.table == config.table and copied.rewards == config.rewards
        np.testing.assert_array_equal(copied.task.scene, config.task.scene)
    assert make_config(config).rewards["pot"] == 2.0


@pytest.mark.parametrize(("name", "kind"), [("task", "TaskSection"), ("rewards", "RewardsSection")])
def test_a_section_of_the_wrong_type_is_named_as_such(name: str, kind: str) -> None:
    message = rf"^{name} must be a {kind} or a mapping of its keys, got 5$"
    with pytest.raises(ValueError, match=message):
        PoolEnv(**{name: 5})


# -- E: ranges and noise the simulator could not strike --------------------------------------


def test_the_largest_normal_draw_bounds_the_kernels_sampler() -> None:
    """The bound is the ziggurat's edge plus its tail's, fed doubles below 1 (noise.py)."""
    from numba.np.random._constants import ki_double, wi_double, ziggurat_nor_r

    bound = ziggurat_nor_r + math.sqrt(2.0 * 53.0 * math.log(2.0))
    assert bound <= MAX_NORMAL_DRAW < bound + 0.01
    inside = max(float(k) * float(w) for k, w in zip(ki_double, wi_double, strict=True))
    assert inside <= ziggurat_nor_r  # a draw inside the ziggurat stays below its edge


@pytest.mark.parametrize("model", ["roll", "spin"])
def test_the_speed_ceiling_is_the_simulators_limit_over_the_strike(model: str) -> None:
    table = Table(model=model)
    env = PoolEnv(scene="one_ball", model=model)
    limit = strike_speed_limit(table, env.config.tip_limit)
    if model == "roll":
        assert limit == pytest.approx(max_speed(table), rel=1e-11)
    else:  # the energy with the spin at the tip limit: v^2 (1 + 2.5 c^2), c the contact offset
        contact = env.config.tip_limit / (1.0 + table.cue_tip_radius / table.ball_radius)
        expected = max_speed(table) / math.sqrt(1.0 + 2.5 * contact**2)
        assert limit == pytest.approx(expected, rel=1e-11)
        assert limit < max_speed(table) * 0.8


@pytest.mark.parametrize("model", ["roll", "spin"])
def test_a_speed_range_at_the_ceiling_plays_and_one_beyond_is_refused(model: str) -> None:
    table = Table(model=model)
    env = PoolEnv(scene="one_ball", model=model)
    limit = strike_speed_limit(table, env.config.tip_limit)
    with pytest.raises(ValueError, match=r"speed_range=\(0\.45, 2000\): its top speed must be"):
        PoolEnv(speed_range=(0.45, 2000), model=model)
    with pytest.raises(ValueError, match=rf"at most {limit:.6g} m/s"):
        PoolEnv(speed_range=(0.45, limit * (1 + 1e-9)), model=model)
    fast = PoolVectorEnv(8, scene="one_ball", model=model, speed_range=(0.45, limit))
    fast.reset(seed=0)
    actions = np.ones((8, fast.config.action_size), dtype=np.float32)
    if model == "spin":  # the tip on the miscue circle, every direction: the spin's worst
        angles = np.linspace(0.0, 2.0 * np.pi, 8, endpoint=False)
        actions[:, 2], actions[:, 3] = np.cos(angles), np.sin(angles)
    *_, info = fast.step(actions)  # every shot at the top speed: the simulator takes them all
    np.testing.assert_allclose(info["speed"], limit, rtol=1e-12)


def test_a_break_speed_range_beyond_the_ceiling_is_refused_where_it_is_given() -> None:
    limit = strike_speed_limit(Table(), None)
    with pytest.raises(ValueError, match=r"break_speed_range=\(8, 2000\): its top speed must"):
        PoolEnv(game="nine", scene="nine_ball", break_speed_range=(8, 2000), model="roll")
    with pytest.raises(ValueError, match=r"break_speed_range=\(8, 2000\)"):
        PoolVectorEnv(2, game="nine", scene="nine_ball", break_speed_range=(8, 2000), model="roll")
    PoolEnv(game="nine", scene="nine_ball", break_speed_range=(8, limit), model="roll")


def test_noise_whose_draws_could_pass_the_ceiling_is_refused_naming_it() -> None:
    table = Table()
    top = strike_speed_limit(table, None)
    largest = (top - 4.5) / MAX_NORMAL_DRAW  # the default speed range's top is 4.5 m/s
    k_max = largest / fastfiz_sigmas(table)[1]
    with pytest.raises(ValueError, match=rf"noise=\('fastfiz', 1000\).*k at most {k_max:.6g}"):
        PoolEnv(noise=("fastfiz", 1000), model="roll")
    with pytest.raises(ValueError, match=rf"noise=\(0\.1, 40\.0\).*at most {largest:.6g} m/s"):
        PoolEnv(noise=(0.1, 40.0), model="roll")
    below = largest * (1 - 1e-9)  # one rounding of the bound's own arithmetic under it
    assert PoolEnv(noise=(0.1, below), model="roll").config.noise == (0.1, below)
    # a break's top speed counts too: the same sigma is refused under the rules
    with pytest.raises(ValueError, match="break_speed_range's top speed 12 m/s"):
        PoolEnv(game="nine", scene="nine_ball", noise=(0.1, below), model="roll")


def test_an_angle_sigma_past_half_a_turn_is_refused() -> None:
    with pytest.raises(ValueError, match=r"noise=\('fastfiz', 5000\): k must be at most 1440"):
        PoolEnv(noise=("fastfiz", 5000))
    # The message does not promise 1440: at the default speeds the speed sigma bounds k lower,
    # and that bound, named in its own message, is one k accepted and the next refused.
    with pytest.raises(ValueError, match=r"k at most (\d+\.?\d*)") as refused:
        PoolEnv(noise=("fastfiz", 1440))
    largest = float(re.search(r"k at most (\d+\.?\d*)", str(refused.value)).group(1))
    assert 100 < largest < 1440
    PoolEnv(noise=("fastfiz", 0.999 * largest))
    with pytest.raises(ValueError, match=r"the angle's sigma must lie in \[0, pi\]"):
        PoolEnv(noise=(3.5, 0.1))
    assert PoolEnv(noise=(math.pi, 0.1)).config.noise == (math.pi, 0.1)


def test_a_two_player_front_refuses_a_game_its_rules_contradict() -> None:
    pytest.importorskip("pettingzoo", reason="needs the multiagent extra")
    from pool_env.envs.multiagent import PoolDuelEnv, VersusPolicyEnv

    with pytest.raises(ValueError, match=r"game='eight' but rules=.* names game 'ten'"):
        PoolDuelEnv("eight", rules={"game": "ten"}, scene="ten_ball")
    with pytest.raises(ValueError, match=r"game='nine' but rules=.* names game 'eight'"):
        VersusPolicyEnv(game="nine", rules=WpaRules(game="eight"), scene="eight_ball")
    # The rules alone name the game: its id's defaults (scene, shot limit) follow it.
    assert PoolDuelEnv(rules={"game": "ten"}).config.n_object_balls == 10


def test_another_games_rules_options_are_refused_not_dropped() -> None:
    nine = default_config(game="nine", scene="nine_ball", end_on_foul=True)
    with pytest.raises(ValueError, match=r"game='solitaire' replaces game 'nine'.*end_on_foul"):
        PoolEnv(config=nine, game="solitaire", scene="random")
    # A game with the same rules section keeps them; defaults carry over without a word.
    assert PoolEnv(config=nine, game="eight", scene="eight_ball").config.rules.end_on_foul
    plain = default_config(game="nine", scene="nine_ball")
    assert PoolEnv(config=plain, game="solitaire", scene="random").config.rules.game == "solitaire"
