"""A team mind off the ball: layer 1's interception, going home, searching.

Steps 4 and 5 of :mod:`robotsoccer.skills.team`'s module docstring: the chaser intercepts with
layer 1 (a turn-angle net, §5, or a lead net) or runs straight at the ball; every other player
goes to its formation home shifted toward the ball; one that sees no ball searches for it.
"""

from __future__ import annotations

import math

from field_models.protocol import Action, Dash, Percept, Turn, wrap_angle
from robotsoccer.skills.lead import (
    ahead_of,
    track_angle,
)
from robotsoccer.skills.localise import Pose
from robotsoccer.skills.motion import turn_then_go
from robotsoccer.skills.team_base import MindBase
from robotsoccer.skills.team_look import BACK_STEP_TOLERANCES, LOOK_COVER_RAD
from robotsoccer.skills.team_setup import (
    BALL_SHIFT_X,
    BALL_SHIFT_Y,
    COMING_SHARE,
    FACING_RAD,
    GOALIE_RANGE_UNITS,
    MEMORY_TICKS,
    NEAR_REACHES,
    SEARCH_TURN_RAD,
)


class ChaseMind(MindBase):
    """A team mind's chase, home and search (module docstring)."""

    def _chase(self, percept: Percept) -> tuple[Action, ...]:
        """Layer 1's interception (the net) or straight at the ball."""
        ball = percept.ball
        assert ball is not None
        bd, ba = ball.distance_m, ball.angle_rad
        previous = self._previous_bd
        self._previous_bd = bd
        ta = 0.0
        reach = self.setup.reach_m
        coming = previous is not None and previous - bd > COMING_SHARE * reach
        lead_angle = self._lead_angle(bd, previous) if coming else None
        if lead_angle is not None:
            ta = wrap_angle(lead_angle - ba)
            self.intent = "intercept"
        elif (
            self.interception is not None
            and coming
            and previous is not None
            and NEAR_REACHES * reach < bd <= self.setup.trigger_distance_m
        ):
            xy = self._ball_xy or (0.0, 0.0)
            ta = self.interception(bd, ba, previous, self._previous_xy, xy)
            self.intent = "intercept"
        else:
            self.intent = "chase"
        self._previous_xy = self._ball_xy
        angle = wrap_angle(ba + ta)
        near = bd <= NEAR_REACHES * reach  # near the ball: run on only once facing it (no circling)
        return turn_then_go(angle, (Dash(100.0),), facing_rad=FACING_RAD, turn_only=near)

    def _lead_angle(self, bd: float, previous: float | None) -> float | None:
        """The direction to aim the lead net's τ ahead of the ball, or None (no lead, no fit).

        Asked only of a ball coming toward the player from beyond the near zone, within the
        trigger distance: where §5's net was trained to meet it.
        """
        pose, ball = self.localiser.pose, self._ball_xy
        velocity = self._track.velocity()
        if self.lead is None or pose is None or ball is None or velocity is None:
            return None
        if previous is None or not NEAR_REACHES * self.setup.reach_m < bd:
            return None
        if bd > self.setup.trigger_distance_m:
            return None
        angle = track_angle(ball, velocity, (pose.x, pose.y))
        aim = ahead_of(ball, velocity, self.lead(bd, angle, previous), self.setup.ball_law)
        return math.atan2(aim[1] - pose.y, aim[0] - pose.x) - pose.heading

    def _go_home(self, percept: Percept, pose: Pose | None) -> tuple[Action, ...]:
        ball = percept.ball
        if pose is None:
            self.intent = "search"
            return (Turn(SEARCH_TURN_RAD),)
        tx, ty = self._home_target()
        dx, dy = tx - pose.x, ty - pose.y
        self.intent = "home"
        tolerance = self.setup.home_tolerance_m
        if self.setup.steady_turns or self.setup.dead_band:  # home until twice the tolerance away
            self._at_home = math.hypot(dx, dy) <= tolerance * (2.0 if self._at_home else 1.0)
            far = not self._at_home
        else:
            far = math.hypot(dx, dy) > tolerance
        if far and self.setup.dead_band:
            angle = math.atan2(dy, dx) - pose.heading
            return self._drive_to(angle, math.hypot(dx, dy), tolerance, 80.0)
        if far:
            angle = wrap_angle(math.atan2(dy, dx) - pose.heading)
            power = 80.0
            near = math.hypot(dx, dy) <= BACK_STEP_TOLERANCES * tolerance
            if self.setup.look == "neck" and near and abs(angle) > 0.5 * math.pi:
                # A short step back: backwards, the smaller turn (the neck keeps the ball).
                angle, power = wrap_angle(angle - math.pi), -power
            return turn_then_go(angle, (Dash(power),), facing_rad=2.0 * FACING_RAD)
        # Home: face the ball; looking with the neck, only when the head cannot keep it in view.
        facing = LOOK_COVER_RAD if self.setup.look == "neck" else FACING_RAD
        if ball is None:
            return ()
        return turn_then_go(ball.angle_rad, (), facing_rad=facing)

    def _home_target(self) -> tuple[float, float]:
        setup = self.setup
        hx, hy = setup.home[self.number]
        if self._ball_xy is None:
            return hx, hy
        bx, by = self._ball_xy
        if self.is_goalie:
            gx = setup.own_goal_xy[0]
            inward = -1.0 if gx > 0 else 1.0
            post = GOALIE_RANGE_UNITS * setup.unit_m
            return gx + inward * setup.goalie_depth_m, max(-post, min(0.5 * by, post))
        x = hx + BALL_SHIFT_X * bx
        y = hy + BALL_SHIFT_Y * (by - hy)
        lx, ly = setup.half_length_m - setup.unit_m, setup.half_width_m - setup.unit_m
        return max(-lx, min(x, lx)), max(-ly, min(y, ly))

    def _no_ball(self, percept: Percept, pose: Pose | None) -> tuple[Action, ...]:
        remembered = self._ball_xy
        recent = percept.tick - self._seen_tick <= MEMORY_TICKS
        if self.setup.sees_all_round:
            # An overhead camera sees the whole table whatever the heading: a ball missing from
            # a frame is a missed detection (specs/robot_physics.md), not a ball out of view.
            # Turning to look for it would turn away from play; the body keeps its command.
            return ()
        if self.setup.look == "neck" and pose is not None and not (self.chasing and recent):
            # The neck looks for the ball (team_look); the body walks home meanwhile. A chaser
            # that lost the ball a moment ago goes after where it was, as below.
            return self._go_home(percept, pose)
        if self.setup.steady_turns and recent and not self.chasing and pose is not None:
            # Steady turns: a player that turned away from the ball to go home trusts where it
            # saw it, and goes on home rather than turning back to look (and away again).
            home = self._go_home(percept, pose)
            if self.intent == "home" and home:
                return home
        if remembered is not None and pose is not None:
            # Turn toward where the ball was last seen (a search with a memory).
            angle = wrap_angle(
                math.atan2(remembered[1] - pose.y, remembered[0] - pose.x) - pose.heading
            )
            if abs(angle) > FACING_RAD:
                self.intent = "search"
                return (Turn(angle),)
            if self.setup.steady_turns:
                self._ball_xy = None  # facing where it was and not seeing it: it is not there
        self.intent = "search"
        return (Turn(SEARCH_TURN_RAD),)
