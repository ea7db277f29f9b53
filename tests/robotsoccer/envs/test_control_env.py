"""The per-step control environments: API conformance, determinism, bad input, frames."""

from __future__ import annotations

from typing import Any

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

from field_models.presets import PresetError
from robotsoccer.envs import GO_TO_BALL_ID, SCORE_ID
from robotsoccer.envs.control_spaces import DiscreteAction, observation_names
from robotsoccer.envs.go_to_ball import GoToBallEnv
from robotsoccer.envs.score import ScoreEnv

FIELDS = ("robot_physics", "soccer_server")
IDS = (GO_TO_BALL_ID, SCORE_ID)


def rollout(env: gym.Env[Any, Any], seed: int, actions: list[Any]) -> list[Any]:
    """Observations, rewards, ends and labels of the given actions from reset(seed)."""
    obs, _ = env.reset(seed=seed)
    out: list[Any] = [np.asarray(obs).tolist()]
    for action in actions:
        obs, reward, terminated, truncated, info = env.step(action)
        out.append((np.asarray(obs).tolist(), reward, terminated, truncated, info["label"]))
        if terminated or truncated:
            break
    return out


@pytest.mark.parametrize("field", FIELDS)
@pytest.mark.parametrize("env_id", IDS)
def test_check_env_passes_on_both_fields(env_id: str, field: str) -> None:
    env = gym.make(env_id, field_model=field, render_mode="rgb_array", max_time_s=3.0)
    check_env(env.unwrapped, skip_render_check=False)


@pytest.mark.parametrize(
    ("field", "options"),
    [
        ("robot_physics", {"action": "primitives"}),
        ("robot_physics", {"action": "commands", "privileged": True}),
        ("soccer_server", {"action": "primitives", "privileged": True}),
        ("robot_physics", {"ideal_actuation": True, "perfect_perception": True}),
    ],
)
def test_check_env_passes_with_every_action_kind_and_option(
    field: str, options: dict[str, Any]
) -> None:
    check_env(GoToBallEnv(field, max_time_s=2.0, **options))


def test_spaces_are_as_documented() -> None:
    go = GoToBallEnv()
    assert go.action_space == gym.spaces.Box(-1.0, 1.0, (2,), np.float32)
    assert go.observation_space.shape == (len(observation_names(0, 0)),) == (16,)
    score = ScoreEnv()
    assert score.preset == "vss" and len(score.players) == 6
    assert score.observation_space.shape == (len(observation_names(2, 3)),) == (36,)
    server = GoToBallEnv("soccer_server")
    assert server.action_space.shape == (8,)
    assert GoToBallEnv(action="primitives").action_space == gym.spaces.Discrete(6)
    privileged = ScoreEnv("soccer_server", privileged=True).observation_space
    assert isinstance(privileged, gym.spaces.Dict)
    assert privileged["state"].shape == (4 + 6 * 6,)


@pytest.mark.parametrize("field", FIELDS)
def test_the_same_seed_and_actions_give_the_same_episode(field: str) -> None:
    env = ScoreEnv(field, max_time_s=2.0)
    rng = np.random.default_rng(1)
    actions = [rng.uniform(-1.0, 1.0, env.action_space.shape).astype(np.float32)
               for _ in range(40)]  # fmt: skip
    first = rollout(env, 7, actions)
    assert rollout(ScoreEnv(field, max_time_s=2.0), 7, actions) == first
    assert rollout(env, 8, actions) != first


def test_a_multi_process_vector_env_plays_the_single_envs_episodes() -> None:
    """Sub-environment i after reset(seed=s) is the single env seeded s + i, in its process."""
    envs = gym.make_vec(GO_TO_BALL_ID, num_envs=2, vectorization_mode="async", max_time_s=1.0)
    actions = [np.array([[0.8, 0.5], [-0.3, 0.9]], np.float32)] * 12
    try:
        obs, _ = envs.reset(seed=11)
        steps = [obs.copy()]
        for action in actions:
            obs, reward, *_ = envs.step(action)
            steps.append((obs.copy(), reward.copy()))
    finally:
        envs.close()
    for i in range(2):
        single = GoToBallEnv(max_time_s=1.0)
        obs, _ = single.reset(seed=11 + i)
        np.testing.assert_array_equal(obs, steps[0][i])
        for k, action in enumerate(actions):
            obs, reward, *_ = single.step(action[i])
            np.testing.assert_array_equal(obs, steps[k + 1][0][i])
            assert reward == steps[k + 1][1][i]


def test_bad_input_is_refused_with_a_clear_error() -> None:
    env = GoToBallEnv()
    with pytest.raises(RuntimeError, match="before reset"):
        env.step(np.zeros(2, np.float32))
    env.reset(seed=0)
    with pytest.raises(ValueError, match=r"shape \(2,\), got shape \(3,\)"):
        env.step(np.zeros(3))
    with pytest.raises(ValueError, match="NaN or infinite"):
        env.step(np.array([np.nan, 0.0]))
    with pytest.raises(ValueError, match="NaN or infinite"):
        env.step(np.array([np.inf, 0.0]))
    with pytest.raises(ValueError, match="non-numeric"):
        env.step("forward")
    discrete = GoToBallEnv(action="primitives")
    discrete.reset(seed=0)
    for bad, match in ((6, "0..5"), (2.5, "integer"), (np.nan, "NaN"), ([1, 2], "one integer")):
        with pytest.raises(ValueError, match=match):
            discrete.step(bad)
    discrete.step(np.int64(DiscreteAction.FORWARD))
    with pytest.raises(ValueError, match="unknown action 'jump'"):
        GoToBallEnv(action="jump")
    with pytest.raises(ValueError, match="drives wheels"):
        GoToBallEnv("soccer_server", action="wheels")
    with pytest.raises(PresetError, match="unknown preset 'nope'"):
        ScoreEnv(preset="nope")
    with pytest.raises(ValueError, match="unknown field model"):
        GoToBallEnv("marbles")
    with pytest.raises(ValueError, match="unknown reward term 'style'"):
        GoToBallEnv(reward_weights={"style": 1.0})
    with pytest.raises(ValueError, match="players_per_side"):
        ScoreEnv(players_per_side=4)
    with pytest.raises(ValueError, match="reset options"):
        env.reset(options={"hard": True})
    with pytest.raises(TypeError, match="unexpected keyword"):
        gym.make(SCORE_ID, colour="red")
    with pytest.raises(ValueError, match="render_mode"):
        GoToBallEnv(render_mode="video")


def test_box_actions_outside_their_bounds_are_clipped() -> None:
    outside = rollout(GoToBallEnv(), 3, [np.array([5.0, -7.0])] * 10)
    inside = rollout(GoToBallEnv(), 3, [np.array([1.0, -1.0])] * 10)
    assert outside == inside


def test_an_episode_ends_after_the_step_that_ended_it() -> None:
    env = ScoreEnv("soccer_server", max_time_s=1.0)
    env.reset(seed=0)
    truncated = False
    while not truncated:
        *_, terminated, truncated, _ = env.step(env.action_space.sample())
        if terminated:
            break
    with pytest.raises(RuntimeError, match="ended"):
        env.step(env.action_space.sample())


def test_go_to_ball_succeeds_when_the_player_faces_the_target_at_the_ball() -> None:
    env = GoToBallEnv(max_time_s=2.0)
    env.reset(seed=0)
    arena = env._arena
    assert arena is not None
    ball = arena.ball_state()
    tx, ty = env.target_xy
    heading = float(np.arctan2(ty - ball.y, tx - ball.x))
    # Behind the ball as seen from the target, facing it: success at the next tick.
    back = env.facts.touch_distance_m + 0.005
    arena.place_player(env.learner, ball.x - back * np.cos(heading),
                       ball.y - back * np.sin(heading), heading)  # fmt: skip
    _, reward, terminated, truncated, info = env.step(np.zeros(2, np.float32))
    assert terminated and not truncated and info["is_success"] and info["label"] == "SUCCESS"
    assert info["reward_terms"]["success"] == 1.0 and reward > 0.9


def test_ideal_actuation_has_no_link_loss_or_latency() -> None:
    env = GoToBallEnv(ideal_actuation=True, max_time_s=3.0)
    env.reset(seed=0)
    for _ in range(60):
        *_, terminated, truncated, _ = env.step(np.array([0.3, 0.35], np.float32))
        if terminated or truncated:
            break
    link = env._arena.link  # type: ignore[union-attr]
    assert link.sent > 50 and link.lost == 0 and link.latency_ticks == 0


# ----------------------------------------------------------------------------- frames


def ball_centre(frame: np.ndarray) -> np.ndarray:
    """Mean pixel of the ball's colour."""
    mask = np.all(frame == (255, 120, 0), axis=-1)
    assert mask.any()
    return np.argwhere(mask).mean(axis=0)


@pytest.mark.parametrize("field", FIELDS)
@pytest.mark.parametrize("cls", [GoToBallEnv, ScoreEnv])
def test_frames_show_the_ball_rolling(cls: type[GoToBallEnv | ScoreEnv], field: str) -> None:
    env = cls(field, render_mode="rgb_array", render_width=320)
    env.reset(seed=2)
    arena = env._arena
    assert arena is not None
    pitch = env.facts.pitch
    speed = min(0.4 * pitch.length_m, 0.5 * env.facts.ball_max_speed_mps)  # [m/s]
    arena.place_ball(0.0, 0.3 * pitch.half_width_m, speed, 0.0)
    before = env.render()
    assert before.shape == (before.shape[0], 320, 3) and before.dtype == np.uint8
    noop = np.zeros(env.action_space.shape, np.float32)
    for _ in range(3):
        env.step(noop)
    after = env.render()
    assert after.shape == before.shape
    moved = ball_centre(after) - ball_centre(before)
    assert moved[1] > 1.0  # columns: the ball rolled toward +x


def test_human_mode_streams_the_episode_to_a_rerun_recording(tmp_path: Any) -> None:
    env = GoToBallEnv(render_mode="human", max_time_s=1.0)
    env._view.recording_path = tmp_path / "live.rrd"
    env.reset(seed=0)
    for _ in range(3):
        env.step(np.array([0.5, 0.5], np.float32))
    env.close()
    assert (tmp_path / "live.rrd").stat().st_size > 1000


def test_options_come_as_a_record_or_as_its_keywords() -> None:
    from robotsoccer.envs.control import ControlOptions

    record = ControlOptions(action="primitives", frames_per_step=2, max_time_s=3.0)
    by_record = GoToBallEnv("soccer_server", options=record)
    by_keyword = GoToBallEnv(
        "soccer_server", action="primitives", frames_per_step=2, max_time_s=3.0
    )
    assert by_record.options == by_keyword.options == record
    assert (by_record.action_kind, by_record.frames_per_step, by_record.max_ticks) == (
        by_keyword.action_kind,
        2,
        by_keyword.max_ticks,
    )
    with pytest.raises(ValueError, match="not both"):
        GoToBallEnv(options=record, frames_per_step=1)
    with pytest.raises(ValueError, match="frames_per_step"):
        ControlOptions(frames_per_step=0)
