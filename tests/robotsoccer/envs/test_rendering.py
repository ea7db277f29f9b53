"""Frames from the environments that existed before the per-step ones, and the raster itself."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

from field_models.protocol import LEFT, RIGHT, BodyState, PlayerRef, Truth
from field_models.registry import field_facts
from robotsoccer.envs import INTERCEPT_ID
from robotsoccer.envs.intercept import InterceptEnv
from robotsoccer.envs.passing import pass_parallel_env
from robotsoccer.replay.raster import FieldPainter

BALL = (255, 120, 0)


def ball_centre(frame: np.ndarray) -> np.ndarray:
    mask = np.all(frame == BALL, axis=-1)
    assert mask.any()
    return np.argwhere(mask).mean(axis=0)


def test_the_painter_puts_the_ball_where_it_is() -> None:
    facts = field_facts("robot_physics", "vss")
    players = (PlayerRef(LEFT, 1), PlayerRef(RIGHT, 1))
    painter = FieldPainter(facts.pitch, players, facts.player_shape, width_px=300)
    truth = Truth(
        0,
        0.0,
        BodyState(0.5, 0.3, 0.0),
        {players[0]: BodyState(-0.3, 0.0, 0.0), players[1]: BodyState(0.3, 0.0, 3.1)},
    )
    frame = painter.paint(truth)
    assert frame.shape == painter.shape_hw3 and frame.shape[1] == 300 and frame.dtype == np.uint8
    row, col = ball_centre(frame)
    expected_col, expected_row = painter.pixel(0.5, 0.3)
    assert abs(col - expected_col) < 1.0 and abs(row - expected_row) < 1.0
    off_field = Truth(0, 0.0, BodyState(50.0, 50.0, 0.0), {})
    assert not np.all(painter.paint(off_field) == BALL, axis=-1).any()  # drawn nowhere


@pytest.mark.parametrize("field", ["robot_physics", "soccer_server"])
def test_the_intercept_env_draws_the_ball_moving_from_decision_to_verdict(field: str) -> None:
    env = gym.make(INTERCEPT_ID, field_model=field, render_mode="rgb_array")
    env.reset(seed=0)
    before = env.render()
    env.step(np.zeros(1, np.float32))
    after = env.render()
    assert isinstance(before, np.ndarray) and before.ndim == 3 and before.shape[2] == 3
    assert np.linalg.norm(ball_centre(after) - ball_centre(before)) > 2.0


def test_the_batched_vector_env_draws_each_sub_envs_decision() -> None:
    envs = gym.make_vec(INTERCEPT_ID, num_envs=2, field_model="soccer_server",
                        render_mode="rgb_array")  # fmt: skip
    envs.reset(seed=3)
    frames = envs.render()
    assert frames is not None and len(frames) == 2
    single = InterceptEnv("soccer_server", render_mode="rgb_array")
    for i, frame in enumerate(frames):
        single.reset(seed=3 + i)
        np.testing.assert_array_equal(frame, single.render())
    with pytest.raises(ValueError, match="render_mode"):
        gym.make_vec(INTERCEPT_ID, num_envs=2, field_model="soccer_server", render_mode="human")


def test_the_pass_env_draws_frames() -> None:
    env = pass_parallel_env("soccer_server", render_mode="rgb_array")
    obs, _ = env.reset(seed=1)
    before = env.render()
    while env.agents:
        mask = obs["passer"]["action_mask"]
        passer = int(np.argmax(mask)) if mask.any() else 0
        actions = {a: np.zeros(1, np.float32) for a in env.agents if a != "passer"}
        obs, *_ = env.step({**actions, "passer": passer})
    after = env.render()
    assert before.shape == after.shape and before.shape[2] == 3
    assert np.linalg.norm(ball_centre(after) - ball_centre(before)) > 2.0
