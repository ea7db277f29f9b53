"""The ``"motor"`` drive: Chipmunk alone moves the robots between drive events (issue 21 item 1).

The default ``"kinematic"`` drive (:class:`~field_models.robot_physics.world.RobotWorld`) ramps
each robot's wheel speeds in Python every tick and points its kinematic control body along the
robot's heading then. This drive (``robot.drive = "motor"`` in a preset) sets each control body
only at **drive events** and leaves every tick between them to ``cpSpaceStep``:

* **the drive direction follows the turn inside Chipmunk.** A robot turning at ω with forward
  speed v moves about the centre of its arc, v/ω to its left. The control body spins at ω and
  the drive joint's anchor on it is put v/ω from its centre, square to the robot's heading: that
  point moves at v along a direction that turns at ω, so the `PivotJoint` pulls the robot along
  its arc with no Python per tick. (The joint has no position bias and the control body no mass,
  so only the anchor point's velocity counts, not where it is.) At ω = 0 the control body simply
  moves at v along the heading. The joints and their grip caps are the kinematic drive's (world
  docstring; shared ``specs/robot_physics.md`` §3.2 option A): traction, skids and pushing are
  modelled the same way.
* **the wheel ramp is a staircase of segments.** While a wheel ramps, an event every
  :data:`SEGMENT_S` (and where a wheel reaches its target) sets the control body to the mean of
  the ramped wheel speeds over the segment ahead (in closed form: the ramp is linear there), and
  the grip caps carry the robot to it (at up to μ·g, faster than the ramp). Once both wheels are
  at their targets, one more event a segment later re-aims the drive direction at the robot's
  heading (the robot's spin has caught up with the last step by then); after that nothing runs
  until the next wheel targets.

What differs from the kinematic drive (measured in the README, "The motor drive"): the ramp is
followed in steps of a segment rather than every tick, and between events the drive direction
turns at the commanded rate rather than following the robot's actual heading, so a robot turned
by a collision is pulled along its old arc, up to its grip, until its next event.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import pymunk
from pymunk._chipmunk import lib as _cp

from field_models.protocol import PlayerRef
from field_models.robot_physics.config import RobotPhysicsPreset
from field_models.robot_physics.world import RobotWorld
from field_models.seeding import Rng

# The same cffi fast path as world.py: reads and writes of the control bodies at events.
_get_angle = _cp.cpBodyGetAngle
_set_velocity = _cp.cpBodySetVelocity
_set_spin = _cp.cpBodySetAngularVelocity
_set_anchor = _cp.cpPivotJointSetAnchorA

_NEVER = 1 << 62
"""A tick that never comes."""

SEGMENT_S = 1.0 / 30.0
"""Longest time between a ramping robot's drive events [s]: one camera frame of the presets."""

STRAIGHT_RADIUS_M = 1.0e4
"""An arc wider than this is driven as a straight line (its turn over a segment is negligible)."""

_TICK_EPS = 1e-9
"""Slack when counting a ramp's ticks (a whole number of ramp steps must not count one more)."""


class _Plan:
    """One robot's drive between events: the wheels at the last event, targets, next event."""

    __slots__ = (
        "anchored",
        "body_ptr",
        "control_moving",
        "control_ptr",
        "left",
        "left_target",
        "next_tick",
        "pivot_ptr",
        "right",
        "right_target",
        "settled",
        "tick",
    )

    def __init__(self, body: pymunk.Body, control: pymunk.Body, pivot: pymunk.PivotJoint) -> None:
        self.body_ptr = body._body
        self.control_ptr = control._body
        self.pivot_ptr = pivot._constraint
        self.tick = 0  # tick of the last event; left/right are the wheel speeds then
        self.left = 0.0
        self.right = 0.0
        self.left_target = 0.0
        self.right_target = 0.0
        self.next_tick = _NEVER
        self.settled = True  # at the targets and re-aimed once since
        self.anchored = False  # the drive anchor is off the control body's centre (an arc)
        self.control_moving = False  # the control body has a velocity (a straight drive)

    def reset(self, tick: int) -> None:
        """Wheels stopped, targets zero, no event due (a placed robot)."""
        self.tick = tick
        self.left = self.right = self.left_target = self.right_target = 0.0
        self.next_tick = _NEVER
        self.settled = True
        self.anchored = False
        self.control_moving = False


def _ramped(speed: float, target: float, step: float) -> float:
    """`speed` moved toward `target` by at most `step` (>= 0)."""
    if speed < target:
        return min(speed + step, target)
    return max(speed - step, target)


class MotorWorld(RobotWorld):
    """A :class:`RobotWorld` whose robots are driven at events only (the module docstring).

    The same arguments, bodies, joints and coach-side methods; stepping and actuation differ.
    """

    def __init__(
        self,
        preset: RobotPhysicsPreset,
        refs: Sequence[PlayerRef],
        noise_rng: Rng | None = None,
    ) -> None:
        super().__init__(preset, refs, noise_rng)
        self._segment = max(1, round(SEGMENT_S / self.dt_s))
        self._inv_track = 1.0 / preset.robot.track_m
        pivots = [
            c
            for c in self.space.constraints
            if isinstance(c, pymunk.PivotJoint) and c.a.body_type == pymunk.Body.KINEMATIC
        ]
        by_control = {id(p.a): p for p in pivots}
        self._plans = [_Plan(d.body, d.control, by_control[id(d.control)]) for d in self._drives]
        # The plans with an event at each coming tick (a plan re-planned earlier stays listed
        # under its old tick too; its next_tick tells).
        self._due: dict[int, list[_Plan]] = {}

    # ------------------------------------------------------------------ actuation

    def place_robot(self, index: int, x: float, y: float, heading: float) -> None:
        """Put robot `index` at rest at (x, y) [m] facing `heading` [rad]; wheels stopped."""
        super().place_robot(index, x, y, heading)
        plan = self._plans[index]
        plan.reset(self.tick)
        _set_anchor(plan.pivot_ptr, (0.0, 0.0))

    def set_wheel_targets(self, index: int, left_mps: float, right_mps: float) -> None:
        """Set robot `index`'s wheel-speed targets [m/s], capped; an event for it now."""
        cap = self._max_wheel
        left = max(-cap, min(cap, left_mps))
        right = max(-cap, min(cap, right_mps))
        plan = self._plans[index]
        if left == plan.left_target and right == plan.right_target:
            return  # the running plan already drives to these targets
        self._replan(plan, self.tick, left, right)

    def wheel_speeds(self, index: int) -> tuple[float, float]:
        """Robot `index`'s ramped wheel speeds [m/s] now (the ramp in closed form)."""
        plan = self._plans[index]
        step = (self.tick - plan.tick) * self._ramp_step
        return (
            _ramped(plan.left, plan.left_target, step),
            _ramped(plan.right, plan.right_target, step),
        )

    # ------------------------------------------------------------------ stepping

    def step(self) -> None:
        """Advance one tick: Chipmunk's step, then the drive events due (module docstring)."""
        self.space_step(self._space_ptr, self.dt_s)
        tick = self.tick = self.tick + 1
        if tick == self._noise_tick:
            self._noise_tick += self._noise_ticks
            self._perturb_ball()
        if tick in self._due:
            self._run_events(tick)

    def _run_events(self, tick: int) -> None:
        """Re-plan each robot whose event is due now (each reads and sets only its own bodies)."""
        for plan in self._due.pop(tick):
            if plan.next_tick == tick:
                self._replan(plan, tick, plan.left_target, plan.right_target)

    def _replan(self, plan: _Plan, tick: int, left_target: float, right_target: float) -> None:
        """Bring `plan`'s wheels to `tick` along the ramp, then plan the segment from there.

        New targets (``settled`` reset) or the same; aims the control body for the segment and
        schedules the robot's next event. One method, the ramps written out: it runs at every
        event (speed).
        """
        ramp = self._ramp_step
        step = (tick - plan.tick) * ramp
        left, right = (
            _ramped(plan.left, plan.left_target, step),
            _ramped(plan.right, plan.right_target, step),
        )
        plan.left, plan.right, plan.tick = left, right, tick
        if left_target != plan.left_target or right_target != plan.right_target:
            plan.left_target, plan.right_target = left_target, right_target
            plan.settled = False
        # Ticks to the segment's end: at most a segment, and no wheel reaches its target inside.
        n = _NEVER
        if left != left_target:
            n = math.ceil(abs(left_target - left) / ramp - _TICK_EPS)
        if right != right_target:
            n = min(n, math.ceil(abs(right_target - right) / ramp - _TICK_EPS))
        if n != _NEVER:
            n = max(1, min(n, self._segment))  # a rounding remainder still takes one tick
            # The kinematic drive's speeds over the next n ticks are linear; their mean is the
            # speed after (n + 1) / 2 ramp steps.
            half = 0.5 * (n + 1) * ramp
            left = _ramped(left, left_target, half)
            right = _ramped(right, right_target, half)
            plan.next_tick = tick + n
        elif plan.settled or (left == 0.0 and right == 0.0):
            plan.settled = True
            plan.next_tick = _NEVER
        else:
            plan.settled = True  # one more event, once the robot's spin has caught up
            plan.next_tick = tick + self._segment
        self._aim(plan, 0.5 * (left + right), (right - left) * self._inv_track)
        if plan.next_tick != _NEVER:
            due = self._due.get(plan.next_tick)
            if due is None:
                self._due[plan.next_tick] = [plan]
            else:
                due.append(plan)

    def _aim(self, plan: _Plan, v: float, w: float) -> None:
        """Point the control body so its drive anchor moves at `v` along an arc turning at `w`.

        The joints have no position bias and the control body no mass, so only the velocity of
        the anchor point matters, not where it is: the control body stays where it is, and its
        anchor is put v/w from its centre, square to the robot's heading (module docstring).
        """
        control = plan.control_ptr
        heading = _get_angle(plan.body_ptr)
        if w != 0.0 and abs(v) < STRAIGHT_RADIUS_M * abs(w):
            radius = v / w
            turn = heading - _get_angle(control)  # the heading in the control body's frame
            _set_anchor(plan.pivot_ptr, (radius * math.sin(turn), -radius * math.cos(turn)))
            plan.anchored = True
            if plan.control_moving:
                _set_velocity(control, (0.0, 0.0))
                plan.control_moving = False
        else:
            _set_velocity(control, (v * math.cos(heading), v * math.sin(heading)))
            plan.control_moving = v != 0.0
            if plan.anchored:
                _set_anchor(plan.pivot_ptr, (0.0, 0.0))
                plan.anchored = False
        _set_spin(control, w)


DRIVES = {"kinematic": RobotWorld, "motor": MotorWorld}
"""The world class of each ``robot.drive`` value."""


def make_world(
    preset: RobotPhysicsPreset, refs: Sequence[PlayerRef], noise_rng: Rng | None = None
) -> RobotWorld:
    """The world of `preset`'s drive (``robot.drive``; checked when the preset loads)."""
    return DRIVES[preset.robot.drive](preset, refs, noise_rng)
