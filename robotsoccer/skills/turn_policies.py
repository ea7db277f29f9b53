"""Layer 1's turn-angle rules: TA from (BD, BA, previous BD) for each behaviour (paper §5).

Each rule is a :class:`~robotsoccer.skills.intercept.TurnPolicy` the interception defender
(:class:`~robotsoccer.skills.intercept.DefenderMind`) calls once it is triggered: ``straight``
(:func:`straight_policy`), ``random`` (:class:`RandomPolicy`), ``net`` (:class:`NetPolicy`),
``lookup`` (:class:`LookupPolicy`) and ``analytic`` (:class:`AnalyticPolicy`, Mike Bowling's
rule); :class:`TrainedDomainPolicy` asks a rule only inside the net's training domain.
:func:`~robotsoccer.skills.intercept.make_policy` picks one for a behaviour and loads its
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


TRAINED_DOMAIN_Z = 3.0
"""A net input more than this many training standard deviations from the training mean lies
outside what the net learned (our choice: the usual three-sigma bound)."""


class TrainedDomainPolicy:
    """A turn-angle rule asked only inside its training domain; straight (TA = 0) outside.

    The paper's net learned from one drill's shots (§5): each of its three inputs lies in a
    narrow band (:func:`learning.interception_file.training_spread`). A match asks it of balls
    that come slower and nearer (a pass, a dribble), where its TA is an extrapolation; outside
    :data:`TRAINED_DOMAIN_Z` standard deviations on any input this rule runs straight at the
    ball instead, the baseline's pursuit.

    Attributes:
        asked: Calls so far.
        outside: Of them, calls outside the domain (answered straight).
    """

    def __init__(
        self,
        policy: Callable[[float, float, float, Point | None, Point], float],
        mean: tuple[float, float, float],
        spread: tuple[float, float, float],
        z: float = TRAINED_DOMAIN_Z,
    ) -> None:
        self.policy = policy
        self.mean = mean
        self.spread = spread
        self.z = z
        self.asked = 0
        self.outside = 0

    def inside(self, ball_distance_m: float, ball_angle_rad: float, previous_m: float) -> bool:
        """Every input within `z` training standard deviations of its training mean."""
        values = (ball_distance_m, ball_angle_rad, previous_m)
        return all(
            abs(v - m) <= self.z * s for v, m, s in zip(values, self.mean, self.spread, strict=True)
        )

    def __call__(
        self,
        ball_distance_m: float,
        ball_angle_rad: float,
        previous_ball_distance_m: float,
        previous_ball_xy_m: Point | None,
        ball_xy_m: Point,
    ) -> float:
        """The rule's TA inside the domain, else 0 [rad]."""
        self.asked += 1
        if not self.inside(ball_distance_m, ball_angle_rad, previous_ball_distance_m):
            self.outside += 1
            return 0.0
        return self.policy(
            ball_distance_m,
            ball_angle_rad,
            previous_ball_distance_m,
            previous_ball_xy_m,
            ball_xy_m,
        )


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
