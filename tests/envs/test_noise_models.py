"""FastFiz's execution noise by name (issue 35): each sigma is what the model says it is.

``noise="fastfiz"`` is the computer billiards championships' model (``pool_env.game.noise``):
sigma 0.125 degrees on the aim, 0.075 m/s on the speed and 0.5 mm on each tip offset, times
``k`` for ``("fastfiz", k)``. Here many tables each play one fixed action and the executed
strikes (``info["angle"]``, ``info["speed"]``, ``info["tip"]``) are measured: the sample
standard deviation of each must lie within the chi-square bounds of its sigma.
"""

from __future__ import annotations

import math

import gymnasium as gym
import numpy as np
import pytest

from pool_env import PoolEnv, PoolVectorEnv, Table
from pool_env.game.noise import FASTFIZ_ELEVATION_DEG, NOISE_MODELS

R = Table().ball_radius

#: The model's sigmas as its source gives them (degrees, m/s, metres), written out here so
#: that a wrong constant or unit in the package fails the test.
AIM_DEG, SPEED, TIP_M = 0.125, 0.075, 0.0005

#: Tables per measurement and rounds (a reset and one shot each): n = TABLES * ROUNDS draws.
TABLES, ROUNDS = 1000, 2

#: Standard normal quantile of the bounds: two-sided p ~ 6e-7 per check, so a correct
#: sigma fails about never, while a wrong unit or a missing multiple fails by far.
Z = 5.0

#: The action: absolute aim at +45 degrees (action 0.25 of the full turn), the middle speed
#: (2.475 m/s, far from the clip at 0), a centre-ball tip (far from the miscue circle).
AIM = math.pi / 4
SPEED_MID = (0.45 + 4.5) / 2


def chi2_bounds(n: int, z: float = Z) -> tuple[float, float]:
    """Bounds on ``s / sigma`` for ``n`` normal draws: the chi-square quantiles at ``+-z``.

    ``(n - 1) s^2 / sigma^2`` is chi-square with ``df = n - 1``; its quantiles come from the
    Wilson-Hilferty cube-root normal approximation (relative error under 1e-3 at this df).
    """
    df = n - 1
    c = 2.0 / (9.0 * df)

    def quantile(q: float) -> float:
        return df * (1.0 - c + q * math.sqrt(c)) ** 3

    return math.sqrt(quantile(-z) / df), math.sqrt(quantile(z) / df)


def executed(model: str, noise: object, tables: int = TABLES, rounds: int = ROUNDS) -> dict:
    """The executed angle, speed and (spin) tip of one fixed action on many tables.

    Returns:
        ``"angle"``, ``"speed"`` and on a spin table ``"side"`` and ``"vertical"``: ``(n,)``.
    """
    env = PoolVectorEnv(tables, scene="one_ball", aim="absolute", model=model, noise=noise)
    width = env.single_action_space.shape[0]
    action = np.zeros((tables, width), dtype=np.float32)
    action[:, 0] = 0.25
    out: dict[str, list[np.ndarray]] = {"angle": [], "speed": [], "side": [], "vertical": []}
    for r in range(rounds):
        env.reset(seed=35_000 + r * tables)  # table i: seed + i, every one its own stream
        _, _, _, _, info = env.step(action)
        assert info["_angle"].all()
        out["angle"].append(info["angle"])
        out["speed"].append(info["speed"])
        if model == "spin":
            tips = np.array(info["tip"].tolist())
            out["side"].append(tips[:, 0])
            out["vertical"].append(tips[:, 1])
    env.close()
    return {k: np.concatenate(v) for k, v in out.items() if v}


def expected_sigmas(model: str, k: float) -> dict[str, float]:
    sigmas = {"angle": math.radians(AIM_DEG) * k, "speed": SPEED * k}
    if model == "spin":
        sigmas["side"] = sigmas["vertical"] = TIP_M / R * k
    return sigmas


@pytest.mark.parametrize("model", ["spin", "roll"])
@pytest.mark.parametrize(("noise", "k"), [("fastfiz", 1.0), (("fastfiz", 5), 5.0)])
def test_each_executed_sigma_is_the_models(model: str, noise: object, k: float) -> None:
    draws = executed(model, noise)
    centres = {"angle": AIM, "speed": SPEED_MID, "side": 0.0, "vertical": 0.0}
    sigmas = expected_sigmas(model, k)
    assert set(draws) == set(sigmas)  # a roll table: the aim and the speed, no tip
    low, high = chi2_bounds(TABLES * ROUNDS)
    for name, sigma in sigmas.items():
        errors = draws[name] - centres[name]
        n = errors.size
        mean, std = float(errors.mean()), float(errors.std(ddof=1))
        assert abs(mean) < Z * sigma / math.sqrt(n), (name, mean, sigma)
        assert low < std / sigma < high, (name, std, sigma, (low, high))
    # The components are drawn independently: no correlation beyond chance (|r| < Z / sqrt n).
    names = list(sigmas)
    corr = np.corrcoef([draws[name] for name in names])
    off = np.abs(corr[np.triu_indices(len(names), 1)])
    assert off.max() < Z / math.sqrt(TABLES * ROUNDS), dict(zip(names, corr.tolist(), strict=True))


@pytest.mark.parametrize("model", ["spin", "roll"])
def test_multiple_zero_is_no_noise(model: str) -> None:
    """``("fastfiz", 0)`` is ``noise=None``: the action played as decoded, bit for bit."""
    assert PoolEnv(scene="one_ball", model=model, noise=("fastfiz", 0)).config.noise is None
    draws = executed(model, ("fastfiz", 0), tables=50, rounds=1)
    quiet = executed(model, None, tables=50, rounds=1)
    assert set(draws) == set(quiet)
    for name, values in draws.items():
        np.testing.assert_array_equal(values, quiet[name])
    np.testing.assert_allclose(draws["angle"], AIM, rtol=1e-15)
    np.testing.assert_allclose(draws["speed"], SPEED_MID, rtol=1e-15)
    if model == "spin":
        assert not draws["side"].any() and not draws["vertical"].any()


def test_the_parsed_sigmas_and_what_is_not_applied() -> None:
    """The config holds the sigmas in the env's units; the elevation has no action to move."""
    spin = PoolEnv(model="spin", noise="fastfiz").config.noise
    assert spin == pytest.approx((math.radians(0.125), 0.075, 0.0005 / R), rel=1e-15)
    five = PoolEnv(model="spin", noise=("fastfiz", 5)).config.noise
    assert five == pytest.approx(tuple(5 * s for s in spin), rel=1e-15)
    roll = PoolEnv(noise="fastfiz", model="roll").config.noise
    assert roll == pytest.approx(spin[:2], rel=1e-15)
    small = Table(model="spin", ball_radius=0.026)  # the tip's sigma follows R: 0.5 mm of it
    assert PoolEnv(table=small, noise="fastfiz").config.noise[2] == pytest.approx(0.0005 / 0.026)
    assert FASTFIZ_ELEVATION_DEG == 0.1 and list(NOISE_MODELS) == ["fastfiz"]
    assert PoolEnv(noise=["fastfiz", 2], model="roll").config.noise == pytest.approx(
        (2 * spin[0], 0.15)
    )


@pytest.mark.parametrize(
    "env_id", ["pool_env/OneBall-v1", "pool_env/NineBallGameRoll-v2", "pool_env/EightBallGame-v1"]
)
def test_every_front_takes_the_model_by_name(env_id: str) -> None:
    single = gym.make(env_id, noise=("fastfiz", 5)).unwrapped.config
    vector = gym.make_vec(env_id, num_envs=2, noise=("fastfiz", 5))
    assert vector.unwrapped.config.noise == single.noise
    assert len(single.noise) == (3 if single.spin else 2)
    vector.close()
    if single.game == "solitaire":
        return
    pytest.importorskip("pettingzoo", reason="needs the multiagent extra")
    from pool_env.envs.multiagent import PoolDuelEnv, VersusPolicyEnv

    model = "spin" if single.spin else "roll"
    duel = PoolDuelEnv(single.game, model=model, noise=("fastfiz", 5))
    versus = VersusPolicyEnv(game=single.game, model=model, noise=("fastfiz", 5))
    assert duel.config.noise == versus.duel.config.noise == single.noise


@pytest.mark.parametrize(
    ("noise", "match"),
    [
        ("fastfizz", "unknown noise model 'fastfizz'"),
        ("FastFiz", "unknown noise model 'FastFiz'"),
        (("fastfiz", -1), "k must be >= 0"),
        (("fastfiz", "x"), "k must be a number, got 'x'"),
        (("fastfiz", True), "k must be a number"),
        (("fastfiz", math.inf), "k must be finite"),
        (("fastfiz",), r"takes one multiple k >= 0"),
        (("fastfiz", 1, 2), r"takes one multiple k >= 0"),
        (("fastfizz", 1), "unknown noise model 'fastfizz'"),
    ],
)
def test_bad_spellings_name_the_problem(noise: object, match: str) -> None:
    for model in ("spin", "roll"):
        with pytest.raises(ValueError, match=match):
            PoolEnv(model=model, noise=noise)
    with pytest.raises(ValueError, match=match):
        gym.make("pool_env/NineBallGame-v2", noise=noise)
