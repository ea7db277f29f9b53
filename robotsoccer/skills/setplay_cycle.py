"""The set play's attackers on a client that acts every cycle (issue 28 item 3).

The set play's minds (:class:`~robotsoccer.skills.setplay_carrier.CarrierMind`,
:class:`~robotsoccer.skills.setplay_receiver.SetPlayReceiverMind`) decide at each see, as the
paper's client does: "turn, then dash", one or two body commands. The server runs one body
command per cycle and a new decision replaces what is left of the last
(:mod:`field_models.soccer_server.arena`), so a player that runs dashes on one cycle between two
sees, and an empty decision drops a dash still queued. :class:`CycleAttacker` is the same mind
on a client that sends a command every cycle until the next see, as the match's per-cycle team
minds do (:mod:`robotsoccer.skills.team_cycle`):

* **World model.** Layer 1's per-cycle defender (:class:`~robotsoccer.skills.cycle.
  CycleDefenderMind`), fed every see (:meth:`~robotsoccer.skills.cycle.CycleDefenderMind.
  observe`): its own heading and velocity by dead reckoning from the commands the server carried
  out (:mod:`robotsoccer.skills.reckoning`), the ball's model fitted to its sightings.
* **The decision** is the set-play mind's, unchanged, at each see. Its own heading reckoning
  (:class:`~robotsoccer.skills.ball_sense.Heading`, :class:`~robotsoccer.skills.motion.
  TurnsInFlight`) stays: it notes the turns of the decision it returns, and the turns of the
  plan it did not return (layer 1's, below) are noted for it when they have run, at the cycle
  they were sent for, before its next decision.
* **Meeting a ball with layer 1.** Where the mind asks layer 1 (a receiver meeting its pass, the
  winger collecting), it asks :class:`CycleIntercept`: the world model's own plan
  (:meth:`~robotsoccer.skills.cycle.CycleDefenderMind.decide`, with the drill's TA rule): a
  command every cycle toward the ball's current bearing + TA, turning only where it is worth a
  cycle. The mind gets the plan's first command (what it would have sent); the client sends
  the whole plan.
* **A run goes on.** A decision whose last body command is a dash (the chase or the gentle
  approach toward the ball) repeats that dash every cycle until the next see while the run,
  reckoned by the server's equations, with what the body would still coast after it, stays
  short of the ball's distance at the see less the kick reach: the run comes up to where the
  ball was seen and never into it (the set play's approach must not knock the ball away).
  Kicks, turns and stands are sent as they are.
* **No dash dropped.** A decision with no body command (the mind waits, holds, or is done)
  keeps what is left of the plan instead of an empty one.

Plans run to the next expected see plus :data:`~robotsoccer.skills.team_cycle.
PLAN_EXTRA_CYCLES`. It is a Soccer Server client: the robots' host already acts on every tick
(:mod:`field_models.robot_physics.host`), and the drill refuses it there.

**The neck** (the set play's ``look=neck``): :class:`~robotsoccer.skills.setplay_look.
NeckAttacker` wraps this client, gives it percepts with their directions from the body and adds
the head's neck turn and view to its decision; a wide view (the head scanning) makes sees come
less often, so the plans then run to the next see of that view (:attr:`CycleAttacker.
view_share`). With ``look=body`` the head is the body, as in the paper's client.
"""

from __future__ import annotations

import math
from typing import Protocol

from field_models.arena import FieldFacts
from field_models.protocol import Action, Dash, Percept, Turn
from robotsoccer.skills.ball_sense import Heading
from robotsoccer.skills.ball_tracker import BallTracker
from robotsoccer.skills.cycle import CycleDefenderMind, Sighting
from robotsoccer.skills.intercept import DASH_POWER
from robotsoccer.skills.team_cycle import NOT_BODY, PLAN_EXTRA_CYCLES


class SetPlayMind(Protocol):
    """What :class:`CycleAttacker` needs of a set-play mind (carrier or receiver)."""

    heading: Heading
    tracker: BallTracker
    reach_m: float

    @property
    def done(self) -> bool:
        """It needs no more percepts."""
        ...

    def act(self, percept: Percept) -> tuple[Action, ...]:
        """One decision at a see."""
        ...


class CycleIntercept:
    """Layer 1's interception of a set-play attacker on the per-cycle client (module docstring).

    The mind's interceptor: it returns the first command of the world model's plan and keeps
    the plan for :class:`CycleAttacker`, which sets :attr:`sighting` before each decision.

    Args:
        model: The attacker's world model, with the drill's TA rule and trigger distance.

    Attributes:
        sighting: The ball at this see (None: not seen), set by the client.
        plan: The plan of the last call.
        tick: The tick of the last call (-1: none at this see).
    """

    def __init__(self, model: CycleDefenderMind) -> None:
        self.model = model
        self.sighting: Sighting | None = None
        self.plan: tuple[Action, ...] = ()
        self.tick = -1

    def act(self, percept: Percept) -> tuple[Action, ...]:
        """The plan's first command (the one cycle the see-triggered mind would account for)."""
        model = self.model
        if self.sighting is None or percept.ball is None:
            # A ball not seen: run on once triggered, as the per-cycle defender does.
            plan: tuple[Action, ...] = (
                (Dash(DASH_POWER),) * model.plan_cycles if model.triggered else ()
            )
        else:
            plan = model.decide(percept.body_relative(), self.sighting)
        self.plan, self.tick = plan, percept.tick
        return plan[:1]


class CycleAttacker:
    """A set-play attacker on a client that acts every cycle (module docstring).

    Args:
        mind: The set-play mind (its interceptor, if any, is `meet`).
        model: Its world model (layer 1's per-cycle defender; with no TA rule for the starter,
            which never meets a ball with layer 1).
        meet: Its layer 1, the world model's plan; None: it has none (the starter).
        facts: The field's facts (the server's body equations and see interval).

    Attributes:
        commands_added: Body commands sent beyond the mind's own decisions (runs continued,
            layer 1's plans, plans kept through an empty decision).
        view_share: The next see's interval as a share of the normal view's (set by a head
            that widens its view: :data:`~robotsoccer.skills.team_cycle.VIEW_PERIOD_SHARE`).
    """

    def __init__(
        self,
        mind: SetPlayMind,
        model: CycleDefenderMind,
        meet: CycleIntercept | None,
        facts: FieldFacts,
    ) -> None:
        self.mind = mind
        self.model = model
        self.meet = meet
        self._reckoner = model.reckoner  # the world model's equations
        self._see_cycles = facts.sensor_period_s / facts.dt_s
        self.view_share = 1.0
        self._plan: tuple[Action, ...] = ()
        self._plan_tick = -1
        self._noted = 0  # leading commands of the plan whose turns the mind noted itself
        self.commands_added = 0

    @property
    def done(self) -> bool:
        """The mind's ``done``."""
        return bool(self.mind.done)

    @property
    def plan_cycles(self) -> int:
        """Cycles a plan runs: to the next see of the view, and ``PLAN_EXTRA_CYCLES``."""
        return math.ceil(self._see_cycles * self.view_share - 1e-9) + PLAN_EXTRA_CYCLES

    def act(self, percept: Percept) -> tuple[Action, ...]:
        """The mind's decision at this see, carried on every cycle until the next."""
        tick = percept.tick
        elapsed = tick - self._plan_tick if self._plan_tick >= 0 else 0
        self._note_run(elapsed)
        left = self._plan[elapsed:]
        from_body = percept.body_relative()
        self.model.plan_cycles = self.plan_cycles  # layer 1's plans too run to the next see
        sighting = self.model.observe(from_body)
        meet = self.meet
        if meet is not None:
            meet.sighting = sighting
        actions = self.mind.act(percept)
        others = tuple(a for a in actions if isinstance(a, NOT_BODY))
        body = tuple(a for a in actions if not isinstance(a, NOT_BODY))
        if meet is not None and meet.tick == tick and meet.plan and body == meet.plan[:1]:
            planned, noted = meet.plan, 1  # layer 1's plan: a command every cycle already
        elif body:
            planned, noted = self.continued(from_body, body), len(body)
        else:
            planned, noted = left, max(self._noted - elapsed, 0)  # an empty one drops nothing
        self.commands_added += max(len(planned) - len(body), 0)
        self.model.sent(tick, planned)
        self._plan, self._plan_tick, self._noted = planned, tick, noted
        return others + planned

    def continued(self, percept: Percept, body: tuple[Action, ...]) -> tuple[Action, ...]:
        """`body`, its last dash repeated while the run stays short of the ball (docstring).

        `percept` is body-relative; the run is reckoned from the world model's pose at it.
        """
        last = body[-1]
        ball = percept.ball
        if ball is None or not isinstance(last, Dash) or last.power <= 0.0:
            return body
        if last.direction_rad != 0.0:
            return body
        short = ball.distance_m - self.mind.reach_m
        return self._reckoner.run_on(
            self.model.body, body, last, short, self.plan_cycles, coast=True
        )

    def _note_run(self, elapsed: int) -> None:
        """Note for the mind the turns of the last plan it did not note that have now run.

        The server ran the plan's first `elapsed` commands, one per cycle: command k as if sent
        at the plan's tick + k.
        """
        mind = self.mind
        for k in range(self._noted, min(elapsed, len(self._plan))):
            action = self._plan[k]
            if isinstance(action, Turn):
                mind.heading.note((action,), self._plan_tick + k)
                mind.tracker.note((action,), self._plan_tick + k)
