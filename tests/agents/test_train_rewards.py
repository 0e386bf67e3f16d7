"""Training-time reward terms (``train_rewards``): the training envs only, never the evaluations."""

from __future__ import annotations

import numpy as np
import pytest

import train
from agents.learned.envs import make_env
from agents.training.run_config import TrainConfig, resolve_config, training_env_kwargs
from agents.training.train_lib import PeriodicEval, make_vec

#: OneBall-v1's layout 0 hit full and hard at the centre: the ball drops and the cue ball
#: follows it in (the env's docstring): reward_pot + reward_scratch.
POT_AND_SCRATCH = np.array([0.0, 1.0, 0.0, 0.0], dtype=np.float32)


@pytest.mark.parametrize("vec", ["native", "dummy"])
def test_a_scratch_penalty_pays_in_training_and_not_in_evaluation(vec: str) -> None:
    config = TrainConfig(
        env_id="pool_env/OneBall-v1", n_envs=1, vec=vec, seed=0,
        env_kwargs={"observation": "shots"}, train_rewards={"scratch": -3.0},
    )  # fmt: skip
    venv = make_vec(config)
    evaluation = make_env(config.env_id, config.env_kwargs, config.wrapper)
    try:
        venv.reset()
        _, rewards, _, infos = venv.step(POT_AND_SCRATCH[None])
        assert infos[0]["potted"] == (1,) and infos[0]["scratch"]
        assert rewards[0] == pytest.approx(1.0 - 3.0)  # the pot's +1 and the training -3
        evaluation.reset(seed=0)
        _, reward, *_, info = evaluation.step(POT_AND_SCRATCH)
        assert info["potted"] == (1,) and info["scratch"]
        assert reward == pytest.approx(0.0)  # the env's own: +1 - 1
    finally:
        venv.close()
        evaluation.close()


def test_the_periodic_evaluation_plays_the_envs_own_reward() -> None:
    config = TrainConfig(env_id="pool_env/OneBall-v1", train_rewards={"scratch": -3.0})
    callback = PeriodicEval(config, [])
    try:
        assert callback.env.unwrapped.config.rewards["scratch"] == -1.0
    finally:
        callback.env.close()
    assert training_env_kwargs(config) == {"reward_scratch": -3.0}
    assert config.env_kwargs == {}  # not changed by building the training keywords


def test_a_recipe_names_its_training_rewards_and_the_command_line_overrides() -> None:
    given = resolve_config("pool_env/OneBall-v1", "ppo", {"train_rewards": {"scratch": -2.0}})
    assert given.train_rewards == {"scratch": -2.0}
    assert "train_rewards" not in given.algo_kwargs  # a run key, not PPO's argument


@pytest.mark.parametrize(
    ("rewards", "words"),
    [
        ({"scratch": "a lot"}, "train_rewards scratch: 'a lot' is not a number"),
        ({"scratch": True}, "want a term name and a number"),
        ([-3.0], "must map reward terms to scales"),
    ],
)
def test_bad_training_rewards_are_named(rewards: object, words: str) -> None:
    with pytest.raises(ValueError, match=words):
        training_env_kwargs(TrainConfig(train_rewards=rewards))  # type: ignore[arg-type]


@pytest.mark.parametrize(
    ("text", "words"),
    [
        ("{scatch: -3}", "no reward term 'scatch'"),
        ("[-3]", "--train-rewards must be a YAML mapping"),
        ("{scratch: [", "--train-rewards '{scratch: [' is not YAML"),
    ],
)
def test_the_command_line_refuses_a_bad_training_reward(
    text: str, words: str, capsys: pytest.CaptureFixture[str]
) -> None:
    with pytest.raises(SystemExit) as exit_info:
        train.main(["--train-rewards", text, "--no-baselines"])
    assert exit_info.value.code == 2
    assert words in capsys.readouterr().err
