"""The core of every rerun recording: one stream, the field's statics, buffered rows, closing.

:class:`FieldRecorder` is what a trial's recording
(:class:`~robotsoccer.replay.recording.TrialRecorder`) and a match's
(:class:`~robotsoccer.replay.match_recording.MatchRecorder`) share: it opens the stream (a file, or
a viewer), logs the pitch and the team styles once, buffers the truth, the percepts and the event
lines, sends them in chunks and writes the footer on closing. A subclass gives the layout
(:meth:`FieldRecorder._blueprint`) and the legend (:meth:`FieldRecorder.legend`), and may change the
hooks (drawing sizes, labels, colours, view bounds). The drawing itself is
:mod:`robotsoccer.replay.toolkit`'s.

Speed (notes/tooling.md §1.4): ``rr.log`` costs ~100 µs per call, so the recorder never logs
in the simulation loop. It appends plain floats to per-entity buffers and sends them with
``send_columns`` in chunks of ``chunk_frames`` recorded ticks, which costs a few µs per tick.
Everything sits on a ``sim_time`` duration timeline derived from integer ticks × ``dt_s``
(plus a ``tick`` sequence timeline with the raw tick), never on wall-clock time.

Rerun is imported inside functions only, so importing this module does not load the SDK.
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from types import TracebackType
from typing import TYPE_CHECKING, Self

import numpy as np

from field_models.arena import ArenaEvent, FieldFacts, PlayerShape
from field_models.protocol import Action, BodyState, Percept, Pitch, PlayerRef, Truth
from robotsoccer.replay.geometry import DrawSizes, draw_sizes, outline_template, view_bounds
from robotsoccer.replay.palette import (
    PERCEPT_COLOURS,
    ROUTINE_DECISIONS,
    Colour,
    entity_name,
    is_routine,
)
from robotsoccer.replay.rows import PerceptRows, TeamDrawing, TextRows, TruthRows
from robotsoccer.replay.toolkit import (
    log_pitch,
    log_ring_style,
    log_team_styles,
    open_stream,
    time_indexes,
)

if TYPE_CHECKING:
    import rerun.blueprint as rrb

PERCEPT_LIFETIME_PERIODS = 1.5
"""A percept is shown until this many sensor periods have passed without a newer one."""


@dataclass(frozen=True, slots=True)
class Scene:
    """What a recording draws: the pitch, its players, their clock and look, and its title.

    Attributes:
        pitch: Field geometry, drawn once as static geometry.
        players: Players on the field, in a fixed order (labels, per-team entities, and the
            colour of each player's percepts).
        dt_s: Length of one tick [s]; ``sim_time`` = tick × dt_s.
        player_shape: ``"square"`` (robots, side 2·pitch.player_radius_m) or ``"circle"``
            (Soccer Server players of radius pitch.player_radius_m).
        sensor_period_s: Time between two percepts of one player [s]; a player's percept is
            cleared from the view once :data:`PERCEPT_LIFETIME_PERIODS` of these pass without
            a newer one. None: percepts stay until the next one.
        title: First line of the legend (e.g. the drill, field model and trial); empty: the
            recording id.
    """

    pitch: Pitch
    players: tuple[PlayerRef, ...]
    dt_s: float
    player_shape: PlayerShape = "square"
    sensor_period_s: float | None = None
    title: str = ""

    @classmethod
    def of(cls, facts: FieldFacts, players: tuple[PlayerRef, ...], title: str = "") -> Scene:
        """The scene of a field's trial: its pitch, tick, players' shape and sensor period."""
        return cls(
            facts.pitch, players, facts.dt_s, facts.player_shape, facts.sensor_period_s, title
        )


class FieldRecorder(ABC):
    """Writes one run to a rerun ``.rrd`` file, headless (notes/tooling.md §1).

    Use it as a context manager, or call :meth:`close` at the end: the file's footer is only
    written when the stream disconnects, and ``rerun rrd verify`` fails without it.

    Args:
        path: Output ``.rrd`` file; its folder is created if missing.
        scene: What is drawn (:class:`Scene`).
        recording_id: Rerun recording id (e.g. experiment and trial), shown by the viewer.
        application_id: Rerun application id.
        every_ticks: Record the truth only on ticks that are multiples of this.
        chunk_frames: Recorded ticks buffered before one ``send_columns`` batch.
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
        scene: Scene,
        *,
        recording_id: str,
        application_id: str = "robotsoccer",
        every_ticks: int = 1,
        chunk_frames: int = 1000,
        viewer: bool = False,
    ) -> None:
        pitch, dt_s, sensor_period_s = scene.pitch, scene.dt_s, scene.sensor_period_s
        if not dt_s > 0.0:
            raise ValueError(f"dt_s must be > 0, got {dt_s}")
        if every_ticks < 1:
            raise ValueError(f"every_ticks must be >= 1, got {every_ticks}")
        if chunk_frames < 1:
            raise ValueError(f"chunk_frames must be >= 1, got {chunk_frames}")
        if sensor_period_s is not None and not sensor_period_s > 0.0:
            raise ValueError(f"sensor_period_s must be > 0, got {sensor_period_s}")
        self.sizes = self._draw_sizes(pitch)
        self._template = outline_template(scene.player_shape, self.sizes.player_m)
        self.path = Path(path)
        self.scene = scene
        self.pitch = pitch
        self.players = tuple(scene.players)
        self.dt_s = dt_s
        self.every_ticks = every_ticks
        self.chunk_frames = chunk_frames
        self.sensor_period_s = sensor_period_s
        self.title = scene.title or recording_id
        self._player_shape = scene.player_shape
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
        self._truth = TruthRows(self.players)
        self._percepts: dict[PlayerRef, PerceptRows] = {}
        self._texts: dict[str, TextRows] = {}
        self._last_tick = 0
        self._closed = False
        ids = (application_id, recording_id)
        self._rec = open_stream(self.path, ids, viewer, self._blueprint())
        self._log_static()

    # --- what a subclass gives or changes -------------------------------------------------

    @abstractmethod
    def _blueprint(self) -> rrb.Blueprint:
        """The default layout (built before anything is logged)."""

    @abstractmethod
    def legend(self, outcome: str = "") -> str:
        """The legend shown beside the field (markdown), with `outcome` on top once known."""

    def _draw_sizes(self, pitch: Pitch) -> DrawSizes:
        """How large things are drawn (:func:`draw_sizes`); a subclass may draw larger."""
        return draw_sizes(pitch)

    def _player_label(self, player: PlayerRef) -> str:
        """The label drawn above `player` (and stored with its disc): its id, ``left1``."""
        return str(player)

    def _percept_colour(self, observer: PlayerRef) -> Colour:
        """The colour of `observer`'s percept rings (by its place in the players)."""
        index = self.players.index(observer) if observer in self.players else len(self.players)
        return PERCEPT_COLOURS[index % len(PERCEPT_COLOURS)]

    def _view_bounds(self) -> tuple[list[float], list[float]]:
        """The field view's x and y ranges, in the view's (flipped) frame.

        Room above the field (the view's negative y) is left for the outcome label.
        """
        return view_bounds(self.pitch, 0.105)

    def _log_static(self) -> None:
        """The flip, pitch geometry and the per-entity styles (colours, radii), logged once."""
        log_pitch(self._rec, self.pitch, self._teams)
        log_team_styles(self._rec, self.sizes, self._teams)
        self._log_legend(0)

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

    def _check_open(self) -> None:
        if self._closed:
            raise RuntimeError(f"{type(self).__name__} is closed")

    def log_truth(self, truth: Truth) -> None:
        """Buffer the exact ball and player states of `truth`, if its tick is recorded.

        Players missing from `truth.players` are left out of that tick's rows.
        """
        tick = truth.tick
        if tick % self.every_ticks:
            return
        self._check_open()
        if tick > self._last_tick:
            self._last_tick = tick
        self._truth.add(truth)
        if len(self._truth.ticks) >= self.chunk_frames:
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
        self._check_open()
        tick = percept.tick
        buf = self._percepts.get(percept.player)
        if buf is None:
            buf = self._percepts[percept.player] = PerceptRows()
            base = f"field/perceived/{entity_name(str(percept.player))}"
            log_ring_style(self._rec, base, self._percept_colour(percept.player))
        elif buf.expires is not None and tick > buf.expires:
            buf.add_empty(buf.expires)  # the previous percept went stale before this one came
        if self._percept_life is not None:
            buf.expires = tick + self._percept_life
        if tick > self._last_tick:
            self._last_tick = tick
        buf.add(percept, observer)
        if len(buf.ticks) >= self.chunk_frames:
            self._flush_percepts()

    def log_events(self, events: Sequence[ArenaEvent]) -> None:
        """Buffer arena events as text lines under ``events/<channel>``."""
        self._check_open()
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
                to :data:`~robotsoccer.replay.palette.ROUTINE_DECISIONS`, which the default
                layout hides.
        """
        self._check_open()
        if not is_routine(actions):
            self.log_events([event])
            return
        who = "" if event.player is None else f"{event.player}: "
        text = f"[{event.channel}] {who}{event.text}"
        self._add_text(ROUTINE_DECISIONS, event.tick, text, "DEBUG")

    def _add_text(self, entity: str, tick: int, text: str, level: str) -> None:
        """Append one text row; flush that entity when its buffer is full."""
        buf = self._texts.get(entity)
        if buf is None:
            buf = self._texts[entity] = TextRows()
        buf.add(tick, text, level)
        if len(buf.ticks) >= self.chunk_frames:
            self._flush_texts()

    # --- flushing and closing ---------------------------------------------------------------

    def flush(self) -> None:
        """Send everything buffered to the file sink."""
        self._flush_truth()
        self._flush_percepts()
        self._flush_texts()

    def _flush_truth(self) -> None:
        """Send the buffered truth rows: the ball, then per team centres, outlines, headings."""
        if not self._truth.ticks:
            return
        outlines = self._player_shape == "square" or self._circle_outlines
        drawing = TeamDrawing(
            arrow_m=self.sizes.arrow_length_m,
            # A label is drawn below its point: this puts the id just above the player's body.
            name_above_m=self.sizes.player_m + 0.028 * self.pitch.length_m,
            template=self._template if outlines else None,
        )
        teams = {team: (idx, self._labels[idx]) for team, idx in self._team_index.items()}
        self._truth.send(self._rec, self.dt_s, teams, drawing)
        self._truth = TruthRows(self.players)

    def _flush_percepts(self) -> None:
        """Send each observer's buffered perceived ball and player rings."""
        for observer, buf in self._percepts.items():
            if not buf.ticks:
                continue
            base = f"field/perceived/{entity_name(str(observer))}"
            buf.send(self._rec, base, self.dt_s, self.sizes)
            self._percepts[observer] = PerceptRows(buf.expires)

    def _flush_texts(self) -> None:
        """Send the buffered text rows of every text entity."""
        for entity, buf in self._texts.items():
            if not buf.ticks:
                continue
            buf.send(self._rec, entity, self.dt_s)
            self._texts[entity] = TextRows()

    def _expire_percepts(self) -> None:
        """Clear each percept that went stale before the recording's last tick."""
        for buf in self._percepts.values():
            if buf.expires is not None and buf.expires <= self._last_tick:
                buf.add_empty(buf.expires)
                buf.expires = None

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

    def __enter__(self) -> Self:
        return self

    def __exit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        self.close()
