"""Rerun recordings of trials, and reading, verifying and replaying them (DESIGN.md §5).

A :class:`TrialRecorder` writes one ``.rrd`` file per trial with a default layout (blueprint):
the field on the left, a legend and the events on the right, the time panel below.

The field shows the pitch's markings (boundary, centre line and circle, penalty areas, goals
and posts) once as static geometry; every recorded tick the true ball and players (filled
discs labelled with the player ids, rotated outlines, heading arrows); what each player
*perceived*, converted to the field frame, as hollow rings in a colour of its own, cleared once
that player's latest percept is older than :data:`PERCEPT_LIFETIME_PERIODS` sensor periods; and,
from the verdict on, the outcome above the field with the field's boundary in the outcome's
colour. Small things are drawn no smaller than a fraction of the pitch length
(:func:`draw_sizes`), so the Soccer Server's ball shows on its large pitch; the legend says
which sizes are enlarged. Everything sits on a ``sim_time`` duration timeline derived from
integer ticks × ``dt_s`` (plus a ``tick`` sequence timeline with the raw tick), never on
wall-clock time.

Rerun draws 2-D views with y pointing down, and ignores view coordinates in 2-D views (upstream
issue rerun-io/rerun#1387). The data therefore stay in the field frame (y up), so what is read
back is what was logged, and a static ``Transform3D(scale=[1, -1, 1])`` on the ``field``
entity turns them the right way up in the view, which shows the root frame.

Speed (notes/tooling.md §1.4): ``rr.log`` costs ~100 µs per call, so the recorder never logs
in the simulation loop. It appends plain floats to per-entity buffers and sends them with
``send_columns`` in chunks of ``chunk_frames`` recorded ticks, which costs a few µs per tick.

This module and :mod:`~robotsoccer.replay.match_recording` (whole matches, built on
:class:`TrialRecorder`) are the only modules of the project that import ``rerun``, and they do
so inside functions, so ``import robotsoccer`` (and importing them) never loads the 800 MB SDK.

Entity layout (paths are what :func:`read_entity_positions` takes)::

    field                                            Transform3D: the display flip
    field/lines, field/markings, field/goals/<team>, field/posts    static pitch geometry
    field/ball                                       Points2D, one point per recorded tick
    field/players/<team>                             Points2D centres, labels = player ids
    field/players/<team>/outline                     LineStrips2D rotated outlines
    field/players/<team>/heading                     Arrows2D headings
    field/perceived/<player>/ball                    Ellipses2D ring (empty row: none current)
    field/perceived/<player>/players                 Ellipses2D rings, labels = team+number seen
    field/outcome, field/outcome/frame               the label above the field, the boundary
    legend                                           TextDocument (markdown), outcome on top
    events/<channel>, events/label                   TextLog, "[channel] player: text"
    events/routine                                   TextLog, routine decisions (turns,
                                                     dashes, nothing); hidden by default

A mind's decision goes to ``events/decision`` when it kicks or says something (a kick, a
pass, a set play's call) and to ``events/routine`` when it only steers (turns and dashes) or
does nothing (:meth:`TrialRecorder.log_decision`): a player decides at every percept, and
those lines would bury the few events a viewer looks for. The default layout leaves
``events/routine`` out of the events view; the blueprint panel can add it back.

Positions are stored as float32 (rerun's ``Vec2D``).
"""

from __future__ import annotations

import math
import os
import re
import subprocess
import sys
import warnings
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from types import TracebackType
from typing import TYPE_CHECKING, Any

import numpy as np

from field_models.arena import ArenaEvent, PlayerShape
from field_models.protocol import (
    LEFT,
    RIGHT,
    Action,
    BodyState,
    Kick,
    Percept,
    Pitch,
    PlayerRef,
    Say,
    Truth,
)

if TYPE_CHECKING:
    import rerun as rr
    import rerun.blueprint as rrb

SIM_TIME = "sim_time"
"""Name of the simulated-time (duration) timeline."""
TICK = "tick"
"""Name of the integer-tick (sequence) timeline."""
PERCEPT_LIFETIME_PERIODS = 1.5
"""A percept is shown until this many sensor periods have passed without a newer one."""
MIN_BALL_FRACTION = 0.006
"""The ball is drawn with a radius of at least this fraction of the pitch length."""
MIN_PLAYER_FRACTION = 0.007
"""Players are drawn with a half-size of at least this fraction of the pitch length."""
ROUTINE_DECISIONS = "events/routine"
"""Entity of routine decisions (turns, dashes, nothing): recorded, hidden by default."""

_TEAM_COLOURS: dict[str, tuple[int, int, int]] = {LEFT: (60, 130, 255), RIGHT: (255, 200, 40)}
_OTHER_TEAM_COLOURS = ((200, 80, 220), (80, 220, 160), (240, 90, 90))
# Percept rings: hues far from the team colours, the ball's orange and the pitch's green.
_PERCEPT_COLOURS = ((255, 70, 220), (70, 235, 235), (255, 255, 255), (190, 150, 255))
_PERCEPT_COLOUR_NAMES = ("magenta", "cyan", "white", "lilac")
_BALL_COLOUR = (255, 120, 0)
_LINE_COLOUR = (230, 230, 230)
_ARROW_COLOUR = (255, 255, 255)
_PITCH_COLOUR = (24, 64, 36)
_OUTCOME_COLOURS: dict[str, tuple[int, int, int]] = {
    "GOAL": (255, 80, 80),
    "SAVE": (90, 235, 120),
    "SUCCESS": (90, 235, 120),
}
_OTHER_OUTCOME_COLOUR = (235, 235, 235)
_CIRCLE_SEGMENTS = 12  # outlines dominate file size; a 12-gon reads as round
_MARKING_SEGMENTS = 48  # the centre circle is drawn once, so it may be smooth
# Draw order (rerun's DrawOrder, larger on top): markings under players under the ball under
# the percept rings, so a ring around the true ball stays visible.
_ORDER_MARKINGS = 10.0
_ORDER_PLAYERS = 30.0
_ORDER_OUTLINE = 31.0
_ORDER_HEADING = 32.0
_ORDER_BALL = 40.0
_ORDER_PERCEPT = 50.0
_ORDER_OUTCOME = 60.0
_NAN3 = (math.nan, math.nan, math.nan)
_ANSI = re.compile(r"\x1b\[[0-9;]*m")
_ENTITY_UNSAFE = re.compile(r"[^A-Za-z0-9_\-]")
# Marking proportions of a 105 m FIFA pitch (the Soccer Server's flags sit on them), scaled by
# the pitch length on any field.
_FIFA_LENGTH_M = 105.0
_CENTRE_CIRCLE_M = 9.15
_PENALTY_DEPTH_M = 16.5
_PENALTY_HALF_WIDTH_M = 20.16


# ----------------------------------------------------------------------------- geometry


@dataclass(frozen=True, slots=True)
class DrawSizes:
    """How large things are drawn on one pitch [m] (field frame).

    Attributes:
        ball_m: Ball radius as drawn.
        player_m: Player half-size (square) or radius (circle) as drawn.
        arrow_length_m: Length of a heading arrow from the player's centre.
        arrow_radius_m: Half the width of a heading arrow's line.
        ball_enlarged: The ball is drawn larger than it is.
        players_enlarged: Players are drawn larger than they are.
    """

    ball_m: float
    player_m: float
    arrow_length_m: float
    arrow_radius_m: float
    ball_enlarged: bool
    players_enlarged: bool


def draw_sizes(pitch: Pitch) -> DrawSizes:
    """Drawing sizes on `pitch`: true sizes, but none smaller than a fraction of its length.

    A ball of a few centimetres on a pitch of a hundred metres would be under a pixel at the
    default zoom; :data:`MIN_BALL_FRACTION` and :data:`MIN_PLAYER_FRACTION` keep it visible.
    Heading arrows reach past the body by a pitch-scaled length so they show at the default zoom.
    """
    length = pitch.length_m
    ball = max(pitch.ball_radius_m, MIN_BALL_FRACTION * length)
    player = max(pitch.player_radius_m, MIN_PLAYER_FRACTION * length)
    return DrawSizes(
        ball_m=ball,
        player_m=player,
        arrow_length_m=player + 0.02 * length,
        arrow_radius_m=0.002 * length,
        ball_enlarged=ball > pitch.ball_radius_m,
        players_enlarged=player > pitch.player_radius_m,
    )


def outline_template(shape: PlayerShape, radius_m: float) -> np.ndarray:
    """Closed outline of a player at the origin facing +x, as a (K, 2) array [m].

    Args:
        shape: ``"square"`` (robot physics: side 2·radius) or ``"circle"`` (Soccer Server).
        radius_m: Half-side of the square or radius of the circle [m].

    Returns:
        The polygon's vertices, first vertex repeated last so the strip closes.

    Raises:
        ValueError: If `shape` is neither ``"square"`` nor ``"circle"``.
    """
    if shape == "square":
        unit = np.array([[1.0, 1.0], [-1.0, 1.0], [-1.0, -1.0], [1.0, -1.0], [1.0, 1.0]])
    elif shape == "circle":
        unit = _unit_circle(_CIRCLE_SEGMENTS)
    else:
        raise ValueError(f"player_shape must be 'square' or 'circle', got {shape!r}")
    return radius_m * unit


def _unit_circle(segments: int) -> np.ndarray:
    """A closed polygon on the unit circle, (segments + 1, 2)."""
    a = np.linspace(0.0, 2.0 * math.pi, segments + 1)
    unit = np.column_stack([np.cos(a), np.sin(a)])
    unit[-1] = unit[0]  # close exactly, not to within rounding
    return unit


def place_outlines(template: np.ndarray, poses: np.ndarray) -> np.ndarray:
    """Rotate and translate an outline to many poses at once.

    Args:
        template: (K, 2) outline at the origin facing +x [m].
        poses: (M, 3) rows of x [m], y [m], heading [rad] in the field frame.

    Returns:
        (M, K, 2) outlines in the field frame [m].
    """
    c = np.cos(poses[:, 2])[:, None]
    s = np.sin(poses[:, 2])[:, None]
    tx = template[None, :, 0]
    ty = template[None, :, 1]
    x = poses[:, 0:1] + c * tx - s * ty
    y = poses[:, 1:2] + s * tx + c * ty
    return np.stack([x, y], axis=-1)


def egocentric_to_field(
    observer: BodyState, distance_m: float, angle_rad: float
) -> tuple[float, float]:
    """Field-frame position of something seen at (distance, egocentric angle) by `observer`.

    Egocentric angles are measured from the heading, left positive (protocol.py), so the
    field direction is heading + angle.
    """
    direction = observer.heading + angle_rad
    return (
        observer.x + distance_m * math.cos(direction),
        observer.y + distance_m * math.sin(direction),
    )


def pitch_lines(pitch: Pitch) -> list[np.ndarray]:
    """Boundary rectangle and centre line of `pitch` as line strips [m]."""
    hl, hw = pitch.half_length_m, pitch.half_width_m
    boundary = np.array([[-hl, -hw], [hl, -hw], [hl, hw], [-hl, hw], [-hl, -hw]])
    centre = np.array([[0.0, -hw], [0.0, hw]])
    return [boundary, centre]


def pitch_markings(pitch: Pitch) -> list[np.ndarray]:
    """Centre circle and penalty areas of `pitch` as line strips [m].

    Sized in a FIFA pitch's proportions scaled by the pitch length (the Soccer Server's
    flags sit on a FIFA pitch; the robot table has no markings of its own). A penalty area is
    left out where it would not fit between the goal and the side lines.
    """
    scale = pitch.length_m / _FIFA_LENGTH_M
    hl, hw = pitch.half_length_m, pitch.half_width_m
    strips = [_CENTRE_CIRCLE_M * scale * _unit_circle(_MARKING_SEGMENTS)]
    depth = _PENALTY_DEPTH_M * scale
    half = _PENALTY_HALF_WIDTH_M * scale
    if 0.5 * pitch.goal_width_m < half < hw and depth < hl:
        for side in (-1.0, 1.0):
            x_line, x_in = side * hl, side * (hl - depth)
            strips.append(np.array([[x_line, -half], [x_in, -half], [x_in, half], [x_line, half]]))
    return strips


def goal_box(pitch: Pitch, side: float) -> np.ndarray:
    """Goal-mouth box behind the line x = side·length/2 (side -1: left, +1: right).

    Returns:
        The (4, 2) vertices of the box's three sides [m].
    """
    x_line = side * pitch.half_length_m
    x_back = side * (pitch.half_length_m + pitch.goal_depth_m)
    g = 0.5 * pitch.goal_width_m
    return np.array([[x_line, -g], [x_back, -g], [x_back, g], [x_line, g]])


def goal_posts(pitch: Pitch) -> np.ndarray:
    """Centres of the four goal posts (at the posts' inner edges) [m], shape (4, 2)."""
    hl, g = pitch.half_length_m, 0.5 * pitch.goal_width_m
    return np.array([[-hl, -g], [-hl, g], [hl, -g], [hl, g]])


# Capital letters as strokes on a 4 × 6 grid (x right, y up), for the outcome drawn large on
# the field (rerun 0.41 draws labels in one small UI font with no size setting). Each glyph is
# its strokes separated by spaces, each stroke its points as digit pairs "xy".
_GLYPHS: dict[str, str] = {
    "A": "0004264440 0343",
    "B": "00063645443303 3342413000",
    "C": "4536160501103041",
    "D": "00062644422000",
    "E": "46060040 0333",
    "F": "460600 0333",
    "G": "45361605011030414323",
    "H": "0006 4046 0343",
    "I": "1636 2620 1030",
    "J": "4641301001",
    "K": "0006 4602 1340",
    "L": "060040",
    "M": "0006234640",
    "N": "00064046",
    "O": "100105163645413010",
    "P": "00063645443303",
    "Q": "100105163645413010 2240",
    "R": "00063645443303 2340",
    "S": "453616050413334241301001",
    "T": "0646 2620",
    "U": "060110304146",
    "V": "062046",
    "W": "0610233046",
    "X": "0046 0640",
    "Y": "062346 2320",
    "Z": "06460040",
    "-": "1333",
    # Digits and the colon, for the score of a match (match_recording.py).
    "0": "100105163645413010",
    "1": "152620 1030",
    "2": "05163645440040",
    "3": "0516364544334241301001 1333",
    "4": "30360242",
    "5": "4606033342413000",
    "6": "4536160501103041423303",
    "7": "064610",
    "8": "13040516364544331302011030414233",
    "9": "0110304145361605041343",
    ":": "2122 2425",
}
_GLYPH_WIDTH, _GLYPH_HEIGHT = 4, 6  # the grid
_GLYPH_ADVANCE = _GLYPH_WIDTH + 2  # from one letter to the next: a letter and a gap


def text_width(text: str, height_m: float) -> float:
    """Width of `text` in the stroke letters of :func:`text_strokes` of height `height_m` [m]."""
    if not text:
        return 0.0
    return ((len(text) - 1) * _GLYPH_ADVANCE + _GLYPH_WIDTH) * height_m / _GLYPH_HEIGHT


def text_strokes(
    text: str, *, height_m: float, centre_x_m: float, base_y_m: float
) -> list[np.ndarray]:
    """`text` in large stroke letters, centred on x = centre_x_m above y = base_y_m [m].

    Capital letters, digits, ``-`` and ``:`` are drawn (lower case as capitals); other
    characters leave a gap. Used for the outcome and a match's score, which must read at a
    glance.

    Returns:
        One (K, 2) line strip per stroke, in the field frame.
    """
    unit = height_m / _GLYPH_HEIGHT
    x0 = centre_x_m - 0.5 * text_width(text, height_m)
    strips: list[np.ndarray] = []
    for i, char in enumerate(text.upper()):
        for stroke in _GLYPHS.get(char, "").split():
            xy = np.array([int(d) for d in stroke], dtype=np.float64).reshape(-1, 2) * unit
            xy[:, 0] += x0 + i * _GLYPH_ADVANCE * unit
            xy[:, 1] += base_y_m
            strips.append(xy)
    return strips


def team_colour(team: str, teams: Sequence[str]) -> tuple[int, int, int]:
    """Display colour of a team: fixed for LEFT/RIGHT, from a small palette otherwise."""
    if team in _TEAM_COLOURS:
        return _TEAM_COLOURS[team]
    others = [t for t in teams if t not in _TEAM_COLOURS]
    index = others.index(team) if team in others else len(others)
    return _OTHER_TEAM_COLOURS[index % len(_OTHER_TEAM_COLOURS)]


def outcome_colour(label: str) -> tuple[int, int, int]:
    """Display colour of a trial label: red for a goal, green for a save, light grey otherwise."""
    return _OUTCOME_COLOURS.get(label, _OTHER_OUTCOME_COLOUR)


def outcome_text(label: str, detail: str = "") -> str:
    """The outcome as shown on the field and in the legend: ``"GOAL — why"``."""
    return f"{label} — {detail}" if detail else label


def recording_name(index: int, label: str) -> str:
    """File name of trial `index`'s recording once its outcome `label` is known.

    ``trial_0007_GOAL.rrd``: the label is made safe for a file name.
    """
    return f"trial_{index:04d}_{entity_name(label)}.rrd"


def _lighter(colour: tuple[int, int, int], amount: float = 0.45) -> tuple[int, int, int]:
    """`colour` mixed with white, for outlines drawn over a disc of that colour."""
    r, g, b = (round(c + amount * (255 - c)) for c in colour)
    return (r, g, b)


def _length_text(metres: float) -> str:
    """A length for the legend: centimetres below a metre, metres above."""
    return f"{100.0 * metres:.3g} cm" if metres < 1.0 else f"{metres:.3g} m"


def _seen_label(team: str | None, number: int | None) -> str:
    """Label of a perceived player: what the sensor identified, '?' for the unknown parts."""
    if team is None and number is None:
        return "?"
    return f"{team if team is not None else '?'}{number if number is not None else '?'}"


def entity_name(text: str) -> str:
    """Make `text` safe as one entity-path part."""
    return _ENTITY_UNSAFE.sub("_", text) or "_"


def time_indexes(ticks: Sequence[int], dt_s: float) -> list[Any]:
    """The ``sim_time`` (ns from integer ticks, never accumulated) and ``tick`` index columns."""
    import rerun as rr

    tick_arr = np.asarray(ticks, dtype=np.int64)
    # Rounded to whole ns per tick, so 1/240 s ticks do not truncate to ...666 ns.
    ns = np.rint(tick_arr * (dt_s * 1e9)).astype(np.int64).astype("timedelta64[ns]")
    return [rr.TimeColumn(SIM_TIME, duration=ns), rr.TimeColumn(TICK, sequence=tick_arr)]


def is_routine(actions: Sequence[Action]) -> bool:
    """Whether a decision only steers or waits: turns and dashes, or nothing (no kick, no say).

    >>> from field_models.protocol import Dash, Turn
    >>> is_routine((Turn(0.5), Dash(100.0))), is_routine(()), is_routine((Kick(80.0, 0.0),))
    (True, True, False)
    """
    return not any(isinstance(action, Kick | Say) for action in actions)


def text_log_view(
    name: str, origin: str, *, entity_column: bool = True, hidden: Sequence[str] = ()
) -> rrb.TextLogView:
    """A text-log view of `origin` that shows each line's body first, then its entity.

    By default rerun 0.41 puts the entity path and level first, and in a narrow view the body
    is cut off (``rrb.TextLogColumns``, blueprint/archetypes/text_log_columns). Without
    `entity_column` the entity path is hidden too (where the body names its channel).
    Entities in `hidden` (paths without the leading ``/``) are left out of the view's
    contents: recorded, and shown again by adding them in the blueprint panel.
    """
    import rerun.blueprint as rrb

    return rrb.TextLogView(
        name=name,
        origin=origin,
        contents=["+ $origin/**", *(f"- /{path}/**" for path in hidden)],
        columns=rrb.TextLogColumns(
            timeline_columns=[rrb.encodings.TimelineColumn(SIM_TIME)],
            text_log_columns=[
                rrb.encodings.TextLogColumn("body"),
                rrb.encodings.TextLogColumn("entitypath", visible=entity_column),
                rrb.encodings.TextLogColumn("loglevel", visible=False),
            ],
        ),
        format_options=rrb.TextLogFormat(monospace_body=False),
    )


# ----------------------------------------------------------------------------- buffers


class _PerceptBuffer:
    """Rows of one observer's perceived ball and players, waiting for ``send_columns``.

    ``expires`` is the tick at which the latest percept stops being current (None: never, or
    no percept yet); an empty row is added there when no newer percept came.
    """

    __slots__ = (
        "ball_lengths",
        "ball_xy",
        "expires",
        "player_labels",
        "player_lengths",
        "player_xy",
        "ticks",
    )

    def __init__(self, expires: int | None = None) -> None:
        self.ticks: list[int] = []
        self.ball_xy: list[float] = []
        self.ball_lengths: list[int] = []
        self.player_xy: list[float] = []
        self.player_labels: list[str] = []
        self.player_lengths: list[int] = []
        self.expires = expires

    def add_empty(self, tick: int) -> None:
        """A row with neither ball nor players: clears what the viewer shows from `tick`."""
        self.ticks.append(tick)
        self.ball_lengths.append(0)
        self.player_lengths.append(0)


class _TextBuffer:
    """Rows of one text-log entity waiting for ``send_columns``."""

    __slots__ = ("levels", "texts", "ticks")

    def __init__(self) -> None:
        self.ticks: list[int] = []
        self.texts: list[str] = []
        self.levels: list[str] = []


# ----------------------------------------------------------------------------- recorder


class TrialRecorder:
    """Writes one run to a rerun ``.rrd`` file, headless (notes/tooling.md §1).

    Use it as a context manager, or call :meth:`close` at the end: the file's footer is only
    written when the stream disconnects, and ``rerun rrd verify`` fails without it.

    Args:
        path: Output ``.rrd`` file; its folder is created if missing.
        pitch: Field geometry, drawn once as static geometry.
        players: Players on the field, in a fixed order (labels, per-team entities, and the
            colour of each player's percepts).
        dt_s: Length of one tick [s]; ``sim_time`` = tick × dt_s.
        recording_id: Rerun recording id (e.g. experiment and trial), shown by the viewer.
        application_id: Rerun application id.
        player_shape: ``"square"`` (robots, side 2·pitch.player_radius_m) or ``"circle"``
            (Soccer Server players of radius pitch.player_radius_m).
        every_ticks: Record the truth only on ticks that are multiples of this.
        chunk_frames: Recorded ticks buffered before one ``send_columns`` batch.
        sensor_period_s: Time between two percepts of one player [s]; a player's percept is
            cleared from the view once :data:`PERCEPT_LIFETIME_PERIODS` of these pass without
            a newer one. None: percepts stay until the next one.
        title: First line of the legend (e.g. the drill, field model and trial).
        viewer: Stream to a rerun viewer instead of writing `path` (an environment's
            ``render_mode="human"``): with a display, the viewer beside this interpreter is
            spawned (or reused, when one listens); without one, the stream goes to rerun's
            default address, where a viewer started later (``rerun``) picks it up.

    Raises:
        ValueError: On a bad shape, a non-positive dt_s, every_ticks, chunk_frames or
            sensor_period_s.
    """

    _circle_outlines = True
    """Whether round players get an outline too (a subclass may leave it out: the outlines
    are most of a recording's bytes, and a circle's outline says nothing of its heading)."""

    def __init__(
        self,
        path: Path,
        *,
        pitch: Pitch,
        players: tuple[PlayerRef, ...],
        dt_s: float,
        recording_id: str,
        application_id: str = "robotsoccer",
        player_shape: PlayerShape = "square",
        every_ticks: int = 1,
        chunk_frames: int = 1000,
        sensor_period_s: float | None = None,
        title: str = "",
        viewer: bool = False,
    ) -> None:
        if not dt_s > 0.0:
            raise ValueError(f"dt_s must be > 0, got {dt_s}")
        if every_ticks < 1:
            raise ValueError(f"every_ticks must be >= 1, got {every_ticks}")
        if chunk_frames < 1:
            raise ValueError(f"chunk_frames must be >= 1, got {chunk_frames}")
        if sensor_period_s is not None and not sensor_period_s > 0.0:
            raise ValueError(f"sensor_period_s must be > 0, got {sensor_period_s}")
        self.sizes = self._draw_sizes(pitch)
        self._template = outline_template(player_shape, self.sizes.player_m)
        self.path = Path(path)
        self.pitch = pitch
        self.players = tuple(players)
        self.dt_s = dt_s
        self.every_ticks = every_ticks
        self.chunk_frames = chunk_frames
        self.sensor_period_s = sensor_period_s
        self.title = title or recording_id
        self._player_shape = player_shape
        # Whole ticks a percept stays current; the small epsilon keeps an exact multiple exact.
        self._percept_life: int | None = (
            None
            if sensor_period_s is None
            else max(1, math.ceil(PERCEPT_LIFETIME_PERIODS * sensor_period_s / dt_s - 1e-9))
        )
        self._teams: tuple[str, ...] = tuple(dict.fromkeys(p.team for p in self.players))
        self._team_index = {
            team: np.array([i for i, p in enumerate(self.players) if p.team == team])
            for team in self._teams
        }
        self._labels = np.array([self._player_label(p) for p in self.players])
        self._ticks: list[int] = []
        self._ball_xy: list[float] = []
        self._poses: list[float] = []  # x, y, heading per player per recorded tick (NaN: absent)
        self._percepts: dict[PlayerRef, _PerceptBuffer] = {}
        self._texts: dict[str, _TextBuffer] = {}
        self._last_tick = 0
        self._outcome: tuple[int, str, str] | None = None
        self._closed = False

        import rerun as rr

        self._rec: rr.RecordingStream = rr.RecordingStream(
            application_id, recording_id=recording_id
        )
        if viewer and _has_display():
            rr.spawn(
                executable_path=str(rerun_executable()),
                recording=self._rec,
                default_blueprint=self._blueprint(),
            )
        elif viewer:
            self._rec.connect_grpc(default_blueprint=self._blueprint())
        else:
            self.path.parent.mkdir(parents=True, exist_ok=True)
            self._rec.save(self.path, default_blueprint=self._blueprint())
        self._log_static()

    # --- setup ---------------------------------------------------------------------------

    def _draw_sizes(self, pitch: Pitch) -> DrawSizes:
        """How large things are drawn (:func:`draw_sizes`); a subclass may draw larger."""
        return draw_sizes(pitch)

    def _player_label(self, player: PlayerRef) -> str:
        """The label drawn above `player` (and stored with its disc): its id, ``left1``."""
        return str(player)

    def _view_bounds(self) -> tuple[list[float], list[float]]:
        """The field view's x and y ranges, in the view's (flipped) frame.

        Room above the field (the view's negative y) is left for the outcome label.
        """
        pitch = self.pitch
        margin = 0.03 * pitch.length_m
        x_max = pitch.half_length_m + pitch.goal_depth_m + margin
        top = pitch.half_width_m + 0.105 * pitch.length_m
        return [-x_max, x_max], [-top, pitch.half_width_m + margin]

    def _blueprint(self) -> rrb.Blueprint:
        """The field beside the legend and the events, side panels collapsed, on ``sim_time``.

        The field view's origin is the root, so the ``field`` entity's flip applies to what it
        shows (a view's own origin transform would not). The events view shows the message
        body first (:func:`text_log_view`).
        """
        import rerun.blueprint as rrb

        x_range, y_range = self._view_bounds()
        field_view = rrb.Spatial2DView(
            name="field (y up; truth filled, percepts as rings)",
            origin="/",
            contents="/field/**",
            background=rrb.Background(kind="SolidColor", color=_PITCH_COLOUR),
            visual_bounds=rrb.VisualBounds2D(x_range=x_range, y_range=y_range),
        )
        legend = rrb.TextDocumentView(name="legend", origin="/legend")
        events = text_log_view("events", "/events", hidden=(ROUTINE_DECISIONS,))
        return rrb.Blueprint(
            rrb.Horizontal(
                field_view,
                rrb.Vertical(legend, events, row_shares=[3, 5]),
                column_shares=[5, 2],
            ),
            rrb.BlueprintPanel(state="collapsed"),
            rrb.SelectionPanel(state="collapsed"),
            rrb.TimePanel(timeline=SIM_TIME, state="collapsed"),
        )

    def _log_static(self) -> None:
        """The flip, pitch geometry and the per-entity styles (colours, radii), logged once."""
        import rerun as rr

        rec, pitch, sizes = self._rec, self.pitch, self.sizes
        # The display flip: field frame (y up) to rerun's 2-D frame (y down).
        rec.log("field", rr.Transform3D(scale=[1.0, -1.0, 1.0]), static=True)
        line_radius = rr.Radius.ui_points(1.0)
        rec.log(
            "field/lines",
            rr.LineStrips2D(
                pitch_lines(pitch),
                radii=line_radius,
                colors=_LINE_COLOUR,
                draw_order=_ORDER_MARKINGS,
            ),
            static=True,
        )
        rec.log(
            "field/markings",
            rr.LineStrips2D(
                pitch_markings(pitch),
                radii=line_radius,
                colors=_LINE_COLOUR,
                draw_order=_ORDER_MARKINGS,
            ),
            static=True,
        )
        for team, side in ((LEFT, -1.0), (RIGHT, 1.0)):
            rec.log(
                f"field/goals/{team}",
                rr.LineStrips2D(
                    [goal_box(pitch, side)],
                    radii=rr.Radius.ui_points(2.5),
                    colors=team_colour(team, self._teams),
                    draw_order=_ORDER_MARKINGS,
                ),
                static=True,
            )
        rec.log(
            "field/posts",
            rr.Points2D(
                goal_posts(pitch),
                radii=rr.Radius.ui_points(4.0),
                colors=_LINE_COLOUR,
                draw_order=_ORDER_MARKINGS,
            ),
            static=True,
        )
        rec.log(
            "field/ball",
            rr.Points2D.from_fields(
                radii=sizes.ball_m, colors=_BALL_COLOUR, draw_order=_ORDER_BALL
            ),
            static=True,
        )
        for team in self._teams:
            colour = team_colour(team, self._teams)
            base = f"field/players/{entity_name(team)}"
            # The discs keep the ids as labels (hover, read-back) but do not show them: rerun
            # draws a point's label over the point. The ids show on anchors above the players.
            rec.log(
                base,
                rr.Points2D.from_fields(
                    radii=sizes.player_m,
                    colors=colour,
                    show_labels=False,
                    draw_order=_ORDER_PLAYERS,
                ),
                static=True,
            )
            rec.log(
                f"{base}/name",
                rr.Points2D.from_fields(
                    radii=0.0,
                    colors=_ARROW_COLOUR,  # label text takes this colour: white reads best
                    show_labels=True,
                    draw_order=_ORDER_PLAYERS,
                ),
                static=True,
            )
            rec.log(
                f"{base}/outline",
                rr.LineStrips2D.from_fields(
                    radii=rr.Radius.ui_points(1.5),
                    colors=_lighter(colour),
                    draw_order=_ORDER_OUTLINE,
                ),
                static=True,
            )
            rec.log(
                f"{base}/heading",
                rr.Arrows2D.from_fields(
                    radii=sizes.arrow_radius_m, colors=_ARROW_COLOUR, draw_order=_ORDER_HEADING
                ),
                static=True,
            )
        self._log_legend(0)

    def _percept_colour(self, observer: PlayerRef) -> tuple[int, int, int]:
        """The colour of `observer`'s percept rings (by its place in the players)."""
        index = self.players.index(observer) if observer in self.players else len(self.players)
        return _PERCEPT_COLOURS[index % len(_PERCEPT_COLOURS)]

    def _log_percept_style(self, observer: PlayerRef) -> None:
        """Static style of one observer's percept rings: its own colour, thin lines."""
        import rerun as rr

        colour = self._percept_colour(observer)
        base = f"field/perceived/{entity_name(str(observer))}"
        for entity in (f"{base}/ball", f"{base}/players"):
            self._rec.log(
                entity,
                rr.Ellipses2D.from_fields(
                    line_radii=rr.Radius.ui_points(1.5),
                    colors=colour,
                    show_labels=False,  # the seen identities clutter; hover shows them
                    draw_order=_ORDER_PERCEPT,
                ),
                static=True,
            )

    def legend(self, outcome: str = "") -> str:
        """The legend shown beside the field (markdown), with `outcome` on top once known."""
        sizes, pitch = self.sizes, self.pitch
        teams = "; ".join(
            f"{_colour_name(team_colour(team, self._teams))}: "
            + ", ".join(str(p) for p in self.players if p.team == team)
            for team in self._teams
        )
        body = "square robots" if self._player_shape == "square" else "round players"
        ball = f"radius {_length_text(pitch.ball_radius_m)}"
        if sizes.ball_enlarged:
            ball += f", **drawn enlarged** to {_length_text(sizes.ball_m)}"
        players = f"{body} ({teams})"
        if sizes.players_enlarged:
            players += (
                f", half-size {_length_text(pitch.player_radius_m)} "
                f"**drawn enlarged** to {_length_text(sizes.player_m)}"
            )
        rings = ", ".join(
            f"{_PERCEPT_COLOUR_NAMES[i % len(_PERCEPT_COLOUR_NAMES)]}: what {p} perceives"
            for i, p in enumerate(self.players)
        )
        gone = (
            f" They vanish {PERCEPT_LIFETIME_PERIODS:g} sensor periods after that player's "
            "latest percept; the ball's ring also when a percept has no ball."
            if self._percept_life is not None
            else ""
        )
        lines = [
            f"### {outcome}" if outcome else "### outcome: not yet decided",
            "",
            self.title,
            "",
            f"- **Truth** (filled): orange disc = the ball ({ball}); discs = {players}; "
            "white arrow = heading.",
            f"- **Percepts** (hollow rings, small = ball, large = player): {rings}.{gone}",
            "- The field is shown y up (left turns counter-clockwise); markings in FIFA "
            "proportions. **Events** below: commands, sees, hears, referee, link, decisions, "
            "the outcome.",
        ]
        return "\n".join(lines)

    def _log_legend(self, tick: int, outcome: str = "") -> None:
        """Log the legend at `tick` (on both timelines), with `outcome` on top if given."""
        import rerun as rr

        self._rec.send_columns(
            "legend",
            indexes=time_indexes([tick], self.dt_s),
            columns=rr.TextDocument.columns(
                text=[self.legend(outcome)], media_type=["text/markdown"]
            ),
        )

    # --- logging (hot path: plain-float appends only) --------------------------------------

    def log_truth(self, truth: Truth) -> None:
        """Buffer the exact ball and player states of `truth`, if its tick is recorded.

        Players missing from `truth.players` are left out of that tick's rows.
        """
        tick = truth.tick
        if tick % self.every_ticks:
            return
        if self._closed:
            raise RuntimeError("TrialRecorder is closed")
        self._ticks.append(tick)
        if tick > self._last_tick:
            self._last_tick = tick
        ball = truth.ball
        self._ball_xy.append(ball.x)
        self._ball_xy.append(ball.y)
        states = truth.players
        poses = self._poses
        for ref in self.players:
            s = states.get(ref)
            if s is None:
                poses.extend(_NAN3)
            else:
                poses.extend((s.x, s.y, s.heading))
        if len(self._ticks) >= self.chunk_frames:
            self.flush()

    def log_percept(self, percept: Percept, observer: BodyState) -> None:
        """Buffer what `percept.player` perceived, converted to the field frame.

        Logged at ``percept.tick`` (when the client got it), so latency shows as the perceived
        ball trailing the true one. A percept without a ball clears the perceived ball; with a
        sensor period given, a percept older than :data:`PERCEPT_LIFETIME_PERIODS` periods
        with no newer one is cleared at that age.

        Args:
            percept: The player's egocentric view.
            observer: The pose to convert from: the observer's true pose (for the sensor's
                own view, pass its pose at ``percept.observed_tick``).
        """
        if self._closed:
            raise RuntimeError("TrialRecorder is closed")
        tick = percept.tick
        buf = self._percepts.get(percept.player)
        if buf is None:
            buf = self._percepts[percept.player] = _PerceptBuffer()
            self._log_percept_style(percept.player)
        elif buf.expires is not None and tick > buf.expires:
            buf.add_empty(buf.expires)  # the previous percept went stale before this one came
        if self._percept_life is not None:
            buf.expires = tick + self._percept_life
        if tick > self._last_tick:
            self._last_tick = tick
        buf.ticks.append(tick)
        ball = percept.ball
        if ball is None:
            buf.ball_lengths.append(0)
        else:
            buf.ball_xy.extend(egocentric_to_field(observer, ball.distance_m, ball.angle_rad))
            buf.ball_lengths.append(1)
        for seen in percept.players:
            buf.player_xy.extend(egocentric_to_field(observer, seen.distance_m, seen.angle_rad))
            buf.player_labels.append(_seen_label(seen.team, seen.number))
        buf.player_lengths.append(len(percept.players))
        if len(buf.ticks) >= self.chunk_frames:
            self._flush_percepts()

    def log_events(self, events: Sequence[ArenaEvent]) -> None:
        """Buffer arena events as text lines under ``events/<channel>``."""
        if self._closed:
            raise RuntimeError("TrialRecorder is closed")
        for event in events:
            # The channel leads the text: the events view's Body column is what a reader sees
            # first, and a decision and the command it became read alike without it.
            who = "" if event.player is None else f"{event.player}: "
            text = f"[{event.channel}] {who}{event.text}"
            self._add_text(f"events/{entity_name(event.channel)}", event.tick, text, "INFO")

    def log_decision(self, event: ArenaEvent, actions: Sequence[Action]) -> None:
        """Buffer a mind's decision: kicks and says as events, the rest as routine.

        Args:
            event: The decision as a ``decision`` event (its text: the commands it became).
            actions: The actions decided: a decision with a kick or a say is logged like any
                event (``events/decision``); one of turns and dashes only, or of nothing, goes
                to :data:`ROUTINE_DECISIONS`, which the default layout hides.
        """
        if self._closed:
            raise RuntimeError("TrialRecorder is closed")
        if not is_routine(actions):
            self.log_events([event])
            return
        who = "" if event.player is None else f"{event.player}: "
        text = f"[{event.channel}] {who}{event.text}"
        self._add_text(ROUTINE_DECISIONS, event.tick, text, "DEBUG")

    def log_label(self, tick: int, label: str, detail: str = "") -> None:
        """Record the trial's outcome (e.g. ``"GOAL"``, ``"SUCCESS"``) and why, at `tick`.

        A text line under ``events/label``; from `tick` on, the outcome above the field (in
        the label's colour, with the boundary in that colour too) and on top of the legend.
        A later call replaces an earlier one from its own tick on.
        """
        if self._closed:
            raise RuntimeError("TrialRecorder is closed")
        text = outcome_text(label, detail)
        self._add_text("events/label", tick, f"{label}: {detail}" if detail else label, "INFO")
        if tick > self._last_tick:
            self._last_tick = tick
        self._log_outcome(tick, label, text)

    def _log_outcome(self, tick: int, label: str, text: str) -> None:
        """Show the outcome from `tick` on: on the field and on top of the legend.

        Large letters and the reason above the field, and the boundary in the outcome's colour.
        Logged once per trial, so plain ``log`` calls at `tick` serve.
        """
        import rerun as rr

        pitch, rec = self.pitch, self._rec
        length, top = pitch.length_m, pitch.half_width_m
        colour = outcome_colour(label)
        rec.set_time(SIM_TIME, duration=np.timedelta64(round(tick * (self.dt_s * 1e9)), "ns"))
        rec.set_time(TICK, sequence=tick)
        try:
            # Above the top side line, in the room :meth:`_view_bounds` leaves: the reason (a
            # label, drawn below its anchor point) just above the line, the label above that.
            strokes = text_strokes(
                label, height_m=0.05 * length, centre_x_m=0.0, base_y_m=top + 0.045 * length
            )
            rec.log(
                "field/outcome",
                rr.LineStrips2D(
                    strokes,
                    colors=colour,
                    radii=rr.Radius.ui_points(3.0),
                    draw_order=_ORDER_OUTCOME,
                ),
            )
            rec.log(
                "field/outcome/reason",
                rr.Points2D(
                    [[0.0, top + 0.035 * length]],
                    labels=text,
                    colors=_ARROW_COLOUR,  # label text takes this colour: white reads best
                    radii=0.0,
                    show_labels=True,
                    draw_order=_ORDER_OUTCOME,
                ),
            )
            rec.log(
                "field/outcome/frame",
                rr.LineStrips2D(
                    [pitch_lines(pitch)[0]],
                    colors=colour,
                    radii=rr.Radius.ui_points(4.0),
                    draw_order=_ORDER_OUTCOME,
                ),
            )
        finally:
            rec.reset_time()
        self._log_legend(tick, text)
        self._outcome = (tick, label, text)

    def _add_text(self, entity: str, tick: int, text: str, level: str) -> None:
        """Append one text row; flush that entity when its buffer is full."""
        buf = self._texts.get(entity)
        if buf is None:
            buf = self._texts[entity] = _TextBuffer()
        buf.ticks.append(tick)
        buf.texts.append(text)
        buf.levels.append(level)
        if len(buf.ticks) >= self.chunk_frames:
            self._flush_texts()

    @property
    def outcome(self) -> tuple[int, str, str] | None:
        """The latest :meth:`log_label`: (tick, label, text as shown), or None."""
        return self._outcome

    # --- flushing ---------------------------------------------------------------------------

    def flush(self) -> None:
        """Send everything buffered to the file sink."""
        self._flush_truth()
        self._flush_percepts()
        self._flush_texts()

    def _flush_truth(self) -> None:
        """Send the buffered truth rows: the ball, then per team centres, outlines, headings."""
        if not self._ticks:
            return
        import rerun as rr

        rec = self._rec
        indexes = time_indexes(self._ticks, self.dt_s)
        n_rows = len(self._ticks)
        ball = np.asarray(self._ball_xy, dtype=np.float64).reshape(n_rows, 2)
        rec.send_columns("field/ball", indexes=indexes, columns=rr.Points2D.columns(positions=ball))
        poses = np.asarray(self._poses, dtype=np.float64).reshape(n_rows, len(self.players), 3)
        arrow_m = self.sizes.arrow_length_m
        # A label is drawn below its point: this puts the id just above the player's body.
        name_above = self.sizes.player_m + 0.028 * self.pitch.length_m
        for team in self._teams:
            idx = self._team_index[team]
            team_poses = poses[:, idx, :]
            present = ~np.isnan(team_poses[:, :, 0])
            lengths = present.sum(axis=1).tolist()
            flat = team_poses[present]  # row-major: time order, then player order
            labels = np.broadcast_to(self._labels[idx], present.shape)[present].tolist()
            headings = np.column_stack([np.cos(flat[:, 2]), np.sin(flat[:, 2])])
            base = f"field/players/{entity_name(team)}"
            rec.send_columns(
                base,
                indexes=indexes,
                columns=rr.Points2D.columns(positions=flat[:, :2], labels=labels).partition(
                    lengths
                ),
            )
            rec.send_columns(
                f"{base}/name",
                indexes=indexes,
                columns=rr.Points2D.columns(
                    positions=flat[:, :2] + (0.0, name_above), labels=labels
                ).partition(lengths),
            )
            if self._player_shape == "square" or self._circle_outlines:
                rec.send_columns(
                    f"{base}/outline",
                    indexes=indexes,
                    columns=rr.LineStrips2D.columns(
                        strips=place_outlines(self._template, flat)
                    ).partition(lengths),
                )
            rec.send_columns(
                f"{base}/heading",
                indexes=indexes,
                columns=rr.Arrows2D.columns(
                    origins=flat[:, :2], vectors=arrow_m * headings
                ).partition(lengths),
            )
        self._ticks = []
        self._ball_xy = []
        self._poses = []

    def _flush_percepts(self) -> None:
        """Send each observer's buffered perceived ball and player rings."""
        import rerun as rr

        # The ring sizes go in every row: half_sizes is Ellipses2D's required component, so a
        # static one would fix the instance count at one and draw a ring where none is current.
        ball_ring = 1.5 * self.sizes.ball_m
        player_ring = 2.0 * self.sizes.player_m
        for observer, buf in self._percepts.items():
            if not buf.ticks:
                continue
            indexes = time_indexes(buf.ticks, self.dt_s)
            base = f"field/perceived/{entity_name(str(observer))}"
            ball = np.asarray(buf.ball_xy, dtype=np.float64).reshape(-1, 2)
            self._rec.send_columns(
                f"{base}/ball",
                indexes=indexes,
                columns=rr.Ellipses2D.columns(
                    centers=ball, half_sizes=np.full_like(ball, ball_ring)
                ).partition(buf.ball_lengths),
            )
            seen = np.asarray(buf.player_xy, dtype=np.float64).reshape(-1, 2)
            self._rec.send_columns(
                f"{base}/players",
                indexes=indexes,
                columns=rr.Ellipses2D.columns(
                    centers=seen,
                    half_sizes=np.full_like(seen, player_ring),
                    labels=buf.player_labels,
                ).partition(buf.player_lengths),
            )
            self._percepts[observer] = _PerceptBuffer(buf.expires)

    def _flush_texts(self) -> None:
        """Send the buffered text rows of every text entity."""
        import rerun as rr

        for entity, buf in self._texts.items():
            if not buf.ticks:
                continue
            self._rec.send_columns(
                entity,
                indexes=time_indexes(buf.ticks, self.dt_s),
                columns=rr.TextLog.columns(text=buf.texts, level=buf.levels),
            )
            self._texts[entity] = _TextBuffer()

    def _expire_percepts(self) -> None:
        """Clear each percept that went stale before the recording's last tick."""
        for buf in self._percepts.values():
            if buf.expires is not None and buf.expires <= self._last_tick:
                buf.add_empty(buf.expires)
                buf.expires = None

    # --- closing ----------------------------------------------------------------------------

    def close(self) -> None:
        """Clear stale percepts, flush the buffers and disconnect (writes the footer).

        Idempotent.
        """
        if self._closed:
            return
        try:
            self._expire_percepts()
            self.flush()
        finally:
            self._closed = True
            self._rec.disconnect()

    def __enter__(self) -> TrialRecorder:
        return self

    def __exit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        self.close()


def _colour_name(colour: tuple[int, int, int]) -> str:
    """The name the legend gives a team colour."""
    names = {
        _TEAM_COLOURS[LEFT]: "blue",
        _TEAM_COLOURS[RIGHT]: "yellow",
        _OTHER_TEAM_COLOURS[0]: "purple",
        _OTHER_TEAM_COLOURS[1]: "teal",
        _OTHER_TEAM_COLOURS[2]: "red",
    }
    return names.get(colour, "coloured")


# ----------------------------------------------------------------------------- reading back


def rerun_executable() -> Path:
    """The ``rerun`` CLI installed beside the running interpreter (the rerun-sdk wheel's)."""
    name = "rerun.exe" if os.name == "nt" else "rerun"
    return Path(sys.executable).parent / name


def _cli_env() -> dict[str, str]:
    """Environment for the rerun CLI: ``CI=true`` keeps it from writing analytics files."""
    return {**os.environ, "CI": "true"}


def _check_with_reader(path: Path, *, read_chunks: bool) -> tuple[bool, str]:
    """Read `path` with ``RrdReader``: optionally decode every chunk, then require the footer.

    ``rerun rrd verify`` (0.41) accepts a file whose last few dozen bytes (the footer) were
    cut off; ``RrdReader.store()`` refuses it, so this check backs the CLI up.
    """
    from rerun.chunk import RrdReader

    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # the reader warns on footer-less files; we report
            reader = RrdReader(str(path))
            n_chunks = len(reader.stream().to_chunks()) if read_chunks else 0
            reader.store()
    except Exception as err:  # the reader raises RuntimeError; report anything as a failure
        return False, f"{path}: {err}"
    detail = f"{n_chunks} chunks read, " if read_chunks else ""
    return True, f"{path}: {detail}footer present"


def verify_recording(path: Path) -> tuple[bool, str]:
    """Check that an ``.rrd`` file is complete and decodes.

    Runs ``rerun rrd verify`` (the CLI beside ``sys.executable``, with ``CI=true``) and then
    requires the footer with ``RrdReader``; without the executable, reads the whole file with
    ``RrdReader`` instead.

    Returns:
        Whether the file verified, and a one-line message saying why or why not.
    """
    path = Path(path)
    if not path.is_file():
        return False, f"{path}: no such file"
    exe = rerun_executable()
    if not exe.is_file():
        return _check_with_reader(path, read_chunks=True)
    try:
        proc = subprocess.run(
            [str(exe), "rrd", "verify", str(path)],
            env=_cli_env(),
            capture_output=True,
            text=True,
            timeout=600,
            check=False,
        )
    except (OSError, subprocess.TimeoutExpired) as err:
        return False, f"{path}: could not run {exe}: {err}"
    lines = [ln.strip() for ln in _ANSI.sub("", proc.stdout + proc.stderr).splitlines()]
    message = " | ".join(ln for ln in lines if ln) or f"rerun rrd verify exited {proc.returncode}"
    if proc.returncode != 0:
        return False, message
    ok, footer_message = _check_with_reader(path, read_chunks=False)
    return (True, message) if ok else (False, footer_message)


def read_entity_positions(path: Path, entity: str) -> np.ndarray:
    """Read the positions logged under one entity back from an ``.rrd`` file (for tests).

    Takes the first position-like column (``Points2D:positions``, ``Arrows2D:origins``,
    ``Boxes2D:centers``) of every temporal chunk of `entity`, sorted by ``sim_time``; rows with
    several instances contribute them in logged order. Works on footer-less files too.

    Args:
        path: The ``.rrd`` file.
        entity: Entity path, with or without the leading ``/`` (e.g. ``"field/ball"``).

    Returns:
        A (N, 2) float64 array (float32 values, as rerun stores them); (0, 2) if none.
    """
    from rerun.chunk import RrdReader

    target = "/" + entity.strip("/")
    times: list[np.ndarray] = []
    points: list[np.ndarray] = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # footer-less files warn but read fine
        chunks = RrdReader(str(path)).stream().to_chunks()
    for chunk in chunks:
        if chunk.entity_path != target:
            continue
        batch = chunk.to_record_batch()
        names = batch.schema.names
        if SIM_TIME not in names:
            continue  # static styles
        column = next(
            (n for n in names if n.endswith((":positions", ":origins", ":centers"))), None
        )
        if column is None:
            continue
        values = batch.column(column)
        lengths = values.value_lengths().fill_null(0).to_numpy(zero_copy_only=False)
        xy = np.asarray(values.flatten().flatten(), dtype=np.float64).reshape(-1, 2)
        row_ns = batch.column(SIM_TIME).cast("int64").to_numpy(zero_copy_only=False)
        times.append(np.repeat(row_ns, lengths))
        points.append(xy)
    if not points:
        return np.zeros((0, 2))
    order = np.argsort(np.concatenate(times), kind="stable")
    return np.concatenate(points)[order]


# ----------------------------------------------------------------------------- replay


def _has_display() -> bool:
    """Whether a graphical session is available to open the native viewer in."""
    return bool(os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"))


def replay(path: Path) -> int:
    """Open a recording in the rerun viewer, or say how to, headless (``robotsoccer replay``).

    With a display, spawns the viewer on the file (detached) and returns 0. Without one,
    prints how to open it on a desktop or serve it to a browser, verifies it and prints the
    result.

    Returns:
        0 when the viewer was spawned or the file verifies, 1 when it does not verify, 2 when
        the file does not exist.
    """
    path = Path(path)
    if not path.is_file():
        print(f"robotsoccer replay: no such file: {path}", file=sys.stderr)
        return 2
    exe = rerun_executable()
    if _has_display():
        try:
            subprocess.Popen(
                [str(exe), str(path)],
                env=_cli_env(),
                stdin=subprocess.DEVNULL,
                stdout=subprocess.DEVNULL,
                stderr=subprocess.DEVNULL,
                start_new_session=True,  # the viewer outlives this command
            )
        except OSError as err:
            print(f"could not start the rerun viewer ({exe}): {err}")
        else:
            print(f"opened the rerun viewer on {path}")
            return 0
    else:
        print("no display found (neither DISPLAY nor WAYLAND_DISPLAY is set).")
    # The venv's rerun is not on PATH unless the venv is active; name it in full. The web
    # viewer binds to localhost: serving to all interfaces is the user's explicit choice.
    print(f"On a desktop, open it with:      {exe} {path}")
    print(f"To serve it to a web browser:    {exe} --web-viewer --bind 127.0.0.1 {path}")
    print("  then open the http://127.0.0.1:9090 address it prints")
    print(f"verifying {path} ...", flush=True)
    ok, message = verify_recording(path)
    print(f"{'verified' if ok else 'verification FAILED'}: {message}")
    return 0 if ok else 1
