"""The motion skill: turns in flight (reckon and hold), turn then go, the one dribble rule."""

from __future__ import annotations

import dataclasses
import math

import pytest

from field_models.protocol import (
    LEFT,
    RIGHT,
    Dash,
    Percept,
    PlayerRef,
    SeenBall,
    SeenLandmark,
    Turn,
)
from field_models.registry import field_facts
from robotsoccer.drills import match_setup, setplay_kicks
from robotsoccer.drills.match import MatchDrill
from robotsoccer.drills.setplay import SetPlayDrill
from robotsoccer.skills.ball_sense import Heading
from robotsoccer.skills.intercept import DefenderMind
from robotsoccer.skills.motion import (
    DRIBBLE_PERIODS,
    DRIBBLE_UNITS,
    PUSH_DRIBBLE_POWER,
    TurnsInFlight,
    dribble_power,
    stop_speed,
    turn_then_go,
)
from robotsoccer.skills.team import TeamMind
from robotsoccer.skills.turn_policies import straight_policy
from tests.robotsoccer.skills.test_team import percept, setup

ME = PlayerRef(LEFT, 7)


def seen(tick: int, observed: int, ball_angle: float) -> Percept:
    """A percept with the ball 5 m away at `ball_angle` and the goal flag straight ahead."""
    marks = (SeenLandmark("g r", 30.0, 0.0),)
    return Percept(ME, tick, observed, SeenBall(5.0, ball_angle), (), (), marks)


# ----------------------------------------------------------------------------- reckoning


def test_a_sent_turn_is_reckoned_into_the_view_until_a_percept_shows_it() -> None:
    turns = TurnsInFlight(settle=3)
    turns.sent(10, 0.5)
    assert turns.heading_rad == 0.5 and turns.shown_rad == 0.0
    # Observed at 12 (< 10 + 3) the percept predates the turn: its ball is 0.5 rad further
    # right in the frame the player now faces; the flag straight ahead likewise.
    view = turns.view(seen(14, 12, 0.2))
    assert view.ball is not None and view.ball.angle_rad == pytest.approx(0.2 - 0.5)
    assert view.landmarks[0].angle_rad == pytest.approx(-0.5)
    assert turns.in_flight(12) == 0.5
    shown = seen(15, 13, 0.2)
    assert turns.view(shown) is shown  # observed at 13 it shows the turn: nothing to reckon
    assert turns.in_flight(13) == 0.0 and turns.shown_rad == 0.5 and turns.heading_rad == 0.5


def test_turns_in_flight_add_and_leave_in_the_order_they_show() -> None:
    turns = TurnsInFlight(settle=2)
    turns.note((Turn(0.3), Dash(100.0)), 4)
    turns.note((Turn(-0.1),), 5)
    assert turns.in_flight(5) == pytest.approx(0.2)
    assert turns.in_flight(6) == pytest.approx(-0.1) and turns.shown_rad == pytest.approx(0.3)
    assert turns.in_flight(7) == 0.0 and turns.shown_rad == pytest.approx(0.2)
    turns.sent(8, 3.0)
    turns.sent(8, 3.0)  # the reckoned heading stays wrapped; the shown sum does not
    assert turns.heading_rad == pytest.approx(0.2 + 6.0 - 2.0 * math.pi)
    turns.in_flight(10)
    assert turns.shown_rad == pytest.approx(6.2)


def test_a_settle_that_depends_on_the_angle_shows_a_small_turn_before_a_big_one() -> None:
    turns = TurnsInFlight(settle=lambda angle: 1 if abs(angle) < 1.0 else 5)
    turns.sent(0, 2.0)  # shows from 5
    turns.sent(1, 0.1)  # shows from 2
    assert turns.in_flight(3) == 2.0 and turns.shown_rad == 0.1


def test_the_set_play_heading_and_the_defender_keep_their_turns_in_the_motion_skill() -> None:
    heading = Heading(settle_ticks=5)
    heading.note((Turn(0.4),), 10)
    view = heading.view(seen(12, 12, 0.0))
    assert view.ball is not None and view.ball.angle_rad == pytest.approx(-0.4)
    assert heading.unseen_rad == 0.4 and heading.rad == 0.4 and heading.turns.in_flight(15) == 0
    defender = DefenderMind(straight_policy, trigger_distance_m=1.0)
    (turn,) = defender.act(seen(20, 20, 0.25))  # beyond the trigger: it faces the ball
    assert turn == Turn(0.25)
    assert defender._heading_at(20) == 0.0 and defender._heading_at(21) == 0.25


# ----------------------------------------------------------------------------- the hold


def test_the_hold_lasts_the_team_setup_s_turn_ticks() -> None:
    # The robots' numbers: 50 ms latency, 1/240 s ticks, spin acceleration 80 rad/s².
    robots = dataclasses.replace(setup(), latency_s=0.05, dt_s=1.0 / 240.0, spin_accel_radps2=80.0)
    ticks = math.ceil((0.05 + math.sqrt(1.0 / 80.0)) * 240.0)  # 0.05 s + sqrt(1 rad / α)
    assert ticks == 39 and robots.turn_ticks(1.0) == ticks
    turns = TurnsInFlight(robots.turn_ticks)
    assert not turns.holding(0)
    turns.sent(100, -1.0)
    assert turns.holding(100 + ticks - 1) and not turns.holding(100 + ticks)
    turns.sent(200, 0.1)
    turns.sent(201, 1.0)  # the last turn sent decides the hold
    assert turns.holding(201 + ticks - 1) and not turns.holding(201 + ticks)


def test_a_team_mind_holds_until_its_turn_shows_or_reckons_it_and_decides() -> None:
    slow = dataclasses.replace(setup(), latency_s=0.5)  # a turn shows 5 ticks later
    ball = SeenBall(10.0, 1.0)  # off to the left: it turns toward it and runs
    hold = TeamMind(7, slow)
    first = hold.act(percept(0.0, 0.0, 0.0, ball=ball, tick=10))
    assert first == (Turn(1.0), Dash(100.0)) and slow.turn_ticks(1.0) == 6
    assert hold.act(percept(0.0, 0.0, 0.0, ball=ball, tick=13)) == ()  # held
    assert hold.act(percept(0.0, 0.0, 0.0, ball=ball, tick=16)) == first  # shown: decides
    reckon = TeamMind(7, dataclasses.replace(slow, turn_latency="reckon"))
    reckon.act(percept(0.0, 0.0, 0.0, ball=ball, tick=10))
    # The same stale percept, reckoned: the ball is straight ahead of the turned player.
    assert reckon.act(percept(0.0, 0.0, 0.0, ball=ball, tick=13)) == (Dash(100.0),)
    with pytest.raises(ValueError, match="turn_latency: expected one of hold, reckon"):
        dataclasses.replace(slow, turn_latency="wait")


# ----------------------------------------------------------------------------- turn then go


def test_turn_then_go_faces_within_an_inclusive_angle_or_leaves_out_a_smaller_turn() -> None:
    run = (Dash(100.0),)
    assert turn_then_go(0.2, run, facing_rad=0.2) == run  # facing: inclusive
    assert turn_then_go(-0.21, run, facing_rad=0.2) == (Turn(-0.21), *run)
    assert turn_then_go(0.5, run, facing_rad=0.2, turn_only=True) == (Turn(0.5),)
    assert turn_then_go(0.5, (), facing_rad=0.2) == (Turn(0.5),)
    assert turn_then_go(0.1, run, least_turn_rad=0.2) == run
    assert turn_then_go(0.2, run, least_turn_rad=0.2) == (Turn(0.2), *run)  # exclusive
    assert turn_then_go(0.0, run) == (Turn(0.0), *run)  # no tolerance: every turn, even by 0


# ----------------------------------------------------------------------------- dribbling


def test_the_dribble_rule_on_the_server_covers_four_units_in_eight_sees() -> None:
    facts = field_facts("soccer_server", "soccer_server_1996")
    kick = facts.kick
    assert kick is not None
    # The ball keeps 0.96 of its speed each 100 ms cycle: v0 (1 - 0.96^20) / (1 - 0.96) · 0.1 s
    # = 4 m in 8 see periods of 250 ms = 20 cycles.
    assert DRIBBLE_PERIODS * facts.sensor_period_s == 2.0 and facts.ball.decay_per_tick == 0.96
    speed = DRIBBLE_UNITS * (1.0 - 0.96) / (1.0 - 0.96**20) / 0.1
    power = dribble_power(facts, 1.0, kick.speed_per_power_mps)
    assert power == pytest.approx(speed / 0.16, rel=1e-12) == pytest.approx(17.9212, abs=1e-4)
    # The set play's carrier and a match's player dribble with that one power.
    plan = SetPlayDrill().plan(facts)
    assert setplay_kicks.kick_powers(facts, plan).dribble == power
    assert match_setup.kick_powers(facts, 100.0).dribble == power


def test_the_dribble_rule_on_the_robots_is_a_catch_up_kick_or_a_push() -> None:
    facts = field_facts("robot_physics", "small_size_1997")
    plan = SetPlayDrill().plan(facts)
    sense = setplay_kicks.ball_sense(facts, plan)
    margin = sense.reach_m - sense.touch_m
    # The coach's kick: at most half the speed the robot stops from within its kick margin,
    # seeing the ball 50 ms late and braking at a: v·0.05 + v²/(2a) = margin / 2.
    a = facts.player_accel_mps2
    stop = a * (math.sqrt(0.05**2 + margin / a) - 0.05)
    assert stop_speed(facts, margin) == pytest.approx(stop)
    assert stop * 0.05 + stop**2 / (2.0 * a) == pytest.approx(margin / 2.0)
    power = dribble_power(facts, margin, sense.speed_per_power_mps)
    assert power == pytest.approx(0.5 * stop / sense.speed_per_power_mps)
    assert setplay_kicks.kick_powers(facts, plan).dribble == power
    # A match has no coach to kick: a pushing player dribbles at the push power.
    assert dribble_power(facts, margin, None) == PUSH_DRIBBLE_POWER
    assert match_setup.kick_powers(facts, 100.0).dribble == PUSH_DRIBBLE_POWER


def test_no_kick_that_carries_the_ball_a_dribble_is_refused() -> None:
    facts = field_facts("soccer_server", "soccer_server_1996")
    with pytest.raises(ValueError, match="no kick sends the ball 4 units"):
        dribble_power(facts, 1.0, 0.001)  # 100 units of power give 0.1 m/s


def test_the_match_option_sets_one_team_both_or_neither_to_reckon() -> None:
    facts = field_facts("robot_physics", "small_size_1997")

    def latencies(value: str) -> list[str]:
        drill = MatchDrill(left="baseline", right="baseline", turn_latency=value)
        return [drill.team_setup(facts, 5, team).turn_latency for team in (LEFT, RIGHT)]

    assert latencies("hold") == ["hold", "hold"] and latencies("reckon") == ["reckon", "reckon"]
    assert latencies("left") == ["reckon", "hold"] and latencies("right") == ["hold", "reckon"]
    with pytest.raises(ValueError, match="turn_latency: expected one of hold, reckon, left, right"):
        MatchDrill(left="baseline", right="baseline", turn_latency="both")
