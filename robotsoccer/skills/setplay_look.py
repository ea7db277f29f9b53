"""The set play's attackers looking with the neck (issue 28 item 3; option ``look=neck``).

On the Soccer Server a player sees along body + neck (:mod:`robotsoccer.skills.team_look`).
The paper's client never turns its neck, so the set play's minds read a percept's directions as
from the body and turn the body to look: a receiver waiting for the pass turns its body to
every move of the ball. With ``look=neck`` every attacker (starter, first receivers, winger,
last receivers; both clients) is a :class:`NeckAttacker`, which:

* gives the mind its percept with the directions measured from the body
  (:meth:`~robotsoccer.skills.team_look.NeckLook.sensed`), so the mind's turns, kicks and
  dashes mean what they did;
* points the head (:meth:`~robotsoccer.skills.team_look.NeckLook.look`, the match's head) at
  the ball while it is seen or was seen within
  :data:`~robotsoccer.skills.team_look.LOOK_MEMORY_TICKS` (its bearing then, less the body's
  turns since), and scans with a wide view when it is not; a ball within kick reach is seen
  all round (the server's ``visible_distance``, 3 m, is beyond the kick reach), so then the
  head looks where the body faces: a carrier looking for its receivers or the goal, or a
  receiver kicking on, sees what its body faces, as its mind expects; a last receiver looking
  for the goal (:attr:`~robotsoccer.skills.setplay_receiver.SetPlayReceiverMind.seeking_goal`)
  scans;
* on the per-cycle client (:class:`~robotsoccer.skills.setplay_cycle.CycleAttacker`), sets
  the plans' length to the next see of the view it asks for.

The minds' own rules for this mode (a waiting receiver reports once its head faces the ball and
keeps it in view without turning its body) are in :mod:`robotsoccer.skills.pass_receivers`,
:mod:`robotsoccer.skills.setplay_receiver` and :mod:`robotsoccer.skills.setplay_carrier`.
Defenders and the goalie keep layer 1's drill minds.
"""

from __future__ import annotations

from typing import Protocol

from field_models.protocol import Action, Percept, Turn, wrap_angle
from robotsoccer.skills.setplay_cycle import CycleAttacker
from robotsoccer.skills.team_cycle import NOT_BODY, VIEW_PERIOD_SHARE
from robotsoccer.skills.team_look import LOOK_MEMORY_TICKS, NeckLook


class LookingMind(Protocol):
    """What :class:`NeckAttacker` needs of a set-play mind (carrier or receiver)."""

    reach_m: float

    @property
    def done(self) -> bool:
        """It needs no more percepts."""
        ...

    @property
    def seeking_goal(self) -> bool:
        """It looks for the goal with its head (the head scans)."""
        ...

    def act(self, percept: Percept) -> tuple[Action, ...]:
        """One decision at a see."""
        ...


class NeckAttacker:
    """A set-play attacker that looks with its neck (module docstring).

    Args:
        mind: The set-play mind (built with `head`).
        head: Its head, shared with the mind (which reads its neck angle).
        client: The per-cycle client carrying `mind`'s decisions; None: the see-triggered
            client (the mind acts itself).
    """

    def __init__(
        self, mind: LookingMind, head: NeckLook, client: CycleAttacker | None = None
    ) -> None:
        self.mind = mind
        self.head = head
        self.client = client
        self._ball: tuple[int, float] | None = None  # (tick, bearing from the body) last seen

    @property
    def done(self) -> bool:
        """The mind's ``done``."""
        return bool(self.mind.done)

    def act(self, percept: Percept) -> tuple[Action, ...]:
        """The mind's decision on the body-relative percept, and the head's look."""
        percept = self.head.sensed(percept)
        target = self.target(percept)
        if self.client is not None:
            self.client.view_share = VIEW_PERIOD_SHARE["wide" if target is None else "normal"]
            actions = self.client.act(percept)
        else:
            actions = self.mind.act(percept)
        # Body commands first: the head allows for the first one's turn (the same cycle's);
        # the server sends says, neck turns and views at once whatever their place.
        body = tuple(a for a in actions if not isinstance(a, NOT_BODY))
        actions = body + tuple(a for a in actions if isinstance(a, NOT_BODY))
        if self._ball is not None and body and isinstance(body[0], Turn):
            # The remembered bearing, from the body after this decision's turn.
            tick, bearing = self._ball
            self._ball = (tick, wrap_angle(bearing - body[0].angle_rad))
        return self.head.look(actions, target)

    def target(self, percept: Percept) -> float | None:
        """Where the head looks, from the body [rad]; None: scan (module docstring).

        `percept` is body-relative. A ball seen is remembered for later percepts.
        """
        if self.mind.seeking_goal:
            return None
        ball = percept.ball
        if ball is not None:
            self._ball = (percept.tick, ball.angle_rad)
            return 0.0 if ball.distance_m <= self.mind.reach_m else ball.angle_rad
        if self._ball is None or percept.tick - self._ball[0] > LOOK_MEMORY_TICKS:
            return None
        return self._ball[1]
