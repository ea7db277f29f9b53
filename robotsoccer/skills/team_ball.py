"""A team mind's chaser on the ball: shoot, pass (layers 2 and 3), dribble; pushing.

Step 3 of :mod:`robotsoccer.skills.team`'s module docstring (layer 2's tree or the closest
teammate, layer 3's :class:`~robotsoccer.skills.team_setup.BallPolicy` hook) and the pushing
team's chaser (its "Pushing": play from behind, meet a ball rolling at it).
"""

from __future__ import annotations

import math

from field_models.protocol import Action, Dash, Kick, Percept, SeenPlayer, Turn, wrap_angle
from robotsoccer.skills.lead import (
    LEAD_CLIP_S,
    ahead_of,
    track_angle,
)
from robotsoccer.skills.localise import Pose
from robotsoccer.skills.motion import turn_then_go
from robotsoccer.skills.passing import open_play_attributes
from robotsoccer.skills.setplay import opponent_in_path
from robotsoccer.skills.team_chase import ChaseMind
from robotsoccer.skills.team_setup import (
    AHEAD_UNITS,
    MIN_PASS_UNITS,
    PUSH_LINE_SHARE,
    SEARCH_TURN_RAD,
    goal_direction,
    in_shooting_range,
)


class BallMind(ChaseMind):
    """A team mind's play on the ball and a pushing team's chaser (module docstring)."""

    def _on_ball(self, percept: Percept, pose: Pose | None) -> tuple[Action, ...]:
        setup = self.setup
        if getattr(self.ball_policy, "every_ball", False):
            # Layer 3 owns every ball-holder decision (TPOT-RL's rule, skills/layer3.py),
            # shooting and dribbling included; without a pose it falls back to the rule below.
            layer3 = self._layer3(percept, pose)
            if layer3 is not None:
                return layer3
        goal = self._goal_direction(percept, pose)
        if goal is not None and in_shooting_range(goal, setup.shoot_range_m):
            self.intent = "shoot"
            if self._spell_kicked != "shoot":
                self.shots += 1
                self._spell_kicked = "shoot"
            return (Kick(setup.powers.shot, goal[1]),)
        direction = 0.0 if goal is None else goal[1]
        if self.is_goalie or opponent_in_path(percept, direction, setup.blocked_m):
            layer3 = self._layer3(percept, pose)
            if layer3 is not None:
                return layer3
            target = self._choose_receiver(percept, pose)
            if target is not None:
                number, angle = target
                self.intent = f"pass {number}" if number else "pass"
                if self._spell_kicked != "pass":
                    self.passes += 1
                    self._spell_kicked = "pass"
                return (Kick(setup.powers.passing, angle),)
        if goal is None:
            self.intent = "search"
            return (Turn(SEARCH_TURN_RAD),)  # hold the ball, look for the goal
        self.intent = "dribble"
        return (Kick(setup.powers.dribble, direction),)

    def _layer3(self, percept: Percept, pose: Pose | None) -> tuple[Action, ...] | None:
        """The ball policy's kick, asked once per spell on the ball (None: no policy/pose)."""
        if self.ball_policy is None:
            return None
        if self._spell_kicked != "layer3":
            self._layer3_kick = self.ball_policy.decide(self.number, percept, pose, self._ball_xy)
            if self._layer3_kick is None:
                return None
            intent = self._layer3_kick[0]
            if intent.startswith("tpot shoot"):
                self.shots += 1
            elif not intent.startswith("tpot keep"):
                self.passes += 1
            self._spell_kicked = "layer3"
        assert self._layer3_kick is not None
        self.intent, actions = self._layer3_kick
        return actions

    def _goal_direction(self, percept: Percept, pose: Pose | None) -> tuple[float, float] | None:
        """(distance [m], angle [rad]) of the opponents' goal: seen, else from the pose."""
        return goal_direction(percept, pose, self.setup.attack_right, self.setup.goal_xy)

    def _choose_receiver(self, percept: Percept, pose: Pose | None) -> tuple[int, float] | None:
        """(number or 0, direction [rad]) of the pass, or None: no one to pass to."""
        setup = self.setup
        own = percept.player.team
        candidates = [
            (i, s)
            for i, s in enumerate(percept.players)
            if s.team == own and self._passable(s, pose)
        ]
        if not candidates:
            return None
        if self.evaluator is None:
            _, best = min(candidates, key=lambda c: c[1].distance_m)
            return (best.number or 0, best.angle_rad)
        scored = []
        for index, seen in candidates:
            x = open_play_attributes(percept, index, setup.unit_m, setup.receiver_half)
            scored.append((self.evaluator.success_confidence(x), seen))
        confidence, best = max(scored, key=lambda c: c[0])
        if not confidence >= self.pass_threshold:
            return None
        return (best.number or 0, best.angle_rad)

    def _passable(self, seen: SeenPlayer, pose: Pose | None) -> bool:
        setup = self.setup
        if not MIN_PASS_UNITS * setup.unit_m <= seen.distance_m <= setup.pass_range_m:
            return False
        if pose is None:
            return True
        heading = pose.heading + seen.angle_rad
        ahead = seen.distance_m * math.cos(heading)  # along +x
        if not setup.attack_right:
            ahead = -ahead
        return ahead >= AHEAD_UNITS * setup.unit_m

    # ------------------------------------------------------------------ pushing

    def _push_play(
        self, percept: Percept, pose: Pose, ball_xy: tuple[float, float]
    ) -> tuple[Action, ...]:
        """The chaser of a pushing team (module docstring, "Pushing").

        A ball that comes at the player on its way toward the player's own end is met head-on
        (:meth:`_chase`: layer 1 for the layered team, straight for the baseline), which sends
        it back the way it came. Any other ball is played from behind: the player goes to a
        point behind it on its line to the opponents' goal (around it when on the wrong side)
        and pushes it on from there (:meth:`_on_ball`).
        """
        ball = percept.ball
        assert ball is not None
        if self._meets(pose, ball_xy):
            if self.interception is not None and self.lead is None:
                return self._chase(percept)  # the paper's turn-angle net, as in open fields
            return self._meet(percept, pose, ball_xy)
        setup = self.setup
        bx, by = ball_xy
        gx, gy = setup.goal_xy
        length = math.hypot(gx - bx, gy - by) or 1.0
        tx, ty = (gx - bx) / length, (gy - by) / length  # the way the ball should go
        rx, ry = pose.x - bx, pose.y - by
        along = rx * tx + ry * ty  # > 0: the player stands goal-side of the ball
        across = tx * ry - ty * rx  # which side of the ball's line it stands on
        behind = setup.player_radius_m + setup.reach_m
        self._previous_bd = ball.distance_m
        if along < 0.0 and abs(across) <= PUSH_LINE_SHARE * -along:
            if ball.distance_m <= setup.reach_m:
                return self._on_ball(percept, pose)
            self._spell_kicked = ""
            self.intent = "chase"
            return self._run_to(ball.angle_rad, ball.distance_m)  # behind it: run through
        self._spell_kicked = ""
        if along > -behind and abs(across) < 2.0 * behind:
            side = 1.0 if across >= 0.0 else -1.0  # go round on the side it stands
            target = (bx - ty * side * 2.0 * behind, by + tx * side * 2.0 * behind)
        else:
            target = (bx - tx * 2.0 * behind, by - ty * 2.0 * behind)
        target = self._inside(target)
        self.intent = "approach"
        angle = wrap_angle(math.atan2(target[1] - pose.y, target[0] - pose.x) - pose.heading)
        distance = math.hypot(target[0] - pose.x, target[1] - pose.y)
        if setup.dead_band:  # at full power it overshoots its point and turns round (measured)
            return self._drive_to(angle, distance, setup.reach_m, 100.0)
        return self._run_to(angle, distance)

    def _meet(
        self, percept: Percept, pose: Pose, ball_xy: tuple[float, float]
    ) -> tuple[Action, ...]:
        """Meet a rolling ball as layer 1's lead defender does (`skills.lead`).

        The lead τ is chosen once, at the spell's first percept: the lead net's for a ball that
        rolls free from :attr:`TeamSetup.lead_from_m` out (the shots it learned on), else 0,
        the baseline's straight pursuit. Then at every percept: a turn toward the ball's
        position τ ahead and a dash, one arc on the robots (:class:`~robotsoccer.skills.lead.
        LeadDefenderMind`).
        """
        ball = percept.ball
        velocity = self._track.velocity()
        assert ball is not None and velocity is not None
        bd = ball.distance_m
        previous = bd if self._previous_bd is None else self._previous_bd
        self._previous_bd = bd
        self._lead_s = self._held_lead
        if self._lead_s is None:
            lead = 0.0
            if self.lead is not None and bd >= self.setup.lead_from_m and self._rolls_free(percept):
                angle = track_angle(ball_xy, velocity, (pose.x, pose.y))
                lead = min(LEAD_CLIP_S, max(0.0, self.lead(bd, angle, previous)))
            self._lead_s = lead
        self._spell_kicked = ""
        self.intent = "intercept" if self.lead is not None else "meet"
        aim = self._inside(ahead_of(ball_xy, velocity, self._lead_s, self.setup.ball_law))
        angle = wrap_angle(math.atan2(aim[1] - pose.y, aim[0] - pose.x) - pose.heading)
        tolerance = self.setup.turn_tolerance_rad
        return turn_then_go(angle, (Dash(100.0),), least_turn_rad=tolerance)
