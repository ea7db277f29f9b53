"""The layer-1 Gymnasium environment: Gymnasium's checker, seeds, and the drill it poses."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

from robotsoccer.envs import INTERCEPT_ID, InterceptEnv
from robotsoccer.runs.runner import TrialSpec, run_trial

FIELDS = ["soccer_server", "robot_physics"]


@pytest.mark.filterwarnings("ignore:.*symmetric and normalized")  # TA is in radians, on purpose
@pytest.mark.parametrize("field_model", FIELDS)
def test_gymnasiums_checker_passes(field_model: str) -> None:
    env = gym.make(INTERCEPT_ID, field_model=field_model).unwrapped
    check_env(env, skip_render_check=True)


@pytest.mark.parametrize("field_model", FIELDS)
def test_ta_zero_ends_each_episode_as_the_straight_defenders_trial(field_model: str) -> None:
    env = InterceptEnv(field_model)
    spec = TrialSpec(drill="intercept", field_model=field_model, seed=11).with_options(
        behaviour="straight"
    )
    obs, info = env.reset(seed=11)
    for _ in range(6):
        _, reward, terminated, truncated, end = env.step(np.zeros(1, dtype=np.float32))
        assert terminated and not truncated
        trial = run_trial(spec, info["trial"])
        assert (end["label"], end["ticks"]) == (trial.label, trial.ticks)
        assert reward == (1.0 if trial.label == "SAVE" else 0.0)
        # The observation is the straight defender's recorded example, in units.
        bd, ba, previous_bd, _ = trial.data
        expected = np.array([bd / env.unit_m, ba, previous_bd / env.unit_m])
        np.testing.assert_allclose(obs, expected, rtol=1e-6)
        obs, info = env.reset()


def test_seeds_follow_gymnasium() -> None:
    env = InterceptEnv("soccer_server")
    a = [env.reset(seed=3)[0]] + [env.reset()[0] for _ in range(3)]
    b = [env.reset(seed=3)[0]] + [env.reset()[0] for _ in range(3)]
    np.testing.assert_array_equal(np.array(a), np.array(b))
    assert not np.array_equal(a[0], a[1])  # the stream moves on
    c = env.reset(seed=4)[0]
    assert not np.array_equal(a[0], c)


def test_a_turn_angle_changes_the_outcome_and_step_needs_a_reset() -> None:
    env = InterceptEnv("soccer_server", ball_noise=0.05)
    changed = 0
    for seed in range(8):  # the same episode (seed) played with five turn angles
        labels = set()
        for ta in (-1.2, -0.5, 0.0, 0.5, 1.2):
            env.reset(seed=seed)
            labels.add(env.step(np.array([ta], dtype=np.float32))[4]["label"])
        changed += len(labels) > 1
    assert changed >= 3
    with pytest.raises(RuntimeError, match="reset"):
        env.step(np.zeros(1, dtype=np.float32))
