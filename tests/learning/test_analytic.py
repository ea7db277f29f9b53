"""The analytic predictor (paper §5, Table 1): hand-computed turn angles."""

from __future__ import annotations

import doctest
import math

import pytest

import learning.analytic
from learning.analytic import (
    analytic_turn_angle,
    analytic_turn_angle_xy,
    predicted_ball_position,
)


def test_doctests() -> None:
    result = doctest.testmod(learning.analytic)
    assert result.attempted >= 4 and result.failed == 0


def test_the_motion_vector_is_lengthened_three_times_from_the_older_sighting() -> None:
    # From (6, 2) to (5, 1.5): v = (-1, -0.5); x3 from (6, 2) ends at (3, 0.5) = now + 2 v.
    assert predicted_ball_position(6.0, 2.0, 5.0, 1.5) == (3.0, 0.5)
    assert predicted_ball_position(6.0, 2.0, 5.0, 1.5, motion_multiplier=1.0) == (5.0, 1.5)


@pytest.mark.parametrize(
    ("prev", "now", "ta_deg"),
    [
        ((4.0, 0.0), (3.0, 0.0), 0.0),  # straight at the player: keep facing the ball
        ((3.0, 0.0), (2.0, 0.0), 0.0),  # predicted point is the player itself
        ((2.0, 0.0), (3.0, 0.0), 0.0),  # moving straight away
        ((3.0, 1.0), (3.0, 1.0), 0.0),  # not moving
        ((4.0, 1.0), (3.0, 1.0), 45.0 - math.degrees(math.atan2(1.0, 3.0))),  # 26.565° left
        ((4.0, -1.0), (3.0, -1.0), -(45.0 - math.degrees(math.atan2(1.0, 3.0)))),  # mirrored
        ((5.0, -1.0), (5.0, 0.0), math.degrees(math.atan2(2.0, 5.0))),  # crossing: 21.80° left
        ((1.0, 0.1), (0.5, 0.1), 180.0 - 2.0 * math.degrees(math.atan2(0.1, 0.5))),  # behind
        ((2.0, 0.0), (1.0, 0.0), 180.0),  # a half turn is +180°, never -180°
        ((2.0, -0.0), (1.0, -0.0), 180.0),
    ],
)
def test_hand_computed_turn_angles(
    prev: tuple[float, float], now: tuple[float, float], ta_deg: float
) -> None:
    assert math.degrees(analytic_turn_angle_xy(*prev, *now)) == pytest.approx(ta_deg, abs=1e-9)


def test_polar_form_equals_the_cartesian_form() -> None:
    # Ball from (3, 0) to (2, 0.5): it will be at (0, 1.5), 90° left of the heading.
    ba = math.atan2(0.5, 2.0)
    ta = analytic_turn_angle(3.0, 0.0, math.hypot(2.0, 0.5), ba)
    assert ta == pytest.approx(math.pi / 2 - ba, abs=1e-12)
    assert ta == pytest.approx(analytic_turn_angle_xy(3.0, 0.0, 2.0, 0.5), abs=1e-12)


@pytest.mark.parametrize("rotation_rad", [0.3, -1.2, math.pi / 2, 3.0])
def test_turn_angle_does_not_depend_on_the_frame_orientation(rotation_rad: float) -> None:
    # Egocentric or field-aligned positions give the same TA: rotate every sighting.
    prev_d, prev_a, d, a = 6.0, 0.2, 4.5, 0.12
    base = analytic_turn_angle(prev_d, prev_a, d, a)
    turned = analytic_turn_angle(prev_d, prev_a + rotation_rad, d, a + rotation_rad)
    assert turned == pytest.approx(base, abs=1e-12)


def test_a_larger_multiplier_looks_further_ahead() -> None:
    # Ball crossing from the right to the left: looking further ahead turns further left.
    ta3 = analytic_turn_angle_xy(5.0, -1.0, 5.0, 0.0)
    ta5 = analytic_turn_angle_xy(5.0, -1.0, 5.0, 0.0, motion_multiplier=5.0)
    assert ta5 == pytest.approx(math.atan2(4.0, 5.0), abs=1e-12) and ta5 > ta3 > 0.0
