"""Soccer Server sensing as pure functions of the state: see and hear contents.

Implements shared `specs/soccer_server.md` §3 (visual sensing) and §2.6 (say/hear), following
rcssserver's ``VisualSenderPlayerV1`` family line by line where the spec is silent:

* the view cone: an object is seen when ``|direction| < half-angle`` (unrounded angle, strict),
  otherwise it is "felt" as ``(F)``/``(G)``/``(B)``/``(P)`` when within ``visible_distance``;
* distances: ``Q(exp(Q(ln(d + 1e-10), q)), 0.1)`` with ``Q(v, q) = q·rint(v/q)`` (round half
  to even), q = ``quantize_step`` for ball and players, ``quantize_step_l`` for flags, goals and
  lines (§3.3);
* directions in the server's degrees and sign, truncated toward zero or rounded by protocol
  (``SensingParams.direction_mode``, §3.2);
* distance/direction changes (§3.4), included for the ball and flags with probability
  ``1 - clip((D - unum_far)/(unum_too_far - unum_far), 0, 1)``, for players only when the
  uniform number is shown; players' team and number fade with distance (§3.5);
* lines: seen where the line of sight hits them inside their length (§3.6).

Frames and units. Inputs are in OUR frame (x toward the right goal, y up, heading CCW from +x,
radians), positions in metres and **velocities in metres per cycle** (what the server stores
between steps, as :class:`~field_models.soccer_server.dynamics.SoccerServerModel` holds them).
Outputs are in the SERVER's conventions — degrees, with the server's sign: its y axis points
down, so a direction the server reports as ``+d`` is ``-d`` degrees in our CCW frame.
Computations run in server coordinates (y negated, heading negated) so that every formula reads
as the server's. Angles are wrapped by ``field_models.protocol.wrap_angle`` into [-π, π).

Exactness. Every number in a :class:`SeenObject` is the value the text message carries:
distances are multiples of 0.1 m held as the nearest double to the decimal, so rendering with
``%g`` and parsing back gives bit-identical values (the percept fast path relies on it).

Perfect perception (``SensingParams.perfect``): distances, directions (in degrees, server sign)
and changes are the exact floats of the geometry, the team and number are always shown and
changes are always included where the era reports them (``report_changes``, high quality);
the view cone, the felt objects and the see timing are unchanged. The same random numbers are
drawn as in a normal see.

Landmark modes (``observe(..., landmarks=...)``): ``"all"`` (flags, goals and lines: the full
see message), ``"goals"`` (only the two goals, what a robot host also gives; the cheap choice
for percepts) and ``"none"``. Randomness: one ``rng.random`` block per see for the ball and
players, then one block for all flags whenever landmarks are observed, so the ball, the players
and the goals come out the same in every mode that shows them.

Choices: 1996 sees carry no changes and use a reduced landmark set (``SensingParams``
fields ``report_changes``, ``landmark_set``); see timing follows the server's asynchronous
timer (synch-see mode is not modelled); the neck angle is always 0 (the 1996 servers had no
neck and our action set has no ``turn_neck``); player entries never carry a pointing
direction, goalie or tackle mark. The flag loop, the costliest part of a full see, is written
out inline.
"""

from __future__ import annotations

import math
import typing
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Literal, NamedTuple

from field_models import fpmath
from field_models.protocol import PlayerRef, wrap_angle
from field_models.seeding import Rng
from field_models.soccer_server.landmarks import (
    LINES,
    PITCH_HALF_LENGTH_M,
    PITCH_HALF_WIDTH_M,
    landmarks_for,
)
from field_models.soccer_server.sensing_params import QUALITY_FACTOR, WIDTH_FACTOR, SensingParams

EPS = 1.0e-10
"""The server's EPS, added to a distance before its logarithm."""
_TWO_PI = 2.0 * math.pi
_HALF_PI = 0.5 * math.pi
_RAD2DEG = 180.0 / math.pi

LandmarkMode = Literal["all", "goals", "none"]
"""Which landmarks :func:`observe` reports: flags, goals and lines; the goals; none."""
LANDMARK_MODES: tuple[LandmarkMode, ...] = typing.get_args(LandmarkMode)
"""The values of :data:`LandmarkMode`, for callers that check a setting at run time."""

SAY_ALLOWED_CHARS = frozenset(
    "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789 ().+*/?<>_-"
)
"""Characters a say message may hold (§2.6, today's server; applied to every era)."""


# ----------------------------------------------------------------------------- records


class SeenObject(NamedTuple):
    """One object of a see message, as the server reports it.

    Attributes:
        name: Short name without parentheses: ``"b"``, ``"p"``, ``"f r t"``, ``"g l"``,
            ``"l r"``, or a close (felt) object ``"B"``, ``"P"``, ``"F"``, ``"G"``.
        distance: Quantised distance [m] (exact in perfect perception); None in low quality.
        direction: Direction in degrees, server sign (positive = clockwise in our frame): an
            integer, or the exact float in perfect perception.
        dist_change: Distance change [m/cycle], when reported.
        dir_change: Direction change [deg/cycle, server sign], when reported.
        team: The seen player's team name, when shown.
        unum: The seen player's uniform number, when shown.
        body_dir: The seen player's body direction relative to the observer's view [deg].
        head_dir: The seen player's head direction relative to the observer's view [deg].
    """

    name: str
    distance: float | None
    direction: float
    dist_change: float | None = None
    dir_change: float | None = None
    team: str | None = None
    unum: int | None = None
    body_dir: float | None = None
    head_dir: float | None = None


@dataclass(frozen=True, slots=True)
class SeeInfo:
    """The content of one see message: server time and the objects, in message order."""

    time: int
    objects: tuple[SeenObject, ...]

    def find(self, name: str) -> SeenObject | None:
        """The first object with this short name (e.g. ``"b"``, ``"g r"``), or None."""
        for obj in self.objects:
            if obj.name == name:
                return obj
        return None


class HearInfo(NamedTuple):
    """The content of one hear message (§2.6).

    Attributes:
        time: Server time (cycle) of the message.
        sender: ``"player"``, ``"self"``, ``"referee"``, ``"coach"``, ``"online_coach_left"`` or
            ``"online_coach_right"``.
        text: The message; None for the short form (hearing capacity exhausted, protocol >= 8).
        direction: Direction of the speaker relative to the listener's body [deg, server sign].
        team: ``"our"`` or ``"opp"`` for player messages in protocol >= 8, else None.
        unum: The speaker's uniform number for ``"our"`` messages in protocol >= 8, else None.
    """

    time: int
    sender: str
    text: str | None
    direction: int | None = None
    team: str | None = None
    unum: int | None = None


# ----------------------------------------------------------------------------- numbers


def quantize(value: float, step: float) -> float:
    """The server's ``Quantize``: ``step · rint(value / step)`` (round half to even)."""
    return round(value / step) * step


def _decimals(step: float) -> int:
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
    return round(k * resolution_m, _decimals(resolution_m))


def degrees(angle_rad: float, truncate: bool) -> int:
    """Radians to the server's integer degrees: truncated toward zero or rounded half to even."""
    deg = angle_rad * _RAD2DEG
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


# ----------------------------------------------------------------------------- per-params cache


@dataclass(frozen=True, slots=True)
class _Consts:
    """Values derived once per SensingParams object for the hot loop."""

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


_CACHE: dict[int, tuple[SensingParams, _Consts]] = {}


def _power_of_ten_divisor(step: float, decimals: int) -> float:
    """10**decimals when `step` is exactly 10**-decimals (k / 10**n is then the printed k·step)."""
    scale = 10.0**decimals
    return scale if abs(step * scale - 1.0) < 1e-12 else 0.0


def _consts(params: SensingParams) -> _Consts:
    """The derived constants of `params`, cached by identity (params are immutable)."""
    hit = _CACHE.get(id(params))
    if hit is not None and hit[0] is params:
        return hit[1]
    flags = landmarks_for(params.landmark_set)
    rows = tuple(
        (i, f.x, -f.y + 0.0, f.name, "G" if f.name[0] == "g" else "F") for i, f in enumerate(flags)
    )
    res_dec = _decimals(params.distance_resolution_m)
    consts = _Consts(
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
        dir_dec=_decimals(params.dir_change_step_deg),
        rel_step=params.dist_change_rel_step,
        chg_dec=res_dec + _decimals(params.dist_change_rel_step),
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


# ----------------------------------------------------------------------------- see


def observe(
    observer: int,
    x: Sequence[float],
    y: Sequence[float],
    vx: Sequence[float],
    vy: Sequence[float],
    heading: Sequence[float],
    players: tuple[PlayerRef, ...],
    time: int,
    params: SensingParams,
    rng: Rng,
    *,
    landmarks: LandmarkMode = "all",
) -> SeeInfo:
    """What player row `observer` sees now: the content of its see message (§3).

    Args:
        observer: Row of the observing player (1..N; row 0 is the ball).
        x: Per-object x [m], our frame; row 0 = ball, rows 1..N = `players` in order.
        y: Per-object y [m], our frame (up).
        vx: Per-object x velocity [m/cycle].
        vy: Per-object y velocity [m/cycle], our frame.
        heading: Per-object heading [rad], CCW from +x (row 0 unused).
        players: Identities of rows 1..N: ``players[i - 1]`` is row i.
        time: Server time stamped on the message (cycle).
        params: Sensing parameters.
        rng: The trial's sensing generator (identity fading, change inclusion).
        landmarks: ``"all"`` flags, goals and lines (the full message); ``"goals"`` only the
            goals; ``"none"`` no landmarks. Every mode gives the same ball, players and goals
            (same random numbers); the lean ones cost a fraction of the full see.

    Returns:
        The objects in message order: flags and goals, ball, players, lines.
    """
    n = len(players)
    if not 1 <= observer <= n:
        raise ValueError(f"observer row {observer} outside 1..{n}")
    c = _consts(params)
    # Server frame: y down, angles clockwise in ours. Negating y and the heading is exact.
    ox, osy = x[observer], -y[observer]
    ovx, ovy = vx[observer], -vy[observer]
    oth = -heading[observer]
    draws = rng.random(1 + 2 * n).tolist()
    objects: list[SeenObject] = []
    if landmarks not in LANDMARK_MODES:
        raise ValueError(f"landmarks: expected one of {LANDMARK_MODES}; got {landmarks!r}")
    if landmarks != "none":
        rows = c.flags if landmarks == "all" else c.goals
        see_flags = _see_flags_exact if c.perfect else _see_flags
        objects.extend(see_flags(c, rows, ox, osy, ovx, ovy, oth, rng))
    ball = _see_ball(c, ox, osy, ovx, ovy, oth, x[0], -y[0], vx[0], -vy[0], draws[0])
    if ball is not None:
        objects.append(ball)
    for row in range(1, n + 1):
        if row == observer:
            continue
        seen = _see_player(
            c,
            (ox, osy, ovx, ovy, oth),
            (x[row], -y[row], vx[row], -vy[row], -heading[row]),
            players[row - 1],
            draws[2 * row - 1],
            draws[2 * row],
        )
        if seen is not None:
            objects.append(seen)
    if landmarks == "all":
        objects.extend(see_lines(ox, osy, oth, params))
    return SeeInfo(time, tuple(objects))


def _changes(
    c: _Consts, dx: float, dy: float, wx: float, wy: float, d: float, qd: float
) -> tuple[float, float]:
    """Distance and direction change in the server's units and rounding (§3.4, ``calcVel``)."""
    if d == 0.0:
        return 0.0, 0.0
    ex, ey = dx / d, dy / d
    dist_chg = wx * ex + wy * ey
    dir_chg = (wy * ex - wx * ey) / d * _RAD2DEG
    if c.perfect:
        return dist_chg + 0.0, dir_chg + 0.0
    dir_q = 0.0 if dir_chg == 0.0 else round(round(dir_chg / c.dir_step) * c.dir_step, c.dir_dec)
    if abs(dir_q) >= 1e5:  # objects nearly on top of each other: keep what %g prints
        dir_q = _printed(dir_q)
    rel = round(dist_chg / d / c.rel_step) * c.rel_step
    return round(qd * rel, c.chg_dec) + 0.0, dir_q + 0.0


def _printed(value: float) -> float:
    """The value as the server prints it (6 significant digits, ``%g``)."""
    return float(f"{value:g}") + 0.0


def _quant(c: _Consts, d: float, step: float) -> float:
    """Quantised distance (see :func:`quantize_distance`), memoised on the log index.

    In perfect perception, the exact distance.
    """
    if c.perfect:
        return d
    table = c.table_l if step == c.q_l else c.table
    m = round(fpmath.log(d + EPS) / step)
    qd = table.get(m)
    if qd is None:
        qd = table[m] = _from_log_index(c, m, step)
    return qd


def quantised_distance_for_index(params: SensingParams, m: int, step: float) -> float:
    """The distance a see prints for log index `m` (``round(ln(d + EPS) / step)``), memoised.

    The one rule behind :func:`_quant`, for callers that compute the index over arrays
    (:mod:`field_models.soccer_server.batch_sensing`).
    """
    c = _consts(params)
    table = c.table_l if step == c.q_l else c.table
    qd = table.get(m)
    if qd is None:
        qd = table[m] = _from_log_index(c, m, step)
    return qd


def _from_log_index(c: _Consts, m: int, step: float) -> float:
    """``Q(exp(m · step), resolution)`` as the double the message prints."""
    k = round(math.exp(m * step) / c.res)
    return k / c.res_div if c.res_div else round(k * c.res, c.res_dec)


def _direction(c: _Consts, angle_rad: float) -> float:
    """A direction as the see reports it: :func:`degrees`, or exact degrees when perfect."""
    if c.perfect:
        return angle_rad * _RAD2DEG
    return degrees(angle_rad, c.truncate)


def _decide(prob: float, u: float) -> bool:
    """The server's ``decide``: true with probability `prob`, using the uniform draw `u`."""
    if prob >= 1.0:
        return True
    if prob <= 0.0:
        return False
    return u < prob


def _see_flags(
    c: _Consts,
    rows: tuple[tuple[int, float, float, str, str], ...],
    ox: float,
    oy: float,
    ovx: float,
    ovy: float,
    oth: float,
    rng: Rng,
) -> list[SeenObject]:
    """Flags and goals: in the cone with quantised distance, or felt when close (``sendHighFlag``).

    One tight loop (this is the costliest part of a see): the angle wrap, degree conversion and
    distance quantisation of ``wrap_angle``, :func:`degrees` and :func:`quantize_distance` are
    written out inline, with the same operations in the same order.
    """
    out: list[SeenObject] = []
    append = out.append
    half, trunc, high, q_l, vis2 = c.half_angle, c.truncate, c.high, c.q_l, c.vis_dist2
    table = c.table_l
    far, too_far = c.unum_far, c.unum_too_far
    pi, two_pi, atan2, sqrt, log = math.pi, _TWO_PI, fpmath.atan2, math.sqrt, fpmath.log
    new = tuple.__new__
    draws = rng.random(len(c.flags)).tolist() if c.changes and high else None
    for i, fx, fy, name, close in rows:
        dx = fx - ox
        dy = fy - oy
        ang = atan2(dy, dx) - oth
        if not -pi <= ang < pi:
            ang = (ang + pi) % two_pi - pi
        if -half < ang < half:
            deg = ang * _RAD2DEG
            direction = int(deg) if trunc else round(deg)
            if not high:
                append(new(SeenObject, (name, None, direction, None, None, None, None, None, None)))
                continue
            d = sqrt(dx * dx + dy * dy)
            m = round(log(d + EPS) / q_l)  # the quantised log-distance fixes the result
            qd = table.get(m)
            if qd is None:
                qd = table[m] = _from_log_index(c, m, q_l)
            # The server's decide(far_probability(qd)): true = no changes.
            if draws is None or (
                qd > far and (qd >= too_far or draws[i] < (qd - far) / (too_far - far))
            ):
                append(new(SeenObject, (name, qd, direction, None, None, None, None, None, None)))
            else:
                dist_chg, dir_chg = _changes(c, dx, dy, -ovx, -ovy, d, qd)
                append(
                    new(
                        SeenObject, (name, qd, direction, dist_chg, dir_chg, None, None, None, None)
                    )
                )
        elif dx * dx + dy * dy <= vis2:
            deg = ang * _RAD2DEG
            direction = int(deg) if trunc else round(deg)
            qd_close = _quant(c, sqrt(dx * dx + dy * dy), q_l) if high else None
            append(SeenObject(close, qd_close, direction))
    return out


def _see_flags_exact(
    c: _Consts,
    rows: tuple[tuple[int, float, float, str, str], ...],
    ox: float,
    oy: float,
    ovx: float,
    ovy: float,
    oth: float,
    rng: Rng,
) -> list[SeenObject]:
    """:func:`_see_flags` in perfect perception: exact values, changes whenever reported."""
    out: list[SeenObject] = []
    if c.changes and c.high:
        rng.random(len(c.flags))  # the draws of a normal see, so the stream stays the same
    for _, fx, fy, name, close in rows:
        dx, dy = fx - ox, fy - oy
        ang = wrap_angle(fpmath.atan2(dy, dx) - oth)
        direction = ang * _RAD2DEG
        d = math.sqrt(dx * dx + dy * dy)
        if -c.half_angle < ang < c.half_angle:
            if not c.high:
                out.append(SeenObject(name, None, direction))
            elif c.changes:
                dist_chg, dir_chg = _changes(c, dx, dy, -ovx, -ovy, d, d)
                out.append(SeenObject(name, d, direction, dist_chg, dir_chg))
            else:
                out.append(SeenObject(name, d, direction))
        elif dx * dx + dy * dy <= c.vis_dist2:
            out.append(SeenObject(close, d if c.high else None, direction))
    return out


def _see_ball(
    c: _Consts,
    ox: float,
    oy: float,
    ovx: float,
    ovy: float,
    oth: float,
    bx: float,
    by: float,
    bvx: float,
    bvy: float,
    u: float,
) -> SeenObject | None:
    """The ball (``sendHighBall`` / ``sendLowBall``)."""
    dx, dy = bx - ox, by - oy
    ang = wrap_angle(fpmath.atan2(dy, dx) - oth)
    d2 = dx * dx + dy * dy
    if -c.half_angle < ang < c.half_angle:
        direction = _direction(c, ang)
        if not c.high:
            return SeenObject("b", None, direction)
        d = math.sqrt(d2)
        qd = _quant(c, d, c.q)
        if not c.changes or (
            not c.perfect and _decide(far_probability(qd, c.unum_far, c.unum_too_far), u)
        ):
            return SeenObject("b", qd, direction)
        dist_chg, dir_chg = _changes(c, dx, dy, bvx - ovx, bvy - ovy, d, qd)
        return SeenObject("b", qd, direction, dist_chg, dir_chg)
    if d2 <= c.vis_dist2:
        qd_close = _quant(c, math.sqrt(d2), c.q) if c.high else None
        return SeenObject("B", qd_close, _direction(c, ang))
    return None


def _see_player(
    c: _Consts,
    me: tuple[float, float, float, float, float],
    it: tuple[float, float, float, float, float],
    who: PlayerRef,
    u_team: float,
    u_unum: float,
) -> SeenObject | None:
    """Another player (``sendHighPlayer`` / ``sendLowPlayer``); `me`/`it` = (x, y, vx, vy, th)."""
    ox, oy, ovx, ovy, oth = me
    px, py, pvx, pvy, pth = it
    dx, dy = px - ox, py - oy
    ang = wrap_angle(fpmath.atan2(dy, dx) - oth)
    d2 = dx * dx + dy * dy
    if not -c.half_angle < ang < c.half_angle:
        if d2 <= c.vis_dist2:
            qd_close = _quant(c, math.sqrt(d2), c.q) if c.high else None
            return SeenObject("P", qd_close, _direction(c, ang))
        return None
    d = math.sqrt(d2)
    qd = _quant(c, d, c.q)
    direction = _direction(c, ang)
    shown = qd if c.high else None
    if not c.perfect:
        if _decide(far_probability(qd, c.team_far, c.team_too_far), u_team):
            return SeenObject("p", shown, direction)
        if _decide(far_probability(qd, c.unum_far, c.unum_too_far), u_unum):
            return SeenObject("p", shown, direction, None, None, who.team)
    if not c.high or not c.changes:
        return SeenObject("p", shown, direction, None, None, who.team, who.number)
    dist_chg, dir_chg = _changes(c, dx, dy, pvx - ovx, pvy - ovy, d, qd)
    rel = wrap_angle(pth - oth)
    body = _direction(c, rel) if c.body else None
    head = body if c.head else None  # no neck: head = body
    return SeenObject("p", qd, direction, dist_chg, dir_chg, who.team, who.number, body, head)


def see_lines(sx: float, sy: float, sth: float, params: SensingParams) -> list[SeenObject]:
    """Lines hit by the line of sight within their length (§3.6, ``sendLine``).

    Args:
        sx: Observer x [m] (same in both frames).
        sy: Observer y in the SERVER frame (y down) [m].
        sth: View direction in the server frame (clockwise in ours) [rad].
        params: Sensing parameters.
    """
    c = _consts(params)
    hl, hw = PITCH_HALF_LENGTH_M, PITCH_HALF_WIDTH_M
    inside = abs(sx) < hl and abs(sy) < hw
    max_lines = 1 if inside else 2
    out: list[SeenObject] = []
    for line in LINES:
        if len(out) >= max_lines:
            break
        seen = _see_line(c, line.name, sx, sy, sth)
        if seen is not None:
            out.append(seen)
    return out


def _see_line(c: _Consts, name: str, sx: float, sy: float, sth: float) -> SeenObject | None:
    """One line, in server coordinates, as ``VisualSenderPlayerV1::sendLine``."""
    hl, hw = PITCH_HALF_LENGTH_M, PITCH_HALF_WIDTH_M
    if name == "l l":
        normal = 0.0 if sx < -hl else math.pi
        to_line, start, stop, vert = -hl - sx, -hw, hw, True
    elif name == "l r":
        normal = math.pi if sx > hl else 0.0
        to_line, start, stop, vert = hl - sx, -hw, hw, True
    elif name == "l t":  # server y = -34
        normal = _HALF_PI if sy < -hw else -_HALF_PI
        to_line, start, stop, vert = -hw - sy, -hl, hl, False
    else:  # "l b", server y = +34
        normal = -_HALF_PI if sy > hw else _HALF_PI
        to_line, start, stop, vert = hw - sy, -hl, hl, False
    s2l = wrap_angle(normal - sth)
    if abs(s2l) >= _HALF_PI:
        return None  # looking parallel to the line or away from it
    offset = to_line * math.tan(s2l)
    hit = sy - offset if vert else sx + offset
    if hit < start or hit > stop:
        return None
    direction = _direction(c, s2l - _HALF_PI if s2l > 0 else s2l + _HALF_PI)
    if not c.high:
        return SeenObject(name, None, direction)
    return SeenObject(name, _quant(c, abs(to_line / math.cos(s2l)), c.q_l), direction)


# ----------------------------------------------------------------------------- see timing


def visual_send_interval(params: SensingParams) -> int:
    """Visual-timer ticks between two sees: 4 at normal width and high quality (§3.1)."""
    factor = WIDTH_FACTOR[params.view_width] * QUALITY_FACTOR[params.view_quality]
    return max(1, round(4 * factor))


@dataclass(frozen=True, slots=True)
class SeeTimer:
    """On which 100 ms cycles a player receives a see message, counted in ms as the server does.

    The server's visual timer fires at the first multiple of ``recv_step`` (10 ms) at or after
    each multiple of ``send_step / 4`` ms; a player's see goes out every
    :func:`visual_send_interval` timer ticks (4 at normal width, high quality), so the interval
    is ``send_step`` ms at normal width. A see fired at time t ms belongs to cycle
    ``floor(t / simulator_step)`` and shows the state after that cycle's step (the step at
    t = 100·c runs before the sensors at the same instant). With ``send_step`` = 150 the cycles
    alternate gaps of 1 and 2 (1, 3, 4, 6, 7, ...); with 500 a see comes every 5 cycles.

    Attributes:
        params: Sensing parameters (send_step, recv_step, simulator_step, view width/quality).
        phase: Timer ticks by which this player's sees are offset (the server's send counter
            starts when the player connects): 0 .. interval - 1.
    """

    params: SensingParams
    phase: int = 0
    _interval: int = field(init=False, repr=False)

    def __post_init__(self) -> None:
        interval = visual_send_interval(self.params)
        if not 0 <= self.phase < interval:
            raise ValueError(f"phase: expected 0..{interval - 1}; got {self.phase}")
        object.__setattr__(self, "_interval", interval)

    def ticks_by(self, t_ms: int) -> int:
        """Visual-timer ticks that have fired at or before time `t_ms` (ticks k = 1, 2, ...)."""
        if t_ms < 0:
            return 0
        recv = self.params.recv_step_ms
        t_floor = (t_ms // recv) * recv
        # Tick k fires at ceil_recv(k * send_step / 4) <= T  <=>  4 k <= 4 floor_recv(T) / s.
        return (4 * t_floor) // self.params.send_step_ms

    def sees_by(self, t_ms: int) -> int:
        """This player's sees sent at or before `t_ms` (at ticks phase + j·interval, j >= 1)."""
        ticks = self.ticks_by(t_ms)
        return max(0, (ticks - self.phase) // self._interval)

    def sees_in_cycle(self, cycle: int) -> int:
        """How many sees this player gets during `cycle` (0, 1, or more for short intervals)."""
        step = self.params.simulator_step_ms
        return self.sees_by(step * (cycle + 1) - 1) - self.sees_by(step * cycle - 1)

    def due(self, cycle: int) -> bool:
        """True when at least one see is sent during `cycle`."""
        return self.sees_in_cycle(cycle) > 0

    def see_cycles(self, first: int, last: int) -> list[int]:
        """The cycles in ``[first, last]`` that carry a see (each once)."""
        return [c for c in range(first, last + 1) if self.due(c)]


# ----------------------------------------------------------------------------- hearing


def say_allowed(text: str, params: SensingParams) -> bool:
    """True when the server would broadcast `text`: short enough and only allowed characters.

    A longer message is dropped whole (§2.6, ``say_msg_size``); so is one with a character
    outside :data:`SAY_ALLOWED_CHARS` (today's rule, also used for the 1996 era: it keeps the
    unquoted old hear format parseable). Empty messages are refused.
    """
    return 0 < len(text) <= params.say_msg_size and all(ch in SAY_ALLOWED_CHARS for ch in text)


def hearers(
    speaker: int, x: Sequence[float], y: Sequence[float], params: SensingParams
) -> list[int]:
    """Player rows within ``audio_cut_dist`` of row `speaker`, the speaker included (§2.6)."""
    sx, sy = x[speaker], y[speaker]
    limit2 = params.audio_cut_dist_m**2
    return [
        row
        for row in range(1, len(x))
        if row == speaker or (x[row] - sx) ** 2 + (y[row] - sy) ** 2 <= limit2
    ]


@dataclass(slots=True)
class HearingBudget:
    """One listener's hearing capacity (§2.6): ``hear_max``, ``hear_inc``, ``hear_decay``.

    With ``hear_per_team`` (servers >= 8) teammates and opponents have separate counters;
    otherwise (1990s) one counter serves both. Referee, coach and own messages cost nothing.
    """

    params: SensingParams
    teammates: int = -1
    opponents: int = -1

    def __post_init__(self) -> None:
        if self.teammates < 0:
            self.teammates = self.params.hear_max
        if self.opponents < 0:
            self.opponents = self.params.hear_max

    def new_cycle(self) -> None:
        """Regain ``hear_inc`` per counter, up to ``hear_max`` (called once per cycle)."""
        p = self.params
        self.teammates = min(p.hear_max, self.teammates + p.hear_inc)
        self.opponents = min(p.hear_max, self.opponents + p.hear_inc)

    def take(self, same_team: bool) -> bool:
        """Spend ``hear_decay`` for a message from a player; False when capacity is short."""
        cost = self.params.hear_decay
        use_team = same_team or not self.params.hear_per_team
        have = self.teammates if use_team else self.opponents
        if have < cost:
            return False
        if use_team:
            self.teammates -= cost
        else:
            self.opponents -= cost
        return True


def hear_direction_truncates(protocol: int) -> bool:
    """Hear directions: truncated before 7, rounded in 7, truncated again from 8 (audio.cpp)."""
    return protocol != 7


def deliver_says(
    says: Sequence[tuple[int, str]],
    x: Sequence[float],
    y: Sequence[float],
    heading: Sequence[float],
    players: tuple[PlayerRef, ...],
    time: int,
    params: SensingParams,
    budgets: dict[int, HearingBudget] | None = None,
) -> dict[int, list[HearInfo]]:
    """Who hears which say of this cycle, as hear-message contents per listener row (§2.6).

    Args:
        says: (speaker row, text) in the order the server received them.
        x: Per-object x [m], our frame (row 0 = ball).
        y: Per-object y [m], our frame.
        heading: Per-object heading [rad], CCW, our frame.
        players: Identities of rows 1..N.
        time: Server time stamped on the messages.
        params: Sensing parameters (range, length cap, capacity, protocol).
        budgets: Hearing capacity per listener row; None = unlimited.

    Returns:
        For each listener row that hears something, its hear messages in order. A message too
        long or with forbidden characters is heard by nobody. Over capacity, protocol >= 8
        listeners get the short form (text None); older ones get nothing.
    """
    out: dict[int, list[HearInfo]] = {}
    protocol = params.protocol_version
    trunc = hear_direction_truncates(protocol)
    for speaker, text in says:
        if not say_allowed(text, params):
            continue
        who = players[speaker - 1]
        for row in hearers(speaker, x, y, params):
            if row == speaker:
                out.setdefault(row, []).append(HearInfo(time, "self", text))
                continue
            same = players[row - 1].team == who.team
            full = budgets is None or budgets[row].take(same)
            heard = _player_hear(
                time, text, full, same, who.number, protocol, trunc, x, y, heading, row, speaker
            )
            if heard is not None:
                out.setdefault(row, []).append(heard)
    return out


def _player_hear(
    time: int,
    text: str,
    full: bool,
    same: bool,
    unum: int,
    protocol: int,
    trunc: bool,
    x: Sequence[float],
    y: Sequence[float],
    heading: Sequence[float],
    row: int,
    speaker: int,
) -> HearInfo | None:
    """One listener's hear message of another player's say (``sendNonSelfPlayerAudio``)."""
    team = ("our" if same else "opp") if protocol >= 8 else None
    number = unum if protocol >= 8 and same else None
    if not full:
        return HearInfo(time, "player", None, None, team, number) if protocol >= 8 else None
    # Direction from the listener's body, server sign: negate our CCW angle.
    rel = wrap_angle(-(fpmath.atan2(y[speaker] - y[row], x[speaker] - x[row]) - heading[row]))
    return HearInfo(time, "player", text, degrees(rel, trunc), team, number)


def referee_hear(time: int, message: str) -> HearInfo:
    """A referee announcement (``goal_l_1``, ``kick_off_r``, ...) as heard by every player."""
    return HearInfo(time, "referee", message)
