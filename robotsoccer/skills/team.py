"""Team play for whole matches: one mind per player, for the layered team and the baseline.

Every mind reads its percept only (DESIGN.md §2) and does what a 1996 client did each time a
percept arrives:

1. **Localise** (:class:`Localiser`): its own position and heading from the landmarks it sees
   and where the field's facts say they stand (the Soccer Server's flags and goals; the
   robots' host gives the two goals). With one landmark it keeps its last heading; with none
   it keeps its last pose.
2. **Who goes for the ball.** It is the *chaser* when no teammate it sees is nearer the ball
   than itself (by :data:`CHASE_MARGIN_UNITS`; a player that was chasing keeps chasing until
   a teammate is that much nearer). The goalie chases only a ball inside its own zone.
3. **With the ball in reach** (the skills of :mod:`robotsoccer.skills.setplay`):

   * the opponents' goal within :attr:`TeamSetup.shoot_range_m`: *shoot*;
   * an opponent in the path within :attr:`TeamSetup.blocked_m`: *pass*: the layered team
     asks layer 2's tree (its own half of the 174 attributes; the receiver's half is unknown,
     as §6 allows: there is no time for the say/hear exchange in open play) and passes to the
     teammate with the highest success confidence if that is at least
     :attr:`TeamMind.pass_threshold`; the baseline passes to the closest teammate ahead (the
     paper's "closest" heuristic). No teammate: dribble on;
   * else *dribble* toward the goal.
4. **Chasing a ball out of reach:** the layered team intercepts with layer 1's net while the
   ball comes toward it within the trigger distance (straight at it otherwise): a turn-angle
   net gives TA, as in §5's drill; a lead net (:mod:`robotsoccer.skills.lead`) the lead τ, and
   the player aims τ ahead of the ball along its velocity, fitted from its last sightings in
   the field frame. The baseline always runs straight at the ball.
5. **Otherwise** it goes to its formation home, shifted toward the ball
   (:data:`BALL_SHIFT_X`, :data:`BALL_SHIFT_Y`), and faces the ball there.

**Pushing** (:attr:`TeamSetup.push_kick`: the 1997 small-size robots had no kicker and moved
the ball with their bodies, `specs/robot_physics.md`). A push sends the ball where the body
goes, so a chaser that runs straight at the ball from the wrong side pushes it toward its own
goal: on `small_size_1997_arc` about half of all goals were such own goals (README, "Matches
(measured)"). The chaser of a pushing team therefore:

* **meets** a ball that rolls at it toward its own end (faster than :data:`MEET_SPEED_MPS`) as
  layer 1's goal-mouth drill does (:class:`~robotsoccer.skills.lead.LeadDefenderMind`): the lead
  τ chosen at the first percept of the meeting, then at every percept a turn toward the ball's
  position τ ahead and a dash (one arc on the robots), no turn hold; meeting head-on sends the
  ball back the way it came. The layered team's τ is its lead net's, asked only where the net
  learned (a ball that rolls free of other players, from :attr:`TeamSetup.lead_from_m` out);
  elsewhere, and always for the baseline, τ = 0: straight pursuit, the drill's own baseline;
* otherwise plays the ball **from behind**: it goes to a point behind the ball on the ball's
  line to the opponents' goal (round the ball, on its own side, when it stands goal-side of
  it) and, once behind it within :data:`PUSH_LINE_SHARE`, runs through it; on the ball it
  shoots, passes or dribbles as above.

Its goalie stands where the drill's defender stood (:attr:`TeamSetup.goalie_depth_m`), meets a
shot on target from the drill's trigger distance out (cutting short the hold of a turn it is
in: the drill's defender reacts at the first frame that shows the shot), and plays a ball in
its zone only from the goal side. With an overhead camera (:attr:`TeamSetup.sees_all_round`)
a ball missing from a frame is a missed detection: no one turns to search for it, and the
ball's track keeps every frame's sighting, also in a turn hold. Everything here is the same
for both teams except τ; on a field with an aimable kick none of it applies.

What a team may not do is read truth: the coach places players for kick-offs (as clients'
``move`` commands would) and the referee restarts play.

Where it lives: :class:`TeamSetup`, :class:`BallPolicy` and the constants named here in
:mod:`robotsoccer.skills.team_setup`; a mind's state and its reading of a rolling ball in
:mod:`robotsoccer.skills.team_base`; steps 4-5 in :mod:`robotsoccer.skills.team_chase`; step 3
and "Pushing" in :mod:`robotsoccer.skills.team_ball`; :class:`TeamMind` here: steps 1-2 and
the decision with its turn holds (the motion skill's hold, :mod:`robotsoccer.skills.motion`,
which also gives every turn then go of these modules).
"""

from __future__ import annotations

import math

from field_models.protocol import Action, Percept, Turn
from robotsoccer.skills.localise import Pose
from robotsoccer.skills.team_ball import BallMind
from robotsoccer.skills.team_look import look_target
from robotsoccer.skills.team_setup import (
    CHASE_MARGIN_UNITS,
)


class TeamMind(BallMind):
    """One player of a match team (module docstring).

    Args:
        number: Its uniform number.
        setup: Its team's plan.
        interception: Layer 1's TA rule (the net); None: run straight at the ball.
        lead: Layer 1's lead rule (a lead net); used instead of `interception` when given.
        evaluator: Layer 2's pass evaluator; None: pass to the closest teammate.
        pass_threshold: The tree's least success confidence for a pass.
        ball_policy: Layer 3: asked instead of the pass rule (once per spell on the ball);
            None: the layered (or baseline) rule.

    Attributes:
        intent: What its last decision was for (``shoot``, ``pass 7``, ``dribble``,
            ``intercept``, ``chase``, ``home``, ``search``).
        shots: Shots it kicked (one per spell on the ball).
        passes: Passes it kicked (one per spell on the ball).
    """

    def act(self, percept: Percept) -> tuple[Action, ...]:
        """One decision (module docstring), its turns remembered until percepts show them.

        Looking with the neck (:attr:`TeamSetup.look`), the mind reasons on the percept with
        its directions from the body, and adds the neck turn and view of
        :mod:`robotsoccer.skills.team_look` to the body's decision.
        """
        if self.setup.look != "neck":
            return self._act(percept)
        percept = self.head.sensed(percept)
        actions = self._act(percept)
        target = look_target(percept, self.localiser.pose, self._ball_xy, self._seen_tick)
        return self.head.look(actions, target)

    def _act(self, percept: Percept) -> tuple[Action, ...]:
        """The body's decision on this percept (module docstring)."""
        reckon = self.setup.turn_latency == "reckon"
        if reckon:
            # The motion skill's reckoning: the percept in the frame of every turn sent.
            percept = self.turns.view(percept)
        elif self.turns.holding(percept.observed_tick):
            # The last turn is not over in what this percept shows (the robots' camera latency
            # and spin-up): deciding again would turn twice and swing about. The body goes on
            # with the last decision (an empty one keeps it, on the robots' host).
            if not self.setup.sees_all_round:
                return ()
            # The overhead camera gives every frame's pose and ball: the ball's track keeps
            # every sighting, so the velocity fit spans consecutive frames (as in layer 1's
            # drill, which decides at each), and a shot at its goal cuts the goalie's hold
            # short: layer 1's defender reacts at the first frame that shows it.
            pose = self._sight(percept)
            if not self._shot_at_goalie(pose):
                return ()
        actions = self._decide(percept)
        if self.ball_policy is not None:
            seen = percept.ball is not None and self.localiser.pose is not None
            self.ball_policy.observe(self.number, percept.tick, self._ball_xy if seen else None)
        if self.setup.steady_turns or (self.setup.dead_band and self._lead_s is None):
            actions = self._steady(percept.tick, actions)
        for action in actions:
            if isinstance(action, Turn):
                # A player meeting a ball re-aims at every percept, as layer 1's drill does:
                # its turns start no hold (reckoned, they turn the frame all the same).
                if reckon or self._lead_s is None:
                    self.turns.sent(percept.tick, action.angle_rad)
                break
        return actions

    def _steady(self, tick: int, actions: tuple[Action, ...]) -> tuple[Action, ...]:
        """Leave out a small turn back within the hold; reckon the turn kept into the heading.

        The hold is :meth:`~robotsoccer.skills.team_setup.TeamSetup.reverse_hold_ticks`; only
        steady turns reckon (the dead band alone leaves the localiser as it was).
        """
        for i, action in enumerate(actions):
            if not isinstance(action, Turn):
                continue
            angle = action.angle_rad
            back = self._last_turn[1] * angle < 0.0 and abs(angle) <= self.setup.reverse_min_rad()
            if back and tick - self._last_turn[0] <= self.setup.reverse_hold_ticks():
                return actions[:i] + actions[i + 1 :]
            self._last_turn = (tick, angle)
            if self.setup.steady_turns:
                self.localiser.turned(angle)
            break
        return actions

    def _decide(self, percept: Percept) -> tuple[Action, ...]:
        # A lead is held only through an unbroken spell of meeting the ball (_meet sets it).
        self._held_lead, self._lead_s = self._lead_s, None
        pose = self._sight(percept)
        ball = percept.ball
        if ball is None:
            self._previous_bd = None
            return self._no_ball(percept, pose)
        self.chasing = self._is_chaser(percept)
        if not self.chasing:
            self._spell_kicked = ""
            self._previous_bd = ball.distance_m
            return self._go_home(percept, pose)
        if self.setup.push_kick and pose is not None and self._ball_xy is not None:
            return self._push_play(percept, pose, self._ball_xy)
        if ball.distance_m <= self.setup.reach_m:
            return self._on_ball(percept, pose)
        self._spell_kicked = ""
        return self._chase(percept)

    def _sight(self, percept: Percept) -> Pose | None:
        """Localise, and put the ball seen in the field frame and on its track."""
        pose = self.localiser.update(percept)
        ball = percept.ball
        if ball is None:
            return pose
        self._seen_tick = percept.tick
        if pose is not None:
            heading = pose.heading + ball.angle_rad
            self._ball_xy = (
                pose.x + ball.distance_m * math.cos(heading),
                pose.y + ball.distance_m * math.sin(heading),
            )
            fresh = percept.observed_tick != self._sighted_tick  # once per frame
            if fresh and (self.lead is not None or self.setup.push_kick):
                self._track.add(percept.observed_tick * self.setup.dt_s, *self._ball_xy)
            self._sighted_tick = percept.observed_tick
        return pose

    # ------------------------------------------------------------------ who chases

    def _is_chaser(self, percept: Percept) -> bool:
        ball = percept.ball
        assert ball is not None
        setup = self.setup
        if self.is_goalie:
            if self._ball_xy is None:
                return ball.distance_m <= setup.reach_m
            gx, gy = setup.own_goal_xy
            bx, by = self._ball_xy
            near = math.hypot(bx - gx, by - gy)
            if setup.push_kick and ball.distance_m <= setup.lead_trigger_m:
                pose = self.localiser.pose
                if self._shot_at_goalie(pose):
                    return True  # a shot at its goal: the goalie meets it (layer 1's drill)
                if near > setup.goalie_zone_m or pose is None:
                    return False
                # In its zone it plays a ball only from the goal side (a push goes out of the
                # goal); going round a ball there turns it into its own goal (measured).
                return (pose.x - bx) * gx > 0.0
            return near <= setup.goalie_zone_m
        bx = ball.distance_m * math.cos(ball.angle_rad)
        by = ball.distance_m * math.sin(ball.angle_rad)
        margin = CHASE_MARGIN_UNITS * setup.unit_m
        mine = ball.distance_m - (margin if self.chasing else 0.0)
        own = percept.player.team
        for seen in percept.players:
            if seen.team != own:
                continue
            tx = seen.distance_m * math.cos(seen.angle_rad)
            ty = seen.distance_m * math.sin(seen.angle_rad)
            if math.hypot(tx - bx, ty - by) < mine:
                return False
        return True
