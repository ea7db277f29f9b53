"""Rerun recordings of whole matches, with a default layout meant for watching (DESIGN.md §5).

A :class:`MatchRecorder` writes one ``.rrd`` file per match from :class:`GameFrame` records
(the truth, the play mode and the score of every tick), the selected player's percepts and
the arena's events. Like a trial's recording
(:class:`~robotsoccer.replay.recording.TrialRecorder`) it is a thin layer on the drawing toolkit:
a :class:`~robotsoccer.replay.field_recorder.FieldRecorder` (static pitch, team colours, heading
arrows and the rotated outlines of square robots, perceived-ball rings, buffered
``send_columns``, the display flip, y up) with the match's own pieces from
:mod:`robotsoccer.replay.match_drawing`. It adds or changes:

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

from collections.abc import Sequence
from dataclasses import replace
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from field_models.arena import ArenaEvent
from field_models.protocol import LEFT, RIGHT, BodyState, Percept, Pitch, PlayerRef
from robotsoccer.replay.field_recorder import FieldRecorder, Scene
from robotsoccer.replay.frames import GameFrame
from robotsoccer.replay.geometry import DrawSizes, draw_sizes, egocentric_to_field, view_bounds
from robotsoccer.replay.match_drawing import (
    HALO,
    SELECTED_COLOUR,
    STATUS_COLOUR,
    BallTrail,
    Scoreboard,
    ScoreRows,
    SightRows,
    log_match_styles,
    send_halo,
)
from robotsoccer.replay.palette import ROUTINE_DECISIONS, entity_name
from robotsoccer.replay.rows import StrokeRows
from robotsoccer.replay.toolkit import field_view, side_by_side, text_log_view, time_indexes

if TYPE_CHECKING:
    import rerun.blueprint as rrb

TRAIL_SECONDS = 1.5
"""Default length of the ball's trail [s]."""
MIN_BALL_FRACTION = 0.009
"""The ball is drawn with a radius of at least this fraction of the pitch length."""
SHOWN_CHANNELS = frozenset({"referee", "decision"})
"""Arena event channels that reach the event log; the others are dropped."""

_VIEW_TOP = 0.11


class MatchRecorder(FieldRecorder):
    """Writes one match to a rerun ``.rrd`` file, headless, with a layout for watching it.

    Use it as a context manager, or call :meth:`close` at the end (the file's footer is only
    written then). Call :meth:`log_frame` once per tick, in tick order; :meth:`log_percept`
    and :meth:`log_events` as percepts and events come. ``log_label`` (a trial's outcome) is
    not meant for matches: it would draw over the scoreboard.

    Args:
        path: Output ``.rrd`` file; its folder is created if missing.
        scene: What is drawn (:class:`~robotsoccer.replay.field_recorder.Scene`): the players'
            teams must be ``LEFT`` and ``RIGHT`` (the score is (left, right)); the selected
            player's perceived ball (and its line of sight) vanish 1.5 sensor periods after its
            latest percept.
        teams: Display names of the left and the right team (e.g. ``("layered", "baseline")``).
        selected: The player whose percepts are drawn and who is highlighted; None: nobody.
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
        scene: Scene,
        *,
        teams: tuple[str, str],
        selected: PlayerRef | None,
        recording_id: str,
        every_ticks: int = 1,
        trail_ticks: int | None = None,
        chunk_frames: int = 1000,
    ) -> None:
        pitch, players, dt_s = scene.pitch, scene.players, scene.dt_s
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
        self._trail = BallTrail(trail_ticks, every_ticks, pitch.length_m)
        self._selected_index = -1 if selected is None else players.index(selected)
        # The line of sight, one row per percept of the selected player (as its ball ring):
        # from where it stood to where it saw the ball; an empty row clears it.
        self._sight = SightRows()
        self._score: tuple[int, int] | None = None
        self._play_mode: str | None = None
        self._clock_s = -1
        self._scores = ScoreRows()
        self._board = StrokeRows()
        self._status = StrokeRows()
        super().__init__(
            path,
            scene,
            recording_id=recording_id,
            every_ticks=every_ticks,
            chunk_frames=chunk_frames,
        )
        self._scoreboard = Scoreboard(pitch, self.team_names, self._teams)

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
        return SELECTED_COLOUR

    def _view_bounds(self) -> tuple[list[float], list[float]]:
        """The field view's x and y ranges (view frame: y down), with the scoreboard's room."""
        return view_bounds(self.pitch, _VIEW_TOP)

    def _blueprint(self) -> rrb.Blueprint:
        """The field on the left; the legend, the goals over time and the events on the right.

        The field view's origin is the root, so the flip on ``field`` applies (as in the trial
        recorder). The selected player's perceived players are recorded but left out of the
        view: rings around half the players distract from the game; the blueprint panel can
        show them. The time panel stays collapsed to its scrubber and play controls: expanded,
        it lists every stream and takes a third of the screen.
        """
        import rerun.blueprint as rrb

        contents = ["+ /field/**"]
        if self.selected is not None:
            contents.append(f"- /field/perceived/{entity_name(str(self.selected))}/players")
        left, right = self.team_names
        field = field_view(f"{left} (blue) vs {right} (yellow)", contents, self._view_bounds())
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
        return side_by_side(
            field, (legend, goals, events), row_shares=[3, 2, 4], column_shares=[7, 3]
        )

    def _log_static(self) -> None:
        """The trial recorder's statics, then the trail, halo, sight and score styles."""
        super()._log_static()
        log_match_styles(self._rec, self.team_names, self._teams)

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
        self._check_open()
        tick = frame.truth.tick
        score = frame.score
        changed = score != self._score
        if changed:
            self._on_score(tick, score)
        clock_s = int(tick * self.dt_s + 1e-9)  # whole seconds; the epsilon keeps 0.1·10 at 1
        if frame.play_mode != self._play_mode or clock_s != self._clock_s:
            self._play_mode = frame.play_mode
            self._clock_s = clock_s
            strokes = self._scoreboard.status_strokes(frame.play_mode, clock_s)
            self._status.add(tick, strokes, STATUS_COLOUR)
        if changed or tick % self.every_ticks == 0:
            self._scores.add(tick, score)
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
        sight = self._sight
        if sight.expires is not None and tick > sight.expires:
            sight.add(sight.expires, None)  # went stale before this one came
        life = self._percept_life
        sight.expires = None if life is None else tick + life
        ball = percept.ball
        seen = (
            None if ball is None else egocentric_to_field(observer, ball.distance_m, ball.angle_rad)
        )
        sight.add(tick, None if seen is None else (observer.x, observer.y, *seen))

    def _expire_percepts(self) -> None:
        """Clear stale percepts (the trial recorder's) and a stale line of sight, at closing."""
        super()._expire_percepts()
        expires = self._sight.expires
        if expires is not None and expires <= self._last_tick:
            self._sight.add(expires, None)
            self._sight.expires = None

    def log_events(self, events: Sequence[ArenaEvent]) -> None:
        """Buffer the referee's and the minds' events; commands, sees, hears and links are dropped.

        Raises:
            RuntimeError: If the recorder is closed.
        """
        self._check_open()
        kept = [event for event in events if event.channel in SHOWN_CHANNELS]
        if kept:
            super().log_events(kept)

    def _on_score(self, tick: int, score: tuple[int, int]) -> None:
        """A new score: redraw the scoreboard; after the first frame, a line in the events."""
        left, right = self.team_names
        previous = self._score
        self._score = score
        self._board.extend(tick, self._scoreboard.strokes(score))
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

    # --- flushing -----------------------------------------------------------------------------

    def flush(self) -> None:
        """Send everything buffered: the match's own rows, then the trial recorder's."""
        self._flush_match_truth()
        self._sight.send(self._rec, "field/selected/sight", self.dt_s)
        self._scores.send(self._rec, self.dt_s)
        self._board.send(self._rec, "field/scoreboard", self.dt_s)
        self._status.send(self._rec, "field/scoreboard/status", self.dt_s)
        super().flush()

    def _flush_match_truth(self) -> None:
        """The trail and the halo of the buffered truth rows (before the base sends them)."""
        truth = self._truth
        if not truth.ticks:
            return
        indexes = time_indexes(truth.ticks, self.dt_s)
        ticks = np.asarray(truth.ticks, dtype=np.int64)
        self._trail.send(self._rec, indexes, ticks, truth.ball())
        if self._selected_index >= 0:
            me = truth.pose_array()[:, self._selected_index, :2]
            send_halo(self._rec, indexes, me, HALO * self.sizes.player_m)
