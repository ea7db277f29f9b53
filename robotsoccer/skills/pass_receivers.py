"""Layer 2's receivers and waiting defenders as client minds (paper §6, Figures 10, 12, 13).

:class:`ReceiverMind` faces the ball once it hears the passer's intention, says its report in
its own slot (:data:`REPORT_SLOT_PERIODS` apart, module :mod:`robotsoccer.skills.passing`'s
step 2), and from the announcement on intercepts with layer 1 if it is the one chosen, else
stands still. :class:`WaitingInterceptorMind` is a defender that faces the ball until the
announcement and then intercepts. Angles in radians; distances in metres (in units inside the
reports).

**Looking with the neck** (a :class:`~robotsoccer.skills.team_look.NeckLook` given: the set
play's ``look=neck``). The receiver reads its percepts with their directions from the body and
keeps the ball in view with its head: its body turns only toward a ball the head cannot point
at (beyond :data:`~robotsoccer.skills.team_look.NECK_MAX_RAD`; the report needs the head to
face the ball, so the view's margin, ``LOOK_COVER_RAD``, does not do here). It reports once its
*head* faces the ball, with the directions measured from the head, so that its report reads as
one from a receiver facing the ball, the view layer 2's tree learned from. Chosen, it turns its
body to the ball once before layer 1 takes over (:meth:`ReceiverMind._face_once`): layer 1
learned from a defender that faces the ball as it starts (measured: without that turn the set
play's first pass failed more often: README, "The set play looking with the neck").
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from field_models.protocol import Action, Mind, Percept, Say, SeenPlayer, Turn, wrap_angle
from learning.pass_codec import MAX_DISTANCE, encode_view
from robotsoccer.skills.pass_messages import INTENT, announced_number, report_text
from robotsoccer.skills.passing import view_arrays
from robotsoccer.skills.team_look import NECK_MAX_RAD, NeckLook, head_relative

REPORT_SLOT_PERIODS = 2.0
"""Sensor periods between two receivers' report slots (step 2 of the conversation in
:mod:`robotsoccer.skills.passing`)."""
FACING_TOLERANCE_RAD = math.radians(10.0)
"""A player "faces the ball" when the ball is within this of its heading."""


class ReceiverMind:
    """A receiver (module docstring): face the ball, report, then intercept or stand.

    Args:
        number: Its uniform number.
        interceptor: Layer 1's interception, used once it is the chosen receiver.
        unit_m: The field's unit [m].
        sensor_period_s: Time between two percepts [s].
        dt_s: One tick [s].
        slot: Its report slot (0, 1, 2, ...).
        say_max_chars: The field's say limit; None: no limit.
        head: Its head, looking with the neck (module docstring): percepts come with their
            directions from the body, the head's neck angle noted; None: it looks with its
            body (percepts from the body, which is the head).
    """

    def __init__(
        self,
        number: int,
        interceptor: Mind,
        *,
        unit_m: float,
        sensor_period_s: float,
        dt_s: float,
        slot: int,
        say_max_chars: int | None,
        head: NeckLook | None = None,
    ) -> None:
        self.number = number
        self.head = head
        self._faced = False
        self.interceptor = interceptor
        self.unit_m = unit_m
        self.slot_ticks = round(slot * REPORT_SLOT_PERIODS * sensor_period_s / dt_s)
        self.say_max_chars = say_max_chars
        self.intent_tick: int | None = None
        self.reported = False
        self.chosen: bool | None = None  # None until the announcement
        self.done = False

    def act(self, percept: Percept) -> tuple[Action, ...]:
        """Before the announcement: face the ball and report; then intercept or stand."""
        for heard in percept.heard:
            if heard.text == INTENT and self.intent_tick is None:
                self.intent_tick = percept.tick
            number = announced_number(heard.text)
            if number is not None and self.chosen is None:
                self.chosen = number == self.number
        if self.chosen is not None:
            if self.chosen:
                return self._face_once(percept) or self.interceptor.act(percept)
            self.done = True  # stands still from now on: it needs no more percepts
            return ()
        if self.head is not None:
            # The neck keeps the ball in view; the body turns only where the head cannot point.
            ball = percept.ball
            if ball is None:
                return ()  # the head scans for it
            if abs(ball.angle_rad) > NECK_MAX_RAD:
                return (Turn(ball.angle_rad),)
            percept = head_relative(percept, self.head.neck_rad)
        ball = percept.ball
        if ball is None:
            return (Turn(math.pi / 2),)  # look for it
        if abs(ball.angle_rad) > FACING_TOLERANCE_RAD:
            if self.head is not None:
                return ()  # the neck turns to the ball: report at a see that shows it ahead
            return (Turn(ball.angle_rad),)
        if (
            self.intent_tick is not None
            and not self.reported
            and percept.tick - self.intent_tick >= self.slot_ticks
        ):
            text = self._report(percept)
            if text is not None:
                self.reported = True
                return (Say(text),)
        return ()

    def _face_once(self, percept: Percept) -> tuple[Action, ...]:
        """Looking with the neck, at its first decision as the one chosen: face the ball.

        Layer 1 learned from a defender facing the ball as it starts (the interception drill,
        §5), and a receiver that kept the ball in view with its neck may stand well off it: it
        turns its body to the ball once, then intercepts. Empty: no turn (facing it, or looking
        with its body, or done already).
        """
        if self.head is None or self._faced:
            return ()
        self._faced = True
        ball = percept.ball
        if ball is None or abs(ball.angle_rad) <= FACING_TOLERANCE_RAD:
            return ()
        return (Turn(ball.angle_rad),)

    def _report(self, percept: Percept) -> str | None:
        """Its report; None when it cannot see the passer (next to the ball)."""
        ball = percept.ball
        assert ball is not None
        own = percept.player.team
        passer = _nearest_to(percept.players, ball.distance_m, ball.angle_rad, own)
        if passer is None:
            return None
        # A player beyond what the message can carry is left out (the set play's defenders that
        # lost the ball run on: layer 1's rule); every pass's players are far nearer.
        farthest_m = MAX_DISTANCE * self.unit_m
        others = [
            s for i, s in enumerate(percept.players) if i != passer and s.distance_m <= farthest_m
        ]
        p = percept.players[passer]
        pd, pa = p.distance_m / self.unit_m, math.degrees(p.angle_rad)
        dist, ang, team = view_arrays(others, own, self.unit_m)
        full = report_text(self.number, encode_view(pd, pa, dist, ang, team), pd)
        if self.say_max_chars is None or len(full) <= self.say_max_chars:
            return full
        short = report_text(self.number, None, pd)
        return short if len(short) <= self.say_max_chars else None


def _nearest_to(
    seen: Sequence[SeenPlayer], distance_m: float, angle_rad: float, team: str
) -> int | None:
    """The seen teammate (or player of unknown team) closest to a point given in polar form."""
    best, best_gap = None, math.inf
    for i, s in enumerate(seen):
        if s.team not in (team, None):
            continue
        gap = (
            distance_m**2
            + s.distance_m**2
            - 2.0 * distance_m * s.distance_m * math.cos(s.angle_rad - angle_rad)
        )
        if gap < best_gap:
            best, best_gap = i, gap
    return best


class WaitingInterceptorMind:
    """A defender: faces the ball until the passer announces, then intercepts (Figure 13).

    Args:
        interceptor: Layer 1's interception.
        still: Stand still after the announcement too (Table 2's "no defenders" test).
    """

    def __init__(self, interceptor: Mind, *, still: bool = False) -> None:
        self.interceptor = interceptor
        self.still = still
        self.started = False
        self.done = False

    def act(self, percept: Percept) -> tuple[Action, ...]:
        """Face the ball; from the announcement on, intercept."""
        if not self.started:
            self.started = any(announced_number(h.text) is not None for h in percept.heard)
        if self.started:
            if self.still:
                self.done = True
                return ()
            return self.interceptor.act(percept)
        ball = percept.ball
        if ball is not None and abs(ball.angle_rad) > FACING_TOLERANCE_RAD:
            return (Turn(wrap_angle(ball.angle_rad)),)
        return ()
