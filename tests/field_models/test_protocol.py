"""Shared rules of field_models.protocol: the one angle wrap and the one goal-line rule."""

from __future__ import annotations

import math

import numpy as np
import pytest

from field_models.protocol import Crossing, Pitch, end_line_crossing, wrap_angle

SERVER_1996 = Pitch(105.0, 68.0, 14.02, 2.44, 0.085, 0.8)
"""The paper's server: no posts, the goal mouth is |y| <= 7.01 at the line."""
SERVER_19 = Pitch(105.0, 68.0, 14.02, 2.44, 0.085, 0.3, goal_post_radius_m=0.06)
"""rcssserver 19: the goal test widens the mouth by the post radius, |y| <= 7.07."""


# ----------------------------------------------------------------------------- wrap_angle


@pytest.mark.parametrize(
    ("angle", "expected"),
    [
        (0.0, 0.0),
        (1.0, 1.0),
        (-math.pi, -math.pi),
        (math.pi, -math.pi),  # [-pi, pi): +pi wraps to -pi
        (1.5 * math.pi, -0.5 * math.pi),
        (-1.5 * math.pi, 0.5 * math.pi),
        (7.0 * math.pi + 0.25, -math.pi + 0.25),
        (-20.0, -20.0 + 6.0 * math.pi),
    ],
)
def test_wrap_angle_on_floats(angle: float, expected: float) -> None:
    wrapped = wrap_angle(angle)
    assert isinstance(wrapped, float)
    assert -math.pi <= wrapped < math.pi
    assert wrapped == pytest.approx(expected, abs=1e-12)


def test_wrap_angle_leaves_an_angle_inside_untouched() -> None:
    for angle in (-math.pi, -3.0, -1e-300, 0.0, 0.1, math.pi - 1e-15):
        assert wrap_angle(angle) == angle  # bit for bit, not recomputed


def test_wrap_angle_on_arrays_equals_the_float_rule_elementwise() -> None:
    angles = np.concatenate(
        [
            np.random.default_rng(1).uniform(-30.0, 30.0, 2000),
            [-math.pi, math.pi, 0.0, 3 * math.pi, -3 * math.pi, 2 * math.pi],
        ]
    )
    wrapped = wrap_angle(angles)
    assert isinstance(wrapped, np.ndarray) and wrapped.shape == angles.shape
    assert np.all((wrapped >= -math.pi) & (wrapped < math.pi))
    np.testing.assert_array_equal(wrapped, [wrap_angle(float(a)) for a in angles])
    np.testing.assert_allclose(np.cos(wrapped), np.cos(angles), atol=1e-12)
    np.testing.assert_allclose(np.sin(wrapped), np.sin(angles), atol=1e-12)


# ----------------------------------------------------------------------------- end lines


def test_goal_at_the_right_end_is_a_goal_for_the_left_team() -> None:
    # §6: the ball's centre crosses x = 52.5 + 0.085 between the posts.
    crossing = end_line_crossing(SERVER_1996, 52.0, 7.0, 53.0, 7.0)
    assert crossing is Crossing.RIGHT_GOAL and crossing.is_goal and crossing > 0
    assert end_line_crossing(SERVER_1996, -52.0, 0.0, -53.0, 1.0) is Crossing.LEFT_GOAL


@pytest.mark.parametrize(
    ("x0", "y0", "x1", "y1", "expected"),
    [
        (52.0, 7.1, 53.0, 7.1, Crossing.RIGHT_WIDE),
        (52.0, -7.2, 53.0, -7.2, Crossing.RIGHT_WIDE),
        (-52.0, 20.0, -54.0, 20.0, Crossing.LEFT_WIDE),
        (-52.0, -7.02, -53.0, -7.02, Crossing.LEFT_WIDE),
    ],
)
def test_wide_of_the_posts(x0: float, y0: float, x1: float, y1: float, expected: Crossing) -> None:
    crossing = end_line_crossing(SERVER_1996, x0, y0, x1, y1)
    assert crossing is expected and not crossing.is_goal
    assert (crossing > 0) == (x1 > 0)  # the sign tells the end


def test_the_crossing_point_decides_not_the_end_point() -> None:
    # Aimed from inside the mouth to a point far outside it: in at the line, so a goal.
    assert end_line_crossing(SERVER_1996, 52.4, 6.5, 55.0, 12.0) is Crossing.RIGHT_GOAL
    # From wide to behind the mouth: wide at the line (y = 7.49 there).
    assert end_line_crossing(SERVER_1996, 52.5, 8.0, 53.0, 5.0) is Crossing.RIGHT_WIDE


def test_the_post_radius_widens_the_mouth() -> None:
    assert end_line_crossing(SERVER_19, 52.0, 7.05, 53.0, 7.05) is Crossing.RIGHT_GOAL
    assert end_line_crossing(SERVER_1996, 52.0, 7.05, 53.0, 7.05) is Crossing.RIGHT_WIDE
    assert end_line_crossing(SERVER_19, 52.0, 7.08, 53.0, 7.08) is Crossing.RIGHT_WIDE


def test_only_a_step_over_the_line_counts() -> None:
    line = 52.5 + 0.085
    # Not yet wholly over, or already beyond at the start of the step, or never near.
    assert end_line_crossing(SERVER_1996, 52.0, 0.0, line, 0.0) is Crossing.NONE
    assert end_line_crossing(SERVER_1996, 53.0, 0.0, 54.0, 0.0) is Crossing.NONE
    assert end_line_crossing(SERVER_1996, 0.0, 0.0, 10.0, 30.0) is Crossing.NONE
    assert end_line_crossing(SERVER_1996, 52.0, 0.0, line + 1e-9, 0.0) is Crossing.RIGHT_GOAL
    assert not Crossing.NONE  # falsy, so `if crossing:` reads as "it crossed"
