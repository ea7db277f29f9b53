"""The analytic interception behaviour the paper compares its net with (§5, Table 1).

Paper §5: Mike Bowling's behaviour "computed the ball's motion vector from its 2 previous
positions and multiplied this vector by 3, thus predicting the ball's position two sensory steps
(500 msec) into the future. The defender's TA was then the angle necessary to move directly
towards the end of the lengthened vector."

Precisely, with the ball's last two sightings p_prev (one sensory step ago) and p_now (now), both
as positions relative to the player in one common orientation (e.g. the player's current frame):

* the motion vector is v = p_now - p_prev; lengthened x3 from p_prev it ends at
  p_end = p_prev + 3 v = p_now + 2 v, the ball two sensory steps ahead;
* TA = wrap(direction of p_end - direction of p_now), in (-pi, pi], left positive: the turn
  *after facing the ball* that points the player at p_end (the drill then does TURN(BA + TA)).

TA does not depend on the frame's orientation, only on positions relative to the player, so the
positions may be egocentric or field-aligned. If the player moved between the two sightings, the
caller must express the previous sighting relative to the player's *current* position. When p_end
is (numerically) at the player, TA is 0: the ball is coming straight at it.
"""

from __future__ import annotations

import math

MOTION_MULTIPLIER = 3.0
"""The paper's factor on the motion vector: x3 from the older sighting, two steps ahead."""

_AT_PLAYER_M = 1e-12
"""Below this distance [m] the predicted point is at the player and has no direction."""


def predicted_ball_position(
    previous_x_m: float,
    previous_y_m: float,
    x_m: float,
    y_m: float,
    motion_multiplier: float = MOTION_MULTIPLIER,
) -> tuple[float, float]:
    """The end of the lengthened motion vector: p_prev + multiplier * (p_now - p_prev) [m].

    >>> predicted_ball_position(4.0, 1.0, 3.0, 1.5)
    (1.0, 2.5)
    """
    return (
        previous_x_m + motion_multiplier * (x_m - previous_x_m),
        previous_y_m + motion_multiplier * (y_m - previous_y_m),
    )


def analytic_turn_angle_xy(
    previous_x_m: float,
    previous_y_m: float,
    x_m: float,
    y_m: float,
    motion_multiplier: float = MOTION_MULTIPLIER,
) -> float:
    """TA [rad] from the ball's previous and current positions relative to the player [m].

    Args:
        previous_x_m: Previous sighting, x relative to the player [m].
        previous_y_m: Previous sighting, y relative to the player [m].
        x_m: Current sighting, x relative to the player [m].
        y_m: Current sighting, y relative to the player [m].
        motion_multiplier: Factor on the motion vector, from the previous sighting (paper: 3).

    Returns:
        The turn after facing the ball toward the predicted point, in (-pi, pi] [rad, left +].

    A ball at (3, 1) that came from (4, 1) will be at (1, 1): turn 45° - 18.43° = 26.57° left.

    >>> round(math.degrees(analytic_turn_angle_xy(4.0, 1.0, 3.0, 1.0)), 2)
    26.57
    """
    end_x, end_y = predicted_ball_position(previous_x_m, previous_y_m, x_m, y_m, motion_multiplier)
    if math.hypot(end_x, end_y) < _AT_PLAYER_M:
        return 0.0
    turn = math.remainder(math.atan2(end_y, end_x) - math.atan2(y_m, x_m), math.tau)
    return math.pi if turn == -math.pi else turn  # (-pi, pi]: a half turn counts as left


def analytic_turn_angle(
    previous_ball_distance_m: float,
    previous_ball_angle_rad: float,
    ball_distance_m: float,
    ball_angle_rad: float,
    motion_multiplier: float = MOTION_MULTIPLIER,
) -> float:
    """TA [rad] from the ball's previous and current egocentric sightings (distance, angle).

    Both sightings must be relative to the player's current position and heading (angles left
    positive); see the module docstring.

    Args:
        previous_ball_distance_m: Distance at the previous sighting [m].
        previous_ball_angle_rad: Direction at the previous sighting [rad].
        ball_distance_m: Distance now (BD) [m].
        ball_angle_rad: Direction now (BA) [rad].
        motion_multiplier: Factor on the motion vector, from the previous sighting (paper: 3).

    Returns:
        The turn after facing the ball, in (-pi, pi] [rad, left positive].

    Ball straight ahead, 4 m then 3 m away: it will be 1 m ahead, so no turn.

    >>> analytic_turn_angle(4.0, 0.0, 3.0, 0.0)
    0.0

    Ball from (3, 0) to (2, 0.5): it will be at (0, 1.5), 90° left; BA = atan2(0.5, 2).

    >>> ta = analytic_turn_angle(3.0, 0.0, math.hypot(2.0, 0.5), math.atan2(0.5, 2.0))
    >>> round(ta, 6) == round(math.pi / 2 - math.atan2(0.5, 2.0), 6)
    True
    """
    return analytic_turn_angle_xy(
        previous_ball_distance_m * math.cos(previous_ball_angle_rad),
        previous_ball_distance_m * math.sin(previous_ball_angle_rad),
        ball_distance_m * math.cos(ball_angle_rad),
        ball_distance_m * math.sin(ball_angle_rad),
        motion_multiplier,
    )
