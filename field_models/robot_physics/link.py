"""The host-to-robot link: navigation primitives in packets, with a rate, a latency and loss.

The paper's host sends commands to the robots over a wireless (infrared) link "using the
robot-specific action codes"; commands "can be broadcast or sent directly to individual agents"
and include "positioning requests and navigation primitives, such as forward, backward, and
turning moves at specific speeds" (§2). Shared `specs/robot_physics.md` §2.4 and §5 item 5 give
the link's numbers: a packet rate, a latency and a loss probability per packet.

Model (all times in integer ticks):

* **Packet slots** are the ticks that are multiples of `packet_period_ticks`; each slot carries
  at most one packet, and one packet carries one :class:`Command`.
* **Queue**: :meth:`Link.send` queues a command; it leaves in the first free slot at or after the
  tick it was sent. The queue holds at most one command per address (a robot or broadcast): a
  newer command to the same address takes the older one's place in line, since the firmware only
  runs the newest command anyway. This keeps the queue bounded when the robots' commands exceed
  the link's rate, without changing anything when they do not.
* **Latency**: a packet that leaves at slot `s` arrives at exactly `s + latency_ticks`.
* **Loss**: each packet is lost independently with `loss_prob`, drawn as it leaves.

The link is lazy: departures up to a tick are worked out when :meth:`Link.deliver` is called for
that tick, so a command sent at tick `t` (after `deliver(t)`) with slot `t` still leaves at `t`.
Because departures are in slot order and the latency is constant, arrivals are in order too.
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass
from enum import IntEnum

from field_models.protocol import PlayerRef
from field_models.robot_physics.config import LinkConfig
from field_models.seeding import Rng


class Primitive(IntEnum):
    """The robots' navigation primitives (paper §2) plus the kicker."""

    STOP = 0
    """Wheels to zero."""
    FORWARD = 1
    """Drive straight ahead at `value` m/s."""
    BACKWARD = 2
    """Drive straight back at `value` m/s."""
    TURN = 3
    """Spin in place at `value` rad/s, left positive."""
    ARC = 4
    """Drive forward at up to `value` m/s while turning at `rate` rad/s (a wheel-speed
    difference): the turn rate is kept, the forward speed is what the wheels' top speed leaves."""
    KICK = 5
    """Fire the kicker at power `value` (0–100); the wheels keep the running command."""
    WHEELS = 6
    """Drive the left wheel at `value` m/s and the right at `rate` m/s (each capped at the top
    wheel speed): the robot-specific action code of a per-step controller (FIRASim's
    ``Command{wheel_left, wheel_right}``)."""


@dataclass(frozen=True, slots=True)
class Command:
    """One command packet's content.

    Attributes:
        seq: Host sequence number, increasing; the firmware drops a command older than the newest
            it ran.
        robot: The addressee, or None for a broadcast to every robot.
        primitive: What to do.
        value: FORWARD/BACKWARD/ARC speed [m/s] (>= 0); TURN rate [rad/s], left positive; KICK
            power (0–100); WHEELS the left wheel's speed [m/s]. Unused by STOP.
        rate: ARC's turn rate [rad/s], left positive; WHEELS the right wheel's speed [m/s];
            unused by the others.
        duration_ticks: How long the motion runs from its arrival, or None: until replaced or
            the firmware's timeout.
        sent_tick: Tick at which the host sent the command.
    """

    seq: int
    robot: PlayerRef | None
    primitive: Primitive
    value: float = 0.0
    duration_ticks: int | None = None
    sent_tick: int = 0
    rate: float = 0.0


_NEVER = 1 << 62
"""A tick that never comes."""


class _Waiting:
    """A queued command and the tick it was sent; mutable so a newer command can take its turn."""

    __slots__ = ("command", "key", "tick")

    def __init__(self, command: Command, tick: int, key: tuple[str, int] | None) -> None:
        self.command = command
        self.tick = tick
        self.key = key  # the addressee's (team, number), what PlayerRef's == compares


class Link:
    """A seeded, lossy, rate-limited, delayed command link (see the module docstring).

    Args:
        config: The loss probability (rate and latency are given again in ticks).
        packet_period_ticks: Ticks between packet slots (>= 1).
        latency_ticks: Ticks from a packet's slot to its arrival (>= 0).
        rng: The trial's link generator.

    Attributes:
        sent: Packets that left (lost or not).
        lost: Packets lost on the way.
        delivered: Packets handed to the robots by :meth:`deliver`.
        superseded: Queued commands replaced by a newer one to the same address before leaving.
    """

    def __init__(
        self,
        config: LinkConfig,
        *,
        packet_period_ticks: int,
        latency_ticks: int,
        rng: Rng,
    ) -> None:
        if packet_period_ticks < 1:
            raise ValueError(f"packet_period_ticks must be >= 1, got {packet_period_ticks}")
        if latency_ticks < 0:
            raise ValueError(f"latency_ticks must be >= 0, got {latency_ticks}")
        self.config = config
        self.packet_period_ticks = packet_period_ticks
        self.latency_ticks = latency_ticks
        self._rng = rng
        self._loss = config.loss_prob
        self._queue: deque[_Waiting] = deque()
        # The queued commands by addressee key: at most one each (a newer one takes the older
        # one's place), so this finds the one a scan of the queue would.
        self._queued: dict[tuple[str, int] | None, _Waiting] = {}
        self._next_slot = 0
        self._in_flight: deque[tuple[int, Command]] = deque()
        self.next_due_tick = _NEVER
        """No :meth:`deliver` before this tick has anything to do (no packet leaves or arrives):
        a caller may skip it until then."""
        self.sent = 0
        self.lost = 0
        self.delivered = 0
        self.superseded = 0

    def send(self, command: Command, tick: int) -> None:
        """Queue `command` at `tick`; it leaves in the first free packet slot at or after `tick`."""
        robot = command.robot
        # PlayerRef's (dataclass) == compares (team, number); the key tuples compare (and hash)
        # the same way without Python-level __eq__ and __hash__ calls. None: a broadcast.
        key = None if robot is None else (robot.team, robot.number)
        waiting = self._queued.get(key)
        if waiting is not None:
            waiting.command = command
            waiting.tick = tick
            self.superseded += 1
            self.next_due_tick = min(self.next_due_tick, tick)
            return
        waiting = self._queued[key] = _Waiting(command, tick, key)
        self._queue.append(waiting)
        self.next_due_tick = min(self.next_due_tick, tick)

    def deliver(self, tick: int) -> list[Command]:
        """Commands that arrive at `tick` (or earlier, if not yet collected), in order."""
        if self._queue:
            self._depart(tick)
        flight = self._in_flight
        out: list[Command] = []
        while flight and flight[0][0] <= tick:
            out.append(flight.popleft()[1])
        self.delivered += len(out)
        self.next_due_tick = min(self._next_departure(), flight[0][0] if flight else _NEVER)
        return out

    def _next_departure(self) -> int:
        """The slot the head of the queue leaves in (:data:`_NEVER` for an empty queue)."""
        if not self._queue:
            return _NEVER
        period = self.packet_period_ticks
        return max(self._next_slot, -(-self._queue[0].tick // period) * period)

    def _depart(self, tick: int) -> None:
        """Send the queued commands whose slots come at or before `tick`."""
        period = self.packet_period_ticks
        queue = self._queue
        while queue:
            waiting = queue[0]
            # First slot at or after the send tick, and not before the next free slot.
            slot = max(self._next_slot, -(-waiting.tick // period) * period)
            if slot > tick:
                return
            queue.popleft()
            del self._queued[waiting.key]
            self._next_slot = slot + period
            self.sent += 1
            if self._loss > 0.0 and self._rng.random() < self._loss:
                self.lost += 1
                continue
            self._in_flight.append((slot + self.latency_ticks, waiting.command))
