"""A team mind's state and how it reads the ball (:mod:`robotsoccer.skills.team`).

:class:`MindBase` holds what one player keeps between percepts and the reading every layer of
the mind shares: whether a ball rolls at it toward its own end (a shot, a clearance; module
docstring of :mod:`robotsoccer.skills.team`, "Pushing"), whether a shot is on its goal, whether
the ball rolls free, and how it runs toward a point.
"""

from __future__ import annotations

import math

from field_models.protocol import Action, Dash, Percept, wrap_angle
from robotsoccer.skills.intercept import TurnPolicy
from robotsoccer.skills.lead import (
    BallTrack,
    LeadPolicy,
    velocity_window,
)
from robotsoccer.skills.localise import Localiser, Pose
from robotsoccer.skills.motion import TurnsInFlight, turn_then_go
from robotsoccer.skills.passing import PassEvaluator
from robotsoccer.skills.team_look import NeckLook
from robotsoccer.skills.team_setup import (
    BACK_SWITCH_RAD,
    FACING_RAD,
    MEET_SPEED_MPS,
    MEMORY_TICKS,
    NEAR_REACHES,
    REVERSE_HOLD_TICKS,
    BallPolicy,
    TeamSetup,
)


class MindBase:
    """A team mind's state and its shared reading of the ball.

    :class:`~robotsoccer.skills.team.TeamMind` documents the arguments.
    """

    def __init__(
        self,
        number: int,
        setup: TeamSetup,
        *,
        interception: TurnPolicy | None = None,
        lead: LeadPolicy | None = None,
        evaluator: PassEvaluator | None = None,
        pass_threshold: float = 0.5,
        ball_policy: BallPolicy | None = None,
    ) -> None:
        self.number = number
        self.setup = setup
        self.interception = interception
        self.lead = lead
        self._track = BallTrack(velocity_window(setup.sensor_period_s))
        self.evaluator = evaluator
        self.pass_threshold = pass_threshold
        self.ball_policy = ball_policy
        self._layer3_kick: tuple[str, tuple[Action, ...]] | None = None  # this spell's choice
        self.localiser = Localiser(setup.landmarks)
        self.is_goalie = number == setup.goalie
        self.intent = "search"
        self.shots = 0
        self.passes = 0
        self.chasing = False
        self._ball_xy: tuple[float, float] | None = None
        self._previous_bd: float | None = None
        self._previous_xy: tuple[float, float] | None = None
        self._spell_kicked = ""  # what it kicked in this spell on the ball
        # The turns it sent and which of them its percepts show (the motion skill): with the
        # hold, a percept that does not show the last one is not decided on.
        self.turns = TurnsInFlight(setup.turn_ticks)
        self._last_turn = (-REVERSE_HOLD_TICKS - 1, 0.0)  # (tick, angle) with steady turns
        self._seen_tick = -MEMORY_TICKS - 1  # the last tick it saw the ball
        self._at_home = False  # with steady turns: arrived home and not yet pushed off it
        self._lead_s: float | None = None  # the lead held while meeting a ball (pushing teams)
        self._held_lead: float | None = None  # ... as the last decision left it
        self._sighted_tick = -1  # the frame of the ball's last sighting on its track
        self._backing = False  # with the dead band: driving to its point backwards
        self.head = NeckLook()  # its neck and view, when it looks with them (setup.look)

    def _meets(self, pose: Pose, ball_xy: tuple[float, float]) -> bool:
        """The ball rolls at the player and toward the player's own end (a shot, a clearance)."""
        velocity = self._track.velocity()
        if velocity is None or not self._track.full():
            return False
        vx, vy = velocity
        if math.hypot(vx, vy) < MEET_SPEED_MPS:
            return False
        toward_own_end = vx * self.setup.own_goal_xy[0] > 0.0
        closing = vx * (pose.x - ball_xy[0]) + vy * (pose.y - ball_xy[1]) > 0.0
        return toward_own_end and closing

    def _inside(self, point: tuple[float, float]) -> tuple[float, float]:
        """`point` moved onto the field where a player's centre can be.

        Not into a goal: a ball met beyond the goal line is a goal already.
        """
        setup = self.setup
        lx = setup.half_length_m - setup.player_radius_m
        ly = setup.half_width_m - setup.player_radius_m
        return max(-lx, min(point[0], lx)), max(-ly, min(point[1], ly))

    def _rolls_free(self, percept: Percept) -> bool:
        """No other player seen within a player's size and reach of the ball.

        The ball then rolls by its own law, as the shots of layer 1's drill do; a ball a player
        pushes on goes where the player goes, which the lead's prediction does not know.
        """
        ball = percept.ball
        assert ball is not None
        bx = ball.distance_m * math.cos(ball.angle_rad)
        by = ball.distance_m * math.sin(ball.angle_rad)
        near = self.setup.player_radius_m + self.setup.reach_m
        for seen in percept.players:
            px = seen.distance_m * math.cos(seen.angle_rad)
            py = seen.distance_m * math.sin(seen.angle_rad)
            if math.hypot(px - bx, py - by) <= near:
                return False
        return True

    def _shot_at_goalie(self, pose: Pose | None) -> bool:
        """This player keeps goal, and the ball rolls at it and between its posts."""
        ball = self._ball_xy
        if not self.is_goalie or pose is None or ball is None:
            return False
        return self._meets(pose, ball) and self._on_target()

    def _on_target(self) -> bool:
        """The ball's perceived track crosses the player's own goal line between the posts."""
        velocity, ball = self._track.velocity(), self._ball_xy
        if velocity is None or ball is None:
            return False
        gx = self.setup.own_goal_xy[0]
        vx, vy = velocity
        if vx * (gx - ball[0]) <= 0.0:
            return False
        crossing = ball[1] + vy * (gx - ball[0]) / vx
        return abs(crossing) <= 0.5 * self.setup.goal_width_m

    def _run_to(self, angle: float, distance_m: float) -> tuple[Action, ...]:
        """Turn toward `angle` and run (on arcs where the host drives them).

        With the dead band it runs on, unturned, while it would pass within a reach of the
        point (:meth:`_drive_to`).
        """
        angle = wrap_angle(angle)
        if self._on_course(angle, distance_m, self.setup.reach_m):
            return (Dash(100.0),)
        # Near the point it runs on only once facing it, or it circles.
        near = distance_m <= NEAR_REACHES * self.setup.reach_m
        return turn_then_go(angle, (Dash(100.0),), facing_rad=FACING_RAD, turn_only=near)

    def _on_course(self, angle: float, distance_m: float, tolerance_m: float) -> bool:
        """Dead band: driving on passes within `tolerance_m` of the point, so a turn gains little.

        The point is `distance_m` away at `angle` from the heading (issue 28 item 5).
        """
        ahead = abs(angle) < 0.5 * math.pi
        return self.setup.dead_band and ahead and distance_m * abs(math.sin(angle)) <= tolerance_m

    def _drive_to(
        self, angle: float, distance_m: float, tolerance_m: float, power: float
    ) -> tuple[Action, ...]:
        """Go a point `distance_m` away at `angle` (wrapped) with the dead band.

        The dash slows to what stops there within the loop's latency
        (:meth:`~robotsoccer.skills.team_setup.TeamSetup.arrive_power`); a point behind is
        driven to backwards (the robots drive as fast either way), and the player keeps its way
        of driving until the point is :data:`BACK_SWITCH_RAD` past the side (at the side,
        switching would turn it 180° between two frames); it turns only off course
        (:meth:`_on_course`) and beyond twice :data:`FACING_RAD`, as without the dead band.
        """
        angle = wrap_angle(angle)
        power = min(power, self.setup.arrive_power(distance_m))
        side = 0.5 * math.pi + (-BACK_SWITCH_RAD if self._backing else BACK_SWITCH_RAD)
        self._backing = abs(angle) > side
        if self._backing:
            angle, power = wrap_angle(angle - math.pi), -power
        if self._on_course(angle, distance_m, tolerance_m):
            return (Dash(power),)
        return turn_then_go(angle, (Dash(power),), facing_rad=2.0 * FACING_RAD)
