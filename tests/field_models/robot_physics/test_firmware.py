from __future__ import annotations

import pytest

from field_models.protocol import LEFT, RIGHT, PlayerRef
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
    return Firmware(ME, ROBOT, PRESET.firmware, timeout_ticks=TIMEOUT)


def forward(seq: int, speed: float = 0.5, duration: int | None = None) -> Command:
    return Command(seq, ME, Primitive.FORWARD, speed, duration)


def test_timeout_in_ticks() -> None:
    assert TIMEOUT == 60


def test_stops_after_timeout_without_commands() -> None:
    fw = make_firmware()
    fw.receive(forward(1), 10)
    for tick in range(10, 10 + TIMEOUT):
        assert fw.update(tick) == (0.5, 0.5)
    assert fw.due(10 + TIMEOUT)
    assert fw.update(10 + TIMEOUT) == (0.0, 0.0)
    assert fw.running is None
    assert not fw.due(10 + TIMEOUT + 1)


def test_new_command_resets_the_watchdog() -> None:
    fw = make_firmware()
    fw.receive(forward(1), 0)
    fw.receive(forward(2, 0.7), 50)
    assert fw.update(50 + TIMEOUT - 1) == (0.7, 0.7)
    assert fw.update(50 + TIMEOUT) == (0.0, 0.0)


def test_stale_and_duplicate_seq_dropped() -> None:
    fw = make_firmware()
    assert fw.receive(forward(5, 0.3), 0)
    assert not fw.receive(forward(3, 0.9), 1)
    assert not fw.receive(forward(5, 0.9), 2)
    assert fw.update(2) == (0.3, 0.3)
    # A dropped command does not feed the watchdog.
    assert fw.update(TIMEOUT) == (0.0, 0.0)


def test_broadcast_accepted_other_address_ignored() -> None:
    fw = make_firmware()
    assert not fw.receive(Command(1, OTHER, Primitive.FORWARD, 0.5), 0)
    assert fw.update(0) == (0.0, 0.0)
    assert fw.receive(Command(2, None, Primitive.BACKWARD, 0.4), 1)
    assert fw.update(1) == (-0.4, -0.4)
    assert fw.receive(Command(3, None, Primitive.STOP), 2)
    assert fw.update(2) == (0.0, 0.0)


def test_duration_expiry() -> None:
    fw = make_firmware()
    fw.receive(forward(1, 0.8, duration=16), 100)
    outputs = [fw.update(t) for t in range(100, 120)]
    assert outputs[:16] == [(0.8, 0.8)] * 16
    assert outputs[16:] == [(0.0, 0.0)] * 4


def test_due_only_when_output_can_change() -> None:
    fw = make_firmware()
    assert not fw.due(0)
    fw.receive(forward(1, 0.8, duration=16), 100)
    assert fw.due(100)
    fw.update(100)
    assert [t for t in range(101, 200) if fw.due(t)][:1] == [116]
    fw.update(116)
    assert not any(fw.due(t) for t in range(117, 400))


def test_due_when_timeout_expires() -> None:
    fw = make_firmware()
    fw.receive(forward(1), 0)
    fw.update(0)
    assert [t for t in range(1, 100) if fw.due(t)][:1] == [TIMEOUT]


def test_targets_capped_at_top_wheel_speed() -> None:
    fw = make_firmware()
    fw.receive(forward(1, 5.0), 0)
    assert fw.update(0) == (ROBOT.max_wheel_speed_mps, ROBOT.max_wheel_speed_mps)
    fw.receive(Command(2, ME, Primitive.TURN, 1000.0), 1)
    left, right = fw.update(1)
    assert left == pytest.approx(-ROBOT.max_wheel_speed_mps)
    assert right == pytest.approx(ROBOT.max_wheel_speed_mps)


def test_turn_left_positive() -> None:
    fw = make_firmware()
    fw.receive(Command(1, ME, Primitive.TURN, 4.0), 0)
    left, right = fw.update(0)
    assert left == pytest.approx(-4.0 * ROBOT.track_m / 2)
    assert right == pytest.approx(4.0 * ROBOT.track_m / 2)


def test_kick_armed_once_and_motion_kept() -> None:
    fw = make_firmware()
    fw.receive(forward(1, 0.6), 0)
    fw.receive(Command(2, ME, Primitive.KICK, 150.0), 1)
    assert fw.take_kick() == 100.0
    assert fw.take_kick() is None
    assert fw.update(1) == (0.6, 0.6)


def test_arc_keeps_the_turn_rate_and_drives_with_what_is_left() -> None:
    fw = make_firmware()
    half = ROBOT.track_m / 2
    fw.receive(Command(1, ME, Primitive.ARC, 0.5, rate=2.0), 0)
    assert fw.update(0) == pytest.approx((0.5 - 2.0 * half, 0.5 + 2.0 * half))
    fast = 20.0  # 0.75 m/s of the 1.2 m/s on each wheel goes to the turn
    fw.receive(Command(2, ME, Primitive.ARC, 5.0, rate=-fast), 1)
    left, right = fw.update(1)
    assert left == pytest.approx(ROBOT.max_wheel_speed_mps)
    assert (left - right) / ROBOT.track_m == pytest.approx(fast)


def test_wheels_set_each_wheel_capped_at_the_top_speed() -> None:
    fw = make_firmware()
    fw.receive(Command(1, ME, Primitive.WHEELS, -0.3, 16, rate=0.4), 0)
    assert fw.update(0) == (-0.3, 0.4)
    assert fw.update(16) == (0.0, 0.0)  # the duration ran out
    vmax = ROBOT.max_wheel_speed_mps
    fw.receive(Command(2, ME, Primitive.WHEELS, 5.0, None, rate=-5.0), 20)
    assert fw.update(20) == (vmax, -vmax)


def test_counters_of_commands_cut_short_and_stale() -> None:
    """Issue 28's counters: a drive command with a duration replaced before it ended."""
    fw = make_firmware()
    fw.receive(Command(1, ME, Primitive.TURN, 2.0, 20), 0)
    fw.update(0)
    fw.receive(forward(2, duration=16), 10)  # the turn had 10 of 20 ticks left
    assert (fw.cut_short, fw.cut_turns) == (1, 1)
    fw.receive(forward(3), 40)  # the forward's 16 ticks ended at 26: carried out in full
    assert (fw.cut_short, fw.cut_turns) == (1, 1)
    fw.receive(forward(4, duration=5), 41)  # the forward without a duration: never cut short
    assert (fw.cut_short, fw.cut_turns) == (1, 1)
    fw.receive(Command(5, ME, Primitive.KICK, 50.0), 42)  # a kick keeps the motion: no cut
    fw.receive(forward(6), 43)  # the forward of 5 ticks still ran: cut short, not a turn
    assert (fw.cut_short, fw.cut_turns) == (2, 1)
    assert not fw.receive(forward(6), 44)
    assert fw.stale == 1
    fw.receive(Command(7, ME, Primitive.ARC, 0.5, 200, rate=3.0), 50)
    fw.receive(forward(8), 50 + TIMEOUT + 1)  # the watchdog stopped the arc: not cut short
    assert (fw.cut_short, fw.cut_turns) == (2, 1)
