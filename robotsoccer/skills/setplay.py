"""Skills built on the two learned layers, and the minds of the set play (paper §7, Figure 15).

Every mind reads percepts only and acts with the field model's actions, so the same code runs on
the Soccer Server model and on the robots (whose host turns a ``Kick`` into a push when the
robot has no kicker, :mod:`field_models.robot_physics.host`).

Skills, each a small function of one percept:

* :func:`chase` — face the ball and run at it (the approach of a dribble);
* :func:`dribble` — with the ball within reach, kick it a short way toward a direction; else
  chase it;
* :func:`shoot` — kick at full power toward the opponents' goal (the landmark ``"g r"`` for the
  left team); turn to look for it while it is out of view;
* :func:`kick_to` — kick toward a seen teammate at pass power (the receiver's kick to the
  winger).

Minds of the play (the drill :mod:`robotsoccer.drills.setplay` places them):

* :class:`CarrierMind` — the player that starts with the ball, and the winger. It dribbles
  toward the goal until it sees an opponent within :attr:`CarrierMind.blocked_distance_m` in
  its path, then hands over to layer 2's :class:`~robotsoccer.skills.passing.PasserMind`
  (intention, the two nearest teammates' reports, the tree's choice, the announced kick). The
  winger first waits for the cue :data:`WINGER_CUE` and intercepts the ball with layer 1's net.
* :class:`SetPlayReceiverMind` — layer 2's :class:`~robotsoccer.skills.passing.ReceiverMind`
  (face the ball, report, intercept with layer 1's net once chosen); once it holds the ball it
  kicks on: to the winger (saying the cue), or at the goal (the last receivers shoot). The last
  receivers listen only from the cue on, so the first pass's conversation is not theirs.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from field_models.protocol import Action, Dash, Kick, Percept, Say, SeenPlayer, Turn, wrap_angle
from robotsoccer.skills.intercept import DefenderMind
from robotsoccer.skills.passing import PasserMind, ReceiverMind

WINGER_CUE = "wing"
"""What the first receiver says as it kicks to the winger (the winger and last receivers wake)."""
SEARCH_TURN_RAD = math.radians(60.0)
"""A player looking for the ball or the goal turns this far per decision."""
FACING_RAD = math.radians(10.0)
"""Within this of the heading, a player runs instead of turning."""
PATH_HALF_ANGLE_RAD = math.radians(30.0)
"""An opponent within this of the direction of play is "in the path" (Figure 15)."""
KEEP_REACH_SHARE = 0.6
"""While its pass is being decided, a carrier keeps the ball within this share of its reach."""
KEEP_DASH_POWER = 60.0
"""Dash power for following the ball then: slow, so as not to knock it on."""
GONE_REACHES = 3.0
"""A ball this many reaches away after the pass decision has been passed (or lost)."""


@dataclass(frozen=True)
class KickPowers:
    """Kick powers of one field (server units; the robots' host maps them to pushes).

    Attributes:
        dribble: A short kick ahead, a few units.
        passing: A pass (layer 1's launch power on the field).
        shot: A shot on goal.
    """

    dribble: float
    passing: float
    shot: float


def goal_bearing(percept: Percept, attack_right: bool) -> tuple[float, float] | None:
    """(distance [m], angle [rad]) of the opponents' goal, or None while it is out of view."""
    mark = percept.landmark("g r" if attack_right else "g l")
    return None if mark is None else (mark.distance_m, mark.angle_rad)


def chase(percept: Percept, *, dash: float = 100.0) -> tuple[Action, ...]:
    """Face the ball and run at it; look for it when it is out of view."""
    ball = percept.ball
    if ball is None:
        return (Turn(SEARCH_TURN_RAD),)
    if abs(ball.angle_rad) > FACING_RAD:
        return (Turn(ball.angle_rad),)
    return (Dash(dash),)


def dribble(
    percept: Percept, direction_rad: float, reach_m: float, power: float
) -> tuple[Action, ...]:
    """Kick the ball a short way toward `direction_rad` (relative) when in reach, else chase it."""
    ball = percept.ball
    if ball is not None and ball.distance_m <= reach_m:
        return (Kick(power, wrap_angle(direction_rad)),)
    return chase(percept)


def shoot(percept: Percept, attack_right: bool, reach_m: float, power: float) -> tuple[Action, ...]:
    """A shot at the goal when the ball is in reach and the goal in view.

    Out of reach it chases the ball; with the goal out of view it turns to look for it.
    """
    ball = percept.ball
    if ball is None or ball.distance_m > reach_m:
        return chase(percept)
    goal = goal_bearing(percept, attack_right)
    if goal is None:
        return (Turn(SEARCH_TURN_RAD),)
    return (Kick(power, goal[1]),)


def find_teammate(percept: Percept, number: int) -> SeenPlayer | None:
    """The teammate with uniform `number` in view (its number seen), or None."""
    own = percept.player.team
    for seen in percept.players:
        if seen.team == own and seen.number == number:
            return seen
    return None


def opponent_in_path(percept: Percept, direction_rad: float, within_m: float) -> bool:
    """Whether an opponent is seen within `within_m` and near the direction of play."""
    own = percept.player.team
    for seen in percept.players:
        if seen.team in (own, None) or seen.distance_m > within_m:
            continue
        if abs(wrap_angle(seen.angle_rad - direction_rad)) <= PATH_HALF_ANGLE_RAD:
            return True
    return False


class CarrierMind:
    """Dribble toward the goal, then pass by the tree (module docstring).

    Args:
        passer: Layer 2's passer, to hand over to (its receivers are the two nearest).
        interceptor: Layer 1's interception, for a winger collecting the ball; None: the
            player starts with the ball.
        attack_right: It attacks the goal at +x (``"g r"``).
        reach_m: Kick reach (touch distance plus a margin on a field without a kick) [m].
        blocked_distance_m: An opponent this close in the path ends the dribble [m].
        powers: The field's kick powers.

    Attributes:
        phase: ``"wait"``, ``"collect"``, ``"dribble"``, ``"pass"`` or ``"done"``.
        passed_tick: The tick of its pass decision, or None.
    """

    def __init__(
        self,
        passer: PasserMind,
        interceptor: DefenderMind | None,
        *,
        attack_right: bool,
        reach_m: float,
        blocked_distance_m: float,
        powers: KickPowers,
    ) -> None:
        self.passer = passer
        self.interceptor = interceptor
        self.attack_right = attack_right
        self.reach_m = reach_m
        self.blocked_distance_m = blocked_distance_m
        self.powers = powers
        self.phase = "dribble" if interceptor is None else "wait"
        self.passed_tick: int | None = None
        self._goal_rad: float | None = None
        self.done = False

    def act(self, percept: Percept) -> tuple[Action, ...]:
        """One decision (module docstring)."""
        if self.phase == "wait":
            if not any(h.text == WINGER_CUE for h in percept.heard):
                return _face_ball(percept)
            self.phase = "collect"
        if self.phase == "collect":
            ball = percept.ball
            if ball is None or ball.distance_m > self.reach_m:
                assert self.interceptor is not None
                return self.interceptor.act(percept)
            self.phase = "dribble"
        if self.phase == "dribble":
            return self._dribble(percept)
        if self.phase == "pass":
            actions = self.passer.act(percept)
            if self.passer.chosen is not None:
                self.passed_tick = self.passer.decided_tick
                self.phase = "done"
                return actions
            return actions + self._keep_ball(percept)
        return self._follow_through(percept)

    def _keep_ball(self, percept: Percept) -> tuple[Action, ...]:
        """While the passer talks: stay with a ball that rolls out of reach."""
        ball = percept.ball
        if ball is not None and ball.distance_m <= KEEP_REACH_SHARE * self.reach_m:
            return ()
        return chase(percept, dash=KEEP_DASH_POWER)

    def _dribble(self, percept: Percept) -> tuple[Action, ...]:
        goal = goal_bearing(percept, self.attack_right)
        if goal is not None:
            self._goal_rad = goal[1]
        ball = percept.ball
        if goal is None and ball is not None and ball.distance_m <= self.reach_m:
            return (Turn(SEARCH_TURN_RAD),)  # hold the ball and look for the goal
        direction = 0.0 if self._goal_rad is None else self._goal_rad
        if (
            ball is not None
            and ball.distance_m <= self.reach_m
            and opponent_in_path(percept, direction, self.blocked_distance_m)
        ):
            self.phase = "pass"
            return self.passer.act(percept)
        return dribble(percept, direction, self.reach_m, self.powers.dribble)

    def _follow_through(self, percept: Percept) -> tuple[Action, ...]:
        """After the decision: keep kicking toward the receiver while the ball is in reach.

        A kicker's first kick sends the ball; a robot without one needs a few pushes, and its
        host turns it first. The receiver is re-found by number in each percept.
        """
        ball, chosen = percept.ball, self.passer.chosen
        if ball is None or chosen is None or ball.distance_m > GONE_REACHES * self.reach_m:
            self.done = ball is not None
            return ()
        if ball.distance_m > self.reach_m:
            return chase(percept)  # the kick missed (the ball had rolled away): go after it
        target = find_teammate(percept, chosen)
        if target is None:
            return (Turn(SEARCH_TURN_RAD),)
        return (Kick(self.powers.passing, target.angle_rad),)


class SetPlayReceiverMind:
    """A receiver of the set play (module docstring).

    Args:
        receiver: Layer 2's receiver (reports; intercepts with layer 1's net once chosen).
        next_teammate: The winger's number (the first receivers kick to it); None: shoot.
        attack_right: It attacks the goal at +x.
        reach_m: Kick reach [m].
        powers: The field's kick powers.
        armed: It listens from the start (the first receivers); False: from the cue on.

    Attributes:
        kicked_tick: The tick of its kick on (to the winger, or the shot), or None.
    """

    def __init__(
        self,
        receiver: ReceiverMind,
        next_teammate: int | None,
        *,
        attack_right: bool,
        reach_m: float,
        powers: KickPowers,
        armed: bool = True,
    ) -> None:
        self.receiver = receiver
        self.next_teammate = next_teammate
        self.attack_right = attack_right
        self.reach_m = reach_m
        self.powers = powers
        self.armed = armed
        self.kicked_tick: int | None = None
        self.done = False

    @property
    def shoots(self) -> bool:
        """Whether it shoots (a last receiver) rather than kicking to the winger."""
        return self.next_teammate is None

    def act(self, percept: Percept) -> tuple[Action, ...]:
        """Report and intercept as layer 2's receiver; holding the ball, kick on."""
        if not self.armed:
            if not any(h.text == WINGER_CUE for h in percept.heard):
                return _face_ball(percept)
            self.armed = True
        if self.receiver.chosen is not True:
            actions = self.receiver.act(percept)
            self.done = self.receiver.done
            return actions
        ball = percept.ball
        if ball is None or ball.distance_m > self.reach_m:
            if self.kicked_tick is not None:
                return ()  # the ball is on its way
            return self.receiver.act(percept)
        return self._kick_on(percept)

    def _kick_on(self, percept: Percept) -> tuple[Action, ...]:
        if self.next_teammate is None:
            shot = shoot(percept, self.attack_right, self.reach_m, self.powers.shot)
            if self.kicked_tick is None and any(isinstance(a, Kick) for a in shot):
                self.kicked_tick = percept.tick
            return shot
        winger = find_teammate(percept, self.next_teammate)
        if winger is None:
            return (Turn(SEARCH_TURN_RAD),)  # hold the ball and look for the winger
        first = self.kicked_tick is None
        self.kicked_tick = percept.tick if first else self.kicked_tick
        kick = Kick(self.powers.passing, winger.angle_rad)
        return (Say(WINGER_CUE), kick) if first else (kick,)


def _face_ball(percept: Percept) -> tuple[Action, ...]:
    ball = percept.ball
    if ball is not None and abs(ball.angle_rad) > FACING_RAD:
        return (Turn(ball.angle_rad),)
    return ()
