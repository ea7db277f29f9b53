"""The set play's starter and winger: dribble, stop, look, pass by the tree (paper §7, Fig. 15).

:class:`CarrierMind` is the player that starts with the ball, and the winger. It dribbles toward
the goal until it sees an opponent within :attr:`CarrierMind.blocked_distance_m` in its path
(Figure 15's "predetermined distance"). Then, as §7 says, it *stops dribbling and considers its
options*: it stops the ball (a kick against its motion), turns until it sees both its receivers
(they may be outside its 90° view cone, §4), and only then hands over to layer 2's
:class:`~robotsoccer.skills.passing.PasserMind` (intention, the two nearest teammates' reports,
the tree's choice, the announcement); standing by a ball at rest, it cannot lose it while they
talk (if it rolls off all the same, it follows and stops it again). It kicks the pass itself,
compensated. The winger first waits, calling :data:`~robotsoccer.skills.setplay.WINGER_CALL`
from the first pass's announcement on, and collects the pass with layer 1's interception once it
hears the cue :data:`~robotsoccer.skills.setplay.WINGER_CUE`.

Carriers dribble by dead reckoning (their own kicks,
:meth:`~robotsoccer.skills.ball_tracker.BallTracker.detach`), as on the server; a winger uses
the camera while it collects. Looking with the neck (a
:class:`~robotsoccer.skills.team_look.NeckLook` given: the set play's ``look=neck``,
:mod:`robotsoccer.skills.setplay_look`), its percepts come with their directions from the body
and a waiting winger keeps the ball in view with its head, turning its body only where the head
cannot (:data:`~robotsoccer.skills.team_look.LOOK_COVER_RAD`); on the cue it faces the ball with
its body once before collecting. The shared skills are :mod:`robotsoccer.skills.setplay`'s;
angles are radians, left positive; distances metres.
"""

from __future__ import annotations

import math

from field_models.protocol import Action, Mind, Percept, Say, Turn
from robotsoccer.skills.ball_sense import BallSense
from robotsoccer.skills.ball_tracker import BallTracker
from robotsoccer.skills.pass_messages import announced_number
from robotsoccer.skills.passing import PasserMind
from robotsoccer.skills.setplay import (
    FACING_RAD,
    SEARCH_TURN_RAD,
    STAND,
    STILL_SHARE,
    WINGER_CALL,
    WINGER_CUE,
    KickPowers,
    approach,
    chase,
    face_ball,
    find_teammate,
    goal_bearing,
    heard_text,
    heard_tick,
    opponent_in_path,
    receive,
)
from robotsoccer.skills.team_look import LOOK_COVER_RAD, NeckLook

VIEW_HALF_ANGLE_RAD = math.radians(40.0)
"""A carrier turns so that its receivers lie within this of its heading: inside the Soccer
Server's 45° half view cone (§4), with a margin for their jitter and the quantised directions."""
LOOK_DECISIONS = 4
"""A carrier turns at most this many times looking for its receivers, then asks anyway."""


class CarrierMind:
    """Dribble toward the goal, stop the ball, look, then pass by the tree (module docstring).

    Args:
        passer: Layer 2's passer, to hand over to (its receivers are the two nearest). It is
            built without a kick power: this mind kicks the pass itself.
        interceptor: Layer 1's interception, for a winger collecting the ball; None: the
            player starts with the ball (at rest).
        sense: The field's ball and kick.
        attack_right: It attacks the goal at +x (``"g r"``).
        blocked_distance_m: An opponent this close in the path ends the dribble [m].
        powers: The field's kick powers.
        calls_after: The receivers of the pass before this player's (a winger calls from their
            announcement on); empty: it never calls.
        head: Its head, looking with the neck (module docstring); None: with its body.

    Attributes:
        phase: ``"wait"``, ``"collect"``, ``"dribble"``, ``"look"``, ``"pass"``, ``"deliver"``
            or ``"done"``.
        passed_tick: The tick of its pass kick, or None.
    """

    def __init__(
        self,
        passer: PasserMind,
        interceptor: Mind | None,
        *,
        sense: BallSense,
        attack_right: bool,
        blocked_distance_m: float,
        powers: KickPowers,
        calls_after: tuple[int, ...] = (),
        head: NeckLook | None = None,
    ) -> None:
        self.passer = passer
        self.head = head
        self.waiting_rad = FACING_RAD if head is None else LOOK_COVER_RAD
        self.interceptor = interceptor
        self.sense = sense
        self.reach_m = sense.reach_m
        self.attack_right = attack_right
        self.blocked_distance_m = blocked_distance_m
        self.powers = powers
        self.calls_after = calls_after
        self.phase = "dribble" if interceptor is None else "wait"
        self.passed_tick: int | None = None
        self.tracker = BallTracker(sense)
        if interceptor is None:
            self.tracker.detach()  # it starts with the ball: it dribbles
        self.heading = sense.heading()
        self._raw: Percept | None = None
        self.calling = False
        self.looks = 0
        self.done = False

    @property
    def raw(self) -> Percept:
        """The percept of the decision under way, as it came (for layer 1 and layer 2's minds)."""
        assert self._raw is not None, "act() first"
        return self._raw

    @property
    def seeking_goal(self) -> bool:
        """Never: a carrier looks for the goal with its body, the ball at its feet."""
        return False

    @property
    def pass_speed_mps(self) -> float:
        """The ball's speed as a pass leaves [m/s]."""
        return self.sense.speed(self.powers.passing)

    def act(self, percept: Percept) -> tuple[Action, ...]:
        """One decision (module docstring).

        Layer 1 and layer 2's minds get the percept as it came; this mind's own skills see it
        in its reckoned frame (:meth:`Heading.view`).
        """
        if not self.tracker.known and self.interceptor is None:
            self.tracker.rest(percept.tick)  # a set play starts with the ball at rest
        self._raw = percept
        view = self.heading.view(percept, self.tracker.observe(percept))
        view = self.tracker.project(view)
        self._see(view)
        actions = self._decide(view)
        self.tracker.note(actions, percept.tick)
        self.heading.note(actions, percept.tick)
        return actions

    def _see(self, percept: Percept) -> None:
        """Remember where the receivers and the goal were seen."""
        own = percept.player.team
        for seen in percept.players:
            if seen.team == own and seen.number in self.passer.receivers:
                self.heading.remember(f"mate{seen.number}", seen.angle_rad)

    def _decide(self, percept: Percept) -> tuple[Action, ...]:
        if self.phase == "wait":
            return self._wait(percept)
        if self.phase == "collect":
            if not self._in_reach(percept):
                assert self.interceptor is not None
                return receive(percept, self.raw, self.tracker, self.interceptor)
            self.phase = "dribble"
            self.tracker.detach()
        if self.phase == "dribble":
            return self._dribble(percept)
        if self.phase == "look":
            return self._look(percept)
        if self.phase == "pass":
            return self._pass(percept)
        if self.phase == "deliver":
            return self._deliver(percept)
        return ()

    def _wait(self, percept: Percept) -> tuple[Action, ...]:
        """A winger: face the ball, call from the first pass on, wake on the cue."""
        if heard_text(percept, WINGER_CUE):
            kick_tick = heard_tick(percept, (WINGER_CUE,))
            self.tracker.launched(percept, self.pass_speed_mps, kick_tick)
            self.phase = "collect"
            self.calling = False
            if self.head is not None:
                # Its body may stand well off the ball (the neck kept it): face it once, as
                # layer 1 learned to start (pass_receivers' module docstring).
                turn = face_ball(percept)
                if turn != STAND:
                    return turn
            return self._decide(percept)
        for heard in percept.heard:
            if announced_number(heard.text) in self.calls_after:
                self.calling = True
        actions = face_ball(percept, self.waiting_rad)
        return (*actions, Say(WINGER_CALL)) if self.calling else actions

    def _in_reach(self, percept: Percept) -> bool:
        ball = percept.ball
        return ball is not None and ball.distance_m <= self.reach_m

    def _dribble(self, percept: Percept) -> tuple[Action, ...]:
        goal = goal_bearing(percept, self.attack_right)
        if not self._in_reach(percept):
            return approach(percept, self.reach_m, self.sense.approach_power)
        if goal is None:
            return self._hold(percept, (Turn(SEARCH_TURN_RAD),))  # look for the goal
        direction = goal[1]
        if opponent_in_path(percept, direction, self.blocked_distance_m):
            self.phase = "look"  # §7: it stops dribbling and considers its options
            return self._hold(percept, ())
        kick, _ = self.tracker.aim(percept, self.sense.speed(self.powers.dribble), direction)
        return self._follow(percept) if kick is None else (kick,)

    def _follow(self, percept: Percept) -> tuple[Action, ...]:
        """The ball rolls as wanted: keep up with it at its pace."""
        vx, vy = self.tracker.velocity(percept)
        power = 100.0 * min(1.0, math.hypot(vx, vy) / self.sense.top_speed_mps)
        return chase(percept, dash=power)

    def _hold(self, percept: Percept, then: tuple[Action, ...]) -> tuple[Action, ...]:
        """Stand, stop the ball (a kick against its motion) if it rolls, then `then`."""
        kick = self.tracker.stop(percept, STILL_SHARE * self.pass_speed_mps)
        then = then or STAND
        return then if kick is None else (kick, *then)

    def _look(self, percept: Percept) -> tuple[Action, ...]:
        """Turn until both receivers are in view (or give up looking), then ask."""
        if not self._in_reach(percept):
            return approach(percept, self.reach_m, self.sense.approach_power)
        turn = self._turn_to_receivers(percept)
        if turn is None or self.looks >= LOOK_DECISIONS:
            self.phase = "pass"
            return self._pass(percept)
        self.looks += 1
        return self._hold(percept, (Turn(turn),))

    def _turn_to_receivers(self, percept: Percept) -> float | None:
        """The turn that brings every receiver into view; None when they are in view now."""
        bearings = [self.heading.relative(f"mate{n}") for n in self.passer.receivers]
        seen = {s.number for s in percept.players if s.team == percept.player.team}
        if all(n in seen for n in self.passer.receivers) and all(
            b is not None and abs(b) <= VIEW_HALF_ANGLE_RAD for b in bearings
        ):
            return None
        known = [b for b in bearings if b is not None]
        if len(known) < len(bearings):
            return SEARCH_TURN_RAD if not known else known[0]
        mid = math.atan2(sum(math.sin(b) for b in known), sum(math.cos(b) for b in known))
        return None if abs(mid) < math.radians(2.0) else mid

    def _pass(self, percept: Percept) -> tuple[Action, ...]:
        """Layer 2's exchange beside the ball; then the pass, kicked here (compensated)."""
        actions = self.passer.act(self.raw)
        if self.passer.chosen is None:
            if not self._in_reach(percept):
                return actions + approach(percept, self.reach_m, self.sense.approach_power)
            return actions + self._hold(percept, ())
        self.phase = "deliver"
        direction = self.passer.pass_direction_rad or 0.0
        self.heading.remember("target", direction)
        return actions + self._deliver(percept)

    def _deliver(self, percept: Percept) -> tuple[Action, ...]:
        """Kick the pass once the ball is in reach, toward the receiver as seen or remembered."""
        chosen = self.passer.chosen
        if not self._in_reach(percept) or chosen is None:
            return approach(percept, self.reach_m, self.sense.approach_power)
        target = find_teammate(percept, chosen)
        direction = target.angle_rad if target is not None else self.heading.relative("target")
        kick, passed = self.tracker.aim(percept, self.pass_speed_mps, direction or 0.0)
        if passed:
            self.passed_tick = percept.tick
            self.phase = "done"
            self.done = True
        return () if kick is None else (kick,)
