"""Rerun recordings of trials, and reading, verifying and replaying them (DESIGN.md §5).

A :class:`TrialRecorder` writes one ``.rrd`` file per run: the pitch (boundary, centre line,
goal posts and goal-mouth boxes) once as static geometry; every recorded tick the true ball and
players (one entity per team: centre points labelled with the player ids, rotated outline
polygons, heading arrows); the positions each player *perceived*, converted to the field frame
beside the truth; commands, referee messages and trial labels as text. Everything sits on a
``sim_time`` duration timeline derived from integer ticks × ``dt_s`` (plus a ``tick`` sequence
timeline with the raw tick), never on wall-clock time.

Speed (notes/tooling.md §1.4): ``rr.log`` costs ~100 µs per call, so the recorder never logs
in the simulation loop. It appends plain floats to per-entity buffers and sends them with
``send_columns`` in chunks of ``chunk_frames`` recorded ticks, which costs a few µs per tick.

This is the only module of the project that imports ``rerun``, and it does so inside functions,
so ``import robotsoccer`` (and importing this module) never loads the 800 MB SDK.

Entity layout (paths are what :func:`read_entity_positions` takes)::

    field/lines, field/goals/<team>, field/posts     static pitch geometry
    field/ball                                       Points2D, one point per recorded tick
    field/players/<team>                             Points2D centres, labels = player ids
    field/players/<team>/outline                     LineStrips2D rotated outlines
    field/players/<team>/heading                     Arrows2D headings
    field/perceived/<player>/ball                    Points2D (empty row: ball not seen)
    field/perceived/<player>/players                 Points2D, labels = team+number seen
    events/<channel>, events/label                   TextLog

Rerun draws 2-D views with y pointing down (upstream issue rerun-io/rerun#1387: view
coordinates are ignored in 2-D views), so the viewer shows the field mirrored top-to-bottom.
The data in the file stay in the field frame (y up), so what is read back is what was logged.
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
from pathlib import Path
from types import TracebackType
from typing import TYPE_CHECKING, Any

import numpy as np

from field_models.arena import ArenaEvent, PlayerShape
from field_models.protocol import LEFT, RIGHT, BodyState, Percept, Pitch, PlayerRef, Truth

if TYPE_CHECKING:
    import rerun as rr
    import rerun.blueprint as rrb

SIM_TIME = "sim_time"
"""Name of the simulated-time (duration) timeline."""
TICK = "tick"
"""Name of the integer-tick (sequence) timeline."""

_TEAM_COLOURS: dict[str, tuple[int, int, int]] = {LEFT: (60, 130, 255), RIGHT: (255, 200, 40)}
_OTHER_TEAM_COLOURS = ((200, 80, 220), (80, 220, 160), (240, 90, 90))
_BALL_COLOUR = (255, 120, 0)
_LINE_COLOUR = (230, 230, 230)
_PERCEIVED_ALPHA = 110
_CIRCLE_SEGMENTS = 12  # outlines dominate file size; a 12-gon reads as round
_NAN3 = (math.nan, math.nan, math.nan)
_ANSI = re.compile(r"\x1b\[[0-9;]*m")
_ENTITY_UNSAFE = re.compile(r"[^A-Za-z0-9_\-]")


# ----------------------------------------------------------------------------- geometry


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
        a = np.linspace(0.0, 2.0 * math.pi, _CIRCLE_SEGMENTS + 1)
        unit = np.column_stack([np.cos(a), np.sin(a)])
        unit[-1] = unit[0]  # close exactly, not to within rounding
    else:
        raise ValueError(f"player_shape must be 'square' or 'circle', got {shape!r}")
    return radius_m * unit


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


def team_colour(team: str, teams: Sequence[str]) -> tuple[int, int, int]:
    """Display colour of a team: fixed for LEFT/RIGHT, from a small palette otherwise."""
    if team in _TEAM_COLOURS:
        return _TEAM_COLOURS[team]
    others = [t for t in teams if t not in _TEAM_COLOURS]
    index = others.index(team) if team in others else len(others)
    return _OTHER_TEAM_COLOURS[index % len(_OTHER_TEAM_COLOURS)]


def _seen_label(team: str | None, number: int | None) -> str:
    """Label of a perceived player: what the sensor identified, '?' for the unknown parts."""
    if team is None and number is None:
        return "?"
    return f"{team if team is not None else '?'}{number if number is not None else '?'}"


def _entity_name(text: str) -> str:
    """Make `text` safe as one entity-path part."""
    return _ENTITY_UNSAFE.sub("_", text) or "_"


def _time_indexes(ticks: Sequence[int], dt_s: float) -> list[Any]:
    """The ``sim_time`` (ns from integer ticks, never accumulated) and ``tick`` index columns."""
    import rerun as rr

    tick_arr = np.asarray(ticks, dtype=np.int64)
    # Rounded to whole ns per tick, so 1/240 s ticks do not truncate to ...666 ns.
    ns = np.rint(tick_arr * (dt_s * 1e9)).astype(np.int64).astype("timedelta64[ns]")
    return [rr.TimeColumn(SIM_TIME, duration=ns), rr.TimeColumn(TICK, sequence=tick_arr)]


# ----------------------------------------------------------------------------- buffers


class _PerceptBuffer:
    """Rows of one observer's perceived ball and players, waiting for ``send_columns``."""

    __slots__ = ("ball_lengths", "ball_xy", "player_labels", "player_lengths", "player_xy", "ticks")

    def __init__(self) -> None:
        self.ticks: list[int] = []
        self.ball_xy: list[float] = []
        self.ball_lengths: list[int] = []
        self.player_xy: list[float] = []
        self.player_labels: list[str] = []
        self.player_lengths: list[int] = []


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
        players: Players on the field, in a fixed order (labels and per-team entities).
        dt_s: Length of one tick [s]; ``sim_time`` = tick × dt_s.
        recording_id: Rerun recording id (e.g. experiment and trial), shown by the viewer.
        application_id: Rerun application id.
        player_shape: ``"square"`` (robots, side 2·pitch.player_radius_m) or ``"circle"``
            (Soccer Server players of radius pitch.player_radius_m).
        every_ticks: Record the truth only on ticks that are multiples of this.
        chunk_frames: Recorded ticks buffered before one ``send_columns`` batch.

    Raises:
        ValueError: On a bad shape, a non-positive dt_s, every_ticks or chunk_frames.
    """

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
    ) -> None:
        if not dt_s > 0.0:
            raise ValueError(f"dt_s must be > 0, got {dt_s}")
        if every_ticks < 1:
            raise ValueError(f"every_ticks must be >= 1, got {every_ticks}")
        if chunk_frames < 1:
            raise ValueError(f"chunk_frames must be >= 1, got {chunk_frames}")
        self._template = outline_template(player_shape, pitch.player_radius_m)
        self.path = Path(path)
        self.pitch = pitch
        self.players = tuple(players)
        self.dt_s = dt_s
        self.every_ticks = every_ticks
        self.chunk_frames = chunk_frames
        self._teams: tuple[str, ...] = tuple(dict.fromkeys(p.team for p in self.players))
        self._team_index = {
            team: np.array([i for i, p in enumerate(self.players) if p.team == team])
            for team in self._teams
        }
        self._labels = np.array([str(p) for p in self.players])
        self._ticks: list[int] = []
        self._ball_xy: list[float] = []
        self._poses: list[float] = []  # x, y, heading per player per recorded tick (NaN: absent)
        self._percepts: dict[PlayerRef, _PerceptBuffer] = {}
        self._texts: dict[str, _TextBuffer] = {}
        self._closed = False

        import rerun as rr

        self._rec: rr.RecordingStream = rr.RecordingStream(
            application_id, recording_id=recording_id
        )
        self.path.parent.mkdir(parents=True, exist_ok=True)
        self._rec.save(self.path, default_blueprint=self._blueprint())
        self._log_static()

    # --- setup ---------------------------------------------------------------------------

    def _blueprint(self) -> rrb.Blueprint:
        """A 2-D view of the field beside a text log of the events, on ``sim_time``."""
        import rerun.blueprint as rrb

        pitch = self.pitch
        margin = 0.05 * pitch.length_m
        x_max = pitch.half_length_m + pitch.goal_depth_m + margin
        y_max = pitch.half_width_m + margin
        return rrb.Blueprint(
            rrb.Horizontal(
                rrb.Spatial2DView(
                    name="field",
                    origin="/field",
                    visual_bounds=rrb.VisualBounds2D(
                        x_range=[-x_max, x_max], y_range=[-y_max, y_max]
                    ),
                ),
                rrb.TextLogView(name="events", origin="/events"),
                column_shares=[3, 1],
            ),
            rrb.TimePanel(timeline=SIM_TIME),
        )

    def _log_static(self) -> None:
        """Pitch geometry and the per-entity styles (colours, radii), logged once as static."""
        import rerun as rr

        rec, pitch = self._rec, self.pitch
        line_radius = rr.Radius.ui_points(1.0)
        rec.log(
            "field/lines",
            rr.LineStrips2D(pitch_lines(pitch), radii=line_radius, colors=_LINE_COLOUR),
            static=True,
        )
        for team, side in ((LEFT, -1.0), (RIGHT, 1.0)):
            rec.log(
                f"field/goals/{team}",
                rr.LineStrips2D(
                    [goal_box(pitch, side)],
                    radii=rr.Radius.ui_points(2.0),
                    colors=team_colour(team, self._teams),
                ),
                static=True,
            )
        rec.log(
            "field/posts",
            rr.Points2D(goal_posts(pitch), radii=rr.Radius.ui_points(4.0), colors=_LINE_COLOUR),
            static=True,
        )
        rec.log(
            "field/ball",
            rr.Points2D.from_fields(radii=pitch.ball_radius_m, colors=_BALL_COLOUR),
            static=True,
        )
        for team in self._teams:
            colour = team_colour(team, self._teams)
            base = f"field/players/{_entity_name(team)}"
            rec.log(
                base,
                rr.Points2D.from_fields(
                    radii=rr.Radius.ui_points(2.5), colors=colour, show_labels=True
                ),
                static=True,
            )
            rec.log(
                f"{base}/outline",
                rr.LineStrips2D.from_fields(radii=rr.Radius.ui_points(1.5), colors=colour),
                static=True,
            )
            rec.log(
                f"{base}/heading",
                rr.Arrows2D.from_fields(radii=rr.Radius.ui_points(1.5), colors=colour),
                static=True,
            )

    def _log_percept_style(self, observer: PlayerRef) -> None:
        """Static colours of one observer's perceived entities: its team's, half transparent."""
        import rerun as rr

        colour = (*team_colour(observer.team, self._teams), _PERCEIVED_ALPHA)
        base = f"field/perceived/{_entity_name(str(observer))}"
        self._rec.log(
            f"{base}/ball",
            rr.Points2D.from_fields(radii=self.pitch.ball_radius_m, colors=colour),
            static=True,
        )
        self._rec.log(
            f"{base}/players",
            rr.Points2D.from_fields(
                radii=0.6 * self.pitch.player_radius_m, colors=colour, show_labels=True
            ),
            static=True,
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
        ball trailing the true one. A percept without a ball clears the perceived ball.

        Args:
            percept: The player's egocentric view.
            observer: The pose to convert from: the observer's true pose (for the sensor's
                own view, pass its pose at ``percept.observed_tick``).
        """
        if self._closed:
            raise RuntimeError("TrialRecorder is closed")
        buf = self._percepts.get(percept.player)
        if buf is None:
            buf = self._percepts[percept.player] = _PerceptBuffer()
            self._log_percept_style(percept.player)
        buf.ticks.append(percept.tick)
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
            text = event.text if event.player is None else f"{event.player}: {event.text}"
            self._add_text(f"events/{_entity_name(event.channel)}", event.tick, text, "INFO")

    def log_label(self, tick: int, label: str, detail: str = "") -> None:
        """Buffer a trial label (e.g. ``"GOAL"``, ``"SUCCESS"``) under ``events/label``."""
        if self._closed:
            raise RuntimeError("TrialRecorder is closed")
        self._add_text("events/label", tick, f"{label}: {detail}" if detail else label, "INFO")

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
        indexes = _time_indexes(self._ticks, self.dt_s)
        n_rows = len(self._ticks)
        ball = np.asarray(self._ball_xy, dtype=np.float64).reshape(n_rows, 2)
        rec.send_columns("field/ball", indexes=indexes, columns=rr.Points2D.columns(positions=ball))
        poses = np.asarray(self._poses, dtype=np.float64).reshape(n_rows, len(self.players), 3)
        for team in self._teams:
            idx = self._team_index[team]
            team_poses = poses[:, idx, :]
            present = ~np.isnan(team_poses[:, :, 0])
            lengths = present.sum(axis=1).tolist()
            flat = team_poses[present]  # row-major: time order, then player order
            labels = np.broadcast_to(self._labels[idx], present.shape)[present].tolist()
            headings = np.column_stack([np.cos(flat[:, 2]), np.sin(flat[:, 2])])
            arrow_m = 1.6 * self.pitch.player_radius_m  # reaches past the body's edge
            base = f"field/players/{_entity_name(team)}"
            rec.send_columns(
                base,
                indexes=indexes,
                columns=rr.Points2D.columns(positions=flat[:, :2], labels=labels).partition(
                    lengths
                ),
            )
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
        """Send each observer's buffered perceived ball and player rows."""
        import rerun as rr

        for observer, buf in self._percepts.items():
            if not buf.ticks:
                continue
            indexes = _time_indexes(buf.ticks, self.dt_s)
            base = f"field/perceived/{_entity_name(str(observer))}"
            ball = np.asarray(buf.ball_xy, dtype=np.float64).reshape(-1, 2)
            self._rec.send_columns(
                f"{base}/ball",
                indexes=indexes,
                columns=rr.Points2D.columns(positions=ball).partition(buf.ball_lengths),
            )
            seen = np.asarray(buf.player_xy, dtype=np.float64).reshape(-1, 2)
            self._rec.send_columns(
                f"{base}/players",
                indexes=indexes,
                columns=rr.Points2D.columns(positions=seen, labels=buf.player_labels).partition(
                    buf.player_lengths
                ),
            )
            self._percepts[observer] = _PerceptBuffer()

    def _flush_texts(self) -> None:
        """Send the buffered text rows of every text entity."""
        import rerun as rr

        for entity, buf in self._texts.items():
            if not buf.ticks:
                continue
            self._rec.send_columns(
                entity,
                indexes=_time_indexes(buf.ticks, self.dt_s),
                columns=rr.TextLog.columns(text=buf.texts, level=buf.levels),
            )
            self._texts[entity] = _TextBuffer()

    # --- closing ----------------------------------------------------------------------------

    def close(self) -> None:
        """Flush the buffers and disconnect, which writes the file's footer. Idempotent."""
        if self._closed:
            return
        try:
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
    print(f"On a desktop, open it with:      rerun {path}")
    print(f"To serve it to a web browser:    rerun --web-viewer {path}")
    print(f"verifying {path} ...", flush=True)
    ok, message = verify_recording(path)
    print(f"{'verified' if ok else 'verification FAILED'}: {message}")
    return 0 if ok else 1
