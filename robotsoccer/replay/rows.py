"""Rows buffered for rerun's ``send_columns``: the truth, percept rings, text logs, stroke text.

Part of the drawing toolkit (:mod:`robotsoccer.replay.toolkit`). A recorder never logs in the
simulation loop (``rr.log`` costs ~100 µs a call, notes/tooling.md §1.4): it appends plain
floats to these buffers, and each buffer sends its rows as columns in one call per entity.

Rerun is imported inside functions only, so importing this module does not load the SDK.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from field_models.protocol import BodyState, Percept, PlayerRef, Truth
from robotsoccer.replay.geometry import DrawSizes, egocentric_to_field, place_outlines
from robotsoccer.replay.palette import entity_name, seen_label
from robotsoccer.replay.toolkit import time_indexes

if TYPE_CHECKING:
    import rerun as rr

_NAN3 = (math.nan, math.nan, math.nan)


class TruthRows:
    """The ball's and the players' true positions at each recorded tick, waiting to be sent.

    Args:
        players: The players, in the fixed order of every row; an absent player's pose is NaN.
    """

    __slots__ = ("ball_xy", "players", "poses", "ticks")

    def __init__(self, players: tuple[PlayerRef, ...]) -> None:
        self.players = players
        self.ticks: list[int] = []
        self.ball_xy: list[float] = []
        self.poses: list[float] = []  # x, y, heading per player per recorded tick (NaN: absent)

    def add(self, truth: Truth) -> None:
        """A row at ``truth.tick``: the ball, then each player's pose (NaN when absent)."""
        self.ticks.append(truth.tick)
        ball = truth.ball
        self.ball_xy.append(ball.x)
        self.ball_xy.append(ball.y)
        states = truth.players
        poses = self.poses
        for ref in self.players:
            s = states.get(ref)
            if s is None:
                poses.extend(_NAN3)
            else:
                poses.extend((s.x, s.y, s.heading))

    def ball(self) -> np.ndarray:
        """(rows, 2): the ball's x, y at each row."""
        return np.asarray(self.ball_xy, dtype=np.float64).reshape(len(self.ticks), 2)

    def pose_array(self) -> np.ndarray:
        """(rows, players, 3): each player's x, y, heading at each row (NaN: absent)."""
        n_rows = len(self.ticks)
        return np.asarray(self.poses, dtype=np.float64).reshape(n_rows, len(self.players), 3)

    def send(
        self,
        rec: rr.RecordingStream,
        dt_s: float,
        teams: dict[str, tuple[np.ndarray, np.ndarray]],
        drawing: TeamDrawing,
    ) -> None:
        """Send the rows: the ball, then per team its centres, names, outlines and headings.

        Args:
            rec: The recording stream.
            dt_s: Length of one tick [s].
            teams: Each team's player indexes (into :attr:`players`) and labels, in the
                order the teams are sent.
            drawing: How the players are drawn.
        """
        import rerun as rr

        indexes = time_indexes(self.ticks, dt_s)
        rec.send_columns(
            "field/ball", indexes=indexes, columns=rr.Points2D.columns(positions=self.ball())
        )
        poses = self.pose_array()
        for team, (idx, labels) in teams.items():
            base = f"field/players/{entity_name(team)}"
            send_team_rows(rec, base, indexes, poses[:, idx, :], labels, drawing)


@dataclass(frozen=True)
class TeamDrawing:
    """How one recording draws its players' rows (the same for every team and chunk).

    Attributes:
        arrow_m: Length of a heading arrow [m].
        name_above_m: Height of a player's name anchor above its centre [m].
        template: The outline at the origin facing +x, (K, 2) [m]; None: no outlines.
    """

    arrow_m: float
    name_above_m: float
    template: np.ndarray | None


def send_team_rows(
    rec: rr.RecordingStream,
    base: str,
    indexes: list[Any],
    poses: np.ndarray,
    labels: np.ndarray,
    drawing: TeamDrawing,
) -> None:
    """Send one team's buffered truth rows: centres, names, outlines (if any) and headings.

    Args:
        rec: The recording stream.
        base: The team's entity (``field/players/<team>``).
        indexes: The rows' time columns (:func:`time_indexes`).
        poses: (rows, team players, 3) x, y, heading; NaN where a player is absent.
        labels: The team's player labels, one per player.
        drawing: Arrow length, name height and outline.
    """
    import rerun as rr

    present = ~np.isnan(poses[:, :, 0])
    lengths = present.sum(axis=1).tolist()
    flat = poses[present]  # row-major: time order, then player order
    row_labels = np.broadcast_to(labels, present.shape)[present].tolist()
    headings = np.column_stack([np.cos(flat[:, 2]), np.sin(flat[:, 2])])
    rec.send_columns(
        base,
        indexes=indexes,
        columns=rr.Points2D.columns(positions=flat[:, :2], labels=row_labels).partition(lengths),
    )
    rec.send_columns(
        f"{base}/name",
        indexes=indexes,
        columns=rr.Points2D.columns(
            positions=flat[:, :2] + (0.0, drawing.name_above_m), labels=row_labels
        ).partition(lengths),
    )
    if drawing.template is not None:
        rec.send_columns(
            f"{base}/outline",
            indexes=indexes,
            columns=rr.LineStrips2D.columns(
                strips=place_outlines(drawing.template, flat)
            ).partition(lengths),
        )
    rec.send_columns(
        f"{base}/heading",
        indexes=indexes,
        columns=rr.Arrows2D.columns(
            origins=flat[:, :2], vectors=drawing.arrow_m * headings
        ).partition(lengths),
    )


class PerceptRows:
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

    def add(self, percept: Percept, observer: BodyState) -> None:
        """A row at ``percept.tick``: what was seen, in the field frame as seen from `observer`."""
        self.ticks.append(percept.tick)
        ball = percept.ball
        if ball is None:
            self.ball_lengths.append(0)
        else:
            self.ball_xy.extend(egocentric_to_field(observer, ball.distance_m, ball.angle_rad))
            self.ball_lengths.append(1)
        for seen in percept.players:
            self.player_xy.extend(egocentric_to_field(observer, seen.distance_m, seen.angle_rad))
            self.player_labels.append(seen_label(seen.team, seen.number))
        self.player_lengths.append(len(percept.players))

    def send(self, rec: rr.RecordingStream, base: str, dt_s: float, sizes: DrawSizes) -> None:
        """Send the rows as rings under `base` (``.../ball``, ``.../players``); rows stay."""
        import rerun as rr

        # The ring sizes go in every row: half_sizes is Ellipses2D's required component, so a
        # static one would fix the instance count at one and draw a ring where none is current.
        ball_ring = 1.5 * sizes.ball_m
        player_ring = 2.0 * sizes.player_m
        indexes = time_indexes(self.ticks, dt_s)
        ball = np.asarray(self.ball_xy, dtype=np.float64).reshape(-1, 2)
        rec.send_columns(
            f"{base}/ball",
            indexes=indexes,
            columns=rr.Ellipses2D.columns(
                centers=ball, half_sizes=np.full_like(ball, ball_ring)
            ).partition(self.ball_lengths),
        )
        seen = np.asarray(self.player_xy, dtype=np.float64).reshape(-1, 2)
        rec.send_columns(
            f"{base}/players",
            indexes=indexes,
            columns=rr.Ellipses2D.columns(
                centers=seen,
                half_sizes=np.full_like(seen, player_ring),
                labels=self.player_labels,
            ).partition(self.player_lengths),
        )


class TextRows:
    """Rows of one text-log entity waiting for ``send_columns``."""

    __slots__ = ("levels", "texts", "ticks")

    def __init__(self) -> None:
        self.ticks: list[int] = []
        self.texts: list[str] = []
        self.levels: list[str] = []

    def add(self, tick: int, text: str, level: str) -> None:
        """One line at `tick`, at rerun log level `level` (``"INFO"``, ``"DEBUG"``)."""
        self.ticks.append(tick)
        self.texts.append(text)
        self.levels.append(level)

    def send(self, rec: rr.RecordingStream, entity: str, dt_s: float) -> None:
        """Send the rows to `entity`; the rows stay (the caller starts a new buffer)."""
        import rerun as rr

        rec.send_columns(
            entity,
            indexes=time_indexes(self.ticks, dt_s),
            columns=rr.TextLog.columns(text=self.texts, level=self.levels),
        )


class StrokeRows:
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
                strips=strips_array(self.strips), colors=np.asarray(self.colours, dtype=np.uint8)
            ).partition(self.lengths),
        )
        self.ticks, self.strips, self.colours, self.lengths = [], [], [], []


def strips_array(strips: Sequence[np.ndarray]) -> Any:
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
