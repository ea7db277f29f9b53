from __future__ import annotations

import math

import pytest

from field_models.protocol import LEFT, RIGHT, PlayerRef, wrap_angle
from field_models.robot_physics.config import load_preset
from field_models.robot_physics.firmware import Firmware
from field_models.robot_physics.link import Command, Primitive

PRESET = load_preset()
ROBOT = PRESET.robot
ME = PlayerRef(LEFT, 1)
OTHER = PlayerRef(RIGHT, 1)
TIMEOUT = PRESET.ticks(PRESET.firmware.timeout_s, "firmware.timeout_s")
DT = PRESET.dt_s


def make_firmware() -> Firmware:
    return Firmware(ME, ROBOT, PRESET.firmware, timeout_ticks=TIMEOUT, dt_s=DT)


def forward(seq: int, speed: float = 0.5, duration: int | None = None) -> Command:
    return Command(seq, ME, Primitive.FORWARD, speed, duration)


def test_timeout_in_ticks() -> None:
    assert TIMEOUT == 60


def test_stops_after_timeout_without_commands() -> None:
    fw = make_firmware()
    fw.receive(forward(1), 10)
    for tick in range(10, 10 + TIMEOUT):
        assert fw.update(tick, 0.0, 0.0) == (0.5, 0.5)
    assert fw.due(10 + TIMEOUT)
    assert fw.update(10 + TIMEOUT, 0.5, 0.5) == (0.0, 0.0)
    assert fw.running is None
    assert not fw.due(10 + TIMEOUT + 1)


def test_new_command_resets_the_watchdog() -> None:
    fw = make_firmware()
    fw.receive(forward(1), 0)
    fw.receive(forward(2, 0.7), 50)
    assert fw.update(50 + TIMEOUT - 1, 0.0, 0.0) == (0.7, 0.7)
    assert fw.update(50 + TIMEOUT, 0.0, 0.0) == (0.0, 0.0)


def test_stale_and_duplicate_seq_dropped() -> None:
    fw = make_firmware()
    assert fw.receive(forward(5, 0.3), 0)
    assert not fw.receive(forward(3, 0.9), 1)
    assert not fw.receive(forward(5, 0.9), 2)
    assert fw.update(2, 0.0, 0.0) == (0.3, 0.3)
    # A dropped command does not feed the watchdog.
    assert fw.update(TIMEOUT, 0.0, 0.0) == (0.0, 0.0)


def test_broadcast_accepted_other_address_ignored() -> None:
    fw = make_firmware()
    assert not fw.receive(Command(1, OTHER, Primitive.FORWARD, 0.5), 0)
    assert fw.update(0, 0.0, 0.0) == (0.0, 0.0)
    assert fw.receive(Command(2, None, Primitive.BACKWARD, 0.4), 1)
    assert fw.update(1, 0.0, 0.0) == (-0.4, -0.4)
    assert fw.receive(Command(3, None, Primitive.STOP), 2)
    assert fw.update(2, 0.0, 0.0) == (0.0, 0.0)


def test_duration_expiry() -> None:
    fw = make_firmware()
    fw.receive(forward(1, 0.8, duration=16), 100)
    outputs = [fw.update(t, 0.0, 0.0) for t in range(100, 120)]
    assert outputs[:16] == [(0.8, 0.8)] * 16
    assert outputs[16:] == [(0.0, 0.0)] * 4


def test_due_only_when_output_can_change() -> None:
    fw = make_firmware()
    assert not fw.due(0)
    fw.receive(forward(1, 0.8, duration=16), 100)
    assert fw.due(100)
    fw.update(100, 0.0, 0.0)
    assert [t for t in range(101, 200) if fw.due(t)][:1] == [116]
    fw.update(116, 0.0, 0.0)
    assert not any(fw.due(t) for t in range(117, 400))


def test_due_when_timeout_expires() -> None:
    fw = make_firmware()
    fw.receive(forward(1), 0)
    fw.update(0, 0.0, 0.0)
    assert [t for t in range(1, 100) if fw.due(t)][:1] == [TIMEOUT]


def test_targets_capped_at_top_wheel_speed() -> None:
    fw = make_firmware()
    fw.receive(forward(1, 5.0), 0)
    assert fw.update(0, 0.0, 0.0) == (ROBOT.max_wheel_speed_mps, ROBOT.max_wheel_speed_mps)
    fw.receive(Command(2, ME, Primitive.TURN, 1000.0), 1)
    left, right = fw.update(1, 0.0, 0.0)
    assert left == pytest.approx(-ROBOT.max_wheel_speed_mps)
    assert right == pytest.approx(ROBOT.max_wheel_speed_mps)


def test_turn_left_positive() -> None:
    fw = make_firmware()
    fw.receive(Command(1, ME, Primitive.TURN, 4.0), 0)
    left, right = fw.update(0, 0.0, 0.0)
    assert left == pytest.approx(-4.0 * ROBOT.track_m / 2)
    assert right == pytest.approx(4.0 * ROBOT.track_m / 2)


def test_kick_armed_once_and_motion_kept() -> None:
    fw = make_firmware()
    fw.receive(forward(1, 0.6), 0)
    fw.receive(Command(2, ME, Primitive.KICK, 150.0), 1)
    assert fw.take_kick() == 100.0
    assert fw.take_kick() is None
    assert fw.update(1, 0.0, 0.0) == (0.6, 0.6)


class Kinematic:
    """A unicycle driven by ramped wheel speeds: the world's motor model without grip limits."""

    def __init__(self, x: float, y: float, heading: float) -> None:
        self.x, self.y, self.heading = x, y, heading
        self.left = self.right = 0.0

    def step(self, left_target: float, right_target: float) -> None:
        dv = ROBOT.wheel_accel_mps2 * DT
        self.left += max(-dv, min(dv, left_target - self.left))
        self.right += max(-dv, min(dv, right_target - self.right))
        v = 0.5 * (self.left + self.right)
        w = (self.right - self.left) / ROBOT.track_m
        mid = self.heading + 0.5 * w * DT
        self.x += v * DT * math.cos(mid)
        self.y += v * DT * math.sin(mid)
        self.heading += w * DT


def drive_goto(target_x: float, target_y: float, heading: float) -> tuple[Kinematic, int]:
    """Run a GOTO with commands repeated every 30 ticks (keeps the watchdog fed)."""
    body = Kinematic(0.3, -0.2, heading)
    c, s = math.cos(heading), math.sin(heading)
    goal_x, goal_y = 0.3 + c * target_x - s * target_y, -0.2 + s * target_x + c * target_y
    fw = make_firmware()
    fw.receive(Command(1, ME, Primitive.GOTO, target_x=target_x, target_y=target_y), 0)
    for tick in range(2400):
        if tick and fw.running is None:
            for coast in range(tick, tick + 60):  # wheels ramp down to rest
                body.step(*fw.update(coast, body.left, body.right))
            assert body.left == body.right == 0.0
            return body, tick
        if tick % 30 == 0 and tick:
            # The host's repeated request, re-expressed from the robot's current frame.
            dx, dy = goal_x - body.x, goal_y - body.y
            ch, sh = math.cos(body.heading), math.sin(body.heading)
            fw.receive(
                Command(
                    tick,
                    ME,
                    Primitive.GOTO,
                    target_x=ch * dx + sh * dy,
                    target_y=-sh * dx + ch * dy,
                ),
                tick,
            )
        assert fw.due(tick)
        body.step(*fw.update(tick, body.left, body.right))
    raise AssertionError("GOTO did not finish")


@pytest.mark.parametrize(
    ("target", "heading"), [((0.6, 0.3), 0.0), ((-0.4, 0.1), 1.0), ((0.05, -0.5), -2.5)]
)
def test_goto_converges_on_kinematic_robot(target: tuple[float, float], heading: float) -> None:
    body, ticks = drive_goto(*target, heading)
    c, s = math.cos(heading), math.sin(heading)
    goal = (0.3 + c * target[0] - s * target[1], -0.2 + s * target[0] + c * target[1])
    miss = math.hypot(body.x - goal[0], body.y - goal[1])
    assert miss <= PRESET.firmware.goto_tolerance_m  # at rest, after the ramp's run-down
    assert ticks < 3 * 240


def test_goto_odometry_alone_reaches_target() -> None:
    """A single GOTO (no repeats) within the watchdog's time: odometry alone gets there."""
    body = Kinematic(0.0, 0.0, 0.0)
    fw = make_firmware()
    fw.receive(Command(1, ME, Primitive.GOTO, target_x=0.05, target_y=0.02), 0)
    tick = 0
    while fw.running is not None and tick < TIMEOUT:
        body.step(*fw.update(tick, body.left, body.right))
        tick += 1
    assert fw.running is None
    assert math.hypot(body.x - 0.05, body.y - 0.02) <= PRESET.firmware.goto_tolerance_m + 0.002
    assert abs(wrap_angle(body.heading)) < math.pi / 2
