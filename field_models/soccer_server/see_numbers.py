"""The numbers of a see message: quantisation, degrees, fading and the per-params constants.

rcssserver's rules for the numbers a see message carries (shared `specs/soccer_server.md` §3.2
to §3.5): distances quantised on a log scale (``Q(exp(Q(ln(d + EPS), q)), 0.1)``, with
``Q(v, q) = q·rint(v/q)``), directions in the server's integer degrees, details withheld with a
probability that grows with distance, and the constants derived once per
:class:`~field_models.soccer_server.sensing_params.SensingParams` for the see loop
(:class:`SeeConsts`). Used by :mod:`field_models.soccer_server.sensing` (one see) and
:mod:`field_models.soccer_server.batch_sensing` (many at once).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from field_models import fpmath
from field_models.soccer_server.landmarks import landmarks_for
from field_models.soccer_server.sensing_params import SensingParams

EPS = 1.0e-10
"""The server's EPS, added to a distance before its logarithm."""
RAD2DEG = 180.0 / math.pi
"""Degrees per radian."""


def quantize(value: float, step: float) -> float:
    """The server's ``Quantize``: ``step · rint(value / step)`` (round half to even)."""
    return round(value / step) * step


def decimals(step: float) -> int:
    """Decimal places needed to write multiples of `step` exactly (0.1 → 1, 0.02 → 2)."""
    for n in range(10):
        scaled = step * 10**n
        if abs(scaled - round(scaled)) < 1e-9 * max(1.0, scaled):
            return n
    return 10


def quantize_distance(distance_m: float, log_step: float, resolution_m: float = 0.1) -> float:
    """Reported distance: ``Q(exp(Q(ln(d + EPS), log_step)), resolution)`` (§3.3).

    The result is the double nearest to the decimal the server prints, e.g. 11.18 m gives 11.0
    with ``log_step`` 0.1 (ball, players) and 11.1 with 0.01 (flags).
    """
    k = round(math.exp(round(fpmath.log(distance_m + EPS) / log_step) * log_step) / resolution_m)
    return round(k * resolution_m, decimals(resolution_m))


def degrees(angle_rad: float, truncate: bool) -> int:
    """Radians to the server's integer degrees: truncated toward zero or rounded half to even."""
    deg = angle_rad * RAD2DEG
    return int(deg) if truncate else round(deg)


def far_probability(distance_m: float, far_m: float, too_far_m: float) -> float:
    """Probability that a detail is withheld: 0 up to `far_m`, 1 from `too_far_m`, linear between.

    Equal `far_m` and `too_far_m` (today's team lengths) make a step: withheld only beyond.
    """
    if distance_m <= far_m:
        return 0.0
    if distance_m >= too_far_m:
        return 1.0
    return (distance_m - far_m) / (too_far_m - far_m)


# ----------------------------------------------------------------------------- per-params constants


@dataclass(frozen=True, slots=True)
class SeeConsts:
    """Values derived once per SensingParams object for the see loop (:func:`see_consts`)."""

    half_angle: float
    vis_dist2: float
    q: float
    q_l: float
    res: float
    res_dec: int
    truncate: bool
    high: bool
    changes: bool
    body: bool
    head: bool
    unum_far: float
    unum_too_far: float
    team_far: float
    team_too_far: float
    dir_step: float
    dir_dec: int
    rel_step: float
    chg_dec: int
    res_div: float  # 10**res_dec when the resolution is a power of ten, else 0
    perfect: bool
    table: dict[int, float]  # memo: log index -> quantised distance, step quantize_step
    table_l: dict[int, float]  # the same for quantize_step_l
    # Per flag: index (for its random draw), x, server y (down), name, close name.
    flags: tuple[tuple[int, float, float, str, str], ...]
    goals: tuple[tuple[int, float, float, str, str], ...]  # the rows of "g l" and "g r"


_CACHE: dict[int, tuple[SensingParams, SeeConsts]] = {}


def _power_of_ten_divisor(step: float, decimals: int) -> float:
    """10**decimals when `step` is exactly 10**-decimals (k / 10**n is then the printed k·step)."""
    scale = 10.0**decimals
    return scale if abs(step * scale - 1.0) < 1e-12 else 0.0


def see_consts(params: SensingParams) -> SeeConsts:
    """The derived constants of `params`, cached by identity (params are immutable)."""
    hit = _CACHE.get(id(params))
    if hit is not None and hit[0] is params:
        return hit[1]
    flags = landmarks_for(params.landmark_set)
    rows = tuple(
        (i, f.x, -f.y + 0.0, f.name, "G" if f.name[0] == "g" else "F") for i, f in enumerate(flags)
    )
    res_dec = decimals(params.distance_resolution_m)
    consts = SeeConsts(
        half_angle=params.half_angle_rad,
        vis_dist2=params.visible_distance_m**2,
        q=params.quantize_step,
        q_l=params.quantize_step_l,
        res=params.distance_resolution_m,
        res_dec=res_dec,
        truncate=params.truncate,
        high=params.view_quality == "high",
        changes=params.report_changes,
        body=params.protocol_version >= 4,
        head=params.protocol_version >= 5,
        unum_far=params.unum_far_length_m,
        unum_too_far=params.unum_too_far_length_m,
        team_far=params.team_far_length_m,
        team_too_far=params.team_too_far_length_m,
        dir_step=params.dir_change_step_deg,
        dir_dec=decimals(params.dir_change_step_deg),
        rel_step=params.dist_change_rel_step,
        chg_dec=res_dec + decimals(params.dist_change_rel_step),
        res_div=_power_of_ten_divisor(params.distance_resolution_m, res_dec),
        perfect=params.perfect,
        table={},
        table_l={},
        flags=rows,
        goals=tuple(r for r in rows if r[3] in ("g l", "g r")),
    )
    if len(_CACHE) > 64:  # params objects are few; bound the cache anyway
        _CACHE.clear()
    _CACHE[id(params)] = (params, consts)
    return consts


def printed(value: float) -> float:
    """The value as the server prints it (6 significant digits, ``%g``)."""
    return float(f"{value:g}") + 0.0


def quantised(c: SeeConsts, d: float, step: float) -> float:
    """Quantised distance (see :func:`quantize_distance`), memoised on the log index.

    In perfect perception, the exact distance.
    """
    if c.perfect:
        return d
    table = c.table_l if step == c.q_l else c.table
    m = round(fpmath.log(d + EPS) / step)
    qd = table.get(m)
    if qd is None:
        qd = table[m] = from_log_index(c, m, step)
    return qd


def quantised_distance_for_index(params: SensingParams, m: int, step: float) -> float:
    """The distance a see prints for log index `m` (``round(ln(d + EPS) / step)``), memoised.

    The one rule behind :func:`quantised`, for callers that compute the index over arrays
    (:mod:`field_models.soccer_server.batch_sensing`).
    """
    c = see_consts(params)
    table = c.table_l if step == c.q_l else c.table
    qd = table.get(m)
    if qd is None:
        qd = table[m] = from_log_index(c, m, step)
    return qd


def from_log_index(c: SeeConsts, m: int, step: float) -> float:
    """``Q(exp(m · step), resolution)`` as the double the message prints."""
    k = round(math.exp(m * step) / c.res)
    return k / c.res_div if c.res_div else round(k * c.res, c.res_dec)


def see_direction(c: SeeConsts, angle_rad: float) -> float:
    """A direction as the see reports it: :func:`degrees`, or exact degrees when perfect."""
    if c.perfect:
        return angle_rad * RAD2DEG
    return degrees(angle_rad, c.truncate)


def see_changes(
    c: SeeConsts, dx: float, dy: float, wx: float, wy: float, d: float, qd: float
) -> tuple[float, float]:
    """Distance and direction change in the server's units and rounding (§3.4, ``calcVel``).

    `dx`, `dy` is the object's offset, `wx`, `wy` its velocity relative to the observer (server
    frame, per cycle), `d` the exact distance and `qd` the reported one.
    """
    if d == 0.0:
        return 0.0, 0.0
    ex, ey = dx / d, dy / d
    dist_chg = wx * ex + wy * ey
    dir_chg = (wy * ex - wx * ey) / d * RAD2DEG
    if c.perfect:
        return dist_chg + 0.0, dir_chg + 0.0
    dir_q = 0.0 if dir_chg == 0.0 else round(round(dir_chg / c.dir_step) * c.dir_step, c.dir_dec)
    if abs(dir_q) >= 1e5:  # objects nearly on top of each other: keep what %g prints
        dir_q = printed(dir_q)
    rel = round(dist_chg / d / c.rel_step) * c.rel_step
    return round(qd * rel, c.chg_dec) + 0.0, dir_q + 0.0


def decide(prob: float, u: float) -> bool:
    """The server's ``decide``: true with probability `prob`, using the uniform draw `u`."""
    if prob >= 1.0:
        return True
    if prob <= 0.0:
        return False
    return u < prob
