"""The pymunk world against closed forms: rolling ball, arcs, ramp and grip, walls, goals."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from field_models.protocol import LEFT, RIGHT, Crossing, PlayerRef, end_line_crossing
from field_models.robot_physics.config import load_preset
from field_models.robot_physics.world import RobotWorld

PRESET = load_preset()
ONE = (PlayerRef(LEFT, 1),)


def empty_world(preset=PRESET, refs=ONE, rng=None) -> RobotWorld:
    world = RobotWorld(preset, refs, rng)
    for i in range(len(refs)):
        world.place_robot(i, -1.0 + 0.3 * i, -0.6, 0.0)  # parked out of the way
    return world


@pytest.mark.parametrize("v0", [0.3, 1.0, 2.0])
def test_ball_stops_after_v0_over_a_and_v0_squared_over_2a(v0: float) -> None:
    a = PRESET.ball.rolling_decel_mps2
    # A 2 m/s ball rolls 20 m: use a long field so the walls play no part.
    long_field = dataclasses.replace(PRESET.field, length_m=40.0, width_m=4.0)
    world = empty_world(dataclasses.replace(PRESET, field=long_field))
    world.place_ball(-19.0, 0.0, v0, 0.0)
    ticks = 0
    while world.ball_state().speed > 0.0 and ticks < 100_000:
        world.step()
        ticks += 1
    stop_time = ticks * world.dt_s
    distance = world.ball_state().x + 19.0
    assert stop_time == pytest.approx(v0 / a, rel=0.01)
    assert distance == pytest.approx(v0**2 / (2 * a), rel=0.01)


def unicycle_path(vl: float, vr: float, seconds: float, dt: float) -> tuple[np.ndarray, float]:
    """Exact-ish unicycle integration (fine sub-steps) of the same ramped wheel speeds."""
    r = PRESET.robot
    fine = 20
    h = dt / fine
    x = y = th = 0.0
    left = right = 0.0
    length = 0.0
    for _ in range(round(seconds / dt)):
        # The world ramps once per tick, then the solver moves the body one tick later.
        left += max(-r.wheel_accel_mps2 * dt, min(r.wheel_accel_mps2 * dt, vl - left))
        right += max(-r.wheel_accel_mps2 * dt, min(r.wheel_accel_mps2 * dt, vr - right))
        v, w = 0.5 * (left + right), (right - left) / r.track_m
        for _ in range(fine):
            x += v * math.cos(th + 0.5 * w * h) * h
            y += v * math.sin(th + 0.5 * w * h) * h
            th += w * h
            length += abs(v) * h
    return np.array([x, y, th]), length


@pytest.mark.parametrize(
    ("vl", "vr"), [(0.3, 0.5), (0.5, 0.5), (1.0, 1.2), (-0.3, 0.3), (0.6, 0.2)]
)
def test_robot_follows_the_unicycle_arc(vl: float, vr: float) -> None:
    big = dataclasses.replace(PRESET.field, length_m=20.0, width_m=20.0)
    world = RobotWorld(dataclasses.replace(PRESET, field=big), ONE)
    world.place_robot(0, 0.0, 0.0, 0.0)
    world.place_ball(9.0, 9.0)
    world.set_wheel_targets(0, vl, vr)
    for _ in range(round(2.0 / world.dt_s)):
        world.step()
    expected, length = unicycle_path(vl, vr, 2.0, world.dt_s)
    got = world.robot_state(0)
    error = math.hypot(got.x - expected[0], got.y - expected[1])
    scale = max(length, PRESET.robot.track_m)  # a spin in place has no path: use the track
    assert error <= 0.02 * scale
    assert math.remainder(got.heading - expected[2], 2 * math.pi) == pytest.approx(0.0, abs=0.05)


def max_acceleration(preset, vl: float, vr: float, seconds: float = 1.0) -> float:
    big = dataclasses.replace(preset.field, length_m=20.0, width_m=20.0)
    world = RobotWorld(dataclasses.replace(preset, field=big), ONE)
    world.place_robot(0, -5.0, 0.0, 0.0)
    world.place_ball(9.0, 9.0)
    world.set_wheel_targets(0, vl, vr)
    prev = world.robot_state(0)
    peak = 0.0
    for _ in range(round(seconds / world.dt_s)):
        world.step()
        now = world.robot_state(0)
        peak = max(peak, math.hypot(now.vx - prev.vx, now.vy - prev.vy) / world.dt_s)
        prev = now
    return peak


def test_robot_never_accelerates_faster_than_its_ramp() -> None:
    peak = max_acceleration(PRESET, 1.2, 1.2)
    assert peak <= PRESET.robot.wheel_accel_mps2 * (1 + 1e-6)
    assert peak >= 0.95 * PRESET.robot.wheel_accel_mps2  # the ramp is actually used


def test_robot_never_accelerates_faster_than_its_grip() -> None:
    fast_motor = dataclasses.replace(PRESET.robot, wheel_accel_mps2=40.0)
    preset = dataclasses.replace(PRESET, robot=fast_motor)
    grip = preset.robot.tyre_mu * 9.81
    peak = max_acceleration(preset, 1.2, 1.2)
    assert peak <= grip * (1 + 1e-6)
    assert peak >= 0.95 * grip


def test_robot_skids_when_the_turn_needs_more_than_its_grip() -> None:
    slippery = dataclasses.replace(PRESET.robot, tyre_mu=0.05)
    preset = dataclasses.replace(PRESET, robot=slippery)
    big = dataclasses.replace(preset.field, length_m=20.0, width_m=20.0)
    world = RobotWorld(dataclasses.replace(preset, field=big), ONE)
    world.place_robot(0, 0.0, 0.0, 0.0)
    world.place_ball(9.0, 9.0)
    world.set_wheel_targets(0, 0.8, 1.2)  # centripetal ≈ 5 m/s² ≫ μg ≈ 0.5 m/s²
    lateral = 0.0
    for _ in range(480):
        world.step()
        s = world.robot_state(0)
        lateral = max(lateral, abs(-s.vx * math.sin(s.heading) + s.vy * math.cos(s.heading)))
    assert lateral > 0.05  # sliding sideways: the tyres let go


@settings(max_examples=60, deadline=None)
@given(
    x=st.floats(-0.95, 0.95),
    y=st.floats(-0.95, 0.95),
    direction=st.floats(-math.pi, math.pi),
    preset_name=st.sampled_from(["small_size_1997", "vss"]),
)
def test_fastest_ball_never_leaves_the_walled_field(
    x: float, y: float, direction: float, preset_name: str
) -> None:
    preset = load_preset(preset_name)
    f, r = preset.field, preset.ball.radius_m
    world = RobotWorld(preset, ())
    bx = x * (0.5 * f.length_m - r)
    by = y * (0.5 * f.width_m - r)
    speed = preset.ball.max_speed_mps
    world.place_ball(bx, by, speed * math.cos(direction), speed * math.sin(direction))
    # Contacts are found after overlap (no swept collision, robot_physics.md §3.5), so at impact
    # the ball may sink into a wall by up to one tick of travel; it must never get its centre
    # past the wall's face, and must come to rest fully inside. (Rest, not a fixed time: at
    # any given tick the ball may be in the middle of an impact, sunk by up to the bound above.)
    sink = speed * world.dt_s + 2 * preset.timing.collision_slop_m
    half_l, half_w, half_gw = 0.5 * f.length_m, 0.5 * f.width_m, 0.5 * f.goal_width_m
    at_rest = preset.ball.stop_speed_mps
    for _ in range(round(60.0 / world.dt_s)):  # rolling resistance alone stops it within 40 s
        world.step()
        px, py = world.ball_xy()
        assert abs(py) <= half_w - r + sink
        assert abs(px) <= half_l + f.goal_depth_m - r + sink
        if abs(px) > half_l - r + sink:  # only inside a goal mouth
            assert abs(py) <= half_gw - r + sink
        if world.ball.velocity.length < at_rest:
            break
    assert world.ball.velocity.length < at_rest
    slop = 2 * preset.timing.collision_slop_m
    px, py = world.ball_xy()
    assert abs(py) <= half_w - r + slop
    assert abs(px) <= half_l + f.goal_depth_m - r + slop


@pytest.mark.parametrize(("y", "expected"), [(0.0, Crossing.RIGHT_GOAL), (0.3, None)])
def test_ball_rolls_wholly_into_the_goal_mouth_and_stays_in_it(y, expected) -> None:
    """The one goal-line rule sees the ball cross into the goal; wide of it the wall stops it."""
    world = RobotWorld(PRESET, ())
    world.place_ball(1.0, y, 2.0, 0.0)
    pitch = PRESET.pitch()
    crossings = []
    for _ in range(480):
        before = world.ball_xy()
        world.step()
        crossing = end_line_crossing(pitch, *before, *world.ball_xy())
        if crossing:
            crossings.append(crossing)
    assert crossings == ([] if expected is None else [expected])
    assert world.ball_xy()[0] < 0.5 * PRESET.field.length_m + PRESET.field.goal_depth_m


def test_ball_bounces_off_a_wall_with_the_preset_restitution() -> None:
    world = RobotWorld(PRESET, ())
    world.place_ball(0.0, 0.5, 0.0, 1.0)  # straight up into the top wall
    speeds = []
    for _ in range(240):
        world.step()
        speeds.append(world.ball_state().vy)
    before = max(speeds)
    after = -min(speeds)
    assert after / before == pytest.approx(PRESET.ball.wall_restitution, rel=0.05)


def test_kicker_launches_only_a_ball_in_reach() -> None:
    kicker_robot = dataclasses.replace(
        PRESET.robot,
        kicker=dataclasses.replace(_kicker(), reach_m=0.01, max_speed_mps=3.0, half_angle_rad=0.5),
    )
    preset = dataclasses.replace(PRESET, robot=kicker_robot)
    world = RobotWorld(preset, ONE)
    world.place_robot(0, 0.0, 0.0, 0.0)
    touching = 0.5 * preset.robot.size_m + preset.ball.radius_m + 0.005
    world.place_ball(touching, 0.0)
    assert world.kick(0, 100.0)
    assert world.ball_state().vx == pytest.approx(3.0)
    world.place_ball(touching + 0.05, 0.0)
    assert not world.kick(0, 100.0)
    world.place_ball(-touching, 0.0)
    assert not world.kick(0, 100.0)


def _kicker():
    from field_models.robot_physics.config import KickerConfig

    return KickerConfig(reach_m=0.01, max_speed_mps=3.0, half_angle_rad=0.5)


def test_ball_noise_is_seeded_and_zero_noise_is_exact() -> None:
    noisy = dataclasses.replace(PRESET, ball=dataclasses.replace(PRESET.ball, motion_noise=0.1))

    def run(preset, seed):
        world = RobotWorld(preset, (), np.random.default_rng(seed))
        world.place_ball(-1.0, 0.0, 1.0, 0.0)
        for _ in range(240):
            world.step()
        return world.ball_state()

    assert run(noisy, 1) == run(noisy, 1)
    assert run(noisy, 1) != run(noisy, 2)
    assert run(PRESET, 1).y == 0.0
    assert run(noisy, 1).y != 0.0


def test_same_inputs_give_bit_identical_states() -> None:
    refs = (PlayerRef(LEFT, 1), PlayerRef(RIGHT, 1))

    def run():
        world = RobotWorld(PRESET, refs)
        world.place_robot(0, -0.3, 0.0, 0.0)
        world.place_robot(1, 0.3, 0.05, math.pi)
        world.place_ball(0.0, 0.0)
        world.set_wheel_targets(0, 1.0, 1.0)
        world.set_wheel_targets(1, 0.9, 1.0)
        for _ in range(600):
            world.step()
        return world.truth()

    assert run() == run()
