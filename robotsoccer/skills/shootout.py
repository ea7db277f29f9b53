"""The demo's minds: a shooter that dribbles the ball at the goal, a goalie that chases it.

Both act on percepts only, and both run on either field model (sizes come from the drill).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from field_models.protocol import Action, Dash, Kick, Percept, Turn


@dataclass
class DribbleShooterMind:
    """Get behind the ball (as seen from the goal), then drive through it toward the goal.

    Attributes:
        back_off_m: How far behind the ball to line up [m].
        touch_m: Kick (a kicker fires, a kickerless robot pushes) when the ball is this close [m].
        aim_tolerance_rad: Turn when the target is more than this off the heading [rad].
        search_turn_rad: Turn by this when the ball is not seen [rad].
    """

    back_off_m: float
    touch_m: float
    aim_tolerance_rad: float = 0.25
    search_turn_rad: float = math.radians(40.0)

    def act(self, percept: Percept) -> tuple[Action, ...]:
        """One decision per percept."""
        ball = percept.ball
        if ball is None:
            return (Turn(self.search_turn_rad),)
        bx, by = _xy(ball.distance_m, ball.angle_rad)
        goal = percept.landmark("g r")
        tx, ty = bx, by
        if goal is not None:
            gx, gy = _xy(goal.distance_m, goal.angle_rad)
            ux, uy = _unit(bx - gx, by - gy)  # from the goal through the ball
            lined_up = _cos_between(bx, by, -ux, -uy) > math.cos(math.radians(25.0))
            if lined_up and ball.distance_m < self.touch_m:
                return (Kick(100.0, math.atan2(gy - by, gx - bx)),)
            if not lined_up:
                tx, ty = bx + ux * self.back_off_m, by + uy * self.back_off_m
        angle = math.atan2(ty, tx)
        if abs(angle) > self.aim_tolerance_rad:
            return (Turn(angle),)
        return (Dash(100.0),)


@dataclass
class ChaseGoalieMind:
    """Drive straight at the perceived ball: turn toward it when off by more than a tolerance."""

    aim_tolerance_rad: float = 0.2

    def act(self, percept: Percept) -> tuple[Action, ...]:
        """One decision per percept."""
        if percept.ball is None:
            return ()
        if abs(percept.ball.angle_rad) > self.aim_tolerance_rad:
            return (Turn(percept.ball.angle_rad),)
        return (Dash(100.0),)


def _xy(distance: float, angle: float) -> tuple[float, float]:
    return distance * math.cos(angle), distance * math.sin(angle)


def _unit(x: float, y: float) -> tuple[float, float]:
    n = math.hypot(x, y) or 1.0
    return x / n, y / n


def _cos_between(ax: float, ay: float, bx: float, by: float) -> float:
    na, nb = math.hypot(ax, ay), math.hypot(bx, by)
    if na == 0.0 or nb == 0.0:
        return 1.0
    return (ax * bx + ay * by) / (na * nb)
