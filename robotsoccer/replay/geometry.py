"""Where things are drawn: the pitch's markings, player outlines and drawing sizes [m].

The drawing toolkit's geometry, shared by the rerun recordings (:mod:`robotsoccer.replay.recording`,
:mod:`robotsoccer.replay.match_recording`) and the raster frames of the environments
(:mod:`robotsoccer.replay.raster`). Everything is in the field frame (x towards the right goal,
y up, metres) and imports no drawing library.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from field_models.arena import PlayerShape
from field_models.protocol import BodyState, Pitch

MIN_BALL_FRACTION = 0.006
"""The ball is drawn with a radius of at least this fraction of the pitch length."""
MIN_PLAYER_FRACTION = 0.007
"""Players are drawn with a half-size of at least this fraction of the pitch length."""

_CIRCLE_SEGMENTS = 12  # outlines dominate file size; a 12-gon reads as round
_MARKING_SEGMENTS = 48  # the centre circle is drawn once, so it may be smooth
# Marking proportions of a 105 m FIFA pitch (the Soccer Server's flags sit on them), scaled by
# the pitch length on any field.
_FIFA_LENGTH_M = 105.0
_CENTRE_CIRCLE_M = 9.15
_PENALTY_DEPTH_M = 16.5
_PENALTY_HALF_WIDTH_M = 20.16


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


def view_bounds(pitch: Pitch, room_above: float) -> tuple[list[float], list[float]]:
    """A field view's x and y ranges [m], in the view's frame (y down: the field flipped).

    The pitch and its goals with a margin of 3 % of the pitch length, and above the top side
    line (the view's negative y) room for an outcome or a scoreboard.

    Args:
        pitch: Field geometry.
        room_above: The room above the top side line, as a fraction of the pitch length.
    """
    margin = 0.03 * pitch.length_m
    x_max = pitch.half_length_m + pitch.goal_depth_m + margin
    top = pitch.half_width_m + room_above * pitch.length_m
    return [-x_max, x_max], [-top, pitch.half_width_m + margin]
