"""The batched vector environment is num_envs single InterceptEnvs, step for step."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

from robotsoccer.envs import INTERCEPT_ID, InterceptVectorEnv
from robotsoccer.envs.intercept import InterceptEnv


def test_sub_env_i_plays_the_single_env_stream_of_seed_plus_i() -> None:
    n = 12
    vec = InterceptVectorEnv(n, ball_noise=0.05)
    singles = [InterceptEnv("soccer_server", ball_noise=0.05) for _ in range(n)]
    obs, info = vec.reset(seed=7)
    assert np.array_equal(obs, np.array([e.reset(seed=7 + i)[0] for i, e in enumerate(singles)]))
    assert vec.observation_space.contains(obs) and list(info["seed"]) == list(range(7, 7 + n))
    rng = np.random.default_rng(0)
    saves = 0.0
    for _ in range(3):
        actions = rng.uniform(-1.2, 1.2, (n, 1)).astype(np.float32)
        obs, rewards, terminated, truncated, info = vec.step(actions)
        played = [e.step(actions[i]) for i, e in enumerate(singles)]
        assert np.array_equal(rewards, [p[1] for p in played])
        assert list(info["label"]) == [p[4]["label"] for p in played]
        assert np.array_equal(info["final_obs"], np.array([p[0] for p in played]))
        assert terminated.all() and not truncated.any()
        assert np.array_equal(obs, np.array([e.reset()[0] for e in singles]))  # SAME_STEP
        saves += rewards.sum()
    assert 0 < saves < 3 * n


def test_seeds_per_sub_env_and_reproducibility() -> None:
    a, b = InterceptVectorEnv(3), InterceptVectorEnv(3)
    first = a.reset(seed=[5, 1, 9])[0]
    assert np.array_equal(first, b.reset(seed=[5, 1, 9])[0])
    assert np.array_equal(first[1], InterceptEnv("soccer_server").reset(seed=1)[0])
    step = np.full((3, 1), 0.3, dtype=np.float32)
    assert np.array_equal(a.step(step)[1], b.step(step)[1])
    with pytest.raises(ValueError, match="expected 3 seeds"):
        a.reset(seed=[1, 2])


def test_make_vec_gives_the_batched_env_on_the_server_and_a_sync_one_on_the_robots() -> None:
    vec = gym.make_vec(INTERCEPT_ID, num_envs=4, field_model="soccer_server")
    assert isinstance(vec, InterceptVectorEnv) and vec.num_envs == 4
    assert vec.action_space.shape == (4, 1) and vec.observation_space.shape == (4, 3)
    robots = gym.make_vec(INTERCEPT_ID, num_envs=2, field_model="robot_physics")
    assert isinstance(robots, gym.vector.SyncVectorEnv)
    obs, _ = robots.reset(seed=0)
    assert obs.shape == (2, 3)
    with pytest.raises(ValueError, match="no batched interception"):
        InterceptVectorEnv(2, field_model="robot_physics")


def test_step_needs_a_reset() -> None:
    with pytest.raises(RuntimeError, match="reset"):
        InterceptVectorEnv(2).step(np.zeros((2, 1), dtype=np.float32))
