"""Same-step autoreset for one-shot episodes, and a CleanRL-style PPO loop on the env stack."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.vector import AutoresetMode

from agents.vec.gym_vec import SameStepEpisodeStatistics, make_cleanrl_envs, make_vec
from agents.vec.native_vec import make_native_vec_env

ONE = "pool_env/OneBallRoll-v1"


def _episodes(envs: gym.vector.VectorEnv, steps: int) -> int:
    envs.reset(seed=0)
    ended = 0
    for _ in range(steps):
        *_, terminated, truncated, _ = envs.step(envs.action_space.sample())
        ended += int(np.sum(terminated | truncated))
    return ended


def test_one_shot_episodes_per_vector_step_by_autoreset_mode() -> None:
    n, steps = 16, 20
    # OneBallRoll-v1 ends every episode after one shot. Next-step (Gymnasium's default) spends
    # every other step resetting: 0.5 episodes per table per step; same-step: 1.0.
    default = gym.make_vec(ONE, num_envs=n, vectorization_mode="vector_entry_point")
    assert default.metadata["autoreset_mode"] == AutoresetMode.NEXT_STEP
    assert _episodes(default, steps) / (n * steps) == 0.5
    assert _episodes(make_vec(ONE, n), steps) / (n * steps) == 1.0
    sb3 = make_native_vec_env(ONE, n, 0)  # the SB3 adapter resets in the same step too
    sb3.reset()
    ended = 0
    for _ in range(steps):
        sb3.step_async(np.zeros((n, 2), np.float32))
        ended += int(sb3.step_wait()[2].sum())
    assert ended / (n * steps) == 1.0


def test_same_step_statistics_count_each_episode_with_its_own_reward() -> None:
    n = 8
    envs = SameStepEpisodeStatistics(make_vec(ONE, n))
    raw = make_vec(ONE, n)  # the same tables, unwrapped
    envs.reset(seed=5)
    raw.reset(seed=5)
    rng = np.random.default_rng(0)
    for _ in range(6):
        actions = rng.uniform(-1, 1, (n, 2)).astype(np.float32)
        _, rewards, *_, info = envs.step(actions)
        _, raw_rewards, *_ = raw.step(actions)
        np.testing.assert_array_equal(rewards, raw_rewards)
        assert info["_episode"].all()
        np.testing.assert_array_equal(info["episode"]["r"], raw_rewards)
        np.testing.assert_array_equal(info["episode"]["l"], np.ones(n))
    # Multi-shot episodes: the return is the sum of the episode's shots.
    multi = SameStepEpisodeStatistics(make_vec("pool_env/PoolRoll-v1", 4, max_shots=3))
    multi.reset(seed=1)
    totals = np.zeros(4)
    for _ in range(3):
        _, rewards, _, truncated, info = multi.step(np.zeros((4, 2), np.float32))
        totals += rewards
    assert truncated.all()  # no table cleared 3 balls: each episode is the 3 shots
    assert info["_episode"].all()
    np.testing.assert_array_equal(info["episode"]["r"], totals)
    np.testing.assert_array_equal(info["episode"]["l"], np.full(4, 3))
    with pytest.raises(ValueError, match="SAME_STEP"):
        SameStepEpisodeStatistics(make_vec(ONE, 2, autoreset_mode="NextStep"))


def test_cleanrl_style_ppo_loop_runs_on_the_env_stack() -> None:
    """CleanRL ppo_continuous_action.py's loop, shrunk: rollout, GAE, clipped PPO updates."""
    torch = pytest.importorskip("torch")
    from torch import nn
    from torch.distributions.normal import Normal

    torch.set_num_threads(1)
    torch.manual_seed(0)
    num_envs, num_steps, gamma, gae_lambda, updates = 32, 8, 0.0, 0.0, 3
    envs = make_cleanrl_envs(ONE, num_envs, gamma=gamma)
    obs_dim = envs.single_observation_space.shape[0]
    act_dim = envs.single_action_space.shape[0]

    def mlp(out: int, std: float) -> nn.Sequential:
        layers = [nn.Linear(obs_dim, 64), nn.Tanh(), nn.Linear(64, 64), nn.Tanh()]
        last = nn.Linear(64, out)
        nn.init.orthogonal_(last.weight, std)
        return nn.Sequential(*layers, last)

    critic, actor_mean = mlp(1, 1.0), mlp(act_dim, 0.01)
    actor_logstd = nn.Parameter(torch.zeros(1, act_dim))
    params = [*critic.parameters(), *actor_mean.parameters(), actor_logstd]
    optimizer = torch.optim.Adam(params, lr=3e-4, eps=1e-5)
    before = [p.detach().clone() for p in params]

    next_obs, _ = envs.reset(seed=0)
    next_obs = torch.as_tensor(next_obs, dtype=torch.float32)
    next_done = torch.zeros(num_envs)
    episodes, returns = 0, []
    for _ in range(updates):
        obs_b, act_b, logp_b, rew_b, done_b, val_b = [], [], [], [], [], []
        for _ in range(num_steps):
            with torch.no_grad():
                mean = actor_mean(next_obs)
                dist = Normal(mean, actor_logstd.expand_as(mean).exp())
                action = dist.sample()
                value = critic(next_obs).flatten()
            obs_b.append(next_obs)
            done_b.append(next_done)
            act_b.append(action)
            logp_b.append(dist.log_prob(action).sum(1))
            val_b.append(value)
            obs, reward, terminations, truncations, infos = envs.step(action.numpy())
            rew_b.append(torch.as_tensor(reward, dtype=torch.float32))
            next_obs = torch.as_tensor(obs, dtype=torch.float32)
            next_done = torch.as_tensor(
                np.logical_or(terminations, truncations), dtype=torch.float32
            )
            if "episode" in infos:  # CleanRL's logging of finished episodes
                mask = infos["_episode"]
                episodes += int(mask.sum())
                returns += infos["episode"]["r"][mask].tolist()
        with torch.no_grad():  # GAE, as CleanRL (same-step: next_done closes each episode)
            next_value = critic(next_obs).flatten()
            advantages = torch.zeros(num_steps, num_envs)
            last = torch.zeros(num_envs)
            for t in reversed(range(num_steps)):
                nonterminal = 1.0 - (done_b[t + 1] if t + 1 < num_steps else next_done)
                next_v = val_b[t + 1] if t + 1 < num_steps else next_value
                delta = rew_b[t] + gamma * next_v * nonterminal - val_b[t]
                last = delta + gamma * gae_lambda * nonterminal * last
                advantages[t] = last
            returns_b = advantages + torch.stack(val_b)
        b_obs, b_act = torch.cat(obs_b), torch.cat(act_b)
        b_logp, b_adv, b_ret = torch.cat(logp_b), advantages.flatten(), returns_b.flatten()
        for _ in range(2):
            for mb in torch.randperm(num_envs * num_steps).split(64):
                mean = actor_mean(b_obs[mb])
                dist = Normal(mean, actor_logstd.expand_as(mean).exp())
                ratio = (dist.log_prob(b_act[mb]).sum(1) - b_logp[mb]).exp()
                adv = (b_adv[mb] - b_adv[mb].mean()) / (b_adv[mb].std() + 1e-8)
                pg = torch.max(-adv * ratio, -adv * ratio.clamp(0.8, 1.2)).mean()
                v_loss = 0.5 * ((critic(b_obs[mb]).flatten() - b_ret[mb]) ** 2).mean()
                loss = pg + 0.5 * v_loss - 0.0 * dist.entropy().sum(1).mean()
                optimizer.zero_grad()
                loss.backward()
                nn.utils.clip_grad_norm_(params, 0.5)
                optimizer.step()
    envs.close()
    # Same-step: every table ends one episode per step, and each logged return is a shot's
    # raw reward (pot +1, scratch -1, both 0), not the normalized one the learner saw.
    assert episodes == updates * num_steps * num_envs
    assert set(returns) <= {-1.0, 0.0, 1.0}
    assert any(not torch.equal(b, p.detach()) for b, p in zip(before, params, strict=True))
