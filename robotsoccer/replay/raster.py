"""Frames of the field as RGB arrays, drawn headless with numpy (``render_mode="rgb_array"``).

The same picture a recording shows (:mod:`robotsoccer.replay.recording`, drawn with the toolkit's
:mod:`~robotsoccer.replay.geometry` and :mod:`~robotsoccer.replay.palette`): the pitch's
geometry from its own functions (boundary, centre line and circle, penalty areas, goals and
posts), players as filled bodies in their team's colour with a heading tick, the ball as a
disc, and the same minimum drawing sizes (:func:`~robotsoccer.replay.geometry.draw_sizes`) so
the Soccer Server's ball shows on its large pitch. No display and no window library: the
static pitch is drawn once into an array, and each frame copies it and fills a few masks.

Pixels: the image is ``width_px`` wide and as high as the pitch's proportions need, with a
margin that shows the goals; row 0 is the top (+y), column 0 the left (-x), so the picture is
the field the right way up.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence

import numpy as np
import numpy.typing as npt

from field_models.arena import PlayerShape
from field_models.protocol import Pitch, PlayerRef, Truth
from robotsoccer.replay.geometry import (
    draw_sizes,
    goal_box,
    goal_posts,
    pitch_lines,
    pitch_markings,
)
from robotsoccer.replay.palette import BALL_COLOUR, LINE_COLOUR, PITCH_COLOUR, team_colour

Frame = npt.NDArray[np.uint8]
"""An RGB image, shape (height, width, 3)."""
Colour = tuple[int, int, int] | npt.NDArray[np.uint8]
"""An RGB colour."""

DEFAULT_WIDTH_PX = 480
"""Frame width unless told otherwise [px]."""
MIN_BALL_PX = 2.5
MIN_PLAYER_PX = 4.0
"""Radii below which nothing is drawn smaller, whatever the pitch [px]."""
_SURROUND = (12, 36, 20)
_HEADING = (255, 255, 255)


class FieldPainter:
    """Draws truths of one field into RGB frames (module docstring).

    Args:
        pitch: The field's geometry.
        players: The players, for their team colours.
        player_shape: ``"square"`` (robots) or ``"circle"`` (Soccer Server players).
        width_px: Frame width [px] (>= 32).

    Raises:
        ValueError: A width below 32 pixels.
    """

    def __init__(
        self,
        pitch: Pitch,
        players: Sequence[PlayerRef],
        player_shape: PlayerShape,
        width_px: int = DEFAULT_WIDTH_PX,
    ) -> None:
        if width_px < 32:
            raise ValueError(f"width_px must be >= 32, got {width_px}")
        self.pitch = pitch
        self.shape = player_shape
        margin = pitch.goal_depth_m + 0.04 * pitch.length_m
        self._half_x = pitch.half_length_m + margin
        self._half_y = pitch.half_width_m + 0.04 * pitch.length_m
        self.scale = width_px / (2.0 * self._half_x)
        """Pixels per metre."""
        self.width_px = width_px
        self.height_px = max(1, round(2.0 * self._half_y * self.scale))
        sizes = draw_sizes(pitch)
        self._ball_px = max(sizes.ball_m * self.scale, MIN_BALL_PX)
        self._player_px = max(sizes.player_m * self.scale, MIN_PLAYER_PX)
        teams = tuple(dict.fromkeys(p.team for p in players))
        self._colours = {team: np.array(team_colour(team, teams), np.uint8) for team in teams}
        self._background = self._draw_pitch()

    @property
    def shape_hw3(self) -> tuple[int, int, int]:
        """The frames' array shape: (height, width, 3)."""
        return (self.height_px, self.width_px, 3)

    def pixel(self, x: float, y: float) -> tuple[float, float]:
        """(column, row) of the field point (x, y) [m], as floats."""
        return ((x + self._half_x) * self.scale, (self._half_y - y) * self.scale)

    def paint(self, truth: Truth) -> Frame:
        """The frame of `truth`: the pitch, then the players, then the ball on top."""
        image = self._background.copy()
        for ref, state in truth.players.items():
            colour = self._colours.get(ref.team, np.array((235, 235, 235), np.uint8))
            cx, cy = self.pixel(state.x, state.y)
            self._body(image, cx, cy, state.heading, colour)
            tip = self._player_px * 1.4
            ex, ey = cx + tip * math.cos(state.heading), cy - tip * math.sin(state.heading)
            _line(image, cx, cy, ex, ey, _HEADING, 1.0)
        bx, by = self.pixel(truth.ball.x, truth.ball.y)
        _disc(image, bx, by, self._ball_px, BALL_COLOUR)
        return image

    # ------------------------------------------------------------------ internals

    def _draw_pitch(self) -> Frame:
        """The static picture: surround, pitch, lines, markings, goals, posts."""
        image = np.empty(self.shape_hw3, np.uint8)
        image[:] = _SURROUND
        pitch = self.pitch
        x0, y0 = self.pixel(-pitch.half_length_m, pitch.half_width_m)
        x1, y1 = self.pixel(pitch.half_length_m, -pitch.half_width_m)
        image[max(0, round(y0)) : round(y1), max(0, round(x0)) : round(x1)] = PITCH_COLOUR
        width = max(1.0, self.width_px / 320.0)
        strips = [*pitch_lines(pitch), *pitch_markings(pitch)]
        strips += [goal_box(pitch, side) for side in (-1.0, 1.0)]
        for strip in strips:
            for (ax, ay), (bx, by) in itertools.pairwise(strip):
                _line(image, *self.pixel(ax, ay), *self.pixel(bx, by), LINE_COLOUR, width)
        for px, py in goal_posts(pitch):
            _disc(image, *self.pixel(px, py), max(1.5, width), LINE_COLOUR)
        return image

    def _body(self, image: Frame, cx: float, cy: float, heading: float, colour: Colour) -> None:
        """A player's filled footprint centred on pixel (cx, cy)."""
        r = self._player_px
        if self.shape == "circle":
            _disc(image, cx, cy, r, colour)
            return
        window = _window(image, cx, cy, r * math.sqrt(2.0))
        if window is None:
            return
        rows, cols, yy, xx = window
        c, s = math.cos(heading), math.sin(heading)
        dx, dy = xx - cx, cy - yy  # field axes: y up
        inside = (np.abs(dx * c + dy * s) <= r) & (np.abs(-dx * s + dy * c) <= r)
        image[rows, cols][inside] = colour


def _window(
    image: Frame, cx: float, cy: float, reach: float
) -> tuple[slice, slice, npt.NDArray[np.float64], npt.NDArray[np.float64]] | None:
    """The image rows and columns within `reach` of (cx, cy) and their pixel-centre grids.

    None when that square lies wholly outside the image (a ball out of the picture).
    """
    h, w = image.shape[:2]
    r0, r1 = max(0, math.floor(cy - reach)), min(h, math.ceil(cy + reach) + 1)
    c0, c1 = max(0, math.floor(cx - reach)), min(w, math.ceil(cx + reach) + 1)
    if r0 >= r1 or c0 >= c1:
        return None
    yy, xx = np.mgrid[r0:r1, c0:c1].astype(np.float64) + 0.5
    return slice(r0, r1), slice(c0, c1), yy, xx


def _disc(image: Frame, cx: float, cy: float, radius: float, colour: Colour) -> None:
    """Fill the pixels whose centres lie within `radius` of (cx, cy)."""
    window = _window(image, cx, cy, radius)
    if window is None:
        return
    rows, cols, yy, xx = window
    inside = (xx - cx) ** 2 + (yy - cy) ** 2 <= radius * radius
    image[rows, cols][inside] = colour


def _line(
    image: Frame, ax: float, ay: float, bx: float, by: float, colour: Colour, width: float
) -> None:
    """A segment `width` pixels wide, stamped as points every half pixel (no anti-aliasing)."""
    h, w = image.shape[:2]
    n = max(2, math.ceil(2.0 * math.hypot(bx - ax, by - ay)) + 1)
    t = np.linspace(0.0, 1.0, n)
    half = 0.5 * (width - 1.0)
    offsets = np.arange(-math.floor(half), math.floor(half) + 1)
    xs = (ax + t * (bx - ax))[:, None] + offsets[None, :]
    ys = (ay + t * (by - ay))[:, None]
    cols = np.floor(xs).astype(np.intp).ravel()
    rows = np.repeat(np.floor(ys).astype(np.intp), len(offsets), axis=1).ravel()
    cols2 = np.repeat(np.floor(ax + t * (bx - ax)).astype(np.intp), len(offsets))
    rows2 = (np.floor(ys) + offsets[None, :]).astype(np.intp).ravel()
    rows, cols = np.concatenate([rows, rows2]), np.concatenate([cols, cols2])
    keep = (rows >= 0) & (rows < h) & (cols >= 0) & (cols < w)
    image[rows[keep], cols[keep]] = colour
