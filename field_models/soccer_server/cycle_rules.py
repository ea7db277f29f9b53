"""The rules of one Soccer Server cycle that the single-trial model and the batch share.

Play modes (spec §6), the codes of a pending body command, the layout of a cycle's row of
random numbers (:class:`RowLayout`, see :mod:`field_models.soccer_server.dynamics`) and the pure
formulas of the commands: dash direction and rate (§2.1), turn noise (§2.2), kick
effectiveness and noise (§2.3). :class:`~field_models.soccer_server.dynamics.SoccerServerModel`
runs them one trial at a time, :class:`~field_models.soccer_server.batch.BatchSoccerServer` over
arrays of trials; both give the same numbers seed for seed.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass
from typing import TypeVar

import numpy as np
import numpy.typing as npt

from field_models.protocol import LEFT, RIGHT, PlayerRef
from field_models.seeding import Rng
from field_models.soccer_server.params import DynamicsParams

EPS = 1e-10
"""The server's small distance (``EPS`` in utility.h) added to separations."""
COLLISION_VELOCITY_FACTOR = -0.1
"""Velocity factor of every object that collided in a cycle (§4)."""
COLLISION_PASSES = 10
"""Maximum overlap-resolution passes per cycle (§4)."""
SEPARATION_RETRIES = 10
"""Times a separated pair is spread by 0.01 % more when rounding keeps it overlapping."""

BEFORE_KICK_OFF = "before_kick_off"
PLAY_ON = "play_on"
AFTER_GOAL_MODES = ("goal_l", "goal_r")
"""Internal after-goal modes; announced as ``goal_l_N`` / ``goal_r_N`` instead (§6)."""
RESTART_MODES = (
    "kick_off_l",
    "kick_off_r",
    "free_kick_l",
    "free_kick_r",
    "kick_in_l",
    "kick_in_r",
    "corner_kick_l",
    "corner_kick_r",
    "goal_kick_l",
    "goal_kick_r",
)
"""Modes in which the next accepted kick starts play (``play_on``)."""
PLAY_MODES = (BEFORE_KICK_OFF, PLAY_ON, *AFTER_GOAL_MODES, *RESTART_MODES)
"""Every play mode the model knows, as the server spells them."""
PLAY_MODE_CODE = {mode: code for code, mode in enumerate(PLAY_MODES)}
"""The batch's integer code of each play mode: its index in :data:`PLAY_MODES`."""

NO_COMMAND, DASH, TURN, KICK = 0, 1, 2, 3
"""Codes of the pending body command of a player."""
HALF_PI = 0.5 * math.pi
"""A side dash's direction [rad]: 90° in the server's ``dir_rate`` formula."""


# ----------------------------------------------------------------------------- random rows


@dataclass(frozen=True, slots=True)
class RowLayout:
    """Where each use of randomness sits in one cycle's row of uniforms.

    Attributes:
        move_a, move_b: Movement noise of update slot j (the j-th object updated) (N+1 each).
        turn: Turn noise of each player (N).
        kick_a, kick_b: Kick noise of each player (N each).
        order: Keys whose ascending order is the update order (N+1).
        width: Uniforms per cycle.
    """

    move_a: slice
    move_b: slice
    turn: slice
    kick_a: slice
    kick_b: slice
    order: slice
    width: int


def row_layout(n_players: int) -> RowLayout:
    """The row layout for `n_players` players and the ball."""
    n = n_players + 1
    edges = list(itertools.accumulate([0, n, n, n_players, n_players, n_players, n]))
    move_a, move_b, turn, kick_a, kick_b, order = (
        slice(lo, hi) for lo, hi in itertools.pairwise(edges)
    )
    return RowLayout(move_a, move_b, turn, kick_a, kick_b, order, width=edges[-1])


def draw_rows(rng: Rng, n_players: int, cycles: int) -> np.ndarray:
    """The raw uniforms of `cycles` consecutive cycles of one trial, shape (cycles, width)."""
    return rng.random((cycles, row_layout(n_players).width))


def unit_noise(a: np.ndarray, b: np.ndarray, model: str) -> tuple[np.ndarray, np.ndarray]:
    """A noise vector in units of its size R from two uniforms on [0, 1) (§1.3, §2.3).

    Box model: each axis uniform on [-1, 1). Polar model: radius uniform on [0, 1), angle
    uniform on [-π, π). Elementwise, so it commutes with any reordering of its inputs.
    """
    if model == "box":
        return 2.0 * a - 1.0, 2.0 * b - 1.0
    theta = math.pi * (2.0 * b - 1.0)
    return a * np.cos(theta), a * np.sin(theta)


def turn_factor(u: np.ndarray, player_rand: float) -> np.ndarray:
    """``1 + ξ`` with ξ uniform on [-player_rand, player_rand) (§2.2)."""
    return 1.0 + player_rand * (2.0 * u - 1.0)


# ----------------------------------------------------------------------------- pure formulas


def kick_effectiveness(gap_m: float, dir_diff_rad: float, kickable_margin_m: float) -> float:
    """The kick's effectiveness k (§2.3, since [CL 4.03]).

    Args:
        gap_m: Distance between the surfaces of player and ball [m].
        dir_diff_rad: Absolute angle of the ball off the player's heading [rad].
        kickable_margin_m: ``kickable_margin`` [m].

    >>> round(kick_effectiveness(0.115, 0.0, 0.7), 6)
    0.958929
    """
    return 1.0 - 0.25 * dir_diff_rad / math.pi - 0.25 * gap_m / kickable_margin_m


def dash_direction(direction_rad: float, params: DynamicsParams) -> float:
    """The direction a dash runs in, relative to the heading, as the server normalises it.

    rcssserver 19.0.0 (commit ce87001) ``src/leg.cpp`` ``normalize_dash_angle`` (lines 44-60,
    called by ``Leg::dash``): the direction is clamped to [``min_dash_angle``,
    ``max_dash_angle``] and then, unless ``dash_angle_step`` is below EPS, rounded to a
    multiple of it with ``rint`` (round half to even, as Python's ``round``). The clamp is in
    the server's clockwise sign, so ours is negated around it. Defaults
    (``src/serverparam.cpp`` lines 352-358): [-180°, 180°], step 1° (45° in 14.0 to 15.5,
    90° in 13.x).

    Args:
        direction_rad: The requested direction, counter-clockwise from the heading [rad].
        params: ``min_dash_angle_rad``, ``max_dash_angle_rad``, ``dash_angle_step_rad``.
    """
    d = -clamp(-direction_rad, params.min_dash_angle_rad, params.max_dash_angle_rad)
    step = params.dash_angle_step_rad
    if step > 0.0:
        d = step * round(d / step)
    return d + 0.0


def dash_rate(direction_rad: float, side_dash_rate: float, back_dash_rate: float) -> float:
    """The factor on a dash's power for its direction (§2.1, rcssserver >= 13).

    rcssserver 19.0.0 ``src/leg.cpp`` ``Leg::calcDashAccel`` (lines 157-163; the same formula
    as the disabled one-leg code of ``Player::dash`` in ``src/player.cpp``, lines 1130-1136):
    for |dir| <= 90°, ``side + (1 - side)·(1 - |dir|/90)``; beyond,
    ``back - (back - side)·(1 - (|dir| - 90)/90)``; clamped to [0, 1]. So 1 straight ahead,
    ``side_dash_rate`` (0.4) at ±90°, ``back_dash_rate`` (0.7) at 180°, linear between.

    >>> dash_rate(math.pi / 2, 0.4, 0.7), dash_rate(math.pi, 0.4, 0.7)
    (0.4, 0.7)
    """
    a = abs(direction_rad)
    if a > HALF_PI:
        rate = back_dash_rate - (back_dash_rate - side_dash_rate) * (1.0 - (a - HALF_PI) / HALF_PI)
    else:
        rate = side_dash_rate + (1.0 - side_dash_rate) * (1.0 - a / HALF_PI)
    return clamp(rate, 0.0, 1.0)


def clamp(value: float, low: float, high: float) -> float:
    """`value` limited to [low, high], as the server clamps command arguments (§2)."""
    return low if value < low else high if value > high else value


def side_of(ref: PlayerRef) -> int:
    """+1 for the left team (defends x < 0), -1 for the right team, 0 for any other team."""
    return 1 if ref.team == LEFT else -1 if ref.team == RIGHT else 0


def out_of_circle(x: float, y: float, radius: float) -> tuple[float, float]:
    """(x, y) moved to the nearest point of the circle of `radius` about the centre if inside."""
    r = math.sqrt(x * x + y * y)
    if r > radius:
        return x, y
    if r == 0.0:
        return radius, 0.0
    return x * (radius / r), y * (radius / r)


Size = TypeVar("Size", float, npt.NDArray[np.float64])
"""A number, or an array of them (the batch's kickers), in :func:`kick_noise_radius`."""


def kick_noise_radius(
    p: DynamicsParams, power: Size, gap: Size, dir_diff: Size, ball_speed: Size
) -> Size:
    """Kick-noise size: box ±kick_rand·P/maxpower (6.07–11.x); polar today's formula (§2.3).

    One kick or a batch of them, element by element in the same operations.
    """
    scale = p.kick_rand * (power / p.maxpower)
    if p.noise_model == "box":
        return scale
    pos_rate = 0.5 + 0.25 * (dir_diff / math.pi + gap / p.kickable_margin_m)
    speed_rate = 0.5 + 0.5 * (ball_speed / (p.ball_speed_max_m_per_cycle * p.ball_decay))
    return scale * (pos_rate + speed_rate)
