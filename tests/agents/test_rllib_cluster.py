"""RLlib on a two-node Ray cluster started on this machine: the sampling runs on the other node.

The head node has no CPU for actors, so the one EnvRunner (1 CPU) can only be placed on the
second node; the learner runs in the driver. One PPO iteration must sample there, change the
policy's weights, and send the new weights back to the EnvRunner on the second node. Every
node binds 127.0.0.1 (``tests/conftest.py``).
"""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np
import pytest

ray = pytest.importorskip(
    "ray", reason="needs the rllib extra (ray[rllib]): pip install -e '.[rllib]'"
)
pytest.importorskip("ray.rllib", reason="needs the rllib extra: pip install -e '.[rllib]'")

from ray.cluster_utils import Cluster  # noqa: E402

from agents.integrations.rllib_train import build_config, resolve_run  # noqa: E402

ONE = "pool_env/OneBallRoll-v1"


@pytest.fixture
def two_nodes() -> Iterator[tuple[str, str]]:
    """A head node without CPUs and a second node with one; the driver connected."""
    if ray.is_initialized():
        ray.shutdown()
    cluster = Cluster(
        initialize_head=True, head_node_args={"num_cpus": 0, "include_dashboard": False}
    )
    try:
        second = cluster.add_node(num_cpus=1)
        cluster.wait_for_nodes()
        ray.init(address=cluster.address, log_to_driver=False)
        yield cluster.head_node.node_id, second.node_id
    finally:
        ray.shutdown()
        cluster.shutdown()


def _where(runner) -> tuple[str, str, int]:  # type: ignore[no-untyped-def]
    """On an EnvRunner: the node it runs on, the env it steps and that env's tables."""
    env = runner.env.unwrapped
    return ray.get_runtime_context().get_node_id(), type(env).__name__, env.num_envs


def test_env_runners_sample_on_the_second_node_and_the_weights_change(
    two_nodes: tuple[str, str],
) -> None:
    head, second = two_nodes
    nodes = [n for n in ray.nodes() if n["Alive"]]
    assert {n["NodeID"] for n in nodes} == {head, second}
    assert {n["NodeManagerAddress"] for n in nodes} == {"127.0.0.1"}  # loopback only
    run = resolve_run(
        ONE,
        {
            "env_runners": 1,
            "n_envs": 8,
            "n_timesteps": 1,
            "sb3_n_envs": 8,  # a train batch of 32 x 8 = 256 steps
            "final_episodes": 0,
            "baselines": False,
            "algo_kwargs": {"n_steps": 32, "batch_size": 128, "n_epochs": 1},
        },
    )
    algo = build_config(run).build_algo()
    try:
        where = algo.env_runner_group.foreach_env_runner(_where, local_env_runner=False)
        assert where == [(second, "PoolVectorEnv", 8)]
        before = algo.learner_group.get_weights()["default_policy"]
        result = algo.train()
        after = algo.learner_group.get_weights()["default_policy"]
        (on_second,) = algo.env_runner_group.foreach_env_runner(
            lambda r: r.module.get_state(), local_env_runner=False
        )
    finally:
        algo.stop()
    assert result["env_runners"]["num_env_steps_sampled_lifetime"] >= 256
    changed = [k for k in before if not np.array_equal(before[k], after[k])]
    assert changed, "one PPO iteration left every weight as it was"
    # The EnvRunner on the second node now acts with the learner's new weights.
    assert on_second and set(on_second) <= set(after)
    for key, value in on_second.items():
        np.testing.assert_array_equal(value, after[key], err_msg=key)
    assert any(k in changed for k in on_second)
