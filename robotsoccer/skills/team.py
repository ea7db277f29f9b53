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
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Protocol

from field_models.arena import BallLaw
from field_models.protocol import Action, Dash, Kick, Percept, SeenPlayer, Turn, wrap_angle
from learning.pass_features import pass_attributes, passer_attributes, unknown_half
from robotsoccer.skills.intercept import TurnPolicy
from robotsoccer.skills.lead import (
    LEAD_CLIP_S,
    BallTrack,
    LeadPolicy,
    ahead_of,
    track_angle,
    velocity_window,
)
from robotsoccer.skills.localise import Localiser, Pose
from robotsoccer.skills.passing import PassEvaluator, view_arrays
from robotsoccer.skills.setplay import KickPowers, opponent_in_path

REVERSE_HOLD_TICKS = 10
"""With steady turns, a turn the other way within this many ticks of the last needs ..."""
REVERSE_MIN_RAD = math.radians(60.0)
"""... more than this (a ball that moved behind the player still turns it)."""
MEMORY_TICKS = 20
"""With steady turns, a ball seen this recently is trusted where it was (going home)."""
SEARCH_TURN_RAD = math.radians(60.0)
"""A player that sees no ball turns this far per decision to find it."""
FACING_RAD = math.radians(12.0)
"""Within this of the heading a player runs; farther, it turns first."""
CHASE_MARGIN_UNITS = 2.0
"""Hysteresis of the chaser rule [units]."""
BALL_SHIFT_X = 0.4
"""A home shifts this share of the ball's x toward the ball."""
BALL_SHIFT_Y = 0.2
"""... and this share of the ball's offset in y."""
NEAR_REACHES = 3.0
"""A ball within this many reaches is near: turn to it before running (no circling), and
layer 1's net is not asked (it learned to meet a ball from afar, §5)."""
COMING_SHARE = 0.1
"""The ball comes toward the player when its distance fell by this share of the reach since
the last percept (the net's case, §5)."""
MIN_PASS_UNITS = 6.0
"""Teammates nearer than this are not passed to (the ball would barely leave)."""
GOALIE_RANGE_UNITS = 5.0
"""The goalie keeps within this of the goal's centre line [units], half the ball's y."""
PUSH_LINE_SHARE = 0.5
"""A pushing player runs through the ball when it stands behind it within this share of its
distance behind, off the ball's line to the goal (about 27°: the push goes goalward)."""
MEET_SPEED_MPS = 0.2
"""A pushing team meets a ball head-on only when it rolls faster than this [m/s]."""
AHEAD_UNITS = -5.0
"""A teammate is a pass candidate when at least this far ahead of the passer (negative: a
little behind is fine)."""


class BallPolicy(Protocol):
    """A learned choice of where to send the ball (layer 3, :mod:`robotsoccer.skills.layer3`).

    The mind asks it where the layered team would ask layer 2's tree (step 3's *pass*), and
    tells it every percept's sighting of the ball, for its rewards.
    """

    def decide(
        self, number: int, percept: Percept, pose: Pose | None, ball_xy: tuple[float, float] | None
    ) -> tuple[str, tuple[Action, ...]] | None:
        """(intent, actions) of its kick, or None: the layered team's rule decides."""
        ...

    def observe(self, number: int, tick: int, ball_xy: tuple[float, float] | None) -> None:
        """Player `number` saw the ball at `ball_xy` (field frame [m]), or did not (None)."""
        ...


@dataclass(frozen=True, slots=True)
class TeamSetup:
    """One team's plan on one field (the match drill fills it from the field's facts).

    Attributes:
        attack_right: The team attacks the goal at +x.
        home: Formation home of each uniform number, field frame [m].
        goalie: The goalie's number, or None.
        landmarks: The field's landmarks (:attr:`FieldFacts.landmarks`).
        unit_m: One drill unit [m].
        reach_m: Kick reach the minds trust (a share of the true reach: sensor noise) [m].
        blocked_m: An opponent this close in the path ends a dribble [m].
        shoot_range_m: The goal this close: shoot [m].
        pass_range_m: Teammates farther than this are not passed to [m].
        trigger_distance_m: Layer 1's trigger distance on the field [m].
        goalie_zone_m: The goalie chases a ball this close to its goal [m].
        home_tolerance_m: Close enough to home [m].
        powers: The field's kick powers.
        half_length_m: Half the pitch's length [m].
        half_width_m: Half its width [m].
        dt_s: One tick [s].
        latency_s: The sensor's latency [s].
        spin_accel_radps2: How fast a player's spin can build up: its acceleration over its
            half-size [rad/s²].
        sensor_period_s: Time between two percepts [s] (the lead's velocity fit).
        ball_law: How the free ball slows down (the lead's prediction); None: it does not.
        steady_turns: Turn without dithering (issue 28): a turn is added to the heading the
            localiser keeps until two landmarks fix it again, and a turn the other way from the
            last one within :data:`REVERSE_HOLD_TICKS` is left out unless it exceeds
            :data:`REVERSE_MIN_RAD`, and a player facing where it last saw the ball without
            seeing it forgets that place (it searches on, one way), and one that is not the
            chaser and saw the ball within :data:`MEMORY_TICKS` goes on home instead of turning
            back to look; a player home stays so until twice the home tolerance away.
            False: the paper's client (turns forgotten until seen).
        push_kick: The players move the ball by pushing it with their bodies (no aimable kick:
            the 1997 small-size robots, `specs/robot_physics.md`): a push sends the ball where
            the body goes, so the minds play it from behind (module docstring, "Pushing").
        lead_from_m: A lead net is asked only of a ball this far or farther when a meeting
            starts: the nearest a shot of its drill is at the trigger (nearer, it would answer
            outside what it learned, and the player meets the ball straight, τ = 0) [m].
        lead_trigger_m: A pushing team's goalie meets a shot on target from this near [m]:
            layer 1's drill's trigger distance (its farthest shot).
        goalie_depth_m: How far in front of its goal line the goalie stands [m].
        sees_all_round: The sensor sees the whole field whatever a player's heading (the
            robots' overhead camera): a ball seen within :data:`MEMORY_TICKS` and missing now
            was missed by the camera, and the player keeps its last command instead of turning
            to search. False: a view cone (the Soccer Server).
        player_radius_m: A player's half size [m] (how far behind the ball it stands).
        goal_width_m: The goal's width [m] (a pushing team's goalie meets shots on target).
        turn_tolerance_rad: Meeting a ball, turns smaller than this are left out (layer 1's
            drill: three sigmas of the sensor's heading noise) [rad].
    """

    attack_right: bool
    home: Mapping[int, tuple[float, float]]
    goalie: int | None
    landmarks: tuple[tuple[str, float, float], ...]
    unit_m: float
    reach_m: float
    blocked_m: float
    shoot_range_m: float
    pass_range_m: float
    trigger_distance_m: float
    goalie_zone_m: float
    home_tolerance_m: float
    powers: KickPowers
    half_length_m: float
    half_width_m: float
    dt_s: float
    latency_s: float
    spin_accel_radps2: float
    sensor_period_s: float = 0.1
    ball_law: BallLaw | None = None
    steady_turns: bool = False
    push_kick: bool = False
    lead_from_m: float = 0.0
    lead_trigger_m: float = 0.0
    goalie_depth_m: float = 0.0
    sees_all_round: bool = False
    player_radius_m: float = 0.0
    goal_width_m: float = 0.0
    turn_tolerance_rad: float = 0.0

    def turn_ticks(self, angle_rad: float) -> int:
        """Ticks until a percept shows a turn by `angle_rad` done: latency plus the spin.

        A body that spins up at ``spin_accel`` and down again turns by a in about
        sqrt(|a| / spin_accel) (the robots' host plans its turns so, `robot_physics.host`).
        """
        spin = math.sqrt(abs(angle_rad) / self.spin_accel_radps2)
        return math.ceil((self.latency_s + spin) / self.dt_s)

    @property
    def goal_xy(self) -> tuple[float, float]:
        """The opponents' goal centre [m]."""
        return (self.half_length_m if self.attack_right else -self.half_length_m, 0.0)

    @property
    def own_goal_xy(self) -> tuple[float, float]:
        """The team's own goal centre [m]."""
        return (-self.goal_xy[0], 0.0)


class TeamMind:
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
        self._hold_until = -1  # percepts sampled before this tick predate the last turn
        self._last_turn = (-REVERSE_HOLD_TICKS - 1, 0.0)  # (tick, angle) with steady turns
        self._seen_tick = -MEMORY_TICKS - 1  # the last tick it saw the ball
        self._at_home = False  # with steady turns: arrived home and not yet pushed off it
        self._lead_s: float | None = None  # the lead held while meeting a ball (pushing teams)
        self._held_lead: float | None = None  # ... as the last decision left it
        self._sighted_tick = -1  # the frame of the ball's last sighting on its track

    def act(self, percept: Percept) -> tuple[Action, ...]:
        """One decision (module docstring), its turns remembered until percepts show them."""
        if percept.observed_tick < self._hold_until:
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
        if self.setup.steady_turns:
            actions = self._steady(percept.tick, actions)
        for action in actions:
            if isinstance(action, Turn) and self._lead_s is None:
                # (a player meeting a ball re-aims at every percept, as layer 1's drill does)
                self._hold_until = percept.tick + self.setup.turn_ticks(action.angle_rad)
                break
        return actions

    def _steady(self, tick: int, actions: tuple[Action, ...]) -> tuple[Action, ...]:
        """Leave out a small turn back within the hold; reckon the turn kept into the heading."""
        for i, action in enumerate(actions):
            if not isinstance(action, Turn):
                continue
            angle = action.angle_rad
            back = self._last_turn[1] * angle < 0.0 and abs(angle) <= REVERSE_MIN_RAD
            if back and tick - self._last_turn[0] <= REVERSE_HOLD_TICKS:
                return actions[:i] + actions[i + 1 :]
            self._last_turn = (tick, angle)
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

    # ------------------------------------------------------------------ on the ball

    def _on_ball(self, percept: Percept, pose: Pose | None) -> tuple[Action, ...]:
        setup = self.setup
        if getattr(self.ball_policy, "every_ball", False):
            # Layer 3 owns every ball-holder decision (TPOT-RL's rule, skills/layer3.py),
            # shooting and dribbling included; without a pose it falls back to the rule below.
            layer3 = self._layer3(percept, pose)
            if layer3 is not None:
                return layer3
        goal = self._goal_direction(percept, pose)
        if goal is not None and goal[0] <= setup.shoot_range_m:
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
        mark = percept.landmark("g r" if self.setup.attack_right else "g l")
        if mark is not None:
            return (mark.distance_m, mark.angle_rad)
        if pose is None:
            return None
        gx, gy = self.setup.goal_xy
        return (
            math.hypot(gx - pose.x, gy - pose.y),
            wrap_angle(math.atan2(gy - pose.y, gx - pose.x) - pose.heading),
        )

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
            others = [s for i, s in enumerate(percept.players) if i != index]
            dist, ang, team = view_arrays(others, own, setup.unit_m)
            mine = passer_attributes(
                seen.distance_m / setup.unit_m, math.degrees(seen.angle_rad), dist, ang, team
            )
            x = pass_attributes(mine, unknown_half())
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
        return self._run_to(angle, math.hypot(target[0] - pose.x, target[1] - pose.y))

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
        if abs(angle) < self.setup.turn_tolerance_rad:
            return (Dash(100.0),)
        return (Turn(angle), Dash(100.0))

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
        """Turn toward `angle` and run (on arcs where the host drives them)."""
        angle = wrap_angle(angle)
        if abs(angle) <= FACING_RAD:
            return (Dash(100.0),)
        if distance_m <= NEAR_REACHES * self.setup.reach_m:
            return (Turn(angle),)  # near: run on only once facing it, or it circles
        return (Turn(angle), Dash(100.0))

    # ------------------------------------------------------------------ chase, home

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
        if abs(angle) <= FACING_RAD:
            return (Dash(100.0),)
        if bd <= NEAR_REACHES * reach:
            return (Turn(angle),)  # near the ball: run on only once facing it, or it circles
        return (Turn(angle), Dash(100.0))

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
        if self.setup.steady_turns:  # hysteresis: home until twice the tolerance away
            self._at_home = math.hypot(dx, dy) <= tolerance * (2.0 if self._at_home else 1.0)
            far = not self._at_home
        else:
            far = math.hypot(dx, dy) > tolerance
        if far:
            angle = wrap_angle(math.atan2(dy, dx) - pose.heading)
            if abs(angle) > 2.0 * FACING_RAD:
                return (Turn(angle), Dash(80.0))
            return (Dash(80.0),)
        if ball is not None and abs(ball.angle_rad) > FACING_RAD:
            return (Turn(ball.angle_rad),)
        return ()

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
