"""Layer 1's turn-angle rules: TA from (BD, BA, previous BD) for each behaviour (paper §5).

Each rule is a :class:`~robotsoccer.skills.intercept.TurnPolicy` the interception defender
(:class:`~robotsoccer.skills.intercept.DefenderMind`) calls once it is triggered: ``straight``
(:func:`straight_policy`), ``random`` (:class:`RandomPolicy`), ``net`` (:class:`NetPolicy`),
``lookup`` (:class:`LookupPolicy`) and ``analytic`` (:class:`AnalyticPolicy`, Mike Bowling's
rule). :func:`~robotsoccer.skills.intercept.make_policy` picks one for a behaviour and loads its
model file. Angles are radians, left positive; distances metres.
"""

from __future__ import annotations

import math
from collections.abc import Callable

from field_models.seeding import Rng
from learning.analytic import MOTION_MULTIPLIER, analytic_turn_angle_xy
from learning.interception_file import TurnAngleFunction

RANDOM_TA_HALF_RANGE_RAD = math.radians(45.0)
"""The training behaviour's TA range: uniform in [-45°, 45°] (paper §5)."""


Point = tuple[float, float]
"""A ball position in the defender's reckoned frame (x, y) [m]."""


def straight_policy(
    ball_distance_m: float,
    ball_angle_rad: float,
    previous_ball_distance_m: float,
    previous_ball_xy_m: Point | None,
    ball_xy_m: Point,
) -> float:
    """TA = 0: move directly toward where the ball was seen (paper §5, "straight")."""
    return 0.0


class RandomPolicy:
    """TA uniform in [-half_range, half_range] from a generator (the training behaviour)."""

    def __init__(self, rng: Rng, half_range_rad: float = RANDOM_TA_HALF_RANGE_RAD) -> None:
        self.rng = rng
        self.half_range_rad = half_range_rad

    def __call__(
        self,
        ball_distance_m: float,
        ball_angle_rad: float,
        previous_ball_distance_m: float,
        previous_ball_xy_m: Point | None,
        ball_xy_m: Point,
    ) -> float:
        """A fresh random TA [rad]."""
        return float(self.rng.uniform(-self.half_range_rad, self.half_range_rad))


class NetPolicy:
    """TA = the interception net's output f(BD, BA, previous BD) (plain Python)."""

    def __init__(self, function: TurnAngleFunction) -> None:
        self.function = function

    def __call__(
        self,
        ball_distance_m: float,
        ball_angle_rad: float,
        previous_ball_distance_m: float,
        previous_ball_xy_m: Point | None,
        ball_xy_m: Point,
    ) -> float:
        """The net's TA [rad]."""
        return self.function(ball_distance_m, ball_angle_rad, previous_ball_distance_m)


class LookupPolicy:
    """TA = the one-dimensional table's entry for BA (paper §5, Table 1)."""

    def __init__(self, table: Callable[[float], float]) -> None:
        self.table = table

    def __call__(
        self,
        ball_distance_m: float,
        ball_angle_rad: float,
        previous_ball_distance_m: float,
        previous_ball_xy_m: Point | None,
        ball_xy_m: Point,
    ) -> float:
        """The table's TA for this BA [rad]."""
        return self.table(ball_angle_rad)


class AnalyticPolicy:
    """TA toward the ball's predicted position two sensory steps ahead (Bowling's rule, §5).

    Without a previous sighting the motion is unknown and TA is 0 (move at the ball).
    """

    def __init__(self, motion_multiplier: float = MOTION_MULTIPLIER) -> None:
        self.motion_multiplier = motion_multiplier

    def __call__(
        self,
        ball_distance_m: float,
        ball_angle_rad: float,
        previous_ball_distance_m: float,
        previous_ball_xy_m: Point | None,
        ball_xy_m: Point,
    ) -> float:
        """The analytic TA [rad] from the two sightings."""
        if previous_ball_xy_m is None:
            return 0.0
        px, py = previous_ball_xy_m
        x, y = ball_xy_m
        return analytic_turn_angle_xy(px, py, x, y, self.motion_multiplier)
