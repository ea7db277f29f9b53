"""The motor drive (``robot.drive = "motor"``) against the closed forms and the kinematic drive."""

from __future__ import annotations

import dataclasses
import math

import pytest

from field_models.benchmarks import ChaseLoad, drive
from field_models.presets import PresetError
from field_models.protocol import LEFT, RIGHT, PlayerRef
from field_models.robot_physics.bench import bench_arena
from field_models.robot_physics.config import GRAVITY_MPS2, RobotPhysicsPreset, load_preset
from field_models.robot_physics.motor import SEGMENT_S, MotorWorld, make_world
from field_models.robot_physics.world import RobotWorld
from tests.field_models.robot_physics.test_world import unicycle_path

PRESET = load_preset()
MOTOR = load_preset("small_size_1997_motor")
ONE = (PlayerRef(LEFT, 1),)


def open_world(preset: RobotPhysicsPreset = MOTOR, **robot: float) -> RobotWorld:
    """One robot at the centre of an empty 20 × 20 m table, facing +x."""
    big = dataclasses.replace(preset.field, length_m=20.0, width_m=20.0)
    changed = dataclasses.replace(preset.robot, **robot)
    world = make_world(dataclasses.replace(preset, field=big, robot=changed), ONE)
    world.place_robot(0, 0.0, 0.0, 0.0)
    world.place_ball(9.0, 9.0)
    return world


def test_the_default_drive_is_the_kinematic_world_and_motor_is_selectable() -> None:
    assert PRESET.robot.drive == "kinematic"
    assert type(make_world(PRESET, ONE)) is RobotWorld
    assert MOTOR.robot.drive == "motor"
    assert isinstance(make_world(MOTOR, ONE), MotorWorld)


def test_an_unknown_drive_is_refused_in_one_line_naming_both(tmp_path) -> None:
    path = tmp_path / "odd.toml"
    path.write_text('base = "small_size_1997"\n\n[robot]\ndrive = "wheels"\n')
    with pytest.raises(PresetError) as caught:
        load_preset(str(path))
    message = str(caught.value)
    assert "\n" not in message
    assert "robot.drive" in message and "kinematic, motor" in message and "'wheels'" in message


@pytest.mark.parametrize(
    ("vl", "vr"), [(0.3, 0.5), (0.5, 0.5), (1.0, 1.2), (-0.3, 0.3), (0.6, 0.2)]
)
def test_motor_robot_follows_the_unicycle_arc(vl: float, vr: float) -> None:
    # The kinematic drive's closed-form test (test_world.py), same tolerances.
    world = open_world()
    world.set_wheel_targets(0, vl, vr)
    for _ in range(round(2.0 / world.dt_s)):
        world.step()
    expected, length = unicycle_path(vl, vr, 2.0, world.dt_s)
    got = world.robot_state(0)
    error = math.hypot(got.x - expected[0], got.y - expected[1])
    assert error <= 0.02 * max(length, MOTOR.robot.track_m)
    assert math.remainder(got.heading - expected[2], 2 * math.pi) == pytest.approx(0.0, abs=0.05)


def speed_run(world: RobotWorld, ticks: int) -> tuple[float, float | None]:
    """Drive for `ticks`: (peak acceleration, time the speed first reached 99.9% of the top)."""
    top = world.preset.robot.max_wheel_speed_mps
    prev, peak, reach = world.robot_state(0), 0.0, None
    for tick in range(1, ticks + 1):
        world.step()
        now = world.robot_state(0)
        peak = max(peak, math.hypot(now.vx - prev.vx, now.vy - prev.vy) / world.dt_s)
        if reach is None and now.speed >= 0.999 * top:
            reach = tick * world.dt_s
        prev = now
    return peak, reach


def test_motor_ramp_is_a_staircase_reaching_top_speed_on_time_within_grip() -> None:
    # The kinematic drive never exceeds the ramp (test_world.py); the motor drive follows the
    # ramp in segment steps taken at up to the grip, and is at top speed a few ticks after v/a.
    world = open_world()
    top, accel = MOTOR.robot.max_wheel_speed_mps, MOTOR.robot.wheel_accel_mps2
    world.set_wheel_targets(0, top, top)
    peak, reach = speed_run(world, round(1.0 / world.dt_s))
    grip = MOTOR.robot.tyre_mu * GRAVITY_MPS2
    assert peak <= grip * (1 + 1e-6)
    assert reach is not None
    assert top / accel <= reach <= top / accel + 4 * world.dt_s


def test_motor_robot_never_accelerates_faster_than_its_grip() -> None:
    world = open_world(wheel_accel_mps2=40.0)
    world.set_wheel_targets(0, 1.2, 1.2)
    peak, _ = speed_run(world, round(1.0 / world.dt_s))
    grip = MOTOR.robot.tyre_mu * GRAVITY_MPS2
    assert 0.95 * grip <= peak <= grip * (1 + 1e-6)


def test_motor_stop_distance_is_the_ramps_plus_the_staircase_lag() -> None:
    world = open_world()
    top, accel = MOTOR.robot.max_wheel_speed_mps, MOTOR.robot.wheel_accel_mps2
    world.set_wheel_targets(0, top, top)
    for _ in range(round(1.0 / world.dt_s)):
        world.step()
    start = world.robot_state(0).x
    world.set_wheel_targets(0, 0.0, 0.0)
    for _ in range(round(1.0 / world.dt_s)):
        world.step()
    assert world.robot_state(0).speed < 1e-9  # stopped (a denormal may remain)
    # The kinematic drive's one tick of lag, and per staircase step of Δv = a·T the distance
    # lost while the grip (μ·g) takes the robot from one level to the next: Δv² / (2 μ g).
    step = accel * SEGMENT_S
    lag = top * world.dt_s + (top / step) * step**2 / (2 * MOTOR.robot.tyre_mu * GRAVITY_MPS2)
    assert top**2 / (2 * accel) <= world.robot_state(0).x - start <= top**2 / (2 * accel) + lag


def test_motor_robot_skids_when_the_turn_needs_more_than_its_grip() -> None:
    world = open_world(tyre_mu=0.05)
    world.set_wheel_targets(0, 0.8, 1.2)  # centripetal ≈ 5 m/s² ≫ μg ≈ 0.5 m/s²
    lateral = 0.0
    for _ in range(480):
        world.step()
        s = world.robot_state(0)
        lateral = max(lateral, abs(-s.vx * math.sin(s.heading) + s.vy * math.cos(s.heading)))
    assert lateral > 0.05


def test_motor_wheel_speeds_are_the_kinematic_ramps() -> None:
    kinematic, motor = open_world(PRESET), open_world()
    plan = {0: (1.2, 0.4), 30: (-0.5, 1.2), 31: (-0.5, 1.0), 120: (0.0, 0.0), 200: (0.3, 0.3)}
    for tick in range(260):
        if tick in plan:
            kinematic.set_wheel_targets(0, *plan[tick])
            motor.set_wheel_targets(0, *plan[tick])
        kinematic.step()
        motor.step()
        assert motor.wheel_speeds(0) == pytest.approx(kinematic.wheel_speeds(0), abs=1e-12)


def test_between_events_the_motor_world_only_steps_chipmunk(monkeypatch) -> None:
    aims: list[int] = []
    world = open_world()
    assert isinstance(world, MotorWorld)
    original = MotorWorld._aim
    monkeypatch.setattr(
        MotorWorld,
        "_aim",
        lambda self, plan, v, w: (aims.append(self.tick), original(self, plan, v, w)),
    )
    world.set_wheel_targets(0, 1.2, 1.2)  # 96 ticks of ramp: 12 segments of 8 ticks
    for _ in range(400):
        world.step()
    segment = round(SEGMENT_S / world.dt_s)
    ramp_ticks = round(1.2 / (MOTOR.robot.wheel_accel_mps2 * world.dt_s))
    # One event per segment of the ramp, one to re-aim once at speed, then none.
    assert aims == [*range(0, ramp_ticks, segment), ramp_ticks, ramp_ticks + segment]


def test_a_placed_motor_robot_stops_and_stays() -> None:
    world = open_world()
    world.set_wheel_targets(0, 1.0, 0.5)
    for _ in range(60):
        world.step()
    world.place_robot(0, 1.0, 1.0, 0.5)
    assert world.wheel_speeds(0) == (0.0, 0.0)
    for _ in range(60):
        world.step()
    s = world.robot_state(0)
    assert (s.x, s.y, s.heading, s.vx, s.vy) == pytest.approx((1.0, 1.0, 0.5, 0.0, 0.0), abs=1e-9)


def test_a_motor_chase_is_deterministic_and_moves_the_robots() -> None:
    def chase() -> tuple:
        arena = bench_arena(4, 0, "small_size_1997_motor")
        before = arena.truth()
        drive(arena, {ref: ChaseLoad() for ref in arena.players}, 240)
        return before, arena.truth()

    first, second = chase(), chase()
    assert first == second
    before, after = first
    moved = [
        math.dist(
            (before.players[r].x, before.players[r].y), (after.players[r].x, after.players[r].y)
        )
        for r in before.players
    ]
    assert min(moved) > 0.05
    assert PlayerRef(RIGHT, 1) in after.players
