"""Rerun recordings of whole matches, with a default layout meant for watching (DESIGN.md §5).

A :class:`MatchRecorder` writes one ``.rrd`` file per match from :class:`GameFrame` records
(the truth, the play mode and the score of every tick), the selected player's percepts and
the arena's events. It is a :class:`~robotsoccer.replay.recording.TrialRecorder` with more on
the field: it reuses the trial recorder's static pitch, team colours, heading arrows (and the
rotated outlines of square robots), perceived-ball rings, buffered ``send_columns`` and the
display flip (y up), and adds or changes:

- players labelled with their numbers only (with 22 players ``left10`` labels clutter);
  round players get no outline (their arrow shows the heading; 22 outlines a tick were
  over half the file);
- the ball drawn larger (:data:`MIN_BALL_FRACTION`), so the eye finds it among 22 players;
- a fading trail behind the ball (the last ``trail_ticks``, 1.5 s by default);
- the selected player highlighted by a halo, its perceived ball as a ring and its line of
  sight to that ball, all in magenta; other players' percepts are dropped on arrival;
- a scoreboard above the field in large stroke letters (``LAYERED 2 : 1 BASELINE`` in the
  team colours) and beneath it the play mode and the match clock (``PLAY ON 12:34``);
- each team's goals as a scalar series, so a time-series view shows when the goals came;
- referee calls, decisions (passes, shots, the selected player's kicks) and goals in a text
  log; the selected player's routine decisions (turns, dashes, nothing) on their own entity,
  left out of the default layout; the command, see, hear and link channels are dropped: 22
  players send a command every tick, which would bury the few lines a person reads and
  dominate the file.

Layout (blueprint): the field on the left; on the right the legend, the goals over time and
the event log; the time panel collapsed to its scrubber on the ``sim_time`` timeline.

Entity layout (besides the trial recorder's ``field/...``, ``legend`` and ``events/...``)::

    field/players/<team>, .../name       labels are the player numbers
    field/ball/trail                     LineStrips2D, one strip per segment, fading with age
    field/selected                       Ellipses2D halo: a circle around the selected player
    field/selected/sight                 LineStrips2D, at each percept: player -> perceived ball
    field/perceived/<selected>/ball      Ellipses2D ring (the trial recorder's)
    field/perceived/<selected>/players   Ellipses2D rings; recorded, hidden in the field view
    field/scoreboard                     LineStrips2D, the score line, one colour per stroke
    field/scoreboard/status              LineStrips2D, play mode and clock
    score/left, score/right              Scalars, goals so far (every recorded tick)
    events/referee, events/decision      TextLog, "[channel] player: text"
    events/routine                       TextLog, the selected player's routine decisions
                                         (turns, dashes, nothing); hidden by default
    events/score                         TextLog, "[goal] layered: layered 1 : 0 baseline"

Speed: as in the trial recorder, the per-tick work is appending floats to buffers; the trail,
halo, line of sight and score series go out with ``send_columns`` when the truth buffer is
flushed. The scoreboard rows are few (a goal, a play-mode change, a new second on the clock).
A 6000-tick 11 v 11 match recorded every tick costs about 0.5-1 s and 7.5 MB.

Rerun is imported inside functions only, so importing this module does not load the SDK.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from field_models.arena import ArenaEvent, PlayerShape
from field_models.protocol import LEFT, RIGHT, BodyState, Percept, Pitch, PlayerRef
from robotsoccer.replay.frames import GameFrame
from robotsoccer.replay.recording import (
    ROUTINE_DECISIONS,
    SIM_TIME,
    DrawSizes,
    TrialRecorder,
    draw_sizes,
    egocentric_to_field,
    entity_name,
    team_colour,
    text_log_view,
    text_strokes,
    text_width,
    time_indexes,
)

if TYPE_CHECKING:
    import rerun as rr
    import rerun.blueprint as rrb

TRAIL_SECONDS = 1.5
"""Default length of the ball's trail [s]."""
MIN_BALL_FRACTION = 0.009
"""The ball is drawn with a radius of at least this fraction of the pitch length."""
MAX_TRAIL_POINTS = 24
"""At most this many past positions make up the trail (thinned on fine ticks)."""
SHOWN_CHANNELS = frozenset({"referee", "decision"})
"""Arena event channels that reach the event log; the others are dropped."""

_SELECTED_COLOUR = (255, 70, 220)  # magenta: far from both team colours, the ball and the grass
_BALL_COLOUR = (255, 120, 0)  # as recording.py draws the ball
_PITCH_COLOUR = (24, 64, 36)  # and the grass
_WHITE = (235, 235, 235)
_STATUS_COLOUR = (200, 200, 200)
_TRAIL_FADE = 0.85  # the oldest segment is this far blended into the grass, not invisible
_TRAIL_WIDE_PT, _TRAIL_THIN_PT = 3.0, 1.0  # newest and oldest segment half-widths [ui points]
# A trail segment longer than this fraction of the pitch length is a restart (the ball put
# back on a spot), not a kick; the trail is cut there rather than drawn across the field.
_TRAIL_JUMP_FRACTION = 0.15
# Draw orders (the trial recorder's: markings 10, players 30-32, ball 40, percepts 50).
_HALO = 1.6  # the halo's radius in player sizes: clear of a square robot's corners (1.41)
_ORDER_HALO = 29.0
_ORDER_SIGHT = 29.5  # over the halo, under the players: it must not hide a player's arrow
_ORDER_TRAIL = 35.0
_ORDER_BOARD = 60.0
# The scoreboard, above the top side line, in fractions of the pitch length.
_BOARD_BASE, _BOARD_HEIGHT, _BOARD_WIDTH = 0.05, 0.045, 0.92
_STATUS_BASE, _STATUS_HEIGHT = 0.012, 0.022
_VIEW_TOP = 0.11


class MatchRecorder(TrialRecorder):
    """Writes one match to a rerun ``.rrd`` file, headless, with a layout for watching it.

    Use it as a context manager, or call :meth:`close` at the end (the file's footer is only
    written then). Call :meth:`log_frame` once per tick, in tick order; :meth:`log_percept`
    and :meth:`log_events` as percepts and events come. ``log_label`` (a trial's outcome) is
    not meant for matches: it would draw over the scoreboard.

    Args:
        path: Output ``.rrd`` file; its folder is created if missing.
        pitch: Field geometry.
        players: Players on the field, in a fixed order; their teams must be ``LEFT`` and
            ``RIGHT`` (the score is (left, right)).
        dt_s: Length of one tick [s]; ``sim_time`` = tick × dt_s.
        player_shape: ``"square"`` (robots) or ``"circle"`` (Soccer Server players).
        sensor_period_s: Time between two percepts of a player [s]; the selected player's
            perceived ball (and its line of sight) vanish 1.5 periods after its latest percept.
        teams: Display names of the left and the right team (e.g. ``("layered", "baseline")``).
        selected: The player whose percepts are drawn and who is highlighted; None: nobody.
        title: First line of the legend (e.g. the match and its seed).
        recording_id: Rerun recording id.
        every_ticks: Record the truth (and the trail, halo, score series) only on ticks that
            are multiples of this; score and play-mode changes are caught on every tick.
        trail_ticks: Length of the ball's trail in ticks; None: :data:`TRAIL_SECONDS` worth.
        chunk_frames: Recorded ticks buffered before one ``send_columns`` batch.

    Raises:
        ValueError: On a bad shape, non-positive dt_s, every_ticks, chunk_frames,
            sensor_period_s or trail_ticks, a player on neither side, or a selected player
            who is not playing.
    """

    # 22 rotated 12-gons per tick would be over half the file and a third of the time; a round
    # player's heading is its arrow. Square robots keep their rotated outlines.
    _circle_outlines = False

    def __init__(
        self,
        path: Path,
        *,
        pitch: Pitch,
        players: tuple[PlayerRef, ...],
        dt_s: float,
        player_shape: PlayerShape,
        sensor_period_s: float,
        teams: tuple[str, str],
        selected: PlayerRef | None,
        title: str,
        recording_id: str,
        every_ticks: int = 1,
        trail_ticks: int | None = None,
        chunk_frames: int = 1000,
    ) -> None:
        if not dt_s > 0.0:
            raise ValueError(f"dt_s must be > 0, got {dt_s}")
        if trail_ticks is None:
            trail_ticks = max(1, round(TRAIL_SECONDS / dt_s))
        if trail_ticks < 1:
            raise ValueError(f"trail_ticks must be >= 1, got {trail_ticks}")
        if any(p.team not in (LEFT, RIGHT) for p in players):
            raise ValueError("a match's players must be on the LEFT or the RIGHT team")
        if selected is not None and selected not in players:
            raise ValueError(f"selected player {selected} is not among the players")
        # Set before the base class's __init__: it builds the blueprint and logs the statics.
        self.team_names = (teams[0], teams[1])
        self.selected = selected
        self.trail_ticks = trail_ticks
        # Thin the trail to at most MAX_TRAIL_POINTS past positions, on a fixed grid of ticks
        # so a point does not slide along the path from one frame to the next.
        every = max(1, every_ticks)
        self._trail_stride = every * max(1, math.ceil(trail_ticks / (every * MAX_TRAIL_POINTS)))
        self._trail_hist_ticks = np.zeros(0, dtype=np.int64)
        self._trail_hist_xy = np.zeros((0, 2))
        self._selected_index = -1 if selected is None else players.index(selected)
        # The line of sight, one row per percept of the selected player (as its ball ring):
        # from where it stood to where it saw the ball; an empty row clears it.
        self._sight_ticks: list[int] = []
        self._sight_xy: list[float] = []  # 4 floats (from, to) per row that has a line
        self._sight_lengths: list[int] = []
        self._sight_expires: int | None = None
        self._score: tuple[int, int] | None = None
        self._play_mode: str | None = None
        self._clock_s = -1
        self._score_ticks: list[int] = []
        self._score_values: list[float] = []  # left, right per row
        self._board = _StrokeRows()
        self._status = _StrokeRows()
        super().__init__(
            path,
            pitch=pitch,
            players=players,
            dt_s=dt_s,
            recording_id=recording_id,
            player_shape=player_shape,
            every_ticks=every_ticks,
            chunk_frames=chunk_frames,
            sensor_period_s=sensor_period_s,
            title=title,
        )
        length = pitch.length_m
        self._max_trail_step_m = _TRAIL_JUMP_FRACTION * length
        # One height for the whole match: wide enough for two-digit scores, so the letters do
        # not change size when a team reaches ten.
        units = text_width(self._board_text(88, 88), 1.0)
        self._board_height_m = min(_BOARD_HEIGHT * length, _BOARD_WIDTH * length / units)

    # --- layout -------------------------------------------------------------------------------

    def _draw_sizes(self, pitch: Pitch) -> DrawSizes:
        """The trial recorder's sizes, with the ball no smaller than :data:`MIN_BALL_FRACTION`.

        Among 22 players the trial recorder's ball (0.6 % of the pitch length) is lost under
        its own trail and the players' arrows; the ball is what a watcher follows.
        """
        sizes = draw_sizes(pitch)
        ball = max(sizes.ball_m, MIN_BALL_FRACTION * pitch.length_m)
        return replace(sizes, ball_m=ball, ball_enlarged=ball > pitch.ball_radius_m)

    def _player_label(self, player: PlayerRef) -> str:
        """Players are labelled by number: the disc's colour already says the team."""
        return str(player.number)

    def _percept_colour(self, observer: PlayerRef) -> tuple[int, int, int]:
        """The selected player's percepts are magenta, like its halo and line of sight."""
        return _SELECTED_COLOUR

    def _view_bounds(self) -> tuple[list[float], list[float]]:
        """The field view's x and y ranges (view frame: y down), with the scoreboard's room."""
        x_range, (_, bottom) = super()._view_bounds()
        top = self.pitch.half_width_m + _VIEW_TOP * self.pitch.length_m
        return x_range, [-top, bottom]

    def _blueprint(self) -> rrb.Blueprint:
        """The field on the left; the legend, the goals over time and the events on the right.

        The field view's origin is the root, so the flip on ``field`` applies (as in the trial
        recorder). The selected player's perceived players are recorded but left out of the
        view: rings around half the players distract from the game; the blueprint panel can
        show them. The time panel stays collapsed to its scrubber and play controls: expanded,
        it lists every stream and takes a third of the screen.
        """
        import rerun.blueprint as rrb

        x_range, y_range = self._view_bounds()
        contents = ["+ /field/**"]
        if self.selected is not None:
            contents.append(f"- /field/perceived/{entity_name(str(self.selected))}/players")
        left, right = self.team_names
        field_view = rrb.Spatial2DView(
            name=f"{left} (blue) vs {right} (yellow)",
            origin="/",
            contents=contents,
            background=rrb.Background(kind="SolidColor", color=_PITCH_COLOUR),
            visual_bounds=rrb.VisualBounds2D(x_range=x_range, y_range=y_range),
        )
        legend = rrb.TextDocumentView(name="legend", origin="/legend")
        # The whole match, always: by default the view follows the last minute or so, and a
        # goal scored earlier would not show as a step.
        whole = rrb.TimeRange(
            start=rrb.TimeRangeBoundary.infinite(), end=rrb.TimeRangeBoundary.infinite()
        )
        goals = rrb.TimeSeriesView(
            name="goals",
            origin="/score",
            plot_legend=rrb.PlotLegend(corner="LeftTop"),
            axis_x=rrb.TimeAxis(view_range=whole),
        )
        # Each line names its channel ("[referee] ..."): the entity column would only cut it.
        events = text_log_view(
            "events", "/events", entity_column=False, hidden=(ROUTINE_DECISIONS,)
        )
        return rrb.Blueprint(
            rrb.Horizontal(
                field_view,
                rrb.Vertical(legend, goals, events, row_shares=[3, 2, 4]),
                column_shares=[7, 3],
            ),
            rrb.BlueprintPanel(state="collapsed"),
            rrb.SelectionPanel(state="collapsed"),
            rrb.TimePanel(timeline=SIM_TIME, state="collapsed"),
        )

    def _log_static(self) -> None:
        """The trial recorder's statics, then the trail, halo, sight and score styles."""
        import rerun as rr

        super()._log_static()
        rec = self._rec
        rec.log(
            "field/ball/trail", rr.LineStrips2D.from_fields(draw_order=_ORDER_TRAIL), static=True
        )
        rec.log(
            "field/selected",
            rr.Ellipses2D.from_fields(
                line_radii=rr.Radius.ui_points(2.5),
                colors=_SELECTED_COLOUR,
                show_labels=False,
                draw_order=_ORDER_HALO,
            ),
            static=True,
        )
        rec.log(
            "field/selected/sight",
            rr.LineStrips2D.from_fields(
                radii=rr.Radius.ui_points(1.0), colors=_SELECTED_COLOUR, draw_order=_ORDER_SIGHT
            ),
            static=True,
        )
        rec.log(
            "field/scoreboard",
            rr.LineStrips2D.from_fields(radii=rr.Radius.ui_points(2.5), draw_order=_ORDER_BOARD),
            static=True,
        )
        rec.log(
            "field/scoreboard/status",
            rr.LineStrips2D.from_fields(
                radii=rr.Radius.ui_points(1.5), colors=_STATUS_COLOUR, draw_order=_ORDER_BOARD
            ),
            static=True,
        )
        for side, name in zip((LEFT, RIGHT), self.team_names, strict=True):
            rec.log(
                f"score/{side}",
                rr.SeriesLines(colors=team_colour(side, self._teams), names=name, widths=2.0),
                static=True,
            )

    def legend(self, outcome: str = "") -> str:
        """The legend beside the field (markdown): the teams and the key to the drawing."""
        left, right = self.team_names
        trail_s = self.trail_ticks * self.dt_s
        if self.selected is None:
            selected = "No player is selected, so no percepts are drawn."
        else:
            selected = (
                f"**Magenta**: the selected player {self.selected} (halo), the ball as it "
                "perceives it (ring) and its line of sight to that ball. The players it "
                "perceives are recorded but hidden (blueprint panel: "
                f"`field/perceived/{entity_name(str(self.selected))}/players`)."
            )
        lines = [
            f"### {outcome}" if outcome else f"### {self.title}",
            "",
            f"**{left}** (blue, attacks right) vs **{right}** (yellow, attacks left)",
            "",
            "- Discs are players, numbered, with a white arrow for the heading; the orange "
            f"disc is the ball, with a trail of its last {trail_s:.3g} s.",
            f"- {selected}",
            "- Above the field: the score, the play mode and the clock. **goals**: each "
            "team's goals over time. **events**: referee calls, decisions (passes, shots), goals.",
        ]
        if self.sizes.ball_enlarged or self.sizes.players_enlarged:
            lines.append("- Ball and players are drawn larger than they are, to stay visible.")
        return "\n".join(lines)

    # --- logging (hot path) -------------------------------------------------------------------

    def log_frame(self, frame: GameFrame) -> None:
        """Buffer one tick: its truth (if recorded), and the score and play mode when changed.

        Call it every tick, in tick order: goals and play-mode changes are caught on every
        call, the truth, trail and score series only every ``every_ticks``.

        Raises:
            RuntimeError: If the recorder is closed.
        """
        if self._closed:
            raise RuntimeError("MatchRecorder is closed")
        tick = frame.truth.tick
        score = frame.score
        changed = score != self._score
        if changed:
            self._on_score(tick, score)
        clock_s = int(tick * self.dt_s + 1e-9)  # whole seconds; the epsilon keeps 0.1·10 at 1
        if frame.play_mode != self._play_mode or clock_s != self._clock_s:
            self._play_mode = frame.play_mode
            self._clock_s = clock_s
            self._status.add(tick, self._status_strokes(frame.play_mode, clock_s), _STATUS_COLOUR)
        if changed or tick % self.every_ticks == 0:
            self._score_ticks.append(tick)
            self._score_values.extend(score)
        self.log_truth(frame.truth)

    def log_percept(self, percept: Percept, observer: BodyState) -> None:
        """Buffer the selected player's percept (ball ring, line of sight); others are ignored.

        Args:
            percept: A player's egocentric view.
            observer: The pose to convert from (see the trial recorder's ``log_percept``).
        """
        if percept.player != self.selected:
            return
        super().log_percept(percept, observer)
        # Kept at the percept's tick with the ring's lifetime, not per frame from the latest
        # percept: a runner logs a tick's frame before its percepts, and the line would blink.
        tick = percept.tick
        if self._sight_expires is not None and tick > self._sight_expires:
            self._add_sight(self._sight_expires, None)  # went stale before this one came
        life = self._percept_life
        self._sight_expires = None if life is None else tick + life
        ball = percept.ball
        seen = (
            None if ball is None else egocentric_to_field(observer, ball.distance_m, ball.angle_rad)
        )
        self._add_sight(tick, None if seen is None else (observer.x, observer.y, *seen))

    def _add_sight(self, tick: int, line: tuple[float, float, float, float] | None) -> None:
        """One row of the line of sight: (from x, y, to x, y), or None to clear it."""
        self._sight_ticks.append(tick)
        if line is None:
            self._sight_lengths.append(0)
        else:
            self._sight_xy.extend(line)
            self._sight_lengths.append(1)

    def _expire_percepts(self) -> None:
        """Clear stale percepts (the trial recorder's) and a stale line of sight, at closing."""
        super()._expire_percepts()
        expires = self._sight_expires
        if expires is not None and expires <= self._last_tick:
            self._add_sight(expires, None)
            self._sight_expires = None

    def log_events(self, events: Sequence[ArenaEvent]) -> None:
        """Buffer the referee's and the minds' events; commands, sees, hears and links are dropped.

        Raises:
            RuntimeError: If the recorder is closed.
        """
        if self._closed:
            raise RuntimeError("MatchRecorder is closed")
        kept = [event for event in events if event.channel in SHOWN_CHANNELS]
        if kept:
            super().log_events(kept)

    def _on_score(self, tick: int, score: tuple[int, int]) -> None:
        """A new score: redraw the scoreboard; after the first frame, a line in the events."""
        left, right = self.team_names
        previous = self._score
        self._score = score
        self._board.extend(tick, self._board_strokes(score))
        if previous is None:
            return
        scorers = [
            name
            for name, old, new in zip(self.team_names, previous, score, strict=True)
            if new > old
        ]
        who = " and ".join(scorers) if scorers else "score corrected"
        line = f"[goal] {who}: {left} {score[0]} : {score[1]} {right}"
        self._add_text("events/score", tick, line, "INFO")

    # --- the scoreboard -----------------------------------------------------------------------

    def _board_text(self, left_goals: int, right_goals: int) -> str:
        """The score line, ``layered 2 : 1 baseline``."""
        left, right = self.team_names
        return f"{left} {left_goals} : {right_goals} {right}"

    def _board_strokes(self, score: tuple[int, int]) -> list[tuple[np.ndarray, tuple[int, ...]]]:
        """The score line's strokes, each with its colour: the teams' parts in their colours.

        Each part is drawn from the whole line with every other character blanked (a blank
        leaves a gap of the same width), so the parts land where they would in the whole line.
        """
        left = self.team_names[0]
        text = self._board_text(*score)
        colon = text.index(":", len(left) + 1)
        parts = (
            (0, colon - 1, team_colour(LEFT, self._teams)),
            (colon, colon + 1, _WHITE),
            (colon + 2, len(text), team_colour(RIGHT, self._teams)),
        )
        base = self.pitch.half_width_m + _BOARD_BASE * self.pitch.length_m
        out: list[tuple[np.ndarray, tuple[int, ...]]] = []
        for start, stop, colour in parts:
            masked = " " * start + text[start:stop] + " " * (len(text) - stop)
            for stroke in text_strokes(
                masked, height_m=self._board_height_m, centre_x_m=0.0, base_y_m=base
            ):
                out.append((stroke, colour))
        return out

    def _status_strokes(self, play_mode: str, clock_s: int) -> list[np.ndarray]:
        """Play mode and clock beneath the score: ``PLAY ON  12:34`` (``_`` reads as a gap)."""
        minutes, seconds = divmod(clock_s, 60)
        length = self.pitch.length_m
        return text_strokes(
            f"{play_mode}  {minutes:02d}:{seconds:02d}",
            height_m=_STATUS_HEIGHT * length,
            centre_x_m=0.0,
            base_y_m=self.pitch.half_width_m + _STATUS_BASE * length,
        )

    # --- flushing -----------------------------------------------------------------------------

    def flush(self) -> None:
        """Send everything buffered: the match's own rows, then the trial recorder's."""
        self._flush_match_truth()
        self._flush_sight()
        self._flush_score()
        self._board.send(self._rec, "field/scoreboard", self.dt_s)
        self._status.send(self._rec, "field/scoreboard/status", self.dt_s)
        super().flush()

    def _flush_match_truth(self) -> None:
        """The trail and the halo of the buffered truth rows (before the base sends them)."""
        if not self._ticks:
            return
        import rerun as rr

        rec = self._rec
        ticks = np.asarray(self._ticks, dtype=np.int64)
        n_rows = len(ticks)
        indexes = time_indexes(self._ticks, self.dt_s)
        ball = np.asarray(self._ball_xy, dtype=np.float64).reshape(n_rows, 2)
        strips, colours, radii, lengths = self._trail_rows(ticks, ball)
        rec.send_columns(
            "field/ball/trail",
            indexes=indexes,
            columns=rr.LineStrips2D.columns(strips=strips, colors=colours, radii=radii).partition(
                lengths
            ),
        )
        if self._selected_index >= 0:
            poses = np.asarray(self._poses, dtype=np.float64).reshape(n_rows, len(self.players), 3)
            me = poses[:, self._selected_index, :2]
            here = ~np.isnan(me[:, 0])
            # A circle, not a disc: a filled disc swamps a robot drawn at its true size. The
            # sizes go in every row (Ellipses2D's required component, as for percept rings).
            centres = me[here]
            rec.send_columns(
                "field/selected",
                indexes=indexes,
                columns=rr.Ellipses2D.columns(
                    centers=centres, half_sizes=np.full_like(centres, _HALO * self.sizes.player_m)
                ).partition(here.astype(int)),
            )

    def _flush_sight(self) -> None:
        """Send the buffered rows of the selected player's line of sight."""
        if not self._sight_ticks:
            return
        import rerun as rr

        self._rec.send_columns(
            "field/selected/sight",
            indexes=time_indexes(self._sight_ticks, self.dt_s),
            columns=rr.LineStrips2D.columns(
                strips=np.asarray(self._sight_xy, dtype=np.float32).reshape(-1, 2, 2)
            ).partition(self._sight_lengths),
        )
        self._sight_ticks, self._sight_xy, self._sight_lengths = [], [], []

    def _trail_rows(
        self, ticks: np.ndarray, ball: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray, list[int]]:
        """The trail of each buffered row: its segments (S, 2, 2), colours, radii, counts.

        A row's trail joins the ball's positions at the recorded ticks on the trail's grid
        within the last ``trail_ticks`` to the ball's position now; it is cut at the latest
        jump (a restart). Older segments are blended further into the grass and drawn thinner.
        """
        hist = len(self._trail_hist_ticks)
        all_ticks = np.concatenate([self._trail_hist_ticks, ticks])
        all_xy = np.concatenate([self._trail_hist_xy, ball])
        on_grid = all_ticks % self._trail_stride == 0
        starts = np.searchsorted(all_ticks, ticks - self.trail_ticks, side="right")
        step = np.zeros(len(all_ticks))
        step[1:] = np.hypot(*(all_xy[1:] - all_xy[:-1]).T)  # from the previous recorded tick
        jumps = np.flatnonzero(step > self._max_trail_step_m)
        seg_a: list[np.ndarray] = []
        seg_b: list[np.ndarray] = []
        ages: list[np.ndarray] = []
        lengths: list[int] = []
        for row, start in enumerate(starts.tolist()):
            now = hist + row
            # Cut at the latest jump into this window: the trail starts where the ball landed.
            cut = np.searchsorted(jumps, now, side="right")
            if cut and jumps[cut - 1] > start:
                start = int(jumps[cut - 1])
            idx = np.flatnonzero(on_grid[start:now]) + start
            idx = np.append(idx, now)
            pts = all_xy[idx]
            seg_a.append(pts[:-1])
            seg_b.append(pts[1:])
            ages.append((all_ticks[now] - all_ticks[idx[:-1]]) / self.trail_ticks)
            lengths.append(len(idx) - 1)
        strips = np.stack([np.concatenate(seg_a), np.concatenate(seg_b)], axis=1)
        age = np.clip(np.concatenate(ages), 0.0, 1.0)[:, None]
        ball_rgb = np.asarray(_BALL_COLOUR, dtype=np.float64)
        grass = np.asarray(_PITCH_COLOUR, dtype=np.float64)
        colours = np.rint((1.0 - _TRAIL_FADE * age) * ball_rgb + _TRAIL_FADE * age * grass)
        # Negative radii are ui points (rerun's Radius.ui_points): the trail reads at any zoom.
        radii = -(_TRAIL_WIDE_PT - (_TRAIL_WIDE_PT - _TRAIL_THIN_PT) * age[:, 0])
        keep = all_ticks > ticks[-1] - self.trail_ticks
        self._trail_hist_ticks = all_ticks[keep]
        self._trail_hist_xy = all_xy[keep]
        return strips, colours.astype(np.uint8), radii.astype(np.float32), lengths

    def _flush_score(self) -> None:
        """Send the buffered score rows as one scalar series per team."""
        if not self._score_ticks:
            return
        import rerun as rr

        indexes = time_indexes(self._score_ticks, self.dt_s)
        values = np.asarray(self._score_values, dtype=np.float64).reshape(-1, 2)
        for column, side in enumerate((LEFT, RIGHT)):
            self._rec.send_columns(
                f"score/{side}",
                indexes=indexes,
                columns=rr.Scalars.columns(scalars=values[:, column]),
            )
        self._score_ticks = []
        self._score_values = []

    def __enter__(self) -> MatchRecorder:
        return self


class _StrokeRows:
    """Rows of stroke text (a scoreboard line) waiting for ``send_columns``: one per change."""

    __slots__ = ("colours", "lengths", "strips", "ticks")

    def __init__(self) -> None:
        self.ticks: list[int] = []
        self.strips: list[np.ndarray] = []
        self.colours: list[tuple[int, ...]] = []
        self.lengths: list[int] = []

    def add(self, tick: int, strokes: list[np.ndarray], colour: tuple[int, ...]) -> None:
        """One row of `strokes`, all in `colour`."""
        self.extend(tick, [(stroke, colour) for stroke in strokes])

    def extend(self, tick: int, strokes: list[tuple[np.ndarray, tuple[int, ...]]]) -> None:
        """One row of strokes, each with its own colour."""
        self.ticks.append(tick)
        self.strips.extend(stroke for stroke, _ in strokes)
        self.colours.extend(colour for _, colour in strokes)
        self.lengths.append(len(strokes))

    def send(self, rec: rr.RecordingStream, entity: str, dt_s: float) -> None:
        """Send the rows to `entity` of the recording stream `rec`, and empty the buffer."""
        if not self.ticks:
            return
        import rerun as rr

        rec.send_columns(
            entity,
            indexes=time_indexes(self.ticks, dt_s),
            columns=rr.LineStrips2D.columns(
                strips=_strips_array(self.strips), colors=np.asarray(self.colours, dtype=np.uint8)
            ).partition(self.lengths),
        )
        self.ticks, self.strips, self.colours, self.lengths = [], [], [], []


def _strips_array(strips: Sequence[np.ndarray]) -> Any:
    """Line strips of different lengths as one Arrow array of rerun's ``LineStrip2D`` type.

    rerun 0.41 converts a list of strips one by one (~40 µs each); a match's clock alone has
    thousands of strokes. Built here from one concatenated array, it is the same Arrow array,
    several times faster.
    """
    import pyarrow as pa
    import rerun as rr

    arrow_type = rr.components.LineStrip2DBatch([]).as_arrow_array().type
    points = (
        np.concatenate(strips).astype(np.float32).ravel() if strips else np.zeros(0, np.float32)
    )
    offsets = np.zeros(len(strips) + 1, dtype=np.int32)
    np.cumsum([len(strip) for strip in strips], out=offsets[1:])
    inner = pa.FixedSizeListArray.from_arrays(pa.array(points), 2)
    return pa.ListArray.from_arrays(pa.array(offsets), inner).cast(arrow_type)
