"""The central host's actuation: a mind's actions become primitives on the link, in time.

The half of :class:`~field_models.robot_physics.host.CentralHost` that speaks to the robots
(:class:`HostActuation`, its mixin); the other half builds the percepts
(:mod:`field_models.robot_physics.host`).

**Actions to primitives.** :meth:`HostActuation.submit` takes a mind's actions (the Soccer Server
vocabulary, `field_models.protocol`) and sends one primitive for the first body action (Turn,
Dash or Kick) at once. Let v_max be the top wheel speed, T one camera period, ω_max =
2·v_max/track the top spin rate, and α = 2·a/track the spin acceleration the wheel ramp a allows:

* ``Dash(p)``: FORWARD (p > 0) or BACKWARD (p < 0) at |p|/100 · v_max (p clipped to ±100), held
  for 2·T, so one lost packet does not stall the robot while the next frame's command replaces it
  in time. ``Dash(0)``: STOP. A robot cannot run sideways, so ``Dash(p, d)`` with a direction d
  (wrapped) turns first: the Turn(d) below, then the straight dash; for |d| > 90° it turns by
  d - 180° and drives backwards, whichever needs the smaller turn. (The Soccer Server's side
  and back dash rates do not apply: the robot runs at full power once turned.)
* ``Turn(a)`` (a wrapped to [-π, π)): TURN at ω = min(|a|/T, ω_max, √(α·|a|)) toward a, for
  D = ⌈|a|/(ω·dt)⌉ ticks, with ω then set to |a|/(D·dt) so that ω·D·dt = |a| exactly. The √(α·|a|)
  cap lets the wheel ramp reach ω within D; the ramp's lag at the start is then repaid by its
  run-down at the end, so a turn from rest rotates the robot by a (up to the world's grip and
  discretisation). ``Turn(0)``: STOP.
* ``Turn(a)`` followed by ``Dash(p)`` with p > 0 on a robot whose preset says
  ``robot.turn_style = "arc"``: ARC at the Turn's rate and duration with forward speed
  p/100 · v_max (the firmware keeps the rate and drives as fast as the wheels have room left),
  then the Dash; the robot keeps moving while it turns.
* ``Kick(p, d)`` (d wrapped): with a kicker and |d| within its `half_angle_rad`: KICK(p) (p
  clipped to 0–100); the wheels keep their command. Without a kicker and |d| <=
  :data:`PUSH_HALF_ANGLE_RAD`: push, i.e. FORWARD at p/100 · v_max for 2·T. Otherwise (ball
  direction too far off the heading for the kicker or a push): the Turn(d) above, so that a
  repeated kick becomes a kick once the robot faces d.
* wheel speeds (:meth:`HostActuation.wheels`, a per-step controller's command): WHEELS (left,
  right), held for 2·T like a dash; they replace any pending body actions.
* ``Say(text)``: not sent to the robot; relayed by the host to every other robot's heard buffer,
  with the sender and, when both poses are known, the direction of the sender from the listener.
* ``TurnNeck`` and ``ChangeView``: accepted and ignored. The overhead camera sees the whole
  field at once and a robot has no head: there is nothing to point and no view to change, and
  every percept already reports angles from the body (``Percept.neck_rad`` 0). Ignoring them,
  rather than refusing, keeps one client's code running on both field models (DESIGN.md §2).

**Events** (:meth:`CentralHost.drain_events`, when `keep_events`): every primitive sent, on the
``"link"`` channel (``left1 TURN +2.10 rad/s for 24 ticks``).

**Several body actions in one decision** run in order, as the Soccer Server runs them one per
cycle (the paper's clients send ``(turn ...)`` then ``(dash ...)`` on one see, Figure 4): the
first is sent at once, each later one when the previous one's *duration* has elapsed, and a new
decision for the same robot replaces whatever is still pending. Durations: a TURN its D ticks
above; a FORWARD/BACKWARD (a dash or a push) one camera period T (the next action takes over
from the dash's 2·T hold, as the server's next cycle would); a KICK one link packet period (so
the next command does not take the kick's place in the link's queue before it leaves); a STOP
(``Turn(0)``, ``Dash(0)``) none, so the next action goes out in the same call. Because every
command then waits the same link latency, a FORWARD released D ticks after its TURN reaches the
firmware as the turn ends. The arena calls :meth:`HostActuation.release` once per tick, before the
link delivers; it costs one integer comparison while nothing is pending
(:attr:`~HostActuation.next_release_tick`).
"""

from __future__ import annotations

import math
from collections.abc import Callable

from field_models.arena import ArenaEvent
from field_models.protocol import (
    Action,
    ChangeView,
    Dash,
    Kick,
    PlayerRef,
    Say,
    Turn,
    TurnNeck,
    wrap_angle,
)
from field_models.records import positional_maker
from field_models.robot_physics.link import Command, Link, Primitive
from field_models.robot_physics.trace_text import describe

_make_command = positional_maker(Command)

PUSH_HALF_ANGLE_RAD = 0.2
"""A kicker-less robot pushes the ball only when the kick direction is this close to its heading
(about 11°); otherwise it turns first."""

DASH_HOLD_PERIODS = 2
"""Camera periods a Dash (or a push) is held for, so one lost packet does not stall the robot."""

NEVER = 1 << 62
"""A tick that never comes: :attr:`HostActuation.next_release_tick` when nothing is pending."""


class HostActuation:
    """Translates client actions into link commands and releases queued ones when due.

    A mixin of :class:`~field_models.robot_physics.host.CentralHost`, which owns the state
    named below and sets it up; see the host for its arguments.

    Attributes:
        dropped: Body actions still pending (not sent) when a new decision replaced them
            (issue 28 item 5: the robots' "lost dash"); counted only, nothing depends on it.
        dropped_dashes: Of :attr:`dropped`, the Dash actions.
        next_release_tick: Earliest tick at which a pending body action is due
            (:data:`NEVER` if none).
    """

    refs: tuple[PlayerRef, ...]
    link: Link
    frame_period_ticks: int
    keep_events: bool
    dropped: int
    dropped_dashes: int
    next_release_tick: int
    _dt_s: float
    _vmax: float
    _max_rate: float
    _spin_accel: float
    _period_s: float
    _hold_ticks: int
    _kick_half_angle: float | None
    _arcs: bool
    _index: dict[PlayerRef, int]
    _row_by_id: dict[int, int]
    _seq: int
    _events: list[ArenaEvent]
    _min_ticks: int
    _pending: list[list[Action]]
    _release_at: list[int]
    _relay: Callable[[PlayerRef, str, int], None]

    def _row_of(self, ref: PlayerRef) -> int:
        """`ref`'s row in :attr:`refs` (as :meth:`_row`); KeyError if it is not there."""
        i = self._row_by_id.get(id(ref), -1)
        if i >= 0 and self.refs[i] is ref:
            return i
        return self._index[ref]

    def submit(self, ref: PlayerRef, actions: tuple[Action, ...], tick: int) -> None:
        """Relay the says of `ref`, send its first body action now and queue the rest.

        A new decision replaces the body actions still pending from the previous one (module
        docstring, "Several body actions in one decision").
        """
        body: list[Action] = []
        for action in actions:
            if isinstance(action, Say):
                self._relay(ref, action.text, tick)
            elif not isinstance(action, TurnNeck | ChangeView):  # no head, one view: ignored
                body.append(action)
        i = self._row_of(ref)
        old = self._pending[i]
        if old:
            self.dropped += len(old)
            self.dropped_dashes += sum(isinstance(a, Dash) for a in old)
        body.reverse()  # popped from the end, in order
        self._pending[i] = body
        if self._arcs and len(body) >= 2:
            duration = self._arc(ref, body[-1], body[-2], tick)
            if duration:
                body.pop()  # the turn runs as the arc; its dash follows when the arc ends
                self._note_due(i, tick + duration)
                return
        self._run_chain(i, ref, tick)

    def release(self, tick: int) -> None:
        """Send the pending body actions that are due at `tick` (the arena calls this per tick)."""
        if tick < self.next_release_tick:
            return
        release_at = self._release_at
        for i, due in enumerate(release_at):
            if due <= tick:
                self._run_chain(i, self.refs[i], tick)
        self.next_release_tick = min(release_at)

    def pending(self, ref: PlayerRef) -> tuple[Action, ...]:
        """The body actions of `ref` not sent yet, in the order they will go."""
        return tuple(reversed(self._pending[self._index[ref]]))

    def _run_chain(self, i: int, ref: PlayerRef, tick: int) -> None:
        """Send robot `i`'s next actions until one lasts; note when the rest is due."""
        chain = self._pending[i]
        duration = 0
        while chain and duration == 0:
            duration = self._translate(ref, chain.pop(), tick)
        self._note_due(i, tick + duration if chain else NEVER)

    def _note_due(self, i: int, due: int) -> None:
        """Robot `i`'s next pending action goes out at `due`."""
        self._release_at[i] = due
        if due < self.next_release_tick:
            self.next_release_tick = due

    def wheels(self, ref: PlayerRef, left_mps: float, right_mps: float, tick: int) -> None:
        """Send WHEELS (left, right) [m/s] to `ref` now, held for the dash time (2·T).

        A new decision: whatever body actions of `ref` were still pending are dropped.
        """
        i = self._index[ref]
        self._pending[i] = []
        self._release_at[i] = NEVER
        self._send(
            ref, Primitive.WHEELS, tick, value=left_mps, duration_ticks=self._hold_ticks,
            rate=right_mps,
        )  # fmt: skip

    def ideal_link(self, link: Link) -> None:
        """Send on `link` from now on, a link without rate limit (one packet slot per tick)."""
        self.link = link
        self._min_ticks = link.packet_period_ticks

    def stop(self, tick: int, ref: PlayerRef | None = None) -> None:
        """Send STOP to `ref`, or broadcast it to every robot when `ref` is None."""
        self._send(ref, Primitive.STOP, tick)

    # ------------------------------------------------------------------------ translation

    def _translate(self, ref: PlayerRef, action: Action, tick: int) -> int:
        """Translate one body action into a command (module docstring); return its duration."""
        if isinstance(action, Dash):
            power = max(-100.0, min(100.0, action.power))
            return self._dash(ref, power / 100.0 * self._vmax, action.direction_rad, tick)
        if isinstance(action, Turn):
            return self._turn(ref, wrap_angle(action.angle_rad), tick)
        if isinstance(action, Kick):
            power = max(0.0, min(100.0, action.power))
            direction = wrap_angle(action.direction_rad)
            if self._kick_half_angle is not None:
                if abs(direction) <= self._kick_half_angle:
                    self._send(ref, Primitive.KICK, tick, value=power)
                    return self._min_ticks
                return self._turn(ref, direction, tick)
            if abs(direction) <= PUSH_HALF_ANGLE_RAD:
                return self._drive(ref, power / 100.0 * self._vmax, tick)
            return self._turn(ref, direction, tick)
        raise TypeError(f"not a body action: {action!r}")

    def _dash(self, ref: PlayerRef, speed_mps: float, direction_rad: float, tick: int) -> int:
        """A dash toward `direction_rad`: straight, or a turn first (module docstring)."""
        direction = wrap_angle(direction_rad)
        if direction == 0.0:
            return self._drive(ref, speed_mps, tick)
        if abs(direction) > 0.5 * math.pi:  # nearer to drive backwards than to turn round
            direction, speed_mps = wrap_angle(direction - math.pi), -speed_mps
            if direction == 0.0:
                return self._drive(ref, speed_mps, tick)
        self._pending[self._row_of(ref)].append(Dash(100.0 * speed_mps / self._vmax))
        return self._turn(ref, direction, tick)

    def _drive(self, ref: PlayerRef, speed_mps: float, tick: int) -> int:
        """FORWARD/BACKWARD at |speed| held for the dash time; STOP for zero. Returns ticks."""
        if speed_mps == 0.0:
            self._send(ref, Primitive.STOP, tick)
            return 0
        primitive = Primitive.FORWARD if speed_mps > 0.0 else Primitive.BACKWARD
        self._send(ref, primitive, tick, value=abs(speed_mps), duration_ticks=self._hold_ticks)
        return max(self.frame_period_ticks, self._min_ticks)

    def _arc(self, ref: PlayerRef, first: Action, second: Action, tick: int) -> int:
        """ARC for a Turn then a forward Dash (module docstring); returns its ticks.

        0 (nothing sent) when the actions are not that pair or the turn is zero.
        """
        if not (
            isinstance(first, Turn)
            and isinstance(second, Dash)
            and second.power > 0.0
            and second.direction_rad == 0.0
        ):
            return 0
        angle = wrap_angle(first.angle_rad)
        if angle == 0.0:
            return 0
        rate, ticks = self.turn_plan(angle)
        speed = min(100.0, second.power) / 100.0 * self._vmax
        self._send(
            ref,
            Primitive.ARC,
            tick,
            value=speed,
            duration_ticks=ticks,
            rate=math.copysign(rate, angle),
        )
        return max(ticks, self._min_ticks)

    def _turn(self, ref: PlayerRef, angle_rad: float, tick: int) -> int:
        """A timed TURN by `angle_rad` (left positive); STOP for zero. Returns its ticks."""
        size = abs(angle_rad)
        if size == 0.0:
            self._send(ref, Primitive.STOP, tick)
            return 0
        rate, ticks = self.turn_plan(size)
        self._send(
            ref, Primitive.TURN, tick, value=math.copysign(rate, angle_rad), duration_ticks=ticks
        )
        return max(ticks, self._min_ticks)

    def turn_plan(self, angle_rad: float) -> tuple[float, int]:
        """Rate [rad/s] and duration [ticks] of a TURN by |angle_rad| (> 0); see the docstring."""
        size = abs(angle_rad)
        dt = self._dt_s
        rate = min(size / self._period_s, self._max_rate, math.sqrt(self._spin_accel * size))
        ticks = max(1, math.ceil(size / (rate * dt) - 1e-9))
        return size / (ticks * dt), ticks

    def _send(
        self,
        ref: PlayerRef | None,
        primitive: Primitive,
        tick: int,
        *,
        value: float = 0.0,
        duration_ticks: int | None = None,
        rate: float = 0.0,
    ) -> None:
        """Number a command, put it on the link and note it as an event."""
        self._seq += 1
        command = _make_command(self._seq, ref, primitive, value, duration_ticks, tick, rate)
        self.link.send(command, tick)
        if self.keep_events:
            who = "all" if ref is None else str(ref)
            self._events.append(ArenaEvent(tick, "link", f"{who} {describe(command)}", ref))
