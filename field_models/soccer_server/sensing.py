"""Soccer Server visual sensing as pure functions of the state: the content of a see message.

Implements shared `specs/soccer_server.md` §3 (visual sensing), following
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
timer (synch-see mode is not modelled); the view points along body + neck (:class:`Bodies`'
``neck``, 0 where left out: the 1996 servers had no neck), and a seen player's head direction is
its body + neck relative to the observer's view; player entries never carry a pointing
direction, goalie or tackle mark. The flag loop, the costliest part of a full see, is written
out inline.

Beside this module: the numbers of a see (:mod:`~field_models.soccer_server.see_numbers`), when
sees are sent (:mod:`~field_models.soccer_server.see_timing`) and hearing, §2.6
(:mod:`~field_models.soccer_server.hearing`).
"""

from __future__ import annotations

import math
import typing
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Literal, NamedTuple

from field_models import fpmath
from field_models.protocol import PlayerRef, wrap_angle
from field_models.seeding import Rng
from field_models.soccer_server.landmarks import LINES, PITCH_HALF_LENGTH_M, PITCH_HALF_WIDTH_M
from field_models.soccer_server.see_numbers import (
    EPS,
    RAD2DEG,
    SeeConsts,
    decide,
    far_probability,
    from_log_index,
    quantised,
    see_changes,
    see_consts,
    see_direction,
)
from field_models.soccer_server.sensing_params import SensingParams

_TWO_PI = 2.0 * math.pi
_HALF_PI = 0.5 * math.pi

LandmarkMode = Literal["all", "goals", "none"]
"""Which landmarks :func:`observe` reports: flags, goals and lines; the goals; none."""
LANDMARK_MODES: tuple[LandmarkMode, ...] = typing.get_args(LandmarkMode)
"""The values of :data:`LandmarkMode`, for callers that check a setting at run time."""


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


# ----------------------------------------------------------------------------- see


class Bodies(NamedTuple):
    """What a see looks at: every object's state, our frame; row 0 the ball, rows 1..N players.

    One record for the state arrays :func:`observe` and the percept routes read (as the models
    hold them, e.g. :class:`~field_models.soccer_server.dynamics.SoccerServerModel`'s columns).

    Attributes:
        x: x [m].
        y: y [m] (up).
        vx: x velocity [m/cycle].
        vy: y velocity [m/cycle].
        heading: heading [rad], CCW from +x (row 0 unused).
        neck: Neck angle relative to the body [rad], CCW (None: every neck is 0). The observer
            looks along heading + neck (§3.1): every direction is relative to that, and a seen
            player's head direction is its own heading + neck.
    """

    x: Sequence[float]
    y: Sequence[float]
    vx: Sequence[float]
    vy: Sequence[float]
    heading: Sequence[float]
    neck: Sequence[float] | None = None


def observe(
    observer: int,
    bodies: Bodies,
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
        bodies: Every object's state (:class:`Bodies`: row 0 the ball, rows 1..N `players`).
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
    c = see_consts(params)
    x, y, vx, vy, heading, neck = bodies
    # Server frame: y down, angles clockwise in ours. Negating y and the heading is exact.
    ox, osy = x[observer], -y[observer]
    ovx, ovy = vx[observer], -vy[observer]
    oth = -heading[observer]
    if neck is not None and neck[observer] != 0.0:  # a zero neck leaves every number as it was
        oth = -wrap_angle(heading[observer] + neck[observer])
    draws = rng.random(1 + 2 * n).tolist()
    objects: list[SeenObject] = []
    if landmarks not in LANDMARK_MODES:
        raise ValueError(f"landmarks: expected one of {LANDMARK_MODES}; got {landmarks!r}")
    if landmarks != "none":
        rows = c.flags if landmarks == "all" else c.goals
        see_flags = _see_flags_exact if c.perfect else _see_flags
        objects.extend(see_flags(c, rows, ox, osy, ovx, ovy, oth, rng))
    ball = _see_ball(c, (ox, osy, ovx, ovy, oth), (x[0], -y[0], vx[0], -vy[0]), draws[0])
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
            0.0 if neck is None else -neck[row],
        )
        if seen is not None:
            objects.append(seen)
    if landmarks == "all":
        objects.extend(see_lines(ox, osy, oth, params))
    return SeeInfo(time, tuple(objects))


def _see_flags(
    c: SeeConsts,
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
            deg = ang * RAD2DEG
            direction = int(deg) if trunc else round(deg)
            if not high:
                append(new(SeenObject, (name, None, direction, None, None, None, None, None, None)))
                continue
            d = sqrt(dx * dx + dy * dy)
            m = round(log(d + EPS) / q_l)  # the quantised log-distance fixes the result
            qd = table.get(m)
            if qd is None:
                qd = table[m] = from_log_index(c, m, q_l)
            # The server's decide(far_probability(qd)): true = no changes.
            if draws is None or (
                qd > far and (qd >= too_far or draws[i] < (qd - far) / (too_far - far))
            ):
                append(new(SeenObject, (name, qd, direction, None, None, None, None, None, None)))
            else:
                dist_chg, dir_chg = see_changes(c, dx, dy, -ovx, -ovy, d, qd)
                append(
                    new(
                        SeenObject, (name, qd, direction, dist_chg, dir_chg, None, None, None, None)
                    )
                )
        elif dx * dx + dy * dy <= vis2:
            deg = ang * RAD2DEG
            direction = int(deg) if trunc else round(deg)
            qd_close = quantised(c, sqrt(dx * dx + dy * dy), q_l) if high else None
            append(SeenObject(close, qd_close, direction))
    return out


def _see_flags_exact(
    c: SeeConsts,
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
        direction = ang * RAD2DEG
        d = math.sqrt(dx * dx + dy * dy)
        if -c.half_angle < ang < c.half_angle:
            if not c.high:
                out.append(SeenObject(name, None, direction))
            elif c.changes:
                dist_chg, dir_chg = see_changes(c, dx, dy, -ovx, -ovy, d, d)
                out.append(SeenObject(name, d, direction, dist_chg, dir_chg))
            else:
                out.append(SeenObject(name, d, direction))
        elif dx * dx + dy * dy <= c.vis_dist2:
            out.append(SeenObject(close, d if c.high else None, direction))
    return out


def _see_ball(
    c: SeeConsts,
    me: tuple[float, float, float, float, float],
    ball: tuple[float, float, float, float],
    u: float,
) -> SeenObject | None:
    """The ball (``sendHighBall`` / ``sendLowBall``).

    `me` is the observer's (x, y, vx, vy, th), `ball` the ball's (x, y, vx, vy): server frame.
    """
    ox, oy, ovx, ovy, oth = me
    bx, by, bvx, bvy = ball
    dx, dy = bx - ox, by - oy
    ang = wrap_angle(fpmath.atan2(dy, dx) - oth)
    d2 = dx * dx + dy * dy
    if -c.half_angle < ang < c.half_angle:
        direction = see_direction(c, ang)
        if not c.high:
            return SeenObject("b", None, direction)
        d = math.sqrt(d2)
        qd = quantised(c, d, c.q)
        if not c.changes or (
            not c.perfect and decide(far_probability(qd, c.unum_far, c.unum_too_far), u)
        ):
            return SeenObject("b", qd, direction)
        dist_chg, dir_chg = see_changes(c, dx, dy, bvx - ovx, bvy - ovy, d, qd)
        return SeenObject("b", qd, direction, dist_chg, dir_chg)
    if d2 <= c.vis_dist2:
        qd_close = quantised(c, math.sqrt(d2), c.q) if c.high else None
        return SeenObject("B", qd_close, see_direction(c, ang))
    return None


def _see_player(
    c: SeeConsts,
    me: tuple[float, float, float, float, float],
    it: tuple[float, float, float, float, float],
    who: PlayerRef,
    u_team: float,
    u_unum: float,
    its_neck: float = 0.0,
) -> SeenObject | None:
    """Another player (``sendHighPlayer`` / ``sendLowPlayer``); `me`/`it` = (x, y, vx, vy, th).

    `its_neck` is the seen player's neck angle in the server's sign (its head is th + neck).
    """
    ox, oy, ovx, ovy, oth = me
    px, py, pvx, pvy, pth = it
    dx, dy = px - ox, py - oy
    ang = wrap_angle(fpmath.atan2(dy, dx) - oth)
    d2 = dx * dx + dy * dy
    if not -c.half_angle < ang < c.half_angle:
        if d2 <= c.vis_dist2:
            qd_close = quantised(c, math.sqrt(d2), c.q) if c.high else None
            return SeenObject("P", qd_close, see_direction(c, ang))
        return None
    d = math.sqrt(d2)
    qd = quantised(c, d, c.q)
    direction = see_direction(c, ang)
    shown = qd if c.high else None
    if not c.perfect:
        if decide(far_probability(qd, c.team_far, c.team_too_far), u_team):
            return SeenObject("p", shown, direction)
        if decide(far_probability(qd, c.unum_far, c.unum_too_far), u_unum):
            return SeenObject("p", shown, direction, None, None, who.team)
    if not c.high or not c.changes:
        return SeenObject("p", shown, direction, None, None, who.team, who.number)
    dist_chg, dir_chg = see_changes(c, dx, dy, pvx - ovx, pvy - ovy, d, qd)
    rel = wrap_angle(pth - oth)
    body = see_direction(c, rel) if c.body else None
    if not c.head:
        head = None
    elif its_neck == 0.0:
        head = body
    else:
        head = see_direction(c, wrap_angle(pth + its_neck - oth))
    return SeenObject("p", qd, direction, dist_chg, dir_chg, who.team, who.number, body, head)


def see_lines(sx: float, sy: float, sth: float, params: SensingParams) -> list[SeenObject]:
    """Lines hit by the line of sight within their length (§3.6, ``sendLine``).

    Args:
        sx: Observer x [m] (same in both frames).
        sy: Observer y in the SERVER frame (y down) [m].
        sth: View direction in the server frame (clockwise in ours) [rad].
        params: Sensing parameters.
    """
    c = see_consts(params)
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


def _see_line(c: SeeConsts, name: str, sx: float, sy: float, sth: float) -> SeenObject | None:
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
    direction = see_direction(c, s2l - _HALF_PI if s2l > 0 else s2l + _HALF_PI)
    if not c.high:
        return SeenObject(name, None, direction)
    return SeenObject(name, quantised(c, abs(to_line / math.cos(s2l)), c.q_l), direction)
