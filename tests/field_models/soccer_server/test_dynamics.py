"""Soccer Server dynamics against the spec's worked numbers (specs/soccer_server.md §2, §4, §6, §8).

Noise is off unless a test says otherwise.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from field_models.protocol import LEFT, RIGHT, BodyState, Dash, Kick, PlayerRef, Say, Turn
from field_models.soccer_server.cycle_rules import (
    PLAY_ON,
    dash_direction,
    dash_rate,
    kick_effectiveness,
)
from field_models.soccer_server.dynamics import SoccerServerModel
from field_models.soccer_server.params import ServerPreset, load_server_preset

ME = PlayerRef(LEFT, 1)
THEM = PlayerRef(RIGHT, 1)
QUIET = {"ball_rand": 0.0, "player_rand": 0.0, "kick_rand": 0.0}


def preset(name: str = "rcssserver_19_async", **changes: object) -> ServerPreset:
    return load_server_preset(name).replace_dynamics(**{**QUIET, **changes})


def model(
    name: str = "rcssserver_19_async", players: tuple[PlayerRef, ...] = (ME,), **changes: object
) -> SoccerServerModel:
    return SoccerServerModel(preset(name, **changes), players, np.random.default_rng(0))


def speed(m: SoccerServerModel, i: int) -> float:
    return math.hypot(m.vx[i], m.vy[i])


# ----------------------------------------------------------------------------- kick (§8.1-4)


def touching_kick(name: str) -> tuple[SoccerServerModel, float]:
    """A player at the origin facing +x, the ball touching it in front, a power-100 kick."""
    m = model(name, referee=False)
    p = m.params
    m.move_ball(p.player_size_m + p.ball_size_m, 0.0)  # ball first: the move resolves overlaps
    m.move_player(1, 0.0, 0.0, 0.0)
    assert m.command(1, Kick(100.0, 0.0))
    return m, m.x[0]


def test_power_100_kick_today_moves_2_7_then_45_m_in_total() -> None:
    m, x0 = touching_kick("rcssserver_19_async")
    positions = {}
    below = None
    for k in range(1, 1001):
        m.step()
        positions[k] = m.x[0] - x0
        if below is None and speed(m, 0) < 0.01:
            below = k
    assert positions[1] == pytest.approx(2.7, abs=1e-12)
    assert m.y[0] == 0.0
    for k, expected in {2: 5.238, 3: 7.6237, 10: 20.762, 20: 31.945, 50: 42.960}.items():
        assert positions[k] == pytest.approx(expected, abs=1e-3)
    assert positions[1000] == pytest.approx(45.0, abs=1e-6)
    assert below == 91


def test_power_100_kick_with_1998_values_travels_40_m() -> None:
    m, x0 = touching_kick("soccer_server_1996")
    below = None
    for k in range(1, 1001):
        m.step()
        if k == 1:
            assert m.x[0] - x0 == pytest.approx(1.6, abs=1e-12)
        if below is None and speed(m, 0) < 0.01:
            below = k
    assert m.x[0] - x0 == pytest.approx(40.0, abs=1e-6)
    assert below == 125


@pytest.mark.parametrize(
    ("gap", "dir_diff", "expected"),
    [
        (0.0, 0.0, 1.0),
        (0.115, 0.0, 1.0 - 0.25 * 0.115 / 0.7),  # §8.2: 0.958929
        (0.46256, 0.25531, 1.0 - 0.020317 - 0.165200),  # §8.3: 0.81448
        (0.7, math.pi, 0.5),  # the worst a kickable ball can be
        (0.35, math.pi / 2, 0.75),
    ],
)
def test_kick_effectiveness_at_hand_computed_points(
    gap: float, dir_diff: float, expected: float
) -> None:
    assert kick_effectiveness(gap, dir_diff, 0.7) == pytest.approx(expected, abs=2e-6)


def test_kick_with_ball_half_a_metre_ahead() -> None:
    m = model(referee=False)
    m.move_ball(0.5, 0.0)
    m.move_player(1, 0.0, 0.0, 0.0)
    m.command(1, Kick(100.0, 0.0))
    m.step()
    assert m.x[0] - 0.5 == pytest.approx(2.589107, abs=1e-6)  # §8.2, measured 2.58911
    assert m.vx[0] == pytest.approx(2.43376, abs=1e-5)


def test_kick_with_angle_and_distance_penalty() -> None:
    # §8.3 in our frame (the server's y is mirrored); measured 2.19915.
    m = model(referee=False)
    m.move_ball(0.5, 0.0)
    m.move_player(1, -0.320128, -0.213876, 0.0)
    m.kick(1, 100.0, 0.0)
    m.step()
    gap = math.hypot(0.820128, 0.213876) - 0.385
    k = kick_effectiveness(gap, math.atan2(0.213876, 0.820128), 0.7)
    assert m.x[0] - 0.5 == pytest.approx(2.7 * k, abs=1e-9)
    assert m.x[0] - 0.5 == pytest.approx(2.19915, abs=1e-4)


def test_1996_kick_has_no_effectiveness_reduction() -> None:
    m = model("soccer_server_1996", referee=False)
    m.move_ball(1.5, 0.0)  # a 0.615 m gap, within the 1.885 m kickable area
    m.move_player(1, 0.0, 0.0, 0.0)
    m.kick(1, 100.0, 0.0)
    m.step()
    assert m.x[0] - 1.5 == pytest.approx(1.6, abs=1e-12)


def test_kick_direction_is_counter_clockwise_from_the_heading() -> None:
    m = model(referee=False)
    m.move_ball(0.0, 0.385)
    m.move_player(1, 0.0, 0.0, math.pi / 2)  # facing +y, ball in front
    m.kick(1, 50.0, math.pi / 2)  # to the player's left: -x
    m.step()
    assert m.x[0] == pytest.approx(-1.35, abs=1e-12)
    assert m.y[0] == pytest.approx(0.385, abs=1e-12)


def test_ball_out_of_kickable_area_is_not_kicked() -> None:
    m = model(referee=False)
    m.move_ball(1.09, 0.0)  # kickable area 1.085 m
    m.move_player(1, 0.0, 0.0, 0.0)
    assert m.kick(1, 100.0, 0.0)  # accepted as a command, refused by the server ("kick fault")
    m.step()
    assert (m.x[0], m.vx[0]) == (1.09, 0.0)


# ----------------------------------------------------------------------------- dash, turn


def test_dash_100_from_rest_today() -> None:
    m = model(referee=False)
    m.move_ball(0.0, 20.0)  # out of the way
    m.move_player(1, -10.0, 0.0, 0.0)
    x = m.x[1]
    moves, stored = [], []
    for _ in range(30):
        m.command(1, Dash(100.0))
        m.step()
        moves.append(m.x[1] - x)
        stored.append(m.vx[1])
        x = m.x[1]
    assert moves[:5] == pytest.approx([0.6, 0.84, 0.936, 0.9744, 0.98976], abs=1e-12)
    assert stored[:3] == pytest.approx([0.24, 0.336, 0.3744], abs=1e-12)
    assert moves[-1] == pytest.approx(1.0, abs=1e-9)  # below the 1.05 cap
    assert stored[-1] == pytest.approx(0.4, abs=1e-9)


def test_dash_100_terminal_speed_with_1998_values() -> None:
    m = model("soccer_server_1996", referee=False)
    m.move_ball(0.0, 20.0)
    m.move_player(1, -30.0, 0.0, 0.0)
    for _ in range(40):
        x = m.x[1]
        m.dash(1, 100.0)
        m.step()
    assert m.x[1] - x == pytest.approx(1.0 / 0.6, abs=1e-9)


def test_dash_follows_the_heading() -> None:
    m = model(referee=False)
    m.move_player(1, 0.0, 10.0, math.pi / 2)
    m.dash(1, 100.0)
    m.step()
    assert m.y[1] - 10.0 == pytest.approx(0.6, abs=1e-12)
    assert m.x[1] == pytest.approx(0.0, abs=1e-12)


def first_push(
    name: str, direction_deg: float, power: float = 100.0, heading: float = 0.0
) -> tuple[float, float]:
    """The first-cycle displacement of a player at rest dashing `direction_deg` (ours, CCW)."""
    m = model(name, referee=False)
    m.move_ball(0.0, 30.0)  # out of the way
    m.move_player(1, 0.0, 0.0, heading)
    assert m.command(1, Dash(power, math.radians(direction_deg)))
    m.step()
    return m.x[1], m.y[1]


@pytest.mark.parametrize(
    ("direction_deg", "rate"),
    [(0.0, 1.0), (45.0, 0.7), (-45.0, 0.7), (90.0, 0.4), (-90.0, 0.4), (135.0, 0.55), (180.0, 0.7)],
)
def test_directed_dash_rate_and_direction_today(direction_deg: float, rate: float) -> None:
    # leg.cpp calcDashAccel: 1 ahead, 0.4 (side_dash_rate) at ±90°, 0.7 (back_dash_rate) at 180°,
    # linear between; the push runs along heading + direction (ours CCW: +90° is to the left).
    x, y = first_push("rcssserver_19_async", direction_deg)
    push = 100.0 * 0.006 * rate
    expected = (
        push * math.cos(math.radians(direction_deg)),
        push * math.sin(math.radians(direction_deg)),
    )
    assert (x, y) == pytest.approx(expected, abs=1e-12)
    assert dash_rate(math.radians(direction_deg), 0.4, 0.7) == pytest.approx(rate, abs=1e-12)


def test_side_dash_goes_sideways_relative_to_the_heading() -> None:
    # Facing +y, a dash at +90° (our left) runs toward -x at 0.4 of the power.
    x, y = first_push("rcssserver_19_async", 90.0, heading=math.pi / 2)
    assert (x, y) == pytest.approx((-0.24, 0.0), abs=1e-12)
    # The server's (dash 100 90) is to the player's right: our -90°.
    x, y = first_push("rcssserver_19_async", -90.0, heading=math.pi / 2)
    assert (x, y) == pytest.approx((0.24, 0.0), abs=1e-12)


def test_dash_direction_is_rounded_to_the_step_and_clamped() -> None:
    d = load_server_preset("rcssserver_19_async").dynamics
    assert dash_direction(math.radians(30.4), d) == pytest.approx(math.radians(30.0), abs=1e-12)
    assert dash_direction(math.radians(-30.6), d) == pytest.approx(math.radians(-31.0), abs=1e-12)
    assert dash_direction(math.radians(0.5), d) == 0.0  # rint: half to even
    assert dash_direction(math.radians(1.5), d) == pytest.approx(math.radians(2.0), abs=1e-12)
    wide = d.replace(dash_angle_step_rad=math.radians(45.0))
    assert dash_direction(math.radians(60.0), wide) == pytest.approx(math.pi / 4, abs=1e-12)
    assert dash_direction(math.radians(70.0), wide) == pytest.approx(math.pi / 2, abs=1e-12)
    free = d.replace(dash_angle_step_rad=0.0)
    assert dash_direction(0.1234, free) == 0.1234  # step 0: any direction
    # The range is the server's (clockwise) one: [-90, 30] server degrees is [-30, 90] ours.
    narrow = d.replace(
        min_dash_angle_rad=math.radians(-90.0), max_dash_angle_rad=math.radians(30.0)
    )
    assert dash_direction(math.radians(60.0), narrow) == pytest.approx(math.radians(60.0))
    assert dash_direction(math.radians(-60.0), narrow) == pytest.approx(math.radians(-30.0))
    assert dash_direction(math.radians(120.0), narrow) == pytest.approx(math.radians(90.0))
    # A rounded direction moves the player exactly like the rounded request.
    assert first_push("rcssserver_19_async", 44.6) == first_push("rcssserver_19_async", 45.0)


def test_dash_rate_is_clamped_to_0_1() -> None:
    assert dash_rate(math.pi, 0.4, 1.7) == 1.0
    assert dash_rate(math.pi / 2, -0.5, 0.7) == 0.0


def test_1996_preset_ignores_the_dash_direction() -> None:
    # The paper's servers had no dash direction: min = max = 0 clamps it to a straight dash.
    straight = first_push("soccer_server_1996", 0.0)
    assert straight == pytest.approx((1.0, 0.0), abs=1e-12)
    for direction in (90.0, -45.0, 180.0):
        assert first_push("soccer_server_1996", direction) == straight
    back = first_push("soccer_server_1996", 90.0, power=-30.0)
    assert back == pytest.approx((-0.3, 0.0), abs=1e-12)  # a negative power still runs back


def test_negative_dash_power_with_a_direction_today_does_nothing() -> None:
    assert first_push("rcssserver_19_async", 90.0, power=-50.0) == (0.0, 0.0)  # min_dash_power 0


@pytest.mark.parametrize(
    ("turn_deg", "speed_mps", "expected_deg"),
    [(90.0, 0.0, 90.0), (90.0, 4.0, 30.0), (180.0, 4.0, 60.0), (-90.0, 4.0, -30.0)],
)
def test_turn_with_inertia(turn_deg: float, speed_mps: float, expected_deg: float) -> None:
    # §8.6: stored speed 0.4 m/cycle (4 m/s): a turn of 90 gives 30 degrees.
    m = model(referee=False)
    m.move_player(1, 0.0, 10.0, 0.0, vx_mps=speed_mps)
    m.command(1, Turn(math.radians(turn_deg)))
    m.step()
    assert math.degrees(m.heading[1]) == pytest.approx(expected_deg, abs=1e-9)


# ----------------------------------------------------------------------------- clamping


def test_arguments_are_clamped_as_the_server_clamps_them() -> None:
    def first_move(name: str, action: Dash | Kick, ball_x: float = 30.0) -> tuple[float, float]:
        m = model(name, referee=False)
        m.move_ball(ball_x, 0.0)
        m.move_player(1, 0.0, 0.0, 0.0)
        m.command(1, action)
        x1, xb = m.x[1], m.x[0]
        m.step()
        return m.x[1] - x1, m.x[0] - xb

    assert first_move("rcssserver_19_async", Dash(150.0)) == first_move(
        "rcssserver_19_async", Dash(100.0)
    )
    assert first_move("rcssserver_19_async", Dash(-50.0))[0] == 0.0  # min_dash_power 0 today
    assert first_move("soccer_server_1996", Dash(-50.0))[0] == pytest.approx(-0.3)  # minpower -30
    kick_200 = first_move("rcssserver_19_async", Kick(200.0, 0.0), ball_x=0.385)
    assert kick_200 == first_move("rcssserver_19_async", Kick(100.0, 0.0), ball_x=0.385)


def test_turn_and_kick_direction_are_clamped_to_the_moment_range() -> None:
    m = model(referee=False)
    m.move_player(1, 0.0, 10.0, 0.0)
    m.turn(1, 4.0)  # beyond 180 degrees: a half turn
    m.step()
    assert abs(m.heading[1]) == pytest.approx(math.pi, abs=1e-12)
    moved = []
    for direction in (-4.0, -math.pi, 4.0):
        m = model(referee=False)
        m.move_ball(0.0, 0.385)  # touching, on the player's left
        m.move_player(1, 0.0, 0.0, 0.0)
        m.kick(1, 10.0, direction)  # beyond 180 degrees: clamped to straight back
        m.step()
        moved.append((m.x[0], m.y[0]))
    k = kick_effectiveness(0.0, math.pi / 2, 0.7)
    for x, y in moved:
        assert (x, y) == (pytest.approx(-0.27 * k, abs=1e-12), pytest.approx(0.385, abs=1e-12))


def test_one_body_command_per_cycle() -> None:
    m = model(referee=False)
    m.move_player(1, 0.0, 10.0, 0.0)
    assert m.command(1, Dash(100.0))
    assert not m.command(1, Turn(1.0))  # ignored, like the server
    assert not m.command(1, Kick(100.0, 0.0))
    assert m.command(1, Say("hi"))  # a say combines with a body command
    m.step()
    assert m.heading[1] == 0.0
    assert m.x[1] == pytest.approx(0.6)
    assert m.said() == [(1, "hi")]
    assert m.command(1, Turn(1.0))  # the next cycle takes a new one
    m.step()
    assert m.heading[1] != 0.0
    assert m.said() == []


def test_say_longer_than_say_msg_size_is_dropped() -> None:
    m = model(referee=False)
    assert not m.say(1, "x" * 11)  # today: 10 characters
    assert m.say(1, "x" * 10)
    m.step()
    assert m.said() == [(1, "x" * 10)]
    old = model("soccer_server_1996")
    assert old.say(1, "y" * 512)


def test_unknown_row_is_refused() -> None:
    m = model()
    with pytest.raises(IndexError):
        m.dash(0, 50.0)  # row 0 is the ball
    with pytest.raises(IndexError):
        m.player_state(2)


# ----------------------------------------------------------------------------- collisions (§4)


def test_collision_pushes_apart_and_reverses_velocity() -> None:
    # §8.12: two players whose centres end a cycle 0.4 m apart.
    m = model(players=(ME, THEM), referee=False)
    m.move_player(1, -0.5, 5.0, 0.0, vx_mps=3.0)
    m.move_player(2, 0.5, 5.0, math.pi, vx_mps=-3.0)
    m.step()
    assert m.x[2] - m.x[1] == pytest.approx(0.6, abs=1e-9)
    assert m.x[1] + m.x[2] == pytest.approx(0.0, abs=1e-12)
    assert m.vx[1] == pytest.approx(-0.1 * 0.4 * 0.3, abs=1e-12)
    assert m.vx[2] == pytest.approx(0.1 * 0.4 * 0.3, abs=1e-12)


def test_move_onto_the_ball_outside_play_on_moves_only_the_player() -> None:
    m = model()
    m.change_mode("kick_off_l")
    m.move_ball(0.0, 0.0)
    m.move_player(1, -0.1, 0.0, 0.0)
    assert (m.x[0], m.y[0]) == (0.0, 0.0)
    assert m.x[1] == pytest.approx(-0.385, abs=1e-9)
    m = model()  # play_on: both move, symmetrically
    m.move_ball(0.0, 0.0)
    m.move_player(1, -0.1, 0.0, 0.0)
    assert m.x[0] - m.x[1] == pytest.approx(0.385, abs=1e-9)
    assert m.x[0] + m.x[1] == pytest.approx(-0.1, abs=1e-9)


def test_before_kick_off_nothing_moves_but_turns() -> None:
    m = model()
    m.move_ball(0.0, 0.0, vx_mps=10.0)
    m.move_player(1, -5.0, 0.0, 0.0, vx_mps=5.0)
    m.change_mode("before_kick_off")
    m.dash(1, 100.0)
    m.step()
    assert (m.x[0], m.x[1]) == (0.0, -5.0)
    assert m.vx[1] == 0.0
    m.turn(1, 1.0)
    m.step()
    assert m.heading[1] == pytest.approx(1.0)


# ----------------------------------------------------------------------------- referee (§6)


def shot(
    name: str = "rcssserver_19_async", players: tuple[PlayerRef, ...] = (ME, THEM), **kw: object
) -> SoccerServerModel:
    """§8.10: ball at (50, 0) moving 1.5 m/cycle toward the right goal."""
    m = model(name, players=players, **kw)
    m.move_ball(50.0, 0.0, vx_mps=15.0)
    for i in range(1, len(players) + 1):
        m.move_player(i, -20.0, 10.0 * i, 0.0)
    return m


def test_goal_is_detected_and_the_referee_restarts_after_50_cycles() -> None:
    m = shot()
    assert m.step() == []
    assert m.x[0] == pytest.approx(51.5)
    assert m.step() == ["goal_l_1"]
    assert (m.x[0], m.vx[0]) == (pytest.approx(52.91), 0.0)  # the ball is frozen
    assert m.play_mode == "goal_l" and m.score_left == 1
    m.move_player(1, 52.0, 0.0, 0.0)  # touching the ball: kicks are refused after a goal
    m.kick(1, 100.0, 0.0)
    assert m.step() == []
    assert (m.x[0], m.vx[0]) == (pytest.approx(52.91), 0.0)
    for _ in range(48):
        assert m.step() == []
    assert m.step() == ["kick_off_r"]
    assert (m.x[0], m.y[0], m.play_mode) == (0.0, 0.0, "kick_off_r")
    # the left (defending) player is back in its half and out of the centre circle
    assert m.x[1] < 0.0 and math.hypot(m.x[1], m.y[1]) == pytest.approx(9.15 + 0.3)


def test_1996_referee_announces_goal_and_kick_off_in_the_same_cycle() -> None:
    m = shot("soccer_server_1996")
    m.step()
    assert m.step() == ["goal_l_1", "kick_off_r"]  # Figure 4: both at time 150
    assert (m.x[0], m.y[0]) == (0.0, 0.0)


def test_goal_without_the_scoring_team_counts_zero() -> None:
    m = shot(players=(THEM,))
    m.step()
    assert m.step() == ["goal_l_0"]


def test_goal_for_the_right_team_and_a_wide_shot() -> None:
    m = model(players=(ME, THEM))
    m.move_ball(-50.0, 0.0, vx_mps=-15.0)
    m.step()
    assert m.step() == ["goal_r_1"]
    m = model(players=(ME, THEM))
    m.move_ball(50.0, 7.5, vx_mps=15.0)  # outside the posts (7.07)
    for _ in range(3):
        assert m.step() == []
    assert m.pitch().goal_post_radius_m == 0.06  # the goal test's mouth: 7.01 + 0.06


def test_goal_between_the_posts_counts_the_post_radius() -> None:
    # rcssserver_19: |y| <= 7.01 + 0.06 at the line is a goal; the 1996 servers had no posts.
    for name, y, expected in [
        ("rcssserver_19_async", 7.05, ["goal_l_1"]),
        ("soccer_server_1996", 7.05, []),
        ("soccer_server_1996", 7.0, ["goal_l_1", "kick_off_r"]),
    ]:
        m = model(name, players=(ME, THEM))
        m.move_ball(52.0, y, vx_mps=10.0)
        assert m.step() == expected, (name, y)


def test_kick_in_a_restart_mode_starts_play() -> None:
    m = model(players=(ME, THEM))
    m.change_mode("kick_off_l")
    m.move_ball(0.0, 0.0)
    m.move_player(1, -0.4, 0.0, 0.0)
    assert m.step() == ["kick_off_l"]  # the trainer's change is announced at the next step
    m.kick(1, 50.0, 0.0)
    assert m.step() == [PLAY_ON]
    assert m.play_mode == PLAY_ON


def test_without_referee_the_ball_crosses_the_line_silently() -> None:
    m = shot(referee=False)
    for _ in range(5):
        assert m.step() == []
    assert m.x[0] > 53.0 and m.play_mode == PLAY_ON


# ----------------------------------------------------------------------------- state, determinism


def test_state_accessors_speak_metres_per_second() -> None:
    m = model()
    m.move_ball(1.0, 2.0, vx_mps=10.0, vy_mps=-5.0)
    assert m.vx[0] == pytest.approx(1.0) and m.vy[0] == pytest.approx(-0.5)
    ball = m.ball_state()
    assert (ball.x, ball.y, ball.vx, ball.vy) == (
        1.0,
        2.0,
        pytest.approx(10.0),
        pytest.approx(-5.0),
    )
    m.move_player(1, -3.0, 4.0, 0.5, vx_mps=2.0)
    me = m.player_state(m.row(ME))
    assert (me.x, me.y, me.heading, me.vx) == (-3.0, 4.0, 0.5, pytest.approx(2.0))
    m.step()
    assert m.cycle == 1


def run_noisy(seed: int) -> list[tuple[float, ...]]:
    m = SoccerServerModel(
        load_server_preset("rcssserver_19_async"), (ME, THEM), np.random.default_rng(seed)
    )
    m.move_ball(0.0, 0.0)
    m.move_player(1, -0.5, 0.0, 0.0)
    m.move_player(2, 5.0, 0.0, math.pi)
    trace = []
    for t in range(300):
        if t % 7 == 0:
            m.kick(1, 60.0, 0.3)
        else:
            m.dash(1, 40.0)
        m.turn(2, 0.2 if t % 2 else -0.2)
        m.step()
        trace.append((*m.x, *m.y, *m.vx, *m.heading))
    return trace


def test_same_seed_same_trajectory() -> None:
    assert run_noisy(11) == run_noisy(11)
    assert run_noisy(11) != run_noisy(12)


# ----------------------------------------------------------------------------- state reads


def test_states_are_body_states_with_velocities_per_second() -> None:
    m = model(players=(ME, THEM))
    m.move_ball(1.0, 2.0, 3.0, -4.0)
    m.move_player(2, -5.0, 6.0, 0.5, 1.5, -2.5)
    dt = m.params.dt_s
    ball, player = m.ball_state(), m.player_state(2)
    assert type(ball) is BodyState and type(player) is BodyState
    assert ball == BodyState(1.0, 2.0, 0.0, m.vx[0] * (1.0 / dt), m.vy[0] * (1.0 / dt))
    assert player == BodyState(-5.0, 6.0, 0.5, m.vx[2] * (1.0 / dt), m.vy[2] * (1.0 / dt))
    assert player.vx == pytest.approx(1.5) and player.heading == 0.5
    for row in (0, 3, -1):
        with pytest.raises(IndexError, match="outside"):
            m.player_state(row)
