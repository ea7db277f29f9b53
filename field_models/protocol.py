"""Records shared by both field models and the client code: who, what is seen, what is done.

Everything is SI inside (metres, seconds, radians). Angles are counter-clockwise positive in a
right-handed field frame (x toward the right goal, y up); egocentric angles are measured from
the player's head (its heading plus ``Percept.neck_rad``, which is 0 unless a Soccer Server
player turned its neck), positive to its left. Degrees appear only at the Soccer Server's message
edge (`field_models.soccer_server`), never here.

The percept is what the paper's clients see (DESIGN.md §2): it carries no truth. The truth
records are what a coach sees.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from enum import IntEnum
from typing import NamedTuple, Protocol, TypeAlias, TypeVar

import numpy as np

LEFT = "left"
"""Team name of the side that defends the goal at x < 0."""
RIGHT = "right"
"""Team name of the side that defends the goal at x > 0."""


@dataclass(frozen=True, slots=True, order=True)
class PlayerRef:
    """A player (robot) identity: its team and uniform number (robot id)."""

    team: str
    number: int

    def __str__(self) -> str:
        return f"{self.team}{self.number}"


# ----------------------------------------------------------------------------- percepts


@dataclass(frozen=True, slots=True)
class SeenBall:
    """The ball as one player perceives it.

    Attributes:
        distance_m: Distance from the player's centre [m].
        angle_rad: Direction relative to the player's head (its heading plus the percept's
            ``neck_rad``, 0 without a neck), left positive [rad].
        distance_change_mps: Rate of change of the distance, when the sensor reports it [m/s].
        angle_change_radps: Rate of change of the direction, when reported [rad/s].
    """

    distance_m: float
    angle_rad: float
    distance_change_mps: float | None = None
    angle_change_radps: float | None = None


@dataclass(frozen=True, slots=True)
class SeenPlayer:
    """Another player as one player perceives it; team or number is None when not known."""

    distance_m: float
    angle_rad: float
    team: str | None = None
    number: int | None = None


@dataclass(frozen=True, slots=True)
class SeenLandmark:
    """A fixed landmark as one player perceives it, named as the Soccer Server names it.

    Goals are ``"g l"`` and ``"g r"`` (the centres of the left and right goal lines); the Soccer
    Server model adds its flags (``"f c t"``, ...). On the robots the host derives the goals from
    the robot's detected pose on the known field.
    """

    name: str
    distance_m: float
    angle_rad: float


@dataclass(frozen=True, slots=True)
class Heard:
    """A message heard: its text, who said it (when known) and from which direction."""

    text: str
    sender: PlayerRef | None = None
    direction_rad: float | None = None
    tick: int = 0


@dataclass(frozen=True, slots=True)
class Percept:
    """One player's egocentric view at one decision time.

    Attributes:
        player: Whose view this is.
        tick: Tick at which the percept reached the client (decision time).
        observed_tick: Tick at which the sensor sampled the world (tick minus latency).
        ball: The ball, or None where the sensor gave nothing.
        players: Other players seen (teammates and opponents).
        heard: Messages heard since the previous percept.
        landmarks: Landmarks seen (goals, flags); empty where the sensor gives none.
        neck_rad: The neck angle relative to the body when the sensor sampled [rad], left
            positive. Every angle above is measured from the head (body + neck), as the
            Soccer Server's see is (spec §3.1); 0 where there is no neck (the robots) or it
            was never turned, so head and body agree. :meth:`body_relative` re-measures the
            angles from the body.
    """

    player: PlayerRef
    tick: int
    observed_tick: int
    ball: SeenBall | None
    players: tuple[SeenPlayer, ...] = ()
    heard: tuple[Heard, ...] = ()
    landmarks: tuple[SeenLandmark, ...] = ()
    neck_rad: float = 0.0

    def landmark(self, name: str) -> SeenLandmark | None:
        """The landmark called `name`, if seen."""
        for mark in self.landmarks:
            if mark.name == name:
                return mark
        return None

    def body_relative(self) -> Percept:
        """This percept with every direction measured from the body (``neck_rad`` 0).

        A mind that turns the neck reasons about where its body points; a percept whose neck
        is already 0 comes back as it is.
        """
        neck = self.neck_rad
        if neck == 0.0:
            return self
        ball = self.ball
        if ball is not None:
            ball = SeenBall(
                ball.distance_m,
                wrap_angle(ball.angle_rad + neck),
                ball.distance_change_mps,
                ball.angle_change_radps,
            )
        players = tuple(
            SeenPlayer(p.distance_m, wrap_angle(p.angle_rad + neck), p.team, p.number)
            for p in self.players
        )
        marks = tuple(
            SeenLandmark(m.name, m.distance_m, wrap_angle(m.angle_rad + neck))
            for m in self.landmarks
        )
        return Percept(
            self.player, self.tick, self.observed_tick, ball, players, self.heard, marks, 0.0
        )


# ----------------------------------------------------------------------------- actions


@dataclass(frozen=True, slots=True)
class Turn:
    """Turn the body by `angle_rad` (left positive). The Soccer Server's `(turn Moment)`."""

    angle_rad: float


@dataclass(frozen=True, slots=True)
class Dash:
    """Run with `power` (server units) toward `direction_rad` relative to the heading.

    The Soccer Server's ``(dash Power Direction)`` (rcssserver >= 13; the direction is 0 in the
    one-argument form and in the paper's era). On the robots the host maps power to a wheel
    speed, power/100 of the robot's top speed, and a direction to a turn first.
    """

    power: float
    direction_rad: float = 0.0


@dataclass(frozen=True, slots=True)
class Kick:
    """Kick with `power` (server units, [0, 100]) toward `direction_rad` relative to the heading."""

    power: float
    direction_rad: float


@dataclass(frozen=True, slots=True)
class TurnNeck:
    """Turn the neck by `angle_rad` (left positive). The Soccer Server's ``(turn_neck Moment)``.

    The neck angle is relative to the body and stays within the server's ``minneckang`` ..
    ``maxneckang`` (±90°, spec §2.2); the view points along body + neck. It is not a body
    command: it may go in the same cycle as a turn, dash or kick (spec §1.1). On the robots
    (an overhead camera sees the whole field, there is no head to turn) it is accepted and
    does nothing, so one client's code runs on both field models.
    """

    angle_rad: float


@dataclass(frozen=True, slots=True)
class ChangeView:
    """Change the view: the Soccer Server's ``(change_view Width Quality)`` (spec §3.1).

    `width` is ``"narrow"``, ``"normal"`` or ``"wide"`` (cone ×½, ×1, ×2 and see interval the
    same), `quality` ``"high"`` or ``"low"`` (low: no distances, see interval halved). Not a
    body command (spec §1.1). On the robots, whose camera has one fixed view, it is accepted
    and does nothing, as :class:`TurnNeck`.
    """

    width: str = "normal"
    quality: str = "high"

    def __post_init__(self) -> None:
        if self.width not in VIEW_WIDTHS:
            raise ValueError(f"view width {self.width!r}: expected one of {VIEW_WIDTHS}")
        if self.quality not in VIEW_QUALITIES:
            raise ValueError(f"view quality {self.quality!r}: expected one of {VIEW_QUALITIES}")


VIEW_WIDTHS = ("narrow", "normal", "wide")
"""The widths of :class:`ChangeView`."""
VIEW_QUALITIES = ("high", "low")
"""The qualities of :class:`ChangeView`."""


@dataclass(frozen=True, slots=True)
class Say:
    """Broadcast a short text message to players within hearing range."""

    text: str


Action: TypeAlias = Turn | Dash | Kick | Say | TurnNeck | ChangeView
"""The action vocabulary shared by both field models (DESIGN.md §2).

Turn, dash and kick are body commands (one per server cycle); say, turn_neck and change_view
go with them (spec §1.1)."""

SIDE_ACTIONS = (Say, TurnNeck, ChangeView)
"""The actions that are not body commands: each field model carries them out at once."""


class Mind(Protocol):
    """A client mind: turns a percept into body actions and says.

    A mind whose work is over (a shooter that has kicked) may set an attribute ``done = True``;
    the runner then stops sending it percepts.
    """

    def act(self, percept: Percept) -> tuple[Action, ...]:
        """Decide what to do on this percept."""
        ...


# ----------------------------------------------------------------------------- truth


class BodyState(NamedTuple):
    """Planar state of a body in the field frame: position [m], heading [rad], velocity [m/s].

    A named tuple rather than a frozen dataclass: coaches read one every tick, and a tuple is
    built several times faster.
    """

    x: float
    y: float
    heading: float
    vx: float = 0.0
    vy: float = 0.0

    @property
    def speed(self) -> float:
        """Speed [m/s]."""
        return math.hypot(self.vx, self.vy)


@dataclass(frozen=True, slots=True)
class Truth:
    """What the coach sees at one tick: the exact state of every object."""

    tick: int
    time_s: float
    ball: BodyState
    players: dict[PlayerRef, BodyState] = field(default_factory=dict)


@dataclass(frozen=True, slots=True)
class Pitch:
    """Field geometry both models expose to coaches and recordings.

    The field is centred on the origin; goals are centred on the lines x = ±length_m/2.

    Attributes:
        length_m: Length between the goal lines [m].
        width_m: Width between the side lines (or walls) [m].
        goal_width_m: Distance between the posts' inner edges [m].
        goal_depth_m: Depth of the goal mouth behind the line [m].
        ball_radius_m: Ball radius [m], for "wholly over the line" tests and drawing.
        player_radius_m: Player body half-size [m], for drawing.
        goal_post_radius_m: Widens the goal mouth by one post radius on each side, as the
            Soccer Server's goal test does (0 where posts are not part of the rule).
    """

    length_m: float
    width_m: float
    goal_width_m: float
    goal_depth_m: float
    ball_radius_m: float
    player_radius_m: float
    goal_post_radius_m: float = 0.0

    @property
    def half_length_m(self) -> float:
        """Half the length [m]."""
        return 0.5 * self.length_m

    @property
    def half_width_m(self) -> float:
        """Half the width [m]."""
        return 0.5 * self.width_m


TWO_PI = 2.0 * math.pi
"""A full turn [rad]."""

Angle = TypeVar("Angle", float, np.ndarray)


def wrap_angle(angle: Angle) -> Angle:
    """Wrap an angle (or an array of them) to [-pi, pi); one already inside comes back unchanged.

    The project's one angle wrap: every model, sensor and skill calls it.

    >>> round(wrap_angle(3 * math.pi / 2), 6)
    -1.570796
    >>> wrap_angle(0.1) == 0.1
    True
    """
    if type(angle) is not float and isinstance(angle, np.ndarray):  # floats skip the check
        inside = (angle >= -math.pi) & (angle < math.pi)
        return np.where(inside, angle, (angle + math.pi) % TWO_PI - math.pi)
    if -math.pi <= angle < math.pi:
        return angle
    return (angle + math.pi) % TWO_PI - math.pi


# ----------------------------------------------------------------------------- goal lines


class Crossing(IntEnum):
    """How the ball's centre crossed an end line during one step (see :func:`end_line_crossing`).

    The sign says which end: positive the right-hand line (x = +length/2, the goal the left
    team attacks), negative the left-hand line.
    """

    NONE = 0
    RIGHT_GOAL = 1
    LEFT_GOAL = -1
    RIGHT_WIDE = 2
    LEFT_WIDE = -2

    @property
    def is_goal(self) -> bool:
        """Whether the ball went in (between the posts)."""
        return abs(self) == 1


_NO_CROSSING = Crossing.NONE  # looked up once: coaches call the rule every tick


def end_line_crossing(pitch: Pitch, x0: float, y0: float, x1: float, y1: float) -> Crossing:
    """Whether the ball's step (x0, y0) → (x1, y1) took it wholly over an end line, and where.

    The project's one goal-line rule, the Soccer Server's (shared `specs/soccer_server.md` §6):
    the ball's centre goes from |x| <= length/2 + ball radius to beyond it, and the straight
    segment of the step crosses that line at |y| <= goal_width/2 + goal_post_radius (a goal)
    or farther out (wide). Referees, coaches and judges of both field models call it.

    >>> pitch = Pitch(105.0, 68.0, 14.02, 2.44, 0.085, 0.8)
    >>> end_line_crossing(pitch, 52.0, 7.0, 53.0, 7.0).name
    'RIGHT_GOAL'
    >>> end_line_crossing(pitch, 52.0, 7.1, 53.0, 7.1).name
    'RIGHT_WIDE'
    """
    line = 0.5 * pitch.length_m + pitch.ball_radius_m
    if abs(x1) <= line or abs(x0) > line:
        return _NO_CROSSING
    edge = line if x1 > 0.0 else -line
    y_cross = y0 + (edge - x0) * (y1 - y0) / (x1 - x0)
    side = 1 if x1 > 0.0 else -1
    if abs(y_cross) > 0.5 * pitch.goal_width_m + pitch.goal_post_radius_m:
        return Crossing(2 * side)
    return Crossing(side)
