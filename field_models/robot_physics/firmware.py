"""A robot's on-board loop: runs the newest command it received, as wheel-speed targets.

The paper's mini-robots "perform the physical navigation actions, decode commands, and can
respond to positioning requests" (§2). This firmware turns the link's primitives
(`field_models.robot_physics.link.Primitive`) into left/right wheel-speed targets; the world applies the motor
ramp and tyre grip to them (shared `specs/robot_physics.md` §3.2, §5 item 2).

Behaviour:

* **Addressing**: a command is accepted when addressed to this robot or broadcast (robot None).
* **Newest wins**: a command whose `seq` is not newer than the newest accepted one is dropped
  (stale or duplicate). An accepted drive command (STOP, FORWARD, BACKWARD, TURN, GOTO) replaces
  the running one; a KICK only arms the kicker (:meth:`Firmware.take_kick`) and leaves the
  running motion as it is, so a robot can kick while driving.
* **Duration**: a command with `duration_ticks = D` accepted at tick `r` drives for update ticks
  `r <= tick < r + D`, then the wheels stop. Without a duration it runs until replaced.
* **Timeout (watchdog)**: once `timeout_ticks` pass after the last accepted command (at ticks
  `>= last + timeout_ticks`), the robot stops, whatever it was doing, GOTO included, so a robot
  whose host went quiet or whose link failed does not drive on.
* **FORWARD/BACKWARD/TURN**: fixed targets (v, v), (-v, -v), (-ω·b/2, ω·b/2) for track b.
* **GOTO**: the target is given in the robot's frame at send time; the firmware takes it as its
  frame at arrival (the host's pose estimate is a camera latency old anyway) and tracks it by
  odometry from the measured wheel speeds passed to :meth:`Firmware.update`. The controller turns
  at ω = k·α toward the target's bearing α (k = `goto_gain_per_s`) and drives at
  v = min(v_max, k·d, √(2·a·d))·max(0, cos α), where d is the distance and a the wheel ramp, so
  it brakes within the ramp and does not overshoot. It ends (wheels stop) within
  `goto_tolerance_m`.
* **Cap**: targets are scaled together so neither wheel exceeds `max_wheel_speed_mps`, which
  keeps the commanded curvature.

:meth:`Firmware.due` says when :meth:`Firmware.update` could change its output, so the arena can
skip quiet ticks: a new command, an expiring duration or timeout, or an active GOTO.
"""

from __future__ import annotations

import math

from field_models.protocol import PlayerRef
from field_models.robot_physics.config import FirmwareConfig, RobotConfig
from field_models.robot_physics.link import Command, Primitive

_NEVER = 1 << 62
"""A tick that never comes."""


class Firmware:
    """One robot's command interpreter and GOTO controller (see the module docstring).

    Args:
        ref: This robot's identity (its link address).
        robot: The robot's geometry and limits (track, top wheel speed, ramp).
        config: Timeout, GOTO gain and tolerance (the timeout is given again in ticks).
        timeout_ticks: Ticks without an accepted command after which the robot stops (>= 1).
        dt_s: Length of one tick [s], for GOTO odometry.
    """

    def __init__(
        self,
        ref: PlayerRef,
        robot: RobotConfig,
        config: FirmwareConfig,
        *,
        timeout_ticks: int,
        dt_s: float,
    ) -> None:
        if timeout_ticks < 1:
            raise ValueError(f"timeout_ticks must be >= 1, got {timeout_ticks}")
        self.ref = ref
        self.robot = robot
        self.config = config
        self.timeout_ticks = timeout_ticks
        self.dt_s = dt_s
        self._vmax = robot.max_wheel_speed_mps
        self._half_track = 0.5 * robot.track_m
        self._inv_track = 1.0 / robot.track_m
        self._gain = config.goto_gain_per_s
        self._two_accel = 2.0 * robot.wheel_accel_mps2
        self._tolerance = config.goto_tolerance_m
        self._max_rate = robot.max_turn_rate_radps

        self._newest_seq: int | None = None
        self._last_rx_tick = -_NEVER
        self._command: Command | None = None
        self._end_tick = _NEVER  # tick at which the running command's duration ends
        self._wake_tick = _NEVER  # first tick at which a duration or the timeout expires
        self._fresh = False  # a command arrived since the last update
        self._left = 0.0  # fixed targets of the running non-GOTO command
        self._right = 0.0
        self._goto = False
        self._goal_x = 0.0  # GOTO target in the robot's current frame [m]
        self._goal_y = 0.0
        self._odom_tick = 0
        self._kick: float | None = None

    # ------------------------------------------------------------------------ commands in

    def receive(self, command: Command, tick: int) -> bool:
        """Take a command that arrived at `tick`; returns whether it was accepted."""
        if command.robot is not None and command.robot != self.ref:
            return False
        if self._newest_seq is not None and command.seq <= self._newest_seq:
            return False
        self._newest_seq = command.seq
        self._last_rx_tick = tick
        self._fresh = True
        if command.primitive is Primitive.KICK:
            self._kick = min(max(command.value, 0.0), 100.0)
        else:
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
        return self._fresh or self._goto or tick >= self._wake_tick

    def update(self, tick: int, left_mps: float, right_mps: float) -> tuple[float, float]:
        """Wheel-speed targets (left, right) [m/s] at `tick`.

        Args:
            tick: The current tick.
            left_mps: Measured left wheel speed [m/s] (GOTO odometry).
            right_mps: Measured right wheel speed [m/s].
        """
        self._fresh = False
        if self._command is None:
            self._wake_tick = _NEVER
            return 0.0, 0.0
        if tick >= self._last_rx_tick + self.timeout_ticks or tick >= self._end_tick:
            self._halt()
            return 0.0, 0.0
        if self._goto:
            return self._goto_step(tick, left_mps, right_mps)
        return self._left, self._right

    @property
    def running(self) -> Command | None:
        """The drive command being run, or None when stopped."""
        return self._command

    # ------------------------------------------------------------------------ internals

    def _start(self, command: Command, tick: int) -> None:
        """Make `command` the running drive command from `tick`."""
        self._command = command
        self._goto = False
        self._end_tick = _NEVER if command.duration_ticks is None else tick + command.duration_ticks
        primitive = command.primitive
        if primitive is Primitive.FORWARD or primitive is Primitive.BACKWARD:
            speed = min(abs(command.value), self._vmax)
            if primitive is Primitive.BACKWARD:
                speed = -speed
            self._left = self._right = speed
        elif primitive is Primitive.TURN:
            rate = max(-self._max_rate, min(self._max_rate, command.value))
            self._left = -rate * self._half_track
            self._right = rate * self._half_track
        elif primitive is Primitive.GOTO:
            self._goto = True
            self._goal_x = command.target_x
            self._goal_y = command.target_y
            self._odom_tick = tick
            self._left = self._right = 0.0
        else:  # STOP
            self._left = self._right = 0.0

    def _halt(self) -> None:
        """Stop: no running command, nothing to wake for."""
        self._command = None
        self._goto = False
        self._end_tick = _NEVER
        self._wake_tick = _NEVER
        self._left = self._right = 0.0

    def _goto_step(self, tick: int, left_mps: float, right_mps: float) -> tuple[float, float]:
        """Advance GOTO odometry to `tick` and return the controller's wheel targets."""
        elapsed_s = (tick - self._odom_tick) * self.dt_s
        self._odom_tick = tick
        if elapsed_s > 0.0:
            speed = 0.5 * (left_mps + right_mps)
            self._move_goal(speed, (right_mps - left_mps) * self._inv_track, elapsed_s)
        gx = self._goal_x
        gy = self._goal_y
        distance = math.hypot(gx, gy)
        if distance <= self._tolerance:
            self._halt()
            return 0.0, 0.0
        bearing = math.atan2(gy, gx)
        rate = max(-self._max_rate, min(self._max_rate, self._gain * bearing))
        cos_b = math.cos(bearing)
        speed = 0.0
        if cos_b > 0.0:
            speed = min(self._vmax, self._gain * distance, math.sqrt(self._two_accel * distance))
            speed *= cos_b
        return self._capped(speed - rate * self._half_track, speed + rate * self._half_track)

    def _move_goal(self, speed_mps: float, rate_radps: float, elapsed_s: float) -> None:
        """Re-express the goal in the robot's frame after it moved on an arc for `elapsed_s`."""
        turn = rate_radps * elapsed_s
        arc = speed_mps * elapsed_s
        half = 0.5 * turn
        # On a circular arc the displacement is the chord, along the mid-arc heading.
        chord = arc * math.sin(half) / half if abs(half) > 1e-9 else arc
        tx = self._goal_x - chord * math.cos(half)
        ty = self._goal_y - chord * math.sin(half)
        c = math.cos(turn)
        s = math.sin(turn)
        self._goal_x = c * tx + s * ty
        self._goal_y = -s * tx + c * ty

    def _capped(self, left: float, right: float) -> tuple[float, float]:
        """Scale both targets down together so neither exceeds the top wheel speed."""
        peak = max(abs(left), abs(right))
        if peak > self._vmax:
            scale = self._vmax / peak
            return left * scale, right * scale
        return left, right
