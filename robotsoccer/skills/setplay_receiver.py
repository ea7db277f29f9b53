"""The set play's receivers: meet the pass, then kick it on at once (paper §7, Figure 15).

:class:`SetPlayReceiverMind` is layer 2's :class:`~robotsoccer.skills.pass_receivers.ReceiverMind`
(face the ball, report, intercept with layer 1 once chosen); once the ball is in reach it kicks
on at once, as the paper's receiver does: a first receiver to the winger (saying the cue),
toward the winger as seen or else as last heard calling; a last receiver at the goal, as seen or
else where it saw the goal before the play reached it (it looks for the goal while it waits,
then turns with the ball to see it before shooting), on the side of the goal mouth away from the
goalie (:func:`~robotsoccer.skills.setplay.shot_direction`). The last receivers listen only from
the winger's call (or cue) on, so the first pass's conversation is not theirs.

**A camera** (the robots). A receiver meets the pass with layer 1, stands still for the last
:data:`SET_PERIODS` periods (so that the heading its kick is aimed by is known), and sends its
kick on first time as soon as the ball will come into reach within :data:`ONE_TOUCH_PERIODS`
(:func:`~robotsoccer.skills.setplay.reach_entry`): the drill's coach fires it when the ball
gets there. A first-time kick whose path would run back into the body is bent round it
(:meth:`~robotsoccer.skills.ball_tracker.BallTracker.aim`). It checks afterwards that the
ball went, and meets it again if not.

**Looking with the neck** (a :class:`~robotsoccer.skills.team_look.NeckLook` given: the set play's
``look=neck``, :mod:`robotsoccer.skills.setplay_look`). Its percepts come with their directions from
the body; layer 2's receiver waits as its module says; a last receiver waiting for the winger looks
for the goal with its head (:attr:`SetPlayReceiverMind.seeking_goal`: the head scans, the body
stands) and keeps the ball in view without turning its body while the head can
(:data:`~robotsoccer.skills.team_look.LOOK_COVER_RAD`). The goal it then remembers is a direction
from the body, as its shot needs. The shared skills are :mod:`robotsoccer.skills.setplay`'s; angles
are radians, left positive; distances metres.
"""

from __future__ import annotations

import math

from field_models.protocol import Action, Percept, Say, Turn
from robotsoccer.skills.ball_sense import BallSense, Vector
from robotsoccer.skills.ball_tracker import BallTracker
from robotsoccer.skills.pass_messages import announced_number
from robotsoccer.skills.pass_receivers import ReceiverMind
from robotsoccer.skills.setplay import (
    FACING_RAD,
    SEARCH_TURN_RAD,
    SLOW_ZONE_REACHES,
    STAND,
    STILL_SHARE,
    WINGER_CALL,
    WINGER_CUE,
    KickPowers,
    approach,
    arrives,
    face_ball,
    find_teammate,
    goal_bearing,
    heard_text,
    heard_tick,
    reach_entry,
    receive,
    shot_direction,
)
from robotsoccer.skills.team_look import LOOK_COVER_RAD, NeckLook

ONE_TOUCH_PERIODS = 1.0
"""A camera-guided receiver sends its kick on when the ball will come into reach within this
many sensor periods: the kick then stays armed until the next decision (drill module)."""
SET_PERIODS = 3.0
"""A camera-guided receiver stops turning and stands when the ball will come into reach within
this many sensor periods: a turn shows in its percepts only after the camera's latency and the
turn's own time (:attr:`BallSense.turn_settle_ticks`), and the kick on is aimed relative to a
heading it must know."""


class SetPlayReceiverMind:
    """A receiver of the set play (module docstring).

    Args:
        receiver: Layer 2's receiver (reports; intercepts with layer 1's net once chosen).
        next_teammate: The winger's number (the first receivers kick to it); None: shoot.
        sense: The field's ball and kick.
        attack_right: It attacks the goal at +x.
        powers: The field's kick powers.
        armed: It listens from the start (the first receivers); False: from the winger's call
            or cue on, looking for the goal meanwhile.
        goal_half_width_m: Half the goal's width [m] (a shot aims inside it, away from the
            goalie: :func:`shot_direction`); 0: at the centre.
        head: Its head, looking with the neck (module docstring); None: with its body.

    Attributes:
        kicked_tick: The tick of its kick on (to the winger, or the shot), or None.
    """

    def __init__(
        self,
        receiver: ReceiverMind,
        next_teammate: int | None,
        *,
        sense: BallSense,
        attack_right: bool,
        powers: KickPowers,
        armed: bool = True,
        goal_half_width_m: float = 0.0,
        head: NeckLook | None = None,
    ) -> None:
        self.receiver = receiver
        self.head = head
        self.waiting_rad = FACING_RAD if head is None else LOOK_COVER_RAD
        self.goal_half_width_m = goal_half_width_m
        self.next_teammate = next_teammate
        self.sense = sense
        self.reach_m = sense.reach_m
        self.attack_right = attack_right
        self.powers = powers
        self.armed = armed
        self.kicked_tick: int | None = None
        self.tracker = BallTracker(sense)
        self.heading = sense.heading()
        self._raw: Percept | None = None
        self.done = False

    @property
    def raw(self) -> Percept:
        """The percept of the decision under way, as it came (for layer 1 and layer 2's minds)."""
        assert self._raw is not None, "act() first"
        return self._raw

    @property
    def shoots(self) -> bool:
        """Whether it shoots (a last receiver) rather than kicking to the winger."""
        return self.next_teammate is None

    @property
    def seeking_goal(self) -> bool:
        """A last receiver looking with its neck for a goal it has not seen yet (docstring)."""
        return (
            self.head is not None
            and not self.armed
            and self.shoots
            and self.heading.relative("goal") is None
        )

    def act(self, percept: Percept) -> tuple[Action, ...]:
        """Report and intercept as layer 2's receiver; holding the ball, kick on.

        Layer 1 and layer 2's minds get the percept as it came; this mind's own skills see it
        in its reckoned frame (:meth:`Heading.view`).
        """
        self._raw = percept
        view = self.heading.view(percept, self.tracker.observe(percept))
        view = self.tracker.project(view)
        self._see(view)
        actions = self._decide(view)
        self.tracker.note(actions, percept.tick)
        self.heading.note(actions, percept.tick)
        return actions

    def _see(self, percept: Percept) -> None:
        goal = goal_bearing(percept, self.attack_right)
        if goal is not None:
            self.heading.remember("goal", goal[1])
        for heard in percept.heard:
            if heard.text == WINGER_CALL and heard.direction_rad is not None:
                self.heading.remember("call", heard.direction_rad)
        if self.next_teammate is not None:
            mate = find_teammate(percept, self.next_teammate)
            if mate is not None:
                self.heading.remember("call", mate.angle_rad)

    def _decide(self, percept: Percept) -> tuple[Action, ...]:
        if not self.armed:
            if not (heard_text(percept, WINGER_CUE) or heard_text(percept, WINGER_CALL)):
                return self._look_for_goal(percept)
            self.armed = True
        if self.receiver.chosen is not True:
            actions = self.receiver.act(self.raw)
            if self.receiver.chosen is True:
                self._pass_announced(percept)
            self.done = self.receiver.done
            return actions
        if self.kicked_tick is not None:
            after = self._after_kick(percept)
            if after != "again":
                self.done = after == "done"
                return STAND if after == "wait" else ()
            self.kicked_tick = None  # the ball never came into reach: meet it again
        ball = percept.ball
        if ball is not None and ball.distance_m <= self.reach_m:
            return self._kick_on(percept)
        if self.tracker.camera is not None:
            return self._meet(percept)
        return receive(percept, self.raw, self.tracker, self.receiver.interceptor)

    def _meet(self, percept: Percept) -> tuple[Action, ...]:
        """A camera-guided receiver meets the pass and kicks it on first time (robots).

        The camera shows the ball its latency late and a decision comes once a frame, so a
        receiver that waits to see the ball in reach sees it after it has hit its body and
        bounced off (the robot's restitution, ``robot.elasticity``): it sends its kick on as
        soon as the ball will come into reach within :data:`ONE_TOUCH_PERIODS` sensor periods
        (the kicker fires when the ball reaches it: :mod:`robotsoccer.drills.setplay`). A ball
        no longer coming at it (deflected, or stopped short) it comes up to gently
        (:func:`approach`), so as not to push it away; else layer 1 takes it into the path.
        """
        ball = percept.ball
        if ball is None:
            return receive(percept, self.raw, self.tracker, self.receiver.interceptor)
        entry = reach_entry(percept, self.tracker, ONE_TOUCH_PERIODS)
        if entry is not None:
            return self._kick_on(percept, entry)
        if arrives(percept, self.tracker, SET_PERIODS):
            return STAND  # no more turns: the kick's direction is reckoned from a still heading
        vx, vy = self.tracker.velocity(percept)
        closing = -(vx * math.cos(ball.angle_rad) + vy * math.sin(ball.angle_rad))
        if closing < STILL_SHARE * self.sense.speed(self.powers.passing):
            return approach(percept, self.reach_m, self.sense.approach_power)
        return receive(percept, self.raw, self.tracker, self.receiver.interceptor)

    def _after_kick(self, percept: Percept) -> str:
        """After the kick on: ``"done"``, ``"wait"`` (to see where the ball went) or ``"again"``.

        On the Soccer Server a kick is a kick: done. A camera-guided receiver's kick fires only
        if the ball comes into reach while it is armed, so the receiver stands until a percept
        shows the ball beyond its slow zone (done) or its fitted velocity shows the ball still
        by it and slow (the kick missed: again).
        """
        ball = percept.ball
        if self.tracker.camera is None:
            return "done"
        if ball is None or not self.tracker.fresh(percept):
            return "wait"
        if ball.distance_m > SLOW_ZONE_REACHES * self.reach_m:
            return "done"
        fit = self.tracker.fitted(percept)
        if fit is not None and math.hypot(*fit) < 0.5 * self.sense.speed(self.powers.passing):
            return "again"
        return "wait"

    def _look_for_goal(self, percept: Percept) -> tuple[Action, ...]:
        """A last receiver, before the play reaches it: find the goal once, then face the ball."""
        if self.seeking_goal:
            return STAND  # the head scans for it
        if self.shoots and self.heading.relative("goal") is None:
            return (Turn(SEARCH_TURN_RAD),)
        return face_ball(percept, self.waiting_rad)

    def _pass_announced(self, percept: Percept) -> None:
        """The pass to it was just announced: the ball comes at the pass speed."""
        texts = [h.text for h in percept.heard if announced_number(h.text) is not None]
        kick_tick = heard_tick(percept, texts)
        self.tracker.launched(percept, self.sense.speed(self.powers.passing), kick_tick)

    def _kick_on(self, percept: Percept, entry: Vector | None = None) -> tuple[Action, ...]:
        """Kick to the winger, or shoot; `entry`: where an armed kick will meet the ball."""
        if self.next_teammate is None:
            return self._shoot(percept, entry)
        winger = find_teammate(percept, self.next_teammate)
        direction = winger.angle_rad if winger is not None else self.heading.relative("call")
        if direction is None:  # never seen nor heard: hold the ball and look
            return self._stop_then(percept, (Turn(SEARCH_TURN_RAD),))
        speed = self.sense.speed(self.powers.passing)
        kick, kicked = self.tracker.aim(
            percept, speed, direction, first_time=self._first(percept, entry)
        )
        if not kicked:
            return () if kick is None else (kick,)
        self.kicked_tick = percept.tick
        return (Say(WINGER_CUE),) if kick is None else (Say(WINGER_CUE), kick)

    def _first(self, percept: Percept, entry: Vector | None) -> Vector | None:
        """Where a camera-guided receiver's first-time kick meets the ball; None without camera.

        At `entry` when it is given, else where the player reckons the ball now.
        """
        ball = percept.ball
        if self.tracker.camera is None or (entry is None and ball is None):
            return None
        if entry is not None or ball is None:
            return entry
        return ball.distance_m * math.cos(ball.angle_rad), ball.distance_m * math.sin(
            ball.angle_rad
        )

    def _shoot(self, percept: Percept, entry: Vector | None = None) -> tuple[Action, ...]:
        """Shoot at the goal in view; else stop the ball and turn to where the goal was seen."""
        goal = goal_bearing(percept, self.attack_right)
        if goal is None:
            remembered = self.heading.relative("goal")
            turn = SEARCH_TURN_RAD if remembered is None else remembered
            return self._stop_then(percept, (Turn(turn),))
        direction = shot_direction(percept, goal, self.goal_half_width_m)
        speed = self.sense.speed(self.powers.shot)
        kick, kicked = self.tracker.aim(
            percept, speed, direction, first_time=self._first(percept, entry)
        )
        if kicked:
            self.kicked_tick = percept.tick
        return () if kick is None else (kick,)

    def _stop_then(self, percept: Percept, then: tuple[Action, ...]) -> tuple[Action, ...]:
        kick = self.tracker.stop(percept, STILL_SHARE * self.sense.speed(self.powers.passing))
        return then if kick is None else (kick, *then)
