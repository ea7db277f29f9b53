"""The receiver's half estimated from the passer's view (issue 28 goal 4)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from learning.pass_features import (
    RECEIVER_VIEW_HALF_ANGLE_DEG,
    estimated_receiver_half,
    estimated_receiver_view,
    receiver_attributes,
)


def _polar(x: float, y: float) -> tuple[float, float]:
    """(distance, direction [deg]) of (x, y) in the passer's frame."""
    return math.hypot(x, y), math.degrees(math.atan2(y, x))


# The receiver stands 10 units to the passer's left, at (0, 10), and faces the passer: its
# heading points along -y, so +x is on its left (counter-clockwise positive).
RECEIVER = _polar(0.0, 10.0)
SCENE = {
    "mate between": ((0.0, 4.0), 1),  # (0, -6) from the receiver: 6 units, straight ahead
    "opponent in cone": ((3.0, 6.0), -1),  # (3, -4): 5 units, 36.87° to the left
    "opponent beside": ((8.0, 10.0), -1),  # (8, 0): 8 units, 90°: out of the cone
    "unknown felt": ((-2.0, 11.0), 0),  # (-2, 1): 2.24 units, behind-right, within the feel
    "mate far": ((0.0, -30.0), 1),  # (0, -40): 40 units, straight ahead
}


def _view() -> tuple[list[float], list[float], list[int]]:
    places = [_polar(*xy) for xy, _ in SCENE.values()]
    return [d for d, _ in places], [a for _, a in places], [t for _, t in SCENE.values()]


def test_a_hand_computed_scene() -> None:
    d, a, t = estimated_receiver_view(*RECEIVER, *_view())
    np.testing.assert_allclose(d, [6.0, 5.0, math.sqrt(5.0), 40.0], atol=1e-12)
    left = math.degrees(math.atan2(3.0, 4.0))  # 36.87°
    behind_right = math.degrees(math.atan2(1.0, -2.0)) + 90.0 - 360.0  # -116.57°
    np.testing.assert_allclose(a, [0.0, left, behind_right, 0.0], atol=1e-9)
    np.testing.assert_array_equal(t, [1, -1, 0, 1])
    half = estimated_receiver_half(*RECEIVER, *_view())
    np.testing.assert_array_equal(half, receiver_attributes(10.0, 0.0, d, a, t))
    # The receiver's teammates by distance: the one between, the passer, the far one.
    np.testing.assert_allclose(half[0:6], [6.0, 0.0, 10.0, 0.0, 40.0, 0.0], atol=1e-9)
    assert math.isnan(half[6])
    # The one opponent in view, its angle an offset from the passer's direction.
    np.testing.assert_allclose(half[20:22], [5.0, left], atol=1e-9)
    assert math.isnan(half[22])


def test_the_cone_edge_and_the_feel_distance() -> None:
    # The receiver at (10, 0) faces -x. Players 5 units from it at offsets 44.9° and 45.1°,
    # and one 2 units straight behind it.
    def at(offset_deg: float, distance: float) -> tuple[float, float]:
        heading = math.radians(180.0 + offset_deg)
        return _polar(10.0 + distance * math.cos(heading), distance * math.sin(heading))

    players = [at(RECEIVER_VIEW_HALF_ANGLE_DEG - 0.1, 5.0), at(45.1, 5.0), at(180.0, 2.0)]
    view = ([p[0] for p in players], [p[1] for p in players], [-1, -1, 1])
    d, a, _ = estimated_receiver_view(10.0, 0.0, *view)
    np.testing.assert_allclose(d, [5.0, 2.0], atol=1e-9)
    np.testing.assert_allclose(np.abs(a), [44.9, 180.0], atol=1e-9)
    d, _, _ = estimated_receiver_view(10.0, 0.0, *view, feel_distance=1.9)
    np.testing.assert_allclose(d, [5.0], atol=1e-9)
    d, _, _ = estimated_receiver_view(10.0, 0.0, *view, half_angle_deg=50.0, feel_distance=0.0)
    np.testing.assert_allclose(d, [5.0, 5.0], atol=1e-9)


def test_players_that_cannot_be_placed_are_left_out() -> None:
    view = ([5.0, math.nan, 4.0], [0.0, 0.0, math.nan], [1, 1, -1])
    d, a, t = estimated_receiver_view(10.0, 0.0, *view)
    assert d.tolist() == [5.0] and a.tolist() == [0.0] and t.tolist() == [1]


def test_an_empty_view_leaves_the_passer_alone() -> None:
    half = estimated_receiver_half(12.0, -30.0, [], [], [])
    np.testing.assert_array_equal(half, receiver_attributes(12.0, 0.0, [], [], []))
    assert half[0] == 12.0 and half[1] == 0.0


def test_an_unseen_receiver_is_refused() -> None:
    with pytest.raises(ValueError, match="receiver must be seen"):
        estimated_receiver_half(math.nan, 0.0, [], [], [])
