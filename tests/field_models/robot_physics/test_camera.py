from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from field_models.protocol import LEFT, RIGHT, PlayerRef, wrap_angle
from field_models.robot_physics.camera import BallDetection, Frame, OverheadCamera, RobotDetection
from field_models.robot_physics.config import CameraConfig, load_preset

PRESET = load_preset()
REFS = (PlayerRef(LEFT, 1), PlayerRef(RIGHT, 1), PlayerRef(RIGHT, 2))
PERIOD = PRESET.ticks(1.0 / PRESET.camera.frame_rate_hz, "camera.frame_rate_hz")
LATENCY = PRESET.ticks(PRESET.camera.latency_s, "camera.latency_s")
# Headings near ±π so that wrapping is exercised.
POSES = ((0.1, -0.2, 3.13), (-0.5, 0.4, -3.1), (1.0, 0.3, 0.5))
BALL = (0.25, -0.1)
Z_999 = 3.2905  # two-sided 99.9% normal quantile


def make_camera(config: CameraConfig = PRESET.camera, seed: int = 7) -> OverheadCamera:
    return OverheadCamera(
        config,
        REFS,
        period_ticks=PERIOD,
        latency_ticks=LATENCY,
        rng=np.random.default_rng(seed),
    )


def run_frames(camera: OverheadCamera, n_frames: int) -> list[Frame]:
    frames: list[Frame] = []
    for k in range(n_frames):
        tick = k * camera.period_ticks
        camera.capture(tick, *BALL, POSES)
        frames.extend(camera.deliver(tick + camera.latency_ticks))
    return frames


def within_binomial(count: int, n: int, p: float) -> bool:
    return abs(count - n * p) <= Z_999 * math.sqrt(n * p * (1.0 - p))


def test_preset_timing_in_ticks() -> None:
    assert (PERIOD, LATENCY) == (8, 12)  # 30 Hz and 50 ms at 240 Hz


def test_capture_due_on_multiples_of_the_period() -> None:
    camera = make_camera()
    due = [t for t in range(40) if camera.capture_due(t)]
    assert due == [0, 8, 16, 24, 32]


def test_latency_equals_preset_exactly() -> None:
    camera = make_camera()
    delivered: list[tuple[int, Frame]] = []
    for tick in range(400):
        if camera.capture_due(tick):
            camera.capture(tick, *BALL, POSES)
        delivered.extend((tick, f) for f in camera.deliver(tick))
    assert len(delivered) == len(range(0, 400 - LATENCY, PERIOD))
    for tick, frame in delivered:
        assert frame.delivery_tick == tick
        assert tick - frame.capture_tick == LATENCY == 12
    captures = [f.capture_tick for _, f in delivered]
    assert captures == sorted(captures)  # FIFO


def test_frame_not_delivered_early() -> None:
    camera = make_camera()
    camera.capture(0, *BALL, POSES)
    for tick in range(LATENCY):
        assert camera.deliver(tick) == []
    assert [f.capture_tick for f in camera.deliver(LATENCY)] == [0]


def test_noise_sigma_matches_preset_within_10_percent() -> None:
    frames = run_frames(make_camera(), 6000)
    cfg = PRESET.camera
    ball_err = np.array([(f.ball.x - BALL[0], f.ball.y - BALL[1]) for f in frames if f.ball])
    robot_err = []
    for f in frames:
        for det in f.robots:
            x, y, h = POSES[REFS.index(det.ref)]
            robot_err.append((det.x - x, det.y - y, wrap_angle(det.heading - h)))
    r = np.array(robot_err)
    for errors, sigma in (
        (ball_err[:, 0], cfg.position_sigma_m),
        (ball_err[:, 1], cfg.position_sigma_m),
        (r[:, 0], cfg.position_sigma_m),
        (r[:, 1], cfg.position_sigma_m),
        (r[:, 2], cfg.heading_sigma_rad),
    ):
        assert abs(np.std(errors) / sigma - 1.0) < 0.10
        assert abs(np.mean(errors)) < 4.0 * sigma / math.sqrt(len(errors))


def test_headings_wrapped() -> None:
    frames = run_frames(make_camera(), 500)
    headings = [d.heading for f in frames for d in f.robots]
    assert all(-math.pi <= h < math.pi for h in headings)
    assert max(headings) > 3.1 and min(headings) < -3.1  # noise crosses the wrap


def test_miss_rates_within_binomial_tolerance() -> None:
    cfg = PRESET.camera
    n_frames = 20000
    frames = run_frames(make_camera(), n_frames)
    ball_misses = sum(f.ball is None for f in frames)
    robot_misses = sum(len(REFS) - len(f.robots) for f in frames)
    assert within_binomial(ball_misses, n_frames, cfg.ball_miss_prob)
    assert within_binomial(robot_misses, n_frames * len(REFS), cfg.robot_miss_prob)
    assert ball_misses > 0 and robot_misses > 0


def test_misses_independent_per_object() -> None:
    p = 0.3
    cfg = dataclasses.replace(PRESET.camera, ball_miss_prob=p, robot_miss_prob=p)
    n_frames = 20000
    frames = run_frames(make_camera(cfg), n_frames)
    seen = [{d.ref for d in f.robots} for f in frames]
    both_robots = sum(REFS[0] not in s and REFS[1] not in s for s in seen)
    ball_and_robot = sum(
        f.ball is None and REFS[2] not in s for f, s in zip(frames, seen, strict=True)
    )
    assert within_binomial(both_robots, n_frames, p * p)
    assert within_binomial(ball_and_robot, n_frames, p * p)


def test_detections_carry_ids_in_refs_order() -> None:
    frames = run_frames(make_camera(), 200)
    for f in frames:
        order = [REFS.index(d.ref) for d in f.robots]
        assert order == sorted(order)


def test_perfect_camera_is_exact_and_immediate() -> None:
    cfg = dataclasses.replace(PRESET.camera, perfect=True, ball_miss_prob=1.0)
    camera = make_camera(cfg)
    assert camera.latency_ticks == 0
    for k in range(50):
        tick = k * PERIOD
        camera.capture(tick, *BALL, POSES)
        (frame,) = camera.deliver(tick)
        assert frame.capture_tick == frame.delivery_tick == tick
        assert frame.ball == BallDetection(*BALL)
        assert frame.robots == tuple(
            RobotDetection(ref, x, y, wrap_angle(h))
            for ref, (x, y, h) in zip(REFS, POSES, strict=True)
        )


def test_same_seed_same_frames() -> None:
    assert run_frames(make_camera(seed=3), 100) == run_frames(make_camera(seed=3), 100)
    assert run_frames(make_camera(seed=3), 100) != run_frames(make_camera(seed=4), 100)


def test_wrong_pose_count_rejected() -> None:
    with pytest.raises(ValueError):
        make_camera().capture(0, *BALL, POSES[:2])
