from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from field_models.protocol import LEFT, RIGHT, Action, Dash, Kick, PlayerRef, Say, Turn
from field_models.robot_physics.camera import BallDetection, Frame, RobotDetection
from field_models.robot_physics.config import KickerConfig, RobotPhysicsPreset, load_preset
from field_models.robot_physics.firmware import Firmware
from field_models.robot_physics.host import CentralHost
from field_models.robot_physics.host_actuation import PUSH_HALF_ANGLE_RAD
from field_models.robot_physics.link import Command, Link, Primitive

PRESET = load_preset()
A = PlayerRef(LEFT, 1)
B = PlayerRef(LEFT, 2)
C = PlayerRef(RIGHT, 1)
REFS = (A, B, C)
PERIOD = 8
DT = PRESET.dt_s
VMAX = PRESET.robot.max_wheel_speed_mps


def make_host(preset: RobotPhysicsPreset = PRESET) -> tuple[CentralHost, Link]:
    link = Link(
        dataclasses.replace(preset.link, loss_prob=0.0),
        packet_period_ticks=1,
        latency_ticks=0,
        rng=np.random.default_rng(0),
    )
    return CentralHost(REFS, preset, link, frame_period_ticks=PERIOD), link


def sent(link: Link, tick: int = 0) -> list[Command]:
    """Commands the host put on the (lossless, zero-latency) link at `tick`."""
    return link.deliver(tick + 1)


def frame(
    ball: tuple[float, float] | None, *robots: tuple[PlayerRef, float, float, float], tick: int = 0
) -> Frame:
    return Frame(
        tick,
        tick + 12,
        None if ball is None else BallDetection(*ball),
        tuple(RobotDetection(*r) for r in robots),
    )


# ----------------------------------------------------------------------------- percepts


def test_percept_geometry_on_hand_made_frame() -> None:
    host, _ = make_host()
    f = frame(
        (0.0, 1.0),
        (A, 0.0, 0.0, math.pi / 2),  # facing +y
        (B, 1.0, 0.0, 0.0),
        (C, -2.0, 0.0, math.pi),
        tick=40,
    )
    pa, pb, pc = host.percepts(f, 52)
    assert (pa.player, pa.tick, pa.observed_tick) == (A, 52, 40)
    # A faces the ball straight ahead; B is on A's right; C on A's left.
    assert pa.ball is not None
    assert pa.ball.distance_m == pytest.approx(1.0)
    assert pa.ball.angle_rad == pytest.approx(0.0)
    seen = {(p.team, p.number): p for p in pa.players}
    assert set(seen) == {(LEFT, 2), (RIGHT, 1)}
    assert seen[(LEFT, 2)].distance_m == pytest.approx(1.0)
    assert seen[(LEFT, 2)].angle_rad == pytest.approx(-math.pi / 2)
    assert seen[(RIGHT, 1)].distance_m == pytest.approx(2.0)
    assert seen[(RIGHT, 1)].angle_rad == pytest.approx(math.pi / 2)
    # B at (1, 0) facing +x: ball at distance √2, 135° to the left.
    assert pb.ball is not None
    assert pb.ball.distance_m == pytest.approx(math.sqrt(2))
    assert pb.ball.angle_rad == pytest.approx(3 * math.pi / 4)
    # C at (-2, 0) facing -x: A is straight behind, reported in [-π, π).
    c_sees_a = next(p for p in pc.players if (p.team, p.number) == (LEFT, 1))
    assert c_sees_a.distance_m == pytest.approx(2.0)
    assert abs(c_sees_a.angle_rad) == pytest.approx(math.pi)
    assert -math.pi <= c_sees_a.angle_rad < math.pi


def test_missed_objects_unknown_and_own_pose_from_last_detection() -> None:
    host, _ = make_host()
    host.percepts(frame((1.0, 0.0), (A, 0.0, 0.0, 0.0), (B, 0.0, 1.0, 0.0)), 12)
    # Next frame: A missed, B missed, ball seen; C seen for the first time.
    pa, pb, pc = host.percepts(frame((0.0, 1.0), (C, 3.0, 0.0, math.pi), tick=8), 20)
    assert host.pose_estimate(A) == (0.0, 0.0, 0.0)
    assert pa.ball is not None
    assert pa.ball.distance_m == pytest.approx(1.0)
    assert pa.ball.angle_rad == pytest.approx(math.pi / 2)  # from A's last pose
    assert [(p.team, p.number) for p in pa.players] == [(RIGHT, 1)]  # B unknown, not carried
    assert pb.ball is not None and pb.ball.distance_m == pytest.approx(0.0)
    assert pc.ball is not None and pc.ball.distance_m == pytest.approx(math.hypot(3.0, 1.0))
    # Ball missed: no ball for anyone.
    assert all(p.ball is None for p in host.percepts(frame(None, (A, 0.0, 0.0, 0.0)), 28))


def test_never_detected_robot_gets_empty_percept() -> None:
    host, _ = make_host()
    pa, pb, pc = host.percepts(frame((1.0, 0.0), (A, 0.0, 0.0, 0.0)), 12)
    assert pc.ball is None and pc.players == ()
    assert pb.ball is None and pb.players == () and pb.heard == ()
    assert pb.observed_tick == 0
    assert pa.ball is not None


# ----------------------------------------------------------------------------- translation


def test_dash_forward_and_backward() -> None:
    host, link = make_host()
    host.submit(A, (Dash(70.0),), 0)
    (c,) = sent(link)
    assert (c.robot, c.primitive, c.duration_ticks, c.sent_tick) == (A, Primitive.FORWARD, 16, 0)
    assert c.value == pytest.approx(0.84)
    host.submit(B, (Dash(-150.0),), 5)
    (c,) = sent(link, 5)
    assert (c.robot, c.primitive, c.value, c.duration_ticks) == (B, Primitive.BACKWARD, VMAX, 16)
    host.submit(A, (Dash(0.0),), 9)
    assert sent(link, 9)[0].primitive is Primitive.STOP
    texts = [e.text for e in host.drain_events()]
    assert texts == [
        "left1 FORWARD 0.84 m/s for 16 ticks",
        "left2 BACKWARD 1.20 m/s for 16 ticks",
        "left1 STOP",
    ]
    assert host.drain_events() == []


def test_turn_rate_and_duration_hand_cases() -> None:
    host, link = make_host()
    spin_accel = 2 * PRESET.robot.wheel_accel_mps2 / PRESET.robot.track_m  # 80 rad/s²
    # 90° left: ramp-limited rate √(80·π/2) = 11.2 rad/s -> ⌈33.6⌉ = 34 ticks.
    host.submit(A, (Turn(math.pi / 2),), 0)
    (c,) = sent(link)
    assert c.primitive is Primitive.TURN and c.duration_ticks == 34
    assert c.value == pytest.approx((math.pi / 2) / (34 * DT))
    assert c.value <= math.sqrt(spin_accel * math.pi / 2)
    # Small right turn: the one-camera-period rate |a|/T, for one period.
    host.submit(A, (Turn(-0.01),), 1)
    (c,) = sent(link, 1)
    assert c.duration_ticks == PERIOD
    assert c.value == pytest.approx(-0.01 / (PERIOD * DT))
    # Angles beyond π are wrapped: 3π/2 left is π/2 right.
    host.submit(A, (Turn(3 * math.pi / 2),), 2)
    (c,) = sent(link, 2)
    assert c.value < 0 and c.duration_ticks == 34
    host.submit(A, (Turn(0.0),), 3)
    assert sent(link, 3)[0].primitive is Primitive.STOP


@pytest.mark.parametrize("angle", [0.05, -0.4, 1.0, -2.0, 3.0])
def test_turn_from_rest_rotates_by_the_angle(angle: float) -> None:
    """Host rate/duration + firmware + ramped wheels: the robot ends rotated by the angle."""
    host, link = make_host()
    fw = Firmware(A, PRESET.robot, PRESET.firmware, timeout_ticks=PRESET.ticks(0.25, "t"))
    host.submit(A, (Turn(angle),), 0)
    for c in sent(link):
        fw.receive(c, 0)
    left = right = heading = 0.0
    dv = PRESET.robot.wheel_accel_mps2 * DT
    for tick in range(200):
        lt, rt = fw.update(tick)
        left += max(-dv, min(dv, lt - left))
        right += max(-dv, min(dv, rt - right))
        heading += (right - left) / PRESET.robot.track_m * DT
    assert left == right == 0.0
    assert heading == pytest.approx(angle, rel=1e-9)  # the ramp's lag is repaid at the end


def test_kick_without_kicker_pushes_or_turns() -> None:
    host, link = make_host()
    assert PRESET.robot.kicker is None
    host.submit(A, (Kick(50.0, 0.1),), 0)
    (c,) = sent(link)
    assert (c.primitive, c.duration_ticks) == (Primitive.FORWARD, 16)
    assert c.value == pytest.approx(0.5 * VMAX)
    host.submit(A, (Kick(50.0, PUSH_HALF_ANGLE_RAD + 0.3),), 1)
    (c,) = sent(link, 1)
    assert c.primitive is Primitive.TURN and c.value > 0


def test_kick_with_kicker() -> None:
    kicker = KickerConfig(reach_m=0.01, max_speed_mps=3.0, half_angle_rad=0.3)
    preset = dataclasses.replace(PRESET, robot=dataclasses.replace(PRESET.robot, kicker=kicker))
    host, link = make_host(preset)
    host.submit(A, (Kick(140.0, -0.25),), 0)
    (c,) = sent(link)
    assert (c.primitive, c.value, c.duration_ticks) == (Primitive.KICK, 100.0, None)
    host.submit(A, (Kick(50.0, -0.5),), 1)
    (c,) = sent(link, 1)
    assert c.primitive is Primitive.TURN and c.value < 0
    assert host.drain_events()[0].text == "left1 KICK 100"


def test_one_body_action_per_submit_and_increasing_seq() -> None:
    host, link = make_host()
    host.submit(A, (Turn(1.0), Dash(100.0), Kick(10.0, 0.0)), 0)
    host.submit(B, (Dash(10.0),), 0)
    cs = sent(link)
    assert [(c.robot, c.primitive) for c in cs] == [(A, Primitive.TURN), (B, Primitive.FORWARD)]
    assert cs[0].seq < cs[1].seq


def test_broadcast_stop_reaches_every_firmware() -> None:
    host, link = make_host()
    fws = [Firmware(r, PRESET.robot, PRESET.firmware, timeout_ticks=60) for r in REFS]
    for fw in fws:
        fw.receive(Command(0, fw.ref, Primitive.FORWARD, 0.5), 0)
    host.stop(3)
    (c,) = sent(link, 3)
    assert c.robot is None
    assert all(fw.receive(c, 4) for fw in fws)
    assert all(fw.update(4) == (0.0, 0.0) for fw in fws)
    assert host.drain_events()[0].text == "all STOP"


# ----------------------------------------------------------------------------- say / hear


def test_say_relayed_to_every_other_robot_once() -> None:
    host, link = make_host()
    f = frame(None, (A, 0.0, 0.0, 0.0), (B, 0.0, 2.0, 0.0), (C, 1.0, 0.0, math.pi))
    host.percepts(f, 12)
    host.submit(A, (Say("pass to me"), Dash(20.0)), 12)
    assert [c.primitive for c in sent(link, 12)] == [Primitive.FORWARD]
    pa, pb, pc = host.percepts(f, 20)
    assert pa.heard == ()
    for p, direction in ((pb, -math.pi / 2), (pc, 0.0)):
        (h,) = p.heard
        assert (h.text, h.sender, h.tick) == ("pass to me", A, 12)
        assert h.direction_rad == pytest.approx(direction)
    assert all(p.heard == () for p in host.percepts(f, 28))
    events = host.drain_events()
    assert [(e.channel, e.text) for e in events] == [
        ("link", "left1 FORWARD 0.24 m/s for 16 ticks"),
    ]


def test_say_from_unseen_robot_has_no_direction() -> None:
    host, _ = make_host()
    host.submit(C, (Say("hi"),), 0)
    pa, pb, pc = host.percepts(frame(None, (A, 0.0, 0.0, 0.0)), 12)
    assert pa.heard[0].direction_rad is None and pa.heard[0].sender == C
    assert pb.heard[0].direction_rad is None
    assert pc.heard == ()


# ----------------------------------------------------------------------------- end to end


def test_host_link_firmware_pipeline_with_latency() -> None:
    link = Link(
        dataclasses.replace(PRESET.link, loss_prob=0.0),
        packet_period_ticks=1,
        latency_ticks=3,
        rng=np.random.default_rng(4),
    )
    host = CentralHost(REFS, PRESET, link, frame_period_ticks=PERIOD)
    fw = Firmware(B, PRESET.robot, PRESET.firmware, timeout_ticks=60)
    outputs = []
    for tick in range(30):
        for c in link.deliver(tick):
            fw.receive(c, tick)
        if tick == 8:
            host.submit(B, (Dash(50.0),), tick)
        outputs.append(fw.update(tick))
    moving = [t for t, o in enumerate(outputs) if o != (0.0, 0.0)]
    assert moving == list(range(11, 27))  # arrives 3 ticks after send, held 2 camera periods


# ----------------------------------------------------------------------------- several actions


def test_turn_then_dash_sends_the_dash_when_the_turn_ends() -> None:
    host, link = make_host()
    host.submit(A, (Turn(math.pi / 2), Dash(100.0)), 0)  # a 34-tick turn (hand case above)
    (c,) = sent(link)
    assert c.primitive is Primitive.TURN and c.duration_ticks == 34
    assert host.pending(A) == (Dash(100.0),)
    assert host.next_release_tick == 34
    for tick in range(1, 34):
        host.release(tick)
        assert sent(link, tick) == []
    host.release(34)
    (c,) = sent(link, 34)
    assert (c.robot, c.primitive, c.value, c.sent_tick) == (A, Primitive.FORWARD, VMAX, 34)
    assert host.pending(A) == () and host.next_release_tick > 10**9


def test_three_actions_run_in_order_with_their_durations() -> None:
    host, link = make_host()
    host.submit(A, (Dash(50.0), Turn(-0.01), Dash(20.0)), 0)
    assert sent(link)[0].primitive is Primitive.FORWARD
    host.release(PERIOD - 1)
    assert sent(link, PERIOD - 1) == []
    host.release(PERIOD)  # a dash lasts one camera period, then the turn (one period, small)
    (c,) = sent(link, PERIOD)
    assert c.primitive is Primitive.TURN and c.duration_ticks == PERIOD
    host.release(2 * PERIOD)
    (c,) = sent(link, 2 * PERIOD)
    assert c.primitive is Primitive.FORWARD and c.value == pytest.approx(0.2 * VMAX)


def test_a_new_decision_replaces_the_pending_actions() -> None:
    host, link = make_host()
    host.submit(A, (Turn(1.0), Dash(100.0)), 0)
    host.submit(B, (Turn(1.0), Dash(60.0)), 0)
    sent(link)
    host.submit(A, (Dash(30.0),), 5)
    (c,) = sent(link, 5)
    assert c.primitive is Primitive.FORWARD and c.value == pytest.approx(0.3 * VMAX)
    assert host.pending(A) == () and host.pending(B) == (Dash(60.0),)
    _, ticks = host.turn_plan(1.0)
    for tick in range(6, ticks + 1):
        host.release(tick)
    (c,) = sent(link, ticks)  # only B's dash: A's was replaced
    assert (c.robot, c.primitive) == (B, Primitive.FORWARD)
    # Issue 28's counter: one pending action (A's dash) dropped by a new decision, no other.
    assert (host.dropped, host.dropped_dashes) == (1, 1)
    host.submit(B, (Kick(50.0, 0.0),), ticks + 1)
    assert (host.dropped, host.dropped_dashes) == (1, 1)  # B's dash had gone: nothing dropped


def test_zero_turn_then_dash_goes_out_at_once() -> None:
    host, link = make_host()
    host.submit(A, (Turn(0.0), Dash(100.0)), 0)
    # STOP then FORWARD in the same tick: the link keeps the newer one for the address.
    (c,) = sent(link)
    assert c.primitive is Primitive.FORWARD
    assert host.pending(A) == ()


def test_kick_then_dash_waits_for_the_kick_packet() -> None:
    kicker = KickerConfig(reach_m=0.01, max_speed_mps=3.0, half_angle_rad=0.3)
    preset = dataclasses.replace(PRESET, robot=dataclasses.replace(PRESET.robot, kicker=kicker))
    host, link = make_host(preset)
    host.submit(A, (Kick(80.0, 0.0), Dash(100.0)), 0)
    assert [c.primitive for c in sent(link)] == [Primitive.KICK]
    host.release(1)  # one packet period (1 tick here) later
    assert [c.primitive for c in sent(link, 1)] == [Primitive.FORWARD]


def test_says_go_at_once_and_do_not_take_a_place_in_the_chain() -> None:
    host, link = make_host()
    host.submit(A, (Turn(0.5), Say("mine"), Dash(100.0)), 0)
    assert [c.primitive for c in sent(link)] == [Primitive.TURN]
    assert host.pending(A) == (Dash(100.0),)
    assert [e.channel for e in host.drain_events()] == ["link"]


def test_turn_then_dash_reaches_the_firmware_as_the_turn_ends() -> None:
    link = Link(
        dataclasses.replace(PRESET.link, loss_prob=0.0),
        packet_period_ticks=1,
        latency_ticks=3,
        rng=np.random.default_rng(4),
    )
    host = CentralHost(REFS, PRESET, link, frame_period_ticks=PERIOD)
    fw = Firmware(B, PRESET.robot, PRESET.firmware, timeout_ticks=60)
    _, turn_ticks = host.turn_plan(0.8)
    outputs = []
    for tick in range(80):
        host.release(tick)
        for c in link.deliver(tick):
            fw.receive(c, tick)
        if tick == 8:
            host.submit(B, (Turn(0.8), Dash(100.0)), tick)
        outputs.append(fw.update(tick))
    turning = [t for t, (left, right) in enumerate(outputs) if left < 0.0 < right]
    forward = [t for t, (left, right) in enumerate(outputs) if left == right > 0.0]
    assert turning == list(range(11, 11 + turn_ticks))
    assert forward == list(range(11 + turn_ticks, 11 + turn_ticks + 2 * PERIOD))


def test_robot_arena_releases_the_dash_of_a_decision() -> None:
    from field_models.registry import make_arena
    from field_models.robot_physics.arena import RobotArena
    from field_models.seeding import TrialRngs

    arena = make_arena(
        "robot_physics", "small_size_1997", (A, C), TrialRngs.for_trial(3, 0), keep_events=True
    )
    assert isinstance(arena, RobotArena)
    arena.place_player(A, 0.0, 0.0, 0.0)
    arena.place_player(C, 0.5, 0.5, 0.0)
    for _ in range(10):
        arena.step()
    arena.submit(A, (Turn(1.0), Dash(100.0)))
    _, turn_ticks = arena.host.turn_plan(1.0)
    for _ in range(turn_ticks + 20):
        arena.step()
    events = [(e.tick, e.channel, e.text) for e in arena.drain_events() if e.player == A]
    assert [(tick, text) for tick, channel, text in events if channel == "command"] == [
        (10, "(turn -57.3)"),
        (10, "(dash 100)"),
    ]
    sent_ = [(tick, text.split()[1]) for tick, channel, text in events if channel == "link"]
    assert sent_ == [(10, "TURN"), (10 + turn_ticks, "FORWARD")]
    state = arena.player_state(A)
    assert math.hypot(state.vx, state.vy) > 0.1  # driving after the turn


@pytest.mark.parametrize(
    ("direction", "turn", "primitive"),
    [
        (0.0, None, Primitive.FORWARD),
        (math.pi, None, Primitive.BACKWARD),
        (0.5, 0.5, Primitive.FORWARD),
        (-2.5, math.pi - 2.5, Primitive.BACKWARD),
    ],
)
def test_a_directed_dash_turns_first_or_drives_backwards(
    direction: float, turn: float | None, primitive: Primitive
) -> None:
    host, link = make_host()
    host.submit(A, (Dash(60.0, direction),), 0)
    (first,) = sent(link)
    if turn is None:
        assert first.primitive is primitive and first.value == pytest.approx(0.6 * VMAX)
        assert host.pending(A) == ()
        return
    assert first.primitive is Primitive.TURN
    assert first.value * first.duration_ticks * DT == pytest.approx(turn)
    due = host.next_release_tick
    assert due == first.duration_ticks
    host.release(due)
    (then,) = sent(link, due)
    assert then.primitive is primitive and then.value == pytest.approx(0.6 * VMAX)


def test_an_arc_robot_drives_while_it_turns_then_dashes() -> None:
    preset = load_preset("small_size_1997_arc")
    host, link = make_host(preset)
    host.submit(A, (Turn(math.pi / 2), Dash(100.0)), 0)
    (c,) = sent(link)
    spin = host.turn_plan(math.pi / 2)
    assert (c.primitive, c.value, c.duration_ticks) == (Primitive.ARC, VMAX, spin[1])
    assert c.rate == pytest.approx(spin[0])  # the same turn as a spin, in the same time
    assert host.pending(A) == (Dash(100.0),)
    host.release(spin[1])
    (c,) = sent(link, spin[1])
    assert c.primitive is Primitive.FORWARD


def test_an_arc_robot_still_spins_for_a_turn_alone() -> None:
    host, link = make_host(load_preset("small_size_1997_arc"))
    host.submit(A, (Turn(-0.5),), 0)
    (c,) = sent(link)
    assert c.primitive is Primitive.TURN and c.value < 0.0


def test_wheels_go_out_at_once_held_and_replace_the_pending_actions() -> None:
    host, link = make_host()
    host.submit(A, (Turn(1.0), Dash(100.0)), 0)
    sent(link)
    host.wheels(A, 0.2, -0.1, 3)
    (c,) = sent(link, 3)
    assert (c.primitive, c.value, c.rate) == (Primitive.WHEELS, 0.2, -0.1)
    assert c.duration_ticks == 2 * PERIOD and host.pending(A) == ()
    assert "WHEELS +0.20 -0.10 m/s" in host.drain_events()[-1].text


def test_robots_accept_and_ignore_a_neck_turn_and_a_view_change() -> None:
    """An overhead camera has no head to turn (host docstring): the same client runs on both."""
    from field_models.protocol import ChangeView, TurnNeck
    from field_models.registry import make_arena
    from field_models.seeding import TrialRngs

    def history(extra: tuple[Action, ...]) -> list[object]:
        arena = make_arena("robot_physics", "small_size_1997", (A, C), TrialRngs.for_trial(3, 0))
        arena.place_player(A, 0.0, 0.0, 0.0)
        arena.place_player(C, 0.5, 0.5, 0.0)
        out: list[object] = []
        for tick in range(60):
            for percept in arena.step():
                assert percept.neck_rad == 0.0
                out.append(percept)
                if percept.player == A and tick % 7 == 0:
                    arena.submit(A, (Turn(0.4), *extra, Dash(60.0)))
                elif percept.player == A and tick % 7 == 3:
                    arena.submit(A, extra)  # a decision of only these is no decision
            out.append(arena.truth())
        return out

    assert history((TurnNeck(0.5), ChangeView("wide", "low"))) == history(())
