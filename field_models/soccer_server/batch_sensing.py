"""What many trials' sees show of one object, as arrays: the batch form of the see's geometry.

For K trials at once, :func:`see_object` gives what a player's percept
(:func:`~field_models.soccer_server.percepts.percept_from_state`) holds for one other object,
the ball or a player: whether the percept has it at all, its reported distance and its
direction. It applies the rules of :mod:`field_models.soccer_server.sensing` with the same
operations in the same order (shared `specs/soccer_server.md` §3):

* the view cone (``|direction| < half-angle``, strict), and the felt object behind the player
  within ``visible_distance``;
* low view quality reports no distance, and a percept leaves such an object out;
* distances quantised on the log scale (§3.3) through the one scalar rule: the log index is
  computed for the array and each index's distance comes from
  :func:`~field_models.soccer_server.see_numbers.quantised_distance_for_index`, once per index;
* directions in the server's integer degrees (truncated or rounded by protocol), turned into
  our counter-clockwise radians as :mod:`~field_models.soccer_server.percepts` does.

Angles and logarithms come from :mod:`field_models.fpmath`, in its array forms, as the scalar
see takes them in its float forms: numpy's own ``arctan2`` and ``log`` round by CPU feature.

What it leaves out, and why that is exact for the callers: a see's random draws decide only
whether distance/direction changes and a player's team and number are shown. The batched
drills' minds read none of those, and the sensing stream feeds nothing else, so the batch
does not draw them. Perfect perception gives the exact distance and direction, as a see does.
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt

from field_models import fpmath
from field_models.protocol import wrap_angle
from field_models.soccer_server.see_numbers import EPS, quantised_distance_for_index
from field_models.soccer_server.sensing_params import SensingParams

Array = npt.NDArray[np.float64]

_RAD2DEG = 180.0 / math.pi
_DEG2RAD = math.pi / 180.0


def see_object(
    params: SensingParams,
    observer: tuple[Array, Array, Array],
    target: tuple[Array, Array],
) -> tuple[npt.NDArray[np.bool_], Array, Array]:
    """What K observers' percepts hold of one object each.

    Args:
        params: The sensing parameters.
        observer: The observers' x, y [m] and heading [rad], our frame (y up, CCW).
        target: The object's x, y [m], our frame.

    Returns:
        (in the percept, distance [m], angle [rad, CCW from the heading]) per trial; distance
        and angle are meaningless where the object is not in the percept.
    """
    ox, oy, heading = observer
    tx, ty = target
    # Server frame (y down, angles clockwise), negations exact, as sensing.observe does.
    dx, dy = tx - ox, -ty - -oy
    ang = wrap_angle(fpmath.atan2_array(dy, dx) - -heading)
    d2 = dx * dx + dy * dy
    in_cone = (-params.half_angle_rad < ang) & (ang < params.half_angle_rad)
    high = params.view_quality == "high"
    shown = (in_cone | (d2 <= params.visible_distance_m**2)) & high
    distance = np.sqrt(d2)
    if params.perfect:
        direction = ang * _RAD2DEG
    else:
        distance = quantised_distances(params, distance)
        deg = ang * _RAD2DEG
        direction = np.trunc(deg) if params.truncate else np.rint(deg)
    return shown, distance, -(direction * _DEG2RAD) + 0.0


def quantised_distances(params: SensingParams, distance_m: Array) -> Array:
    """The see's quantised ball/player distances (step ``quantize_step``) for an array.

    Raises:
        ValueError: A distance that is NaN or infinite: its log index would be cast to an
            arbitrary integer and the table below would span 2^64 entries.
    """
    if not np.isfinite(distance_m).all():
        raise ValueError("see: a distance that is not finite (a position became NaN or inf)")
    step = params.quantize_step
    index = np.rint(fpmath.log_array(distance_m + EPS) / step).astype(np.int64)
    low, high = int(index.min(initial=0)), int(index.max(initial=0))
    table = np.array([quantised_distance_for_index(params, m, step) for m in range(low, high + 1)])
    out: Array = table[index - low]
    return out
