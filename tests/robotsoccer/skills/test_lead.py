"""The lead decision's pieces: the velocity fit, the track angle, the analytic meeting time."""

from __future__ import annotations

import math

import pytest

from field_models.arena import BallLaw
from robotsoccer.skills.lead import (
    BallTrack,
    RandomLead,
    earliest_meeting,
    lead_policy,
    run_distance,
    straight_lead,
    track_angle,
    velocity_window,
)

ROLLING = BallLaw("constant", dt_s=1 / 240, decel_mps2=0.0)


def test_the_velocity_fit_is_exact_on_straight_motion_and_waits_for_its_window() -> None:
    track = BallTrack(4)
    assert track.velocity() is None and not track.full()
    for k in range(4):
        track.add(k / 30, 1.0 - 0.9 * k / 30, 0.2 + 0.3 * k / 30)
    vx, vy = track.velocity() or (0.0, 0.0)
    assert track.full()
    assert vx == pytest.approx(-0.9) and vy == pytest.approx(0.3)
    track.add(4 / 30, 0.0, 0.0)  # the window slides: only the last four count
    assert len(track._seen) == 4


def test_the_window_spans_a_tenth_of_a_second_and_at_least_two_sightings() -> None:
    assert velocity_window(1 / 30) == 4  # the robots' camera
    assert velocity_window(0.25) == 2  # the 1996 server's sees


def test_the_track_angle_is_zero_head_on_and_signed_by_the_side_the_ball_passes() -> None:
    assert track_angle((0.0, 0.0), (1.0, 0.0), (2.0, 0.0)) == pytest.approx(0.0)
    left_of_line = track_angle((0.0, 0.0), (1.0, 0.1), (2.0, 0.0))
    assert left_of_line < 0.0  # velocity turned left of the line to the defender
    assert track_angle((0.0, 0.0), (1.0, -0.1), (2.0, 0.0)) == pytest.approx(-left_of_line)
    assert abs(track_angle((0.0, 0.0), (-1.0, 0.0), (2.0, 0.0))) == pytest.approx(math.pi)


def test_a_run_from_rest_ramps_then_holds_its_top_speed() -> None:
    assert run_distance(-0.1, 1.2, 3.0) == 0.0
    assert run_distance(0.2, 1.2, 3.0) == pytest.approx(0.5 * 3.0 * 0.04)
    assert run_distance(1.0, 1.2, 3.0) == pytest.approx(0.5 * 1.2 * 0.4 + 1.2 * 0.6)


def test_the_earliest_meeting_is_where_the_run_first_reaches_the_ball() -> None:
    # A ball 1 m away coming straight at the defender at 1 m/s; the defender runs at it.
    t = earliest_meeting((1.0, 0.0), (-1.0, 0.0), ROLLING, 1.2, 3.0, delay_s=0.05)
    gap = 1.0 - t
    assert run_distance(t - 0.05, 1.2, 3.0) >= gap
    assert run_distance(t - 0.06, 1.2, 3.0) < 1.0 - (t - 0.01)
    # A ball at rest 0.3 m away: the time to run 0.3 m.
    t_rest = earliest_meeting((0.3, 0.0), (0.0, 0.0), ROLLING, 1.2, 3.0, delay_s=0.0)
    assert run_distance(t_rest, 1.2, 3.0) == pytest.approx(0.3, abs=0.02)


def test_an_unreachable_ball_gives_the_time_of_its_closest_approach() -> None:
    t = earliest_meeting((-1.0, 0.5), (10.0, 0.0), ROLLING, 0.1, 0.1, delay_s=0.0)
    assert t == pytest.approx(0.1, abs=0.011)


def test_the_behaviours_lead_rules() -> None:
    class Fixed:
        def uniform(self, low: float, high: float) -> float:
            return 0.25 * (high - low) + low

    assert lead_policy("still", Fixed()) is None  # type: ignore[arg-type]
    assert lead_policy("straight", Fixed()) is straight_lead  # type: ignore[arg-type]
    random = lead_policy("random", Fixed(), random_max_s=0.8)  # type: ignore[arg-type]
    assert isinstance(random, RandomLead) and random(0.5, 0.1, 0.52) == pytest.approx(0.2)
    with pytest.raises(ValueError, match="needs a model file"):
        lead_policy("net", Fixed())  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="no lead rule"):
        lead_policy("lookup", Fixed())  # type: ignore[arg-type]
