"""Typed, frozen config records of the robot-physics field model, loaded from preset files.

Numbers and their sources: shared `specs/robot_physics.md` §2.5. Every field name carries its
unit. Times that the simulation counts (camera period, latencies, timeouts) must be whole
numbers of physics ticks; :meth:`RobotPhysicsPreset.ticks` converts and refuses anything else,
so that a configured 50 ms latency is exactly 50 ms, never a rounded 45.8.

Every number's range (finite, its sign, a sane maximum) is stated beside its field and checked
whenever a record is built (:mod:`field_models.presets`); the rules between fields (tunnelling,
whole ticks, a robot that fits the table, a ball that fits the goal) are checked on load.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

from field_models.arena import MAX_BALL_NOISE
from field_models.presets import (
    PresetError,
    bounded,
    check_ranges,
    load_record,
    non_negative,
    positive,
    preset_path,
    probability,
    read_preset,
)
from field_models.protocol import Pitch

DEFAULT_PRESET = "small_size_1997"
GRAVITY_MPS2 = 9.81
"""Standard gravity [m/s²]: the tyres' grip is μ·m·g."""


@dataclass(frozen=True, slots=True)
class FieldConfig:
    """The walled field: playing area inside the walls, goals, walls."""

    length_m: float = field(metadata=positive("goal line to goal line, inside the walls", high=100))
    width_m: float = field(metadata=positive("side wall to side wall", high=100))
    goal_width_m: float = field(metadata=positive("between the posts", high=100))
    goal_depth_m: float = field(metadata=positive("goal box depth behind the line", high=10))
    wall_thickness_m: float = field(metadata=positive("static box walls; see tunnelling", high=1))
    corner_fillet_m: float = field(metadata=non_negative("45° corner panel leg length", high=10))

    def __post_init__(self) -> None:
        check_ranges(self)


@dataclass(frozen=True, slots=True)
class KickerConfig:
    """An optional solenoid kicker on the robot's front face."""

    reach_m: float = field(metadata=positive("max gap between front face and ball", high=1))
    max_speed_mps: float = field(metadata=positive("ball speed at kick power 100", high=100))
    half_angle_rad: float = field(
        metadata=positive("ball must be within this of straight ahead", high=math.pi)
    )

    def __post_init__(self) -> None:
        check_ranges(self)


@dataclass(frozen=True, slots=True)
class RobotConfig:
    """A differential-drive mini-robot (square footprint, two wheels)."""

    size_m: float = field(metadata=positive("side of the square footprint", high=1))
    track_m: float = field(metadata=positive("distance between wheel contact points", high=1))
    wheel_radius_m: float = field(metadata=positive(high=1))
    max_wheel_speed_mps: float = field(metadata=positive("wheel surface speed cap", high=20))
    wheel_accel_mps2: float = field(metadata=positive("motor ramp on each wheel's speed", high=200))
    tyre_mu: float = field(
        metadata=positive("tyre-floor friction: traction and skid limit", high=10)
    )
    mass_kg: float = field(metadata=positive(high=100))
    elasticity: float = field(metadata=probability("effective restitution vs the ball"))
    kicker: KickerConfig | None = None
    turn_style: str = "spin"
    """How the host runs a turn followed by a dash: ``"spin"`` in place, then drive (the paper's
    primitives, §2); ``"arc"``: drive forward while turning, with a wheel-speed difference."""
    drive: str = "kinematic"
    """How the world moves the robots: ``"kinematic"``, each tick's wheel ramp and heading set
    from Python (:mod:`.world`); ``"motor"``, Chipmunk alone between drive events (:mod:`.motor`;
    issue 21)."""

    def __post_init__(self) -> None:
        check_ranges(self)

    @property
    def max_turn_rate_radps(self) -> float:
        """Spin rate with the wheels at ±max speed [rad/s]."""
        return 2.0 * self.max_wheel_speed_mps / self.track_m


@dataclass(frozen=True, slots=True)
class BallConfig:
    """A golf ball rolling on the table.

    `motion_noise` is the robot-world counterpart of the Soccer Server's ``ball_rand``
    (soccer_server.md §1.3): every `noise_period_s` the ball's velocity gets a uniform random
    change in [-n·|v|, n·|v|] m/s on each axis, so a resting ball stays at rest and the
    perturbation grows with speed, as the server's does per 100 ms cycle. It is dimensionless.
    """

    radius_m: float = field(metadata=positive(high=0.5))
    mass_kg: float = field(metadata=positive(high=10))
    rolling_decel_mps2: float = field(metadata=positive("constant rolling deceleration", high=100))
    stop_speed_mps: float = field(
        metadata=non_negative("below this the ball is put at rest", high=10)
    )
    wall_restitution: float = field(metadata=probability())
    max_speed_mps: float = field(
        metadata=positive("fastest ball; speeds are clamped to it", high=100)
    )
    motion_noise: float = field(
        default=0.0, metadata=non_negative("ball_rand counterpart", high=MAX_BALL_NOISE)
    )
    noise_period_s: float = field(
        default=0.1, metadata=positive("how often noise is applied", high=60)
    )

    def __post_init__(self) -> None:
        check_ranges(self)


@dataclass(frozen=True, slots=True)
class CameraConfig:
    """The overhead camera: frame rate, latency, noise, missed detections."""

    frame_rate_hz: float = field(metadata=positive(high=1000))
    latency_s: float = field(metadata=non_negative("capture to delivery at the host", high=10))
    position_sigma_m: float = field(metadata=non_negative("Gaussian noise per axis", high=1))
    heading_sigma_rad: float = field(metadata=non_negative(high=math.pi))
    ball_miss_prob: float = field(metadata=probability("per frame"))
    robot_miss_prob: float = field(metadata=probability("per robot per frame"))
    perfect: bool = False

    def __post_init__(self) -> None:
        check_ranges(self)


@dataclass(frozen=True, slots=True)
class LinkConfig:
    """The host-to-robot radio/infrared link."""

    packets_per_s: float = field(metadata=positive("one command per packet", high=10_000))
    latency_s: float = field(metadata=non_negative(high=10))
    loss_prob: float = field(metadata=probability("per packet"))

    def __post_init__(self) -> None:
        check_ranges(self)


@dataclass(frozen=True, slots=True)
class FirmwareConfig:
    """The robot's on-board loop that runs the newest command it received."""

    timeout_s: float = field(
        metadata=positive("stop when no command arrives for this long", high=60)
    )

    def __post_init__(self) -> None:
        check_ranges(self)


@dataclass(frozen=True, slots=True)
class TimingConfig:
    """The physics step and the solver settings."""

    physics_hz: float = field(metadata=bounded(240, 10_000, "ticks per second; >= 240: tunnelling"))
    solver_iterations: int = field(metadata=bounded(1, 1000, "Chipmunk's iterations per step"))
    collision_slop_m: float = field(
        metadata=positive("pymunk default 0.1 is 10 cm in SI", high=0.1)
    )

    def __post_init__(self) -> None:
        check_ranges(self)


@dataclass(frozen=True, slots=True)
class RobotPhysicsPreset:
    """Everything the robot-physics field model and its camera, link and firmware need."""

    name: str
    field: FieldConfig
    robot: RobotConfig
    ball: BallConfig
    camera: CameraConfig
    link: LinkConfig
    firmware: FirmwareConfig
    timing: TimingConfig
    source: str = ""

    @property
    def dt_s(self) -> float:
        """Length of one physics tick [s]."""
        return 1.0 / self.timing.physics_hz

    def ticks(self, seconds: float, what: str, *, least: int = 0) -> int:
        """Convert a duration to whole ticks, refusing one that is not a whole number of ticks.

        `least`: the fewest ticks allowed (1 for a period: a period of 0 ticks never ends).
        """
        exact = seconds * self.timing.physics_hz
        whole = round(exact) if math.isfinite(exact) else -1  # -1: refused just below
        if whole < 0 or abs(exact - whole) > 1e-6:
            raise PresetError(
                f"{self.source or self.name}: key '{what}': expected a whole number of "
                f"{1000 * self.dt_s:.4g} ms ticks, got {seconds!r} s ({exact:.3f} ticks)"
            )
        if whole < least:
            raise PresetError(
                f"{self.source or self.name}: key '{what}': expected at least {least} "
                f"{1000 * self.dt_s:.4g} ms tick(s), got {seconds!r} s"
            )
        return whole

    def pitch(self) -> Pitch:
        """The geometry coaches and recordings see."""
        return Pitch(
            length_m=self.field.length_m,
            width_m=self.field.width_m,
            goal_width_m=self.field.goal_width_m,
            goal_depth_m=self.field.goal_depth_m,
            ball_radius_m=self.ball.radius_m,
            player_radius_m=0.5 * self.robot.size_m,
        )


def load_preset(name_or_path: str = DEFAULT_PRESET) -> RobotPhysicsPreset:
    """Load a robot-physics preset by name (``small_size_1997``, ``vss``) or path.

    A file may start from another preset with ``base = "<name>"`` and state only what differs.

    Raises:
        PresetError: naming the file and the key when the file is missing or wrong.
    """
    path = preset_path(name_or_path, "robot_physics")
    table = read_preset(path, "robot_physics")
    table.setdefault("name", Path(path).stem)
    preset = load_record(RobotPhysicsPreset, {**table, "source": str(path)}, file=path)
    _validate(preset)
    return preset


ROBOTS_ACROSS = 8
"""A robot's side is at most the table's width over this: five a side fit with room to move."""
TURN_STYLES = ("spin", "arc")
"""The values of ``robot.turn_style``."""
DRIVE_NAMES = ("kinematic", "motor")
"""The values of ``robot.drive``."""


def _validate(p: RobotPhysicsPreset) -> None:
    """Cross-field checks a single key's range cannot express."""
    if p.robot.turn_style not in TURN_STYLES:
        raise PresetError(
            f"{p.source}: key 'robot.turn_style': expected one of {', '.join(TURN_STYLES)}, "
            f"got {p.robot.turn_style!r}"
        )
    if p.robot.drive not in DRIVE_NAMES:
        raise PresetError(
            f"{p.source}: key 'robot.drive': expected one of {', '.join(DRIVE_NAMES)}, "
            f"got {p.robot.drive!r}"
        )
    p.ticks(1.0 / p.camera.frame_rate_hz, "camera.frame_rate_hz", least=1)
    p.ticks(p.camera.latency_s, "camera.latency_s")
    p.ticks(p.link.latency_s, "link.latency_s")
    p.ticks(1.0 / p.link.packets_per_s, "link.packets_per_s", least=1)
    p.ticks(p.firmware.timeout_s, "firmware.timeout_s", least=1)
    p.ticks(p.ball.noise_period_s, "ball.noise_period_s", least=1)
    if p.field.goal_width_m >= p.field.width_m:
        raise PresetError(f"{p.source}: key 'field.goal_width_m': expected < field.width_m")
    if p.field.width_m > p.field.length_m:  # drills measure in length / 105
        raise PresetError(f"{p.source}: key 'field.width_m': expected at most field.length_m")
    # Tunnelling rule (robot_physics.md §3.5): the fastest ball moves less than its radius plus
    # half a wall per tick.
    per_tick = p.ball.max_speed_mps * p.dt_s
    if per_tick >= p.ball.radius_m + 0.5 * p.field.wall_thickness_m:
        raise PresetError(
            f"{p.source}: key 'ball.max_speed_mps': {per_tick * 1000:.1f} mm per tick tunnels "
            "through the walls; lower it, thicken the walls or raise timing.physics_hz"
        )
    if p.robot.track_m > p.robot.size_m * math.sqrt(2):
        raise PresetError(f"{p.source}: key 'robot.track_m': wider than the robot")
    # A team of five lines up across the table with room to move between them.
    if p.robot.size_m > p.field.width_m / ROBOTS_ACROSS:
        raise PresetError(
            f"{p.source}: key 'robot.size_m': expected at most field.width_m / {ROBOTS_ACROSS} "
            f"({p.field.width_m / ROBOTS_ACROSS:g} m), got {p.robot.size_m!r}"
        )
    if 2.0 * p.ball.radius_m >= p.field.goal_width_m:
        raise PresetError(f"{p.source}: key 'ball.radius_m': the ball does not fit in the goal")
