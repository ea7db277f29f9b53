"""Team minds on a client that acts every cycle (issue 28 item 3).

The paper's client (:class:`~robotsoccer.skills.team.TeamMind`) decides at each see and sends
one or two body commands ("turn, then dash"); the server runs one body command per cycle, and
a new decision replaces what is left of the last (:mod:`field_models.soccer_server.arena`).
Sees come every 2 cycles (``rcssserver_19``) or 2.5 (``soccer_server_1996``), so a player that
decides "dash" runs on one cycle of two or three, and one whose decision is held (the turn
holds of :mod:`robotsoccer.skills.team`) sends an empty decision that drops the dash still
queued (README, "Team minds on the per-cycle client", measures what this costs).

:class:`CycleTeamMind` is the same mind on a client that sends a command every cycle from a
world model kept between sees, as clients for today's server do (CMUnited-98 onward):

* **World model.** Layer 1's per-cycle defender's (:class:`~robotsoccer.skills.cycle.
  CycleDefenderMind`, fed every see): its own heading and velocity by dead reckoning from the
  commands the server carried out (:mod:`robotsoccer.skills.reckoning`; the commands run
  between two sees are the first ones of the plan sent at the earlier see, one per cycle), and
  the ball's model fitted to its sightings.
* **The decision** is the team mind's, unchanged, at each see: who chases, where home is, what
  to do on the ball, the neck and view.
* **Meeting a ball.** Where the team mind would ask layer 1 — the chaser's ball comes at it from
  within the trigger distance, beyond the near zone (:mod:`robotsoccer.skills.team_chase`) —
  the body's plan is the per-cycle defender's: TA chosen at the first such see by the team's
  rule (the layered team's net; the baseline's straight, TA = 0), then a command every cycle
  toward the ball's current bearing + TA, turning only where it is worth a cycle, with the
  meeting rule (:mod:`robotsoccer.skills.cycle`). Both teams meet so, as the drill's
  ``straight`` and ``net`` both run on the per-cycle client.
* **Every cycle until the next see** (the see interval of its current view, plus
  :data:`PLAN_EXTRA_CYCLES` in case a see comes late): a decision that runs (its last body
  command a dash) toward a point it knows — the ball it chases or intercepts
  (``intent`` ``chase``/``intercept``: the ball's distance less the kick reach) or its home
  (``home``) — goes on dashing at the same power while the reckoned run stays short of the
  point (for home, with what the body would still coast after it: home is a point to stop at).
  A chase that only turns (near the ball the team mind turns before it runs, so as not to
  circle it) dashes at full power once the reckoned turn leaves it facing the ball. Decisions
  on the ball (kicks), turns at home, searches and standing are sent as they are.
* **No dash dropped by a hold.** While the team mind holds a turn (its percept predates the
  turn), the body keeps the plan it has instead of an empty one.

The commands are the same vocabulary as the see-triggered client's; the neck and view actions
go beside the first body command. It is a Soccer Server client: the robots' host already acts
on every tick from the last command (:mod:`field_models.robot_physics.host`).
"""

from __future__ import annotations

import math

from field_models.arena import FieldFacts
from field_models.protocol import Action, ChangeView, Dash, Percept, Say, Turn, TurnNeck, wrap_angle
from robotsoccer.skills.cycle import CycleDefenderMind, Sighting
from robotsoccer.skills.intercept import TurnPolicy
from robotsoccer.skills.lead import LeadPolicy
from robotsoccer.skills.passing import PassEvaluator
from robotsoccer.skills.reckoning import FULL_POWER
from robotsoccer.skills.team import TeamMind
from robotsoccer.skills.team_setup import (
    COMING_SHARE,
    FACING_RAD,
    NEAR_REACHES,
    BallPolicy,
    TeamSetup,
)
from robotsoccer.skills.turn_policies import straight_policy

CLIENT_MODES = ("see", "cycle")
"""A match's clients: the paper's see-triggered :class:`TeamMind`, or :class:`CycleTeamMind`."""

PLAN_EXTRA_CYCLES = 1
"""Cycles planned past the next expected see (a see may come a cycle late)."""

VIEW_PERIOD_SHARE = {"narrow": 0.5, "normal": 1.0, "wide": 2.0}
"""A view width's see interval as a share of the normal one (spec §3.1)."""

RUN_INTENTS = ("chase", "intercept", "home")
"""The decisions that run toward a point the mind knows, and so go on running between sees."""

NOT_BODY = (Say, TurnNeck, ChangeView)
"""Actions that are not body commands: they go out at once, beside the cycle's body command."""


class CycleTeamMind(TeamMind):
    """A team mind on a per-cycle client (module docstring).

    Args:
        number: Its uniform number.
        setup: Its team's plan.
        facts: The field's facts (the server's body equations and see interval).
        interception, lead, evaluator, pass_threshold, ball_policy: As
            :class:`~robotsoccer.skills.team.TeamMind`'s.

    Attributes:
        commands_added: Body commands it added to its team mind's decisions (runs continued
            between sees and plans kept through a hold).
    """

    def __init__(
        self,
        number: int,
        setup: TeamSetup,
        *,
        facts: FieldFacts,
        interception: TurnPolicy | None = None,
        lead: LeadPolicy | None = None,
        evaluator: PassEvaluator | None = None,
        pass_threshold: float = 0.5,
        ball_policy: BallPolicy | None = None,
    ) -> None:
        super().__init__(
            number,
            setup,
            interception=interception,
            lead=lead,
            evaluator=evaluator,
            pass_threshold=pass_threshold,
            ball_policy=ball_policy,
        )
        self._see_cycles = facts.sensor_period_s / facts.dt_s
        # Layer 1's per-cycle defender: the world model (own body, the ball's model) and, for a
        # ball coming at the chaser, its plan with the team's TA rule (straight: TA = 0).
        self._meeting = CycleDefenderMind(
            interception or straight_policy, facts, setup.trigger_distance_m
        )
        self._reckoner = self._meeting.reckoner
        self._plan: tuple[Action, ...] = ()
        self._plan_tick = -1
        self.commands_added = 0

    def act(self, percept: Percept) -> tuple[Action, ...]:
        """The team mind's decision at this see, carried on every cycle until the next."""
        tick = percept.tick
        left = self._plan[tick - self._plan_tick :] if self._plan_tick >= 0 else ()
        from_body = percept.body_relative()
        sighting = self._meeting.observe(from_body)
        previous = self._previous_bd
        holding = self.setup.turn_latency == "hold" and self.turns.holding(percept.observed_tick)
        actions = super().act(percept)
        others = tuple(a for a in actions if isinstance(a, NOT_BODY))
        body: tuple[Action, ...] = tuple(a for a in actions if not isinstance(a, NOT_BODY))
        if not body and holding:
            planned = left  # the held turn's plan goes on (an empty decision would drop it)
        elif sighting is not None and self._meets_coming(sighting, previous):
            self.intent = "intercept"
            planned = self._meeting.decide(from_body, sighting)
        else:
            self._meeting.triggered = False  # the next ball met chooses its TA afresh
            planned = self._continued(percept, body)
        self.commands_added += max(len(planned) - len(body), 0)
        self._meeting.sent(tick, planned)
        self._plan, self._plan_tick = planned, tick
        return others + planned

    def _meets_coming(self, sighting: Sighting, previous_m: float | None) -> bool:
        """The chaser's ball comes at it from within the trigger distance, beyond the near zone.

        The team mind's own condition for asking layer 1 (:mod:`robotsoccer.skills.team_chase`),
        here for both teams: the layered team's TA is its net's, the baseline's 0.
        """
        if self.intent not in ("chase", "intercept") or previous_m is None:
            return False
        bd, reach = sighting.distance_m, self.setup.reach_m
        coming = previous_m - bd > COMING_SHARE * reach
        return coming and NEAR_REACHES * reach < bd <= self.setup.trigger_distance_m

    def _continued(self, percept: Percept, body: tuple[Action, ...]) -> tuple[Action, ...]:
        """`body`, run on every cycle while the run stays short of its point (docstring).

        A run's last dash is repeated; a chase that only turns (near the ball, so as not to
        circle it) dashes at full power once the reckoned turn leaves it facing the ball.
        """
        if not body or self.intent not in RUN_INTENTS:
            return body
        last = body[-1]
        if isinstance(last, Dash) and last.power != 0.0:
            dash = last
        elif isinstance(last, Turn) and self.intent != "home":
            dash = Dash(FULL_POWER)
        else:
            return body
        distance = self._run_distance(percept)
        if distance is None:
            return body
        reckoner = self._reckoner
        start = self._meeting.body
        if isinstance(last, Turn):
            turned = start
            for action in body:
                turned = reckoner.cycle(turned, action)
            missed = wrap_angle(last.angle_rad - wrap_angle(turned[0] - start[0]))
            if abs(missed) > FACING_RAD:
                return body
        # Home is a point to stop at, so the run allows for the coast; a chased ball is run
        # up to, as the see-triggered client dashes at it at every see.
        stops = self.intent == "home"
        return reckoner.run_on(start, body, dash, distance, self._plan_cycles(), coast=stops)

    def _run_distance(self, percept: Percept) -> float | None:
        """How far the decision runs before it should stop [m], or None (not a run)."""
        if self.intent not in RUN_INTENTS:
            return None
        if self.intent == "home":
            pose = self.localiser.pose
            if pose is None:
                return None
            tx, ty = self._home_target()
            return math.hypot(tx - pose.x, ty - pose.y)
        ball = percept.ball
        if ball is None:
            return None
        return ball.distance_m - self.setup.reach_m

    def _plan_cycles(self) -> int:
        """The cycles until the next see of the current view, and :data:`PLAN_EXTRA_CYCLES`."""
        share = VIEW_PERIOD_SHARE.get(self.head.view, 1.0)
        return math.ceil(self._see_cycles * share - 1e-9) + PLAN_EXTRA_CYCLES
