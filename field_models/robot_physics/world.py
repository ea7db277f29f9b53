"""The pymunk world of the mini-robots: walled field, goals, differential-drive robots, a ball.

Modelling (shared `specs/robot_physics.md` §3, measured there):

* **Robots** are dynamic square bodies driven through a kinematic *control body* per robot
  (the pymunk tank pattern, §3.2 option A): a `PivotJoint` with ``max_bias = 0`` and
  ``max_force = μ·m·g`` pulls the robot's velocity toward the wheels' forward speed, and a
  `GearJoint` with a yaw-torque cap pulls its spin toward the wheels' turn rate. The caps are the
  tyres' grip: ask for more than μ·g and the robot skids. The motors are a **wheel-speed ramp**:
  each wheel's speed moves toward its target by at most ``wheel_accel·dt`` per tick.
* **Ball rolling resistance** is a `PivotJoint` to the static body with ``max_force = m·a_roll``
  (§3.4): exact constant deceleration, inside the solver, no Python per step. The ball has an
  infinite moment (a top-down ball does not spin in the plane).
* **Walls** are static boxes outside the field lines, thick enough that the fastest ball cannot
  cross one in a tick (§3.5; checked when the preset loads), with 45° corner panels.
* **Elasticity** in pymunk is the product of the two shapes' values (§3.1), so the ball has 1.0
  and each wall or robot carries the per-pair restitution.
* **Ball-motion noise** (the counterpart of the Soccer Server's ``ball_rand``, see
  :class:`~field_models.robot_physics.config.BallConfig`) perturbs the ball's velocity every
  ``noise_period_s`` by a uniform amount per axis proportional to its speed.

The walls, the ball and the robots' bodies and joints are built by
:mod:`~field_models.robot_physics.world_build`. Time is counted in integer ticks of
``1/physics_hz`` s. This module imports no drawing, logging
or CLI code; observers read :meth:`RobotWorld.truth`.
"""

from __future__ import annotations

import math
import operator
from collections.abc import Sequence

import pymunk
from pymunk._chipmunk import lib as _cp

from field_models.protocol import PlayerRef, wrap_angle
from field_models.robot_physics.config import RobotPhysicsPreset
from field_models.robot_physics.world_build import add_ball, add_robot, add_walls
from field_models.robot_physics.world_truth import WorldTruth
from field_models.seeding import Rng, Stream

# The hot loop calls Chipmunk through pymunk's cffi layer, skipping pymunk's Python property
# wrappers, which cost several times more per call (shared notes/tooling.md §2.4). Only reads,
# velocity writes and the step go this way; bodies and shapes are built and placed through the
# public API. Pinned to pymunk 7 in pyproject.toml.
_get_angle = _cp.cpBodyGetAngle
_set_velocity = _cp.cpBodySetVelocity
_get_velocity = _cp.cpBodyGetVelocity
_set_spin = _cp.cpBodySetAngularVelocity
_space_step = _cp.cpSpaceStep

_row_of = operator.attrgetter("row")  # a drive's index among the robots (sort key)
_NOISE_BLOCK = 512  # noise draws reserved per generator call; part of the numbers (_BallNoise)
_NOISE_CHUNK = 64  # of which computed at a time, from a project stream (speed only)


class _BallNoise:
    """The ball-noise draws in the order the world has always used them (a trial's numbers).

    The world reserves a block of :data:`_NOISE_BLOCK` uniform draws in [-1, 1) from its
    generator and uses them last first, two per perturbation. A short trial uses a few dozen,
    so from a project :class:`~field_models.seeding.Stream` the block is only reserved (the
    stream moves past it, as a draw of the whole block would) and its values are computed
    :data:`_NOISE_CHUNK` at a time from the top: the same numbers in the same order.
    """

    __slots__ = ("_left", "_next", "_rng", "_start")

    def __init__(self, rng: Rng) -> None:
        self._rng = rng
        self._next: list[float] = []  # values not used yet, the next one last
        self._start = 0  # the block's first stream position
        self._left = 0  # block draws below those in _next, not computed yet

    def pair(self) -> tuple[float, float]:
        """The next two noise values (x, then y)."""
        values = self._next
        if len(values) < 2:
            values = self._next = self._refill()
        return values.pop(), values.pop()

    def _refill(self) -> list[float]:
        rng = self._rng
        if not isinstance(rng, Stream):
            return rng.uniform(-1.0, 1.0, _NOISE_BLOCK).tolist()
        if self._left == 0:
            self._start, self._left = rng.position, _NOISE_BLOCK
            rng.position += _NOISE_BLOCK
        count = min(_NOISE_CHUNK, self._left)
        self._left -= count
        # uniform(-1, 1)'s formula, low + (high - low)·u, on each draw.
        return [-1.0 + 2.0 * u for u in rng.draws_list(self._start + self._left, count)]


class _Drive:
    """One robot's body, its control body and its two wheels' ramped speeds."""

    __slots__ = (
        "body",
        "body_ptr",
        "control",
        "control_moving",
        "control_ptr",
        "control_spin",
        "cruising",
        "left",
        "left_target",
        "moving",
        "right",
        "right_target",
        "row",
    )

    def __init__(self, body: pymunk.Body, control: pymunk.Body, row: int) -> None:
        self.row = row  # the robot's index in the world's robots
        self.body = body
        self.control = control
        self.body_ptr = body._body
        self.control_ptr = control._body
        self.control_moving = False
        self.control_spin = 0.0
        self.moving = False  # in the world's list of robots to steer
        self.cruising = False  # in the world's list of robots at steady wheel speeds, driving
        self.left = 0.0
        self.right = 0.0
        self.left_target = 0.0
        self.right_target = 0.0

    def at_rest(self) -> bool:
        """Wheels stopped with zero targets and the control body still: nothing to steer."""
        return (
            self.left == 0.0
            and self.right == 0.0
            and self.left_target == 0.0
            and self.right_target == 0.0
            and not self.control_moving
            and self.control_spin == 0.0
        )


class RobotWorld(WorldTruth):
    """A walled field with robots and a ball, stepped in fixed ticks of ``1/physics_hz`` s.

    Args:
        preset: The robot-physics preset.
        refs: The robots, in a fixed order; index ``i`` in every method means ``refs[i]``.
        noise_rng: Generator for the ball-motion noise (the trial's "movement" stream).

    Its read-outs (states, poses, the truth) are
    :class:`~field_models.robot_physics.world_truth.WorldTruth`'s.
    """

    def __init__(
        self,
        preset: RobotPhysicsPreset,
        refs: Sequence[PlayerRef],
        noise_rng: Rng | None = None,
    ) -> None:
        self.preset = preset
        self.refs = tuple(refs)
        self.dt_s = preset.dt_s
        self.tick = 0
        self._ramp_step = preset.robot.wheel_accel_mps2 * self.dt_s
        self._half_track = 0.5 * preset.robot.track_m
        self._max_wheel = preset.robot.max_wheel_speed_mps
        self.space = pymunk.Space()
        self.space.iterations = preset.timing.solver_iterations
        # pymunk's default slop is 0.1 length units: 10 cm in SI (robot_physics.md §3.1).
        self.space.collision_slop = preset.timing.collision_slop_m
        # Walls, ball, robots: the order the space holds them in (world_build).
        self._walls = add_walls(self.space, preset.field, preset.ball.wall_restitution)
        self.ball = add_ball(self.space, preset.ball)
        self._drives = [
            _Drive(*add_robot(self.space, preset.robot), row) for row in range(len(self.refs))
        ]
        self._body_ptrs = [d.body_ptr for d in self._drives]  # what the read-outs read
        self._index = {ref: i for i, ref in enumerate(self.refs)}
        self._noise_ticks = max(1, round(preset.ball.noise_period_s / self.dt_s))
        # The next tick whose end perturbs the ball (never without a generator).
        self._noise_tick = self._noise_ticks if noise_rng is not None else -1
        self._moving: list[_Drive] = []  # robots whose wheels ramp, in the robots' order
        # Robots whose wheels run steadily at their targets with a non-zero forward speed: only
        # their drive direction follows the heading each tick (:meth:`_cruise`); and the rows
        # (body pointer, control pointer, forward speed) that loop reads.
        self._cruising: list[_Drive] = []
        self._cruise_rows: list[tuple[object, object, float]] = []
        self._noise = _BallNoise(noise_rng) if noise_rng is not None else None
        self._space_ptr = self.space._space
        self.space_step = _space_step
        """Chipmunk's step, called once per tick as ``space_step(space pointer, dt)``.

        A benchmark may wrap it to time the physics alone (:mod:`.bench`).
        """
        self._ball_ptr = self.ball._body
        self.space.step(0.0)  # lets pymunk run its one-off body checks before the fast path

    # ------------------------------------------------------------------ coach side

    def place_robot(self, index: int, x: float, y: float, heading: float) -> None:
        """Put robot `index` at rest at (x, y) [m] facing `heading` [rad]; wheels stopped."""
        d = self._drives[index]
        d.body.position = (x, y)
        d.body.angle = heading
        d.body.velocity = (0.0, 0.0)
        d.body.angular_velocity = 0.0
        d.control.velocity = (0.0, 0.0)
        d.control.angular_velocity = 0.0
        d.control_moving = False
        d.control_spin = 0.0
        d.left = d.right = d.left_target = d.right_target = 0.0
        if d.moving:
            d.moving = False
            self._moving.remove(d)
        self._stop_cruising(d)
        self.space.reindex_shapes_for_body(d.body)

    def place_ball(self, x: float, y: float, vx: float = 0.0, vy: float = 0.0) -> None:
        """Put the ball at (x, y) [m] with velocity (vx, vy) [m/s], clamped to the max speed."""
        self.ball.position = (x, y)
        self.ball.velocity = self._clamp_speed(vx, vy)
        self.space.reindex_shapes_for_body(self.ball)

    def _clamp_speed(self, vx: float, vy: float) -> tuple[float, float]:
        speed = math.hypot(vx, vy)
        cap = self.preset.ball.max_speed_mps
        if speed > cap:
            return vx * cap / speed, vy * cap / speed
        return vx, vy

    # ------------------------------------------------------------------ actuation

    def set_wheel_targets(self, index: int, left_mps: float, right_mps: float) -> None:
        """Set robot `index`'s wheel-speed targets [m/s], capped at its max wheel speed."""
        d = self._drives[index]
        cap = self._max_wheel
        d.left_target = max(-cap, min(cap, left_mps))
        d.right_target = max(-cap, min(cap, right_mps))
        if d.cruising or not d.moving:  # else it is steered already (what _wake checks)
            self._wake(d)

    def drive_bodies(self) -> list[tuple[pymunk.Body, pymunk.Body]]:
        """Each robot's (body, kinematic control body), in the robots' order.

        For a bare-world benchmark that drives the control bodies itself and steps the space
        alone (:mod:`.bench`); :meth:`step` would overwrite what it sets.
        """
        return [(d.body, d.control) for d in self._drives]

    def wheel_speeds(self, index: int) -> tuple[float, float]:
        """Robot `index`'s current (ramped) wheel speeds [m/s], as its encoders read them."""
        d = self._drives[index]
        return d.left, d.right

    def kick(self, index: int, power: float, direction_rad: float = 0.0) -> bool:
        """Fire robot `index`'s kicker with `power` in [0, 100]; True if the ball was in reach.

        The ball is in reach when it touches the robot's front face within the kicker's reach
        and half-angle. It leaves at ``power/100 · kicker.max_speed_mps`` along the heading plus
        `direction_rad`, plus the robot's own velocity.
        """
        kicker = self.preset.robot.kicker
        if kicker is None:
            return False
        body = self._drives[index].body
        heading = body.angle
        dx = self.ball.position.x - body.position.x
        dy = self.ball.position.y - body.position.y
        ahead = dx * math.cos(heading) + dy * math.sin(heading)
        gap = ahead - 0.5 * self.preset.robot.size_m - self.preset.ball.radius_m
        bearing = wrap_angle(math.atan2(dy, dx) - heading)
        if gap > kicker.reach_m or ahead <= 0 or abs(bearing) > kicker.half_angle_rad:
            return False
        speed = max(0.0, min(100.0, power)) / 100.0 * kicker.max_speed_mps
        direction = heading + direction_rad
        vx = speed * math.cos(direction) + body.velocity.x
        vy = speed * math.sin(direction) + body.velocity.y
        self.ball.velocity = self._clamp_speed(vx, vy)
        return True

    # ------------------------------------------------------------------ stepping

    def step(self) -> None:
        """Advance one tick: ramp the wheels, steer the control bodies, step the solver.

        Only the robots whose wheels ramp (:attr:`_moving`) or drive steadily (:attr:`_cruising`)
        cost Python here; a robot at rest, or spinning in place at its targets, is left to
        Chipmunk alone (its control body keeps the velocity and spin it was given).
        """
        if self._moving:
            self._steer()
        if self._cruise_rows:
            self._cruise()
        self.space_step(self._space_ptr, self.dt_s)
        tick = self.tick = self.tick + 1
        if tick == self._noise_tick:
            self._noise_tick += self._noise_ticks
            self._perturb_ball()

    def _steer(self) -> None:
        """Ramp each moving robot's wheels one tick and point its control body (module docstring).

        Each wheel moves toward its target by at most one ramp step.
        """
        ramp, track = self._ramp_step, 2.0 * self._half_track
        cos, sin = math.cos, math.sin
        steady = False
        for d in self._moving:
            left, right = d.left, d.right
            # min(target, x) and max(target, x) written out (the same comparison and result,
            # without a builtin call): x when it is past the target's near side, else target.
            target = d.left_target
            if left != target:
                if left < target:
                    x = left + ramp
                    left = x if x < target else target
                else:
                    x = left - ramp
                    left = x if x > target else target
                d.left = left
            target = d.right_target
            if right != target:
                if right < target:
                    x = right + ramp
                    right = x if x < target else target
                else:
                    x = right - ramp
                    right = x if x > target else target
                d.right = right
            v = 0.5 * (left + right)
            if v != 0.0:
                heading = _get_angle(d.body_ptr)
                _set_velocity(d.control_ptr, (v * cos(heading), v * sin(heading)))
                d.control_moving = True
            elif d.control_moving:
                _set_velocity(d.control_ptr, (0.0, 0.0))
                d.control_moving = False
            spin = (right - left) / track
            if spin != d.control_spin:
                _set_spin(d.control_ptr, spin)
                d.control_spin = spin
            if left == d.left_target and right == d.right_target:
                steady = True
        if steady:
            self._settle()

    def _settle(self) -> None:
        """Take the robots whose wheels reached their targets out of :attr:`_moving`.

        From here until a new target (:meth:`_wake`), :meth:`_steer` would repeat the same
        operations with the same wheel speeds every tick: no ramp, the same forward speed v and
        spin (the spin already set). So a robot with v != 0 goes to :meth:`_cruise`, which does
        what remains (point the control body's velocity along the heading), with the same
        operations on the same numbers; one with v == 0 (at rest, or spinning in place) needs
        nothing: its control body was stopped this tick.
        """
        keep: list[_Drive] = []
        for d in self._moving:
            if d.left == d.left_target and d.right == d.right_target:
                d.moving = False
                if d.control_moving:  # v != 0 this tick
                    d.cruising = True
                    self._cruising.append(d)
            else:
                keep.append(d)
        self._moving = keep
        self._cruise_rows = [
            (d.body_ptr, d.control_ptr, 0.5 * (d.left + d.right)) for d in self._cruising
        ]

    def _cruise(self) -> None:
        """Point each cruising robot's control body along its heading at its steady speed.

        The operations :meth:`_steer` does for such a robot (module docstring), no others.
        """
        cos, sin = math.cos, math.sin
        for body, control, v in self._cruise_rows:
            heading = _get_angle(body)
            _set_velocity(control, (v * cos(heading), v * sin(heading)))

    def _stop_cruising(self, d: _Drive) -> None:
        """Take `d` out of the cruising robots (no-op if it is not there)."""
        if d.cruising:
            d.cruising = False
            self._cruising.remove(d)
            self._cruise_rows = [
                (c.body_ptr, c.control_ptr, 0.5 * (c.left + c.right)) for c in self._cruising
            ]

    def _wake(self, d: _Drive) -> None:
        """Put `d` among the robots :meth:`step` steers (no-op if it is there already)."""
        if d.cruising:
            self._stop_cruising(d)
        if not d.moving and not d.at_rest():
            d.moving = True
            self._moving.append(d)
            self._moving.sort(key=_row_of)  # the robots' order, as before

    def _perturb_ball(self) -> None:
        """Ball-motion noise and the stop threshold, every noise period."""
        b = self.preset.ball
        v = _get_velocity(self._ball_ptr)
        vx, vy = v.x, v.y
        speed = math.hypot(vx, vy)
        if speed < b.stop_speed_mps:
            if speed > 0.0:
                _set_velocity(self._ball_ptr, (0.0, 0.0))
            return
        if b.motion_noise == 0.0:
            return
        assert self._noise is not None
        amp = b.motion_noise * speed
        nx, ny = self._noise.pair()
        _set_velocity(self._ball_ptr, self._clamp_speed(vx + amp * nx, vy + amp * ny))
