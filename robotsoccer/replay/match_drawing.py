"""What a match's recording draws beyond a trial's: the ball's trail, scoreboard, line of sight.

Pieces of :class:`~robotsoccer.replay.match_recording.MatchRecorder`, kept apart so that the
recorder reads as the order of things: :class:`BallTrail` (a fading trail behind the ball, cut
where the ball was put back on a spot), :class:`Scoreboard` (the score line in the teams'
colours and the play mode with the clock, in stroke letters above the field) and
:class:`SightRows` (the selected player's line of sight to the ball it perceives).

Rerun is imported inside functions only, so importing this module does not load the SDK.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from field_models.protocol import LEFT, RIGHT, Pitch
from robotsoccer.replay.lettering import text_strokes, text_width
from robotsoccer.replay.palette import BALL_COLOUR, PITCH_COLOUR, team_colour
from robotsoccer.replay.toolkit import time_indexes

if TYPE_CHECKING:
    import rerun as rr

MAX_TRAIL_POINTS = 24
"""At most this many past positions make up the trail (thinned on fine ticks)."""

WHITE = (235, 235, 235)
"""The scoreboard's colon."""
SELECTED_COLOUR = (255, 70, 220)
"""The selected player's halo, percepts and line of sight: magenta, far from both team
colours, the ball and the grass."""
STATUS_COLOUR = (200, 200, 200)
"""The status line (play mode, clock)."""
HALO = 1.6
"""The halo's radius in player sizes: clear of a square robot's corners (1.41)."""
# Draw orders (the trial recorder's: markings 10, players 30-32, ball 40, percepts 50).
_ORDER_HALO = 29.0
_ORDER_SIGHT = 29.5  # over the halo, under the players: it must not hide a player's arrow
_ORDER_TRAIL = 35.0
_ORDER_BOARD = 60.0
_TRAIL_FADE = 0.85  # the oldest segment is this far blended into the grass, not invisible
_TRAIL_WIDE_PT, _TRAIL_THIN_PT = 3.0, 1.0  # newest and oldest segment half-widths [ui points]
# A trail segment longer than this fraction of the pitch length is a restart (the ball put
# back on a spot), not a kick; the trail is cut there rather than drawn across the field.
_TRAIL_JUMP_FRACTION = 0.15
# The scoreboard, above the top side line, in fractions of the pitch length.
_BOARD_BASE, _BOARD_HEIGHT, _BOARD_WIDTH = 0.05, 0.045, 0.92
_STATUS_BASE, _STATUS_HEIGHT = 0.012, 0.022


class BallTrail:
    """The ball's trail: for each recorded row, segments back over the last ``trail_ticks``.

    Args:
        trail_ticks: Length of the trail in ticks.
        every_ticks: The truth is recorded on multiples of this.
        pitch_length_m: The pitch length [m] (a longer step than a fraction of it is a jump).
    """

    def __init__(self, trail_ticks: int, every_ticks: int, pitch_length_m: float) -> None:
        self.trail_ticks = trail_ticks
        # Thin the trail to at most MAX_TRAIL_POINTS past positions, on a fixed grid of ticks
        # so a point does not slide along the path from one frame to the next.
        every = max(1, every_ticks)
        self._stride = every * max(1, math.ceil(trail_ticks / (every * MAX_TRAIL_POINTS)))
        self._hist_ticks = np.zeros(0, dtype=np.int64)
        self._hist_xy = np.zeros((0, 2))
        self._max_step_m = _TRAIL_JUMP_FRACTION * pitch_length_m

    def rows(
        self, ticks: np.ndarray, ball: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray, list[int]]:
        """The trail of each buffered row: its segments (S, 2, 2), colours, radii, counts.

        A row's trail joins the ball's positions at the recorded ticks on the trail's grid
        within the last ``trail_ticks`` to the ball's position now; it is cut at the latest
        jump (a restart). Older segments are blended further into the grass and drawn thinner.
        The rows' positions are kept as the history of the next call's rows.
        """
        hist = len(self._hist_ticks)
        all_ticks = np.concatenate([self._hist_ticks, ticks])
        all_xy = np.concatenate([self._hist_xy, ball])
        on_grid = all_ticks % self._stride == 0
        starts = np.searchsorted(all_ticks, ticks - self.trail_ticks, side="right")
        step = np.zeros(len(all_ticks))
        step[1:] = np.hypot(*(all_xy[1:] - all_xy[:-1]).T)  # from the previous recorded tick
        jumps = np.flatnonzero(step > self._max_step_m)
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
        ball_rgb = np.asarray(BALL_COLOUR, dtype=np.float64)
        grass = np.asarray(PITCH_COLOUR, dtype=np.float64)
        colours = np.rint((1.0 - _TRAIL_FADE * age) * ball_rgb + _TRAIL_FADE * age * grass)
        # Negative radii are ui points (rerun's Radius.ui_points): the trail reads at any zoom.
        radii = -(_TRAIL_WIDE_PT - (_TRAIL_WIDE_PT - _TRAIL_THIN_PT) * age[:, 0])
        keep = all_ticks > ticks[-1] - self.trail_ticks
        self._hist_ticks = all_ticks[keep]
        self._hist_xy = all_xy[keep]
        return strips, colours.astype(np.uint8), radii.astype(np.float32), lengths

    def send(
        self, rec: rr.RecordingStream, indexes: list[Any], ticks: np.ndarray, ball: np.ndarray
    ) -> None:
        """Send the trail of rows at `ticks` (the ball at `ball`) to ``field/ball/trail``."""
        import rerun as rr

        strips, colours, radii, lengths = self.rows(ticks, ball)
        rec.send_columns(
            "field/ball/trail",
            indexes=indexes,
            columns=rr.LineStrips2D.columns(strips=strips, colors=colours, radii=radii).partition(
                lengths
            ),
        )


class Scoreboard:
    """The score line and the status line (play mode, clock) as stroke letters above the field.

    Args:
        pitch: Field geometry (the lines sit above its top side line).
        team_names: Display names of the left and the right team.
        teams: The players' team ids, for the teams' colours.
    """

    def __init__(self, pitch: Pitch, team_names: tuple[str, str], teams: tuple[str, ...]) -> None:
        self.pitch = pitch
        self.team_names = team_names
        self._teams = teams
        length = pitch.length_m
        # One height for the whole match: wide enough for two-digit scores, so the letters do
        # not change size when a team reaches ten.
        units = text_width(self.text(88, 88), 1.0)
        self.height_m = min(_BOARD_HEIGHT * length, _BOARD_WIDTH * length / units)

    def text(self, left_goals: int, right_goals: int) -> str:
        """The score line, ``layered 2 : 1 baseline``."""
        left, right = self.team_names
        return f"{left} {left_goals} : {right_goals} {right}"

    def strokes(self, score: tuple[int, int]) -> list[tuple[np.ndarray, tuple[int, ...]]]:
        """The score line's strokes, each with its colour: the teams' parts in their colours.

        Each part is drawn from the whole line with every other character blanked (a blank
        leaves a gap of the same width), so the parts land where they would in the whole line.
        """
        left = self.team_names[0]
        text = self.text(*score)
        colon = text.index(":", len(left) + 1)
        parts = (
            (0, colon - 1, team_colour(LEFT, self._teams)),
            (colon, colon + 1, WHITE),
            (colon + 2, len(text), team_colour(RIGHT, self._teams)),
        )
        base = self.pitch.half_width_m + _BOARD_BASE * self.pitch.length_m
        out: list[tuple[np.ndarray, tuple[int, ...]]] = []
        for start, stop, colour in parts:
            masked = " " * start + text[start:stop] + " " * (len(text) - stop)
            for stroke in text_strokes(
                masked, height_m=self.height_m, centre_x_m=0.0, base_y_m=base
            ):
                out.append((stroke, colour))
        return out

    def status_strokes(self, play_mode: str, clock_s: int) -> list[np.ndarray]:
        """Play mode and clock beneath the score: ``PLAY ON  12:34`` (``_`` reads as a gap)."""
        minutes, seconds = divmod(clock_s, 60)
        length = self.pitch.length_m
        return text_strokes(
            f"{play_mode}  {minutes:02d}:{seconds:02d}",
            height_m=_STATUS_HEIGHT * length,
            centre_x_m=0.0,
            base_y_m=self.pitch.half_width_m + _STATUS_BASE * length,
        )


class SightRows:
    """The selected player's line of sight, one row per percept: player -> perceived ball.

    ``expires`` is the tick at which the latest line stops being current (None: never, or no
    line yet); an empty row clears the line.
    """

    __slots__ = ("expires", "lengths", "ticks", "xy")

    def __init__(self) -> None:
        self.ticks: list[int] = []
        self.xy: list[float] = []  # 4 floats (from, to) per row that has a line
        self.lengths: list[int] = []
        self.expires: int | None = None

    def add(self, tick: int, line: tuple[float, float, float, float] | None) -> None:
        """One row: (from x, y, to x, y), or None to clear the line."""
        self.ticks.append(tick)
        if line is None:
            self.lengths.append(0)
        else:
            self.xy.extend(line)
            self.lengths.append(1)

    def send(self, rec: rr.RecordingStream, entity: str, dt_s: float) -> None:
        """Send the buffered rows to `entity`, and empty the buffer (``expires`` stays)."""
        if not self.ticks:
            return
        import rerun as rr

        rec.send_columns(
            entity,
            indexes=time_indexes(self.ticks, dt_s),
            columns=rr.LineStrips2D.columns(
                strips=np.asarray(self.xy, dtype=np.float32).reshape(-1, 2, 2)
            ).partition(self.lengths),
        )
        self.ticks, self.xy, self.lengths = [], [], []


class ScoreRows:
    """Each team's goals so far at the recorded ticks (and at every change), for two series."""

    __slots__ = ("ticks", "values")

    def __init__(self) -> None:
        self.ticks: list[int] = []
        self.values: list[float] = []  # left, right per row

    def add(self, tick: int, score: tuple[int, int]) -> None:
        """One row: the (left, right) score at `tick`."""
        self.ticks.append(tick)
        self.values.extend(score)

    def send(self, rec: rr.RecordingStream, dt_s: float) -> None:
        """Send the rows as one scalar series per team (``score/<side>``), and empty them."""
        if not self.ticks:
            return
        import rerun as rr

        indexes = time_indexes(self.ticks, dt_s)
        values = np.asarray(self.values, dtype=np.float64).reshape(-1, 2)
        for column, side in enumerate((LEFT, RIGHT)):
            rec.send_columns(
                f"score/{side}",
                indexes=indexes,
                columns=rr.Scalars.columns(scalars=values[:, column]),
            )
        self.ticks = []
        self.values = []


def log_match_styles(
    rec: rr.RecordingStream, team_names: tuple[str, str], teams: Sequence[str]
) -> None:
    """Static styles of the trail, the halo, the line of sight, the scoreboard and the series."""
    import rerun as rr

    rec.log("field/ball/trail", rr.LineStrips2D.from_fields(draw_order=_ORDER_TRAIL), static=True)
    rec.log(
        "field/selected",
        rr.Ellipses2D.from_fields(
            line_radii=rr.Radius.ui_points(2.5),
            colors=SELECTED_COLOUR,
            show_labels=False,
            draw_order=_ORDER_HALO,
        ),
        static=True,
    )
    rec.log(
        "field/selected/sight",
        rr.LineStrips2D.from_fields(
            radii=rr.Radius.ui_points(1.0), colors=SELECTED_COLOUR, draw_order=_ORDER_SIGHT
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
            radii=rr.Radius.ui_points(1.5), colors=STATUS_COLOUR, draw_order=_ORDER_BOARD
        ),
        static=True,
    )
    for side, name in zip((LEFT, RIGHT), team_names, strict=True):
        rec.log(
            f"score/{side}",
            rr.SeriesLines(colors=team_colour(side, teams), names=name, widths=2.0),
            static=True,
        )


def send_halo(
    rec: rr.RecordingStream, indexes: list[Any], centres: np.ndarray, radius_m: float
) -> None:
    """Send the selected player's halo: a circle of `radius_m` round each row's centre.

    Args:
        rec: The recording stream.
        indexes: The rows' time columns.
        centres: (rows, 2) the player's x, y; NaN where it is absent (no halo in that row).
        radius_m: The halo's radius [m].
    """
    import rerun as rr

    here = ~np.isnan(centres[:, 0])
    # A circle, not a disc: a filled disc swamps a robot drawn at its true size. The sizes go
    # in every row (Ellipses2D's required component, as for percept rings).
    kept = centres[here]
    rec.send_columns(
        "field/selected",
        indexes=indexes,
        columns=rr.Ellipses2D.columns(
            centers=kept, half_sizes=np.full_like(kept, radius_m)
        ).partition(here.astype(int)),
    )
