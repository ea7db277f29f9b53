"""The one interface every field model implements, and the facts it tells the code above it.

An *arena* is a field model together with its sensing and actuation: on the robots, the pymunk
world plus overhead camera, central host, link and firmware; on the Soccer Server model, the
server's dynamics plus its see/hear messages and command queue. The runner drives it tick by
tick (DESIGN.md §2)::

    percepts = arena.step()              # one tick; percepts that reached clients now
    for p in percepts:
        arena.submit(p.player, mind.act(p))   # acted on from the next tick

Coaches use the truth side (place objects, read exact state); skills only ever get percepts.

**Facts.** Code above the percept/action line never names a concrete model or reads its preset.
What a drill, a report or a recording needs to know about a field — the pitch, the tick, how
often percepts come, how the ball slows down, whether players can kick and how hard — comes
from :class:`FieldFacts` (``arena.facts``, or :func:`field_models.registry.field_facts` before
an arena exists). A new field model fills the same record and passes the conformance suite
(:mod:`field_models.checker`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, fields
from typing import Literal, Protocol, runtime_checkable

from field_models.protocol import Action, BodyState, Percept, Pitch, PlayerRef, Truth

SERVER_PITCH_LENGTH_M = 105.0
"""The Soccer Server's pitch length: the paper's drills are drawn in metres of this pitch."""

EventChannel = Literal["command", "see", "hear", "referee", "link", "decision"]
"""What an :class:`ArenaEvent` is about: a command sent, a percept or message as the client got
it (``see``, ``hear``), a referee call, a lost packet, a mind's decision."""

PlayerShape = Literal["square", "circle"]
"""A player's footprint: the robots' square body, the Soccer Server's circle."""

BallLawKind = Literal["geometric", "constant"]
"""How a free ball slows down: see :class:`BallLaw`."""


@dataclass(frozen=True, slots=True)
class ArenaEvent:
    """Something worth a line in a recording or trace: a command sent, a see, a goal.

    Attributes:
        tick: When it happened.
        channel: What it is about (:data:`EventChannel`).
        text: The line itself: a command or message in the Soccer Server's text form
            (:mod:`field_models.commands`), a primitive sent, a referee call.
        player: The player it concerns, if any.
    """

    tick: int
    channel: EventChannel
    text: str
    player: PlayerRef | None = None


@dataclass(frozen=True, slots=True)
class BallLaw:
    """How a free ball slows down on a field: no noise, no contacts.

    ``"geometric"`` (the Soccer Server, `specs/soccer_server.md` §1.2): in each tick the ball
    moves v·dt, then continues at ``decay_per_tick``·v. ``"constant"`` (a ball rolling on the
    robots' table): it loses ``decel_mps2`` of speed per second until it stops.

    Attributes:
        kind: ``"geometric"`` or ``"constant"``.
        dt_s: The field's tick [s].
        decay_per_tick: Speed factor per tick (geometric) [-].
        decel_mps2: Deceleration (constant) [m/s²].
    """

    kind: BallLawKind
    dt_s: float
    decay_per_tick: float = 1.0
    decel_mps2: float = 0.0

    def distance_in(self, speed_mps: float, time_s: float) -> float:
        """Distance [m] a ball leaving at `speed_mps` covers in `time_s` (it may have stopped).

        On the geometric law `time_s` counts whole and fractional ticks alike.
        """
        if self.kind == "constant":
            a = self.decel_mps2
            if a == 0.0:
                return speed_mps * time_s
            stop = speed_mps / a
            t = min(time_s, stop)
            return speed_mps * t - 0.5 * a * t * t
        n, d, step = time_s / self.dt_s, self.decay_per_tick, speed_mps * self.dt_s
        return step * n if d >= 1.0 else step * (1.0 - d**n) / (1.0 - d)

    def time_to_cover(self, distance_m: float, speed_mps: float) -> float | None:
        """Time [s] a ball leaving at `speed_mps` takes to cover `distance_m`; None: never.

        On the geometric law the time is a fractional number of ticks: the closed form of
        ``distance = v·dt·(1 - d^n) / (1 - d)`` solved for n.
        """
        if speed_mps <= 0.0:
            return None
        if self.kind == "constant":
            a = self.decel_mps2
            if a == 0.0:
                return distance_m / speed_mps
            disc = speed_mps * speed_mps - 2.0 * a * distance_m
            return None if disc < 0.0 else (speed_mps - math.sqrt(disc)) / a
        step, d = speed_mps * self.dt_s, self.decay_per_tick
        if d >= 1.0:
            return distance_m / step * self.dt_s
        left = 1.0 - distance_m * (1.0 - d) / step
        if left <= 0.0 or d <= 0.0:
            return None
        return math.log(left) / math.log(d) * self.dt_s

    def speed_to_cover(self, distance_m: float, time_s: float) -> float | None:
        """Launch speed [m/s] that covers `distance_m` in exactly `time_s`; None: impossible.

        Impossible on the constant law when the ball would have stopped before `time_s`.
        """
        if time_s <= 0.0:
            return None
        if self.kind == "constant":
            speed = distance_m / time_s + 0.5 * self.decel_mps2 * time_s
            return None if speed - self.decel_mps2 * time_s <= 0.0 else speed
        n, d = time_s / self.dt_s, self.decay_per_tick
        per_tick = distance_m / n if d >= 1.0 else distance_m * (1.0 - d) / (1.0 - d**n)
        return per_tick / self.dt_s


@dataclass(frozen=True, slots=True)
class KickFacts:
    """What a player's kick can do to the ball.

    Attributes:
        speed_per_power_mps: Ball speed per unit of kick power, from rest [m/s].
        max_speed_mps: The fastest ball a kick can give [m/s].
        reach_m: Largest centre-to-centre distance at which a kick reaches the ball [m].
        aimable: True where the kick takes a direction (the Soccer Server's ``(kick P D)``);
            False where it fires along the heading (a solenoid kicker).
        half_angle_rad: The ball must lie within this of the heading [rad] (π: anywhere).
    """

    speed_per_power_mps: float
    max_speed_mps: float
    reach_m: float
    aimable: bool
    half_angle_rad: float

    def speed(self, power: float) -> float:
        """Ball speed [m/s] of a kick with `power` on a ball at rest."""
        return min(power * self.speed_per_power_mps, self.max_speed_mps)

    def power_for(self, speed_mps: float) -> float | None:
        """The power that gives `speed_mps`; None above the kick's top speed."""
        if speed_mps > self.max_speed_mps:
            return None
        return speed_mps / self.speed_per_power_mps


@dataclass(frozen=True, slots=True)
class FieldFacts:
    """What code above the percept/action line may know about a field model (module docstring).

    Attributes:
        model: The registered field model's name (for reports and file names; never branch on
            it above the line).
        preset: The preset's name.
        pitch: Field geometry.
        dt_s: One tick [s].
        sensor_period_s: Time between two percepts of one player [s].
        sensor_latency_s: Time from the sensor's sample to the percept [s], or None where the
            model has no such delay to set (an override is refused there).
        ball: How a free ball slows down.
        ball_max_speed_mps: The fastest the ball can move [m/s].
        ball_noise: Ball-motion noise: each period the velocity gets a uniform change in
            ±noise·|v| per axis (the Soccer Server's ``ball_rand``) [-].
        ball_noise_period_s: How often that noise acts [s].
        kick: The players' kick, or None where they have none (robots then push the ball).
        player_top_speed_mps: A player's top speed running straight [m/s].
        player_accel_mps2: A player's largest acceleration from rest [m/s²].
        heading_sigma_rad: Noise on the heading the sensor gives of a player [rad] (0: exact).
        player_shape: Footprint, for drawing.
        perfect_perception: The sensor runs without noise, misses or latency.
        say_max_chars: The longest message a ``Say`` may carry [characters]; None: no limit
            (the robots' host relays any text).
        walled: Walls close the field: the ball bounces back and never leaves it (the robots'
            table). False: the ball can cross the lines, and a referee restarts play.
        turn_inertia_s_per_m: A turn of a player moving at v [m/s] turns it by the commanded
            angle / (1 + this · v) (the Soccer Server's inertia moment, per second); 0 where
            speed does not shorten turns (the robots).
        landmarks: Where the landmarks a percept may name stand, as (name, x [m], y [m]) in
            the field frame: what a client knows of the field to localise itself by.
        dash_rates: (side, back): the share of a dash's push at ±90° and at 180° from the
            heading, linear between (:meth:`dash_factor`; the Soccer Server's
            ``side_dash_rate`` and ``back_dash_rate``, §2.1); None where a dash runs along
            the heading only (the 1996 servers, the robots).
        dash_angle_step_rad: Dash directions are rounded to multiples of this [rad] (0: not
            rounded; the Soccer Server's ``dash_angle_step``).
    """

    model: str
    preset: str
    pitch: Pitch
    dt_s: float
    sensor_period_s: float
    sensor_latency_s: float | None
    ball: BallLaw
    ball_max_speed_mps: float
    ball_noise: float
    ball_noise_period_s: float
    kick: KickFacts | None
    player_top_speed_mps: float
    player_accel_mps2: float
    heading_sigma_rad: float
    player_shape: PlayerShape
    perfect_perception: bool = False
    say_max_chars: int | None = None
    walled: bool = False
    turn_inertia_s_per_m: float = 0.0
    landmarks: tuple[tuple[str, float, float], ...] = ()
    dash_rates: tuple[float, float] | None = None
    dash_angle_step_rad: float = 0.0
    _hash: int = field(init=False, repr=False, compare=False, default=0)

    def __post_init__(self) -> None:
        # Drills key caches by facts once per trial; hashing the nested records each time
        # would cost more than the look-up saves.
        values = tuple(getattr(self, f.name) for f in fields(self) if f.name != "_hash")
        object.__setattr__(self, "_hash", hash(values))

    def __hash__(self) -> int:
        return self._hash

    @property
    def unit_m(self) -> float:
        """One metre of the Soccer Server's pitch on this field: pitch length / 105 [m]."""
        return self.pitch.length_m / SERVER_PITCH_LENGTH_M

    @property
    def touch_distance_m(self) -> float:
        """Centre distance at which a player's body touches the ball [m]."""
        return self.pitch.player_radius_m + self.pitch.ball_radius_m

    def dash_factor(self, direction_rad: float) -> float:
        """The share of a full dash's push that a dash toward `direction_rad` (relative) gets.

        The Soccer Server's rule as
        :func:`field_models.soccer_server.cycle_rules.dash_rate` has it (a test checks the
        two agree): 1 straight ahead, the side rate at ±90°, the back rate at 180°, linear
        between. Without directed dashes only straight ahead pushes.
        """
        a = abs(direction_rad)
        if self.dash_rates is None:
            return 1.0 if a == 0.0 else 0.0
        side, back = self.dash_rates
        half_pi = 0.5 * math.pi
        if a > half_pi:
            rate = back - (back - side) * (1.0 - (a - half_pi) / half_pi)
        else:
            rate = side + (1.0 - side) * (1.0 - a / half_pi)
        return min(max(rate, 0.0), 1.0)


@dataclass(frozen=True, slots=True)
class FieldOptions:
    """Settings a run may change on any field model; None keeps the preset's value.

    A model refuses, with a ValueError naming the setting, one it cannot apply (e.g. a sensor
    latency on a model without one).

    Attributes:
        perfect_perception: Sensor without noise, misses or latency.
        ball_noise: Ball-motion noise (:attr:`FieldFacts.ball_noise`) [-].
        ball_noise_period_s: How often ball noise acts [s].
        sensor_latency_s: Sensor latency [s].
        all_landmarks: Percepts carry every landmark the sensor sees (the Soccer Server's
            flags as well as the goals), for clients that localise themselves; a sensor that
            gives only the goals ignores it. None: the model's default (the goals only).
    """

    perfect_perception: bool = False
    ball_noise: float | None = None
    ball_noise_period_s: float | None = None
    sensor_latency_s: float | None = None
    all_landmarks: bool | None = None

    def __post_init__(self) -> None:
        _check_setting("ball_noise", self.ball_noise, allow_zero=True, high=MAX_BALL_NOISE)
        _check_setting("ball_noise_period_s", self.ball_noise_period_s, allow_zero=False,
                       high=MAX_PERIOD_S)  # fmt: skip
        _check_setting("sensor_latency_s", self.sensor_latency_s, allow_zero=True,
                       high=MAX_LATENCY_S)  # fmt: skip


MAX_BALL_NOISE = 1.0
"""The largest ball-motion noise a run may set [-]: at 1 a perturbation is as large as the
ball's speed (the presets' own limit on ``ball_rand`` and ``motion_noise``)."""
MAX_PERIOD_S = 60.0
"""The longest ball-noise period a run may set [s]."""
MAX_LATENCY_S = 10.0
"""The longest sensor latency a run may set [s]."""


def _check_setting(name: str, value: float | None, *, allow_zero: bool, high: float) -> None:
    """Refuse NaN, infinities, values below 0 (0 where a period is meant) or above `high`."""
    if value is None:
        return
    if not math.isfinite(value) or value < 0.0 or (value == 0.0 and not allow_zero):
        bound = ">= 0" if allow_zero else "> 0"
        raise ValueError(f"{name} must be a finite number {bound}, got {value!r}")
    if value > high:
        raise ValueError(f"{name} must be at most {high:g}, got {value!r}")


class Arena(Protocol):
    """A field model with sensing and actuation, stepped one integer tick at a time."""

    facts: FieldFacts
    """What the code above the line may know about this field."""
    players: tuple[PlayerRef, ...]
    """Players on the field, in a fixed order."""

    @property
    def tick(self) -> int:
        """Ticks stepped since the trial began."""
        ...

    # --- coach side: truth ---------------------------------------------------------------
    def place_player(self, ref: PlayerRef, x: float, y: float, heading: float) -> None:
        """Put a player at rest at (x, y) [m] facing `heading` [rad]."""
        ...

    def place_ball(self, x: float, y: float, vx: float = 0.0, vy: float = 0.0) -> None:
        """Put the ball at (x, y) [m] with velocity (vx, vy) [m/s]."""
        ...

    def ball_state(self) -> BodyState:
        """The ball's exact state (coach only)."""
        ...

    def player_state(self, ref: PlayerRef) -> BodyState:
        """A player's exact state (coach only)."""
        ...

    def truth(self) -> Truth:
        """Exact state of everything (coach and recordings only)."""
        ...

    def score(self) -> tuple[int, int]:
        """Goals of the left and the right team so far, as the field's own referee counts them.

        (0, 0) on a field without a referee; coaches then judge goals themselves.
        """
        ...

    # --- client side: percepts and actions -------------------------------------------------
    def step(self) -> list[Percept]:
        """Advance one tick; return the percepts that reach their clients at the new tick."""
        ...

    def listen(self, refs: frozenset[PlayerRef]) -> None:
        """Build percepts only for these players from now on (default: every player).

        The runner calls it with the players whose minds still think; a field model may then
        skip sensing the others (a speed-up: their percepts would go unread).
        """
        ...

    def submit(self, ref: PlayerRef, actions: tuple[Action, ...]) -> None:
        """Hand a client's actions to the actuation path (acted on from the next tick)."""
        ...

    def drain_events(self) -> list[ArenaEvent]:
        """Events since the last call (commands, sees, losses, referee calls), oldest first.

        Only kept when the arena was built with ``keep_events`` (or ``trace``: then every see
        and hear a client gets is an event too, in the Soccer Server's text form).
        """
        ...


# ----------------------------------------------------------------------------- command counts

COMMAND_COUNTERS = (
    "kick",
    "dash",
    "turn",
    "catch",
    "move",
    "turn_neck",
    "change_view",
    "say",
    "tackle",
    "pointto",
    "attentionto",
)
"""The commands a Soccer Server counts for each player, in the order its monitors and game logs
list them (rcssserver 19's ``(c ...)`` of a show: ``Player``'s counters)."""


@dataclass(frozen=True, slots=True)
class CommandTally:
    """One player's commands as a Soccer Server counts them, and what the last tick's kick did.

    Attributes:
        counts: How many of each command the server carried out since the trial began, one
            per :data:`COMMAND_COUNTERS` (a command the field model has no action for stays 0).
        kicked: A kick took effect in the last tick (the ball was within the kickable area).
        kick_missed: A kick was carried out in the last tick with the ball out of reach.
    """

    counts: tuple[int, ...]
    kicked: bool = False
    kick_missed: bool = False


@runtime_checkable
class CountsCommands(Protocol):
    """An arena that counts its players' commands as a Soccer Server does (an optional extra).

    Game logs in the server's format carry these counts; a field model without them is logged
    with zeros.
    """

    def command_tally(self) -> dict[PlayerRef, CommandTally]:
        """Every player's counts after the last tick."""
        ...


@runtime_checkable
class WheelDrive(Protocol):
    """An arena whose players can be driven wheel by wheel (an optional extra: the robots).

    A per-step controller (:mod:`robotsoccer.envs.control`) asks for it: it sends wheel speeds
    through the same actuation path as every other action (on the robots: host, link,
    firmware), and can switch that path's imperfections off.
    """

    def submit_wheels(self, ref: PlayerRef, left_mps: float, right_mps: float) -> None:
        """Drive `ref`'s wheels at these speeds [m/s] (capped at the top wheel speed) from now.

        Replaces the player's pending actions, as a new decision does; the command is held for
        the actuation path's hold time (a lost packet does not stall the player), after which
        the player stops unless a newer command came.
        """
        ...

    def ideal_actuation(self) -> None:
        """From now on, commands reach the players at once and always.

        No latency, no loss, no watchdog: the actuation twin of ``perfect_perception``.
        """
        ...
