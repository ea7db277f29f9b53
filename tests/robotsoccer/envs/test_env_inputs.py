"""Environments refuse what they cannot play: NaN, infinite or misshapen actions, bad seeds."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

from robotsoccer.envs import INTERCEPT_ID, InterceptVectorEnv, pass_parallel_env
from robotsoccer.envs.intercept import InterceptEnv

BAD_SEEDS = [-1, 2**64, 10**30, 1.5, "3", True, np.float64(2.0)]


@pytest.mark.parametrize(
    "actions",
    [
        np.full((4, 1), np.nan),
        np.array([[0.1], [np.inf], [0.0], [0.0]]),
        np.zeros(8),
        np.zeros((0,)),
        np.zeros((4, 2)),
        np.zeros((2, 2)),
        "left",
    ],
    ids=["nan", "inf", "(8,)", "(0,)", "(4,2)", "(2,2)", "text"],
)
def test_the_vector_env_refuses_bad_actions_and_keeps_its_episodes(actions: object) -> None:
    vec = InterceptVectorEnv(4)
    vec.reset(seed=3)
    with pytest.raises(ValueError, match="actions"):
        vec.step(actions)
    again = InterceptVectorEnv(4)
    again.reset(seed=3)
    ok = np.zeros((4, 1), dtype=np.float32)
    assert np.array_equal(vec.step(ok)[0], again.step(ok)[0])  # nothing was played
    flat, boxed = InterceptVectorEnv(4), InterceptVectorEnv(4)
    flat.reset(seed=3)
    boxed.reset(seed=3)
    assert np.array_equal(flat.step(np.zeros(4))[0], boxed.step(ok)[0])  # (4,) reads as (4, 1)


def test_the_nan_action_of_the_issue_is_a_value_error() -> None:
    vec = gym.make_vec(INTERCEPT_ID, num_envs=1, field_model="soccer_server")
    vec.reset(seed=0)
    with pytest.raises(ValueError, match="finite"):
        vec.step([[float("nan")]])


@pytest.mark.parametrize("field", ["soccer_server", "robot_physics"])
def test_the_single_env_refuses_bad_actions(field: str) -> None:
    env = InterceptEnv(field)
    env.reset(seed=0)
    for bad in (np.array([np.nan]), np.array([-np.inf]), np.zeros(2), np.zeros((1, 1, 2)), []):
        with pytest.raises(ValueError, match="actions"):
            env.step(bad)
    env.step(np.zeros(1, dtype=np.float32))  # the episode waited at its decision


def test_the_sync_vector_env_on_the_robots_refuses_a_misshapen_batch() -> None:
    vec = gym.make_vec(INTERCEPT_ID, num_envs=2, field_model="robot_physics")
    vec.reset(seed=0)
    with pytest.raises(ValueError, match="shape"):
        vec.step(np.zeros(8))
    with pytest.raises(ValueError, match="finite"):
        vec.step(np.array([[0.0], [np.nan]]))


@pytest.mark.parametrize("seed", BAD_SEEDS, ids=repr)
def test_seeds_follow_gymnasiums_rule_in_every_env(seed: object) -> None:
    with pytest.raises(ValueError, match="seed"):
        InterceptEnv("soccer_server").reset(seed=seed)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="seed"):
        InterceptVectorEnv(2).reset(seed=seed)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="seed"):
        InterceptVectorEnv(2).reset(seed=[0, seed])  # type: ignore[list-item]
    with pytest.raises(ValueError, match="seed"):
        pass_parallel_env("soccer_server").reset(seed=seed)  # type: ignore[arg-type]


def test_the_largest_seeds_play_the_single_envs_trials() -> None:
    top = 2**64 - 2
    vec = InterceptVectorEnv(2)
    obs, info = vec.reset(seed=top)
    assert [int(s) for s in info["seed"]] == [top, top + 1]
    singles = [InterceptEnv("soccer_server").reset(seed=s)[0] for s in (top, top + 1)]
    assert np.array_equal(obs, np.array(singles))
    with pytest.raises(ValueError, match="2\\*\\*64"):
        InterceptVectorEnv(3).reset(seed=top)  # top + 2 is not a seed
    pass_parallel_env("soccer_server").reset(seed=2**64 - 1)
