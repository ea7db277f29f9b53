"""A robot's on-board loop: runs the newest command it received, as wheel-speed targets.

The paper's mini-robots "perform the physical navigation actions, decode commands, and can
respond to positioning requests" (§2). This firmware turns the link's primitives
(:class:`field_models.robot_physics.link.Primitive`) into left/right wheel-speed targets; the
world applies the motor ramp and tyre grip to them (shared `specs/robot_physics.md` §3.2, §5
item 2).

Behaviour:

* **Addressing**: a command is accepted when addressed to this robot or broadcast (robot None).
* **Newest wins**: a command whose `seq` is not newer than the newest accepted one is dropped
  (stale or duplicate). An accepted drive command (STOP, FORWARD, BACKWARD, TURN, ARC, WHEELS)
  replaces the running one; a KICK only arms the kicker (:meth:`Firmware.take_kick`) and leaves
  the running motion as it is, so a robot can kick while driving.
* **Duration**: a command with `duration_ticks = D` accepted at tick `r` drives for update ticks
  `r <= tick < r + D`, then the wheels stop. Without a duration it runs until replaced.
* **Timeout (watchdog)**: once `timeout_ticks` pass after the last accepted command (at ticks
  `>= last + timeout_ticks`), the robot stops, whatever it was doing, so a robot
  whose host went quiet or whose link failed does not drive on.
* **FORWARD/BACKWARD/TURN**: fixed targets (v, v), (-v, -v), (-ω·b/2, ω·b/2) for track b.
* **ARC** (speed v, rate ω): (u - ω·b/2, u + ω·b/2) with u = min(v, v_max - |ω|·b/2): the turn
  rate is kept and the forward speed is what the top wheel speed leaves.
* **WHEELS** (left l, right r): (l, r), each clipped to ±v_max.

:meth:`Firmware.due` says when :meth:`Firmware.update` could change its output, so the arena can
skip quiet ticks: a new command, or an expiring duration or timeout.

**Counters** (read by instrumentation, they change nothing; issue 28 item 5, "does a new camera
frame ever replace a command that was not yet carried out?"): :attr:`Firmware.cut_short` counts
drive commands with a duration that a newer drive command replaced before the duration ended,
:attr:`Firmware.cut_turns` those of them that were TURN or ARC (a turn not turned in full), and
:attr:`Firmware.stale` the commands dropped as not newer than the newest accepted one.

Positioning requests are not modelled: no client mind asks for one (every skill steers with
turns and dashes, as on the Soccer Server).
"""

from __future__ import annotations

from field_models.protocol import PlayerRef
from field_models.robot_physics.config import FirmwareConfig, RobotConfig
from field_models.robot_physics.link import Command, Primitive

_NEVER = 1 << 62
"""A tick that never comes."""


class Firmware:
    """One robot's command interpreter (see the module docstring).

    Args:
        ref: This robot's identity (its link address).
        robot: The robot's geometry and limits (track, top wheel speed, top turn rate).
        config: The watchdog timeout (given again in ticks).
        timeout_ticks: Ticks without an accepted command after which the robot stops (>= 1).
    """

    def __init__(
        self,
        ref: PlayerRef,
        robot: RobotConfig,
        config: FirmwareConfig,
        *,
        timeout_ticks: int,
    ) -> None:
        if timeout_ticks < 1:
            raise ValueError(f"timeout_ticks must be >= 1, got {timeout_ticks}")
        self.ref = ref
        self.robot = robot
        self.config = config
        self.timeout_ticks = timeout_ticks
        self._vmax = robot.max_wheel_speed_mps
        self._half_track = 0.5 * robot.track_m
        self._max_rate = robot.max_turn_rate_radps

        self._newest_seq: int | None = None
        self._last_rx_tick = -_NEVER
        self._command: Command | None = None
        self._end_tick = _NEVER  # tick at which the running command's duration ends
        self._wake_tick = _NEVER  # first tick at which a duration or the timeout expires
        self._fresh = False  # a command arrived since the last update
        self._left = 0.0  # wheel targets of the running command
        self._right = 0.0
        self._kick: float | None = None
        self.cut_short = 0
        """Drive commands with a duration replaced by a newer one before the duration ended."""
        self.cut_turns = 0
        """Of :attr:`cut_short`, the TURN and ARC commands (turns not carried out in full)."""
        self.stale = 0
        """Commands dropped because their `seq` was not newer than the newest accepted one."""

    # ------------------------------------------------------------------------ commands in

    def receive(self, command: Command, tick: int) -> bool:
        """Take a command that arrived at `tick`; returns whether it was accepted."""
        robot = command.robot
        if robot is not None and robot is not self.ref and robot != self.ref:
            return False
        if self._newest_seq is not None and command.seq <= self._newest_seq:
            self.stale += 1
            return False
        self._newest_seq = command.seq
        timed_out = tick >= self._last_rx_tick + self.timeout_ticks
        self._last_rx_tick = tick
        self._fresh = True
        if command.primitive is Primitive.KICK:
            self._kick = min(max(command.value, 0.0), 100.0)
        else:
            running = self._command
            if (
                running is not None
                and not timed_out
                and self._end_tick != _NEVER
                and tick < self._end_tick
            ):
                # Replaced while its duration still ran (not stopped by the watchdog).
                self.cut_short += 1
                if running.primitive is Primitive.TURN or running.primitive is Primitive.ARC:
                    self.cut_turns += 1
            self._start(command, tick)
        self._wake_tick = min(self._end_tick, tick + self.timeout_ticks)
        return True

    def take_kick(self) -> float | None:
        """The power (0–100) of a KICK received since the last call, once; else None."""
        kick = self._kick
        self._kick = None
        return kick

    # ------------------------------------------------------------------------ wheels out

    def due(self, tick: int) -> bool:
        """Whether :meth:`update` could change its output at `tick`."""
        return self._fresh or tick >= self._wake_tick

    def update(self, tick: int) -> tuple[float, float]:
        """Wheel-speed targets (left, right) [m/s] at `tick`."""
        self._fresh = False
        if self._command is None:
            self._wake_tick = _NEVER
            return 0.0, 0.0
        if tick >= self._last_rx_tick + self.timeout_ticks or tick >= self._end_tick:
            self._halt()
            return 0.0, 0.0
        return self._left, self._right

    @property
    def wake_tick(self) -> int:
        """The first tick at which :meth:`due` turns true without a new command.

        A huge one when nothing will expire.
        """
        return self._wake_tick

    @property
    def running(self) -> Command | None:
        """The drive command being run, or None when stopped."""
        return self._command

    # ------------------------------------------------------------------------ internals

    def _start(self, command: Command, tick: int) -> None:
        """Make `command` the running drive command from `tick`."""
        self._command = command
        self._end_tick = _NEVER if command.duration_ticks is None else tick + command.duration_ticks
        primitive = command.primitive
        if primitive is Primitive.FORWARD or primitive is Primitive.BACKWARD:
            speed = min(abs(command.value), self._vmax)
            if primitive is Primitive.BACKWARD:
                speed = -speed
            self._left = self._right = speed
        elif primitive is Primitive.ARC:
            rate = max(-self._max_rate, min(self._max_rate, command.rate))
            spin = rate * self._half_track
            forward = min(abs(command.value), self._vmax - abs(spin))
            self._left, self._right = forward - spin, forward + spin
        elif primitive is Primitive.TURN:
            rate = max(-self._max_rate, min(self._max_rate, command.value))
            self._left = -rate * self._half_track
            self._right = rate * self._half_track
        elif primitive is Primitive.WHEELS:
            cap = self._vmax
            self._left = max(-cap, min(cap, command.value))
            self._right = max(-cap, min(cap, command.rate))
        else:  # STOP
            self._left = self._right = 0.0

    def _halt(self) -> None:
        """Stop: no running command, nothing to wake for."""
        self._command = None
        self._end_tick = _NEVER
        self._wake_tick = _NEVER
        self._left = self._right = 0.0
