"""The percepts of every player whose see fires in a cycle, at once: the see's geometry in arrays.

:func:`percepts_of` gives, for the K players whose see fires in one cycle, exactly the percepts
that K calls of :func:`~field_models.soccer_server.percepts.percept_from_state` give, in that
order and from the same generator state, bit for bit
(``tests/field_models/soccer_server/test_percepts_many.py`` compares every field on random
states and sensing settings, and whole pass trials). That one-player route, through
:func:`~field_models.soccer_server.sensing.observe`, stays the specification (shared
`specs/soccer_server.md` §3); this module does the same operations in another order:

* the geometry of every (observer, object) pair — the ball, the other players, then the
  landmarks the mode shows — as (K, M) arrays: offsets in the server frame, the angle, the
  wrap, the view cone (§3.2) and the felt distance; then, for the pairs a percept shows, the
  distance's log index (§3.3) and the direction in the server's degrees. The angle and the
  logarithm come from numpy's own kernels, whose last bits depend on the CPU; a see reports
  only the cone test, whole degrees and the log index, so those agree with the scalar
  :mod:`field_models.fpmath` except next to a boundary, and the few pairs within a safe margin
  of one take the scalar function (in perfect perception, which reports the angle itself,
  :func:`field_models.fpmath.atan2_array` gives every bit);
* the random draws as one block: each see draws ``1 + 2N`` numbers (then one per flag when
  flags carry changes), so K sees in a row read one block of K times that many, row by row;
* per pair shown (a few per observer), the scalar rules themselves: the memoised quantised
  distance, team and number fading (§3.5, ``decide``), the ball's changes (§3.4, the only
  changes a percept keeps);
* the records built by positional makers (no frozen ``__setattr__`` per field).

A cycle of fewer than :data:`ARRAY_PAIRS_MIN` pairs (two players and the ball) is built one see
at a time by that route itself, which is cheaper there. The arena's percepts come from here;
with ``trace=True`` it takes them from the see text.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from functools import lru_cache
from typing import NamedTuple

import numpy as np
import numpy.typing as npt

from field_models import fpmath
from field_models.protocol import (
    Heard,
    Percept,
    PlayerRef,
    SeenBall,
    SeenLandmark,
    SeenPlayer,
    wrap_angle,
)
from field_models.records import positional_maker
from field_models.seeding import Rng
from field_models.soccer_server.percepts import percept_from_state
from field_models.soccer_server.see_numbers import (
    EPS,
    RAD2DEG,
    SeeConsts,
    decide,
    far_probability,
    quantised_distance_for_index,
    see_changes,
    see_consts,
)
from field_models.soccer_server.sensing import LANDMARK_MODES, Bodies, LandmarkMode
from field_models.soccer_server.sensing_params import SensingParams

Array = npt.NDArray[np.float64]
Mask = npt.NDArray[np.bool_]
Index = npt.NDArray[np.intp]

_DEG2RAD = math.pi / 180.0

_make_percept = positional_maker(Percept)
_make_ball = positional_maker(SeenBall)
_make_player = positional_maker(SeenPlayer)
_make_mark = positional_maker(SeenLandmark)

ARRAY_PAIRS_MIN = 32
"""Below this many (observer, object) pairs in a cycle the sees are built one at a time: numpy's
fixed cost per array operation outweighs the per-pair work (measured: with 12 players, 2
observers cost about the same either way, 3 or more are cheaper as arrays)."""

When = tuple[int, Sequence[tuple[Heard, ...]]]
"""The cycle of the sees and, per observer, what it heard since its previous percept."""


def percepts_of(
    observers: Sequence[int],
    bodies: Bodies,
    players: tuple[PlayerRef, ...],
    params: SensingParams,
    rng: Rng,
    time: int,
    heard: Sequence[tuple[Heard, ...]],
    landmarks: LandmarkMode = "goals",
) -> list[Percept]:
    """The percepts of the sees at cycle `time` of the players in rows `observers`, in order.

    Equal, field for field and bit for bit, to ``percept_from_state(row, bodies, players, time,
    params, rng, heard=heard[k], landmarks=landmarks)`` for each row in turn.

    Args:
        observers: Rows of the observing players (1..N), in the order their sees are drawn.
        bodies: Every object's state (row 0 the ball). The arrays assume every head looks
            along its body: with a neck turned the sees are built one at a time.
        players: Identities of rows 1..N.
        params: Sensing parameters.
        rng: The trial's sensing generator.
        time: The cycle the sees show and the percepts reach the clients.
        heard: Per observer, the messages heard since its previous percept.
        landmarks: ``"goals"``, ``"all"`` (flags and goals) or ``"none"``.
    """
    n = len(players)
    _check(observers, n, heard, landmarks)
    if not observers:
        return []
    c = see_consts(params)
    marks = () if landmarks == "none" else c.flags if landmarks == "all" else c.goals
    turned = bodies.neck is not None and any(bodies.neck)
    if turned or len(observers) * (n + len(marks)) < ARRAY_PAIRS_MIN:
        return [
            percept_from_state(
                row, bodies, players, time, params, rng, heard=heard[k], landmarks=landmarks
            )
            for k, row in enumerate(observers)
        ]
    layout = _layout_of(players, tuple(observers), marks, (c.q, c.q_l))
    per_see = 1 + 2 * n + (len(c.flags) if landmarks != "none" and c.changes and c.high else 0)
    draws = rng.random(len(observers) * per_see).tolist()
    build = _Builder(c, params, layout, _Geometry.of(layout, bodies), bodies)
    return build.percepts(players, (draws, per_see), (time, heard))


def _check(
    observers: Sequence[int], n: int, heard: Sequence[tuple[Heard, ...]], landmarks: str
) -> None:
    """Refuse observers outside rows 1..n, a heard list of another length, an unknown mode."""
    if len(heard) != len(observers):
        raise ValueError(f"heard: {len(heard)} entries for {len(observers)} observers")
    if any(not 1 <= row <= n for row in observers):
        raise ValueError(f"observer rows {list(observers)} not all inside 1..{n}")
    if landmarks not in LANDMARK_MODES:
        raise ValueError(f"landmarks: expected one of {LANDMARK_MODES}; got {landmarks!r}")


class _Layout(NamedTuple):
    """Which object each (observer, column) pair is; fixed for a set of observers.

    A pair's flat position is ``k * M + column`` (row-major (K, M) arrays): the shown pairs are
    gathered by flat positions, numpy's cheapest gather.
    """

    observer_rows: tuple[int, ...]  # (K,) rows of the observers
    observer_column: Index  # (K, 1) the same rows, a column to gather the observers' state
    columns: Index  # (K, M): ball, the other players in row order, then the landmarks
    feels: Mask  # (M,): a close object is felt (ball, players), not a landmark (no name)
    flat_column: Index  # (K * M,) each flat position's column
    flat_steps: Array  # (K * M,) log step of the distance quantisation, q or q_l (§3.3)
    flat_log_edge: Array  # (K * M,) 0.5 less twice SAFE_MARGIN_LOG in steps (_log_indices)
    row_starts: Index  # (K + 1,) flat position of each observer's first pair, then K * M
    team_draws: tuple[tuple[int, ...], ...]  # per observer, each player column's team draw
    ids: tuple[tuple[tuple[str, int], ...], ...]  # per observer, its columns' (team, number)
    mark_x: tuple[float, ...]  # (L,) landmark x [m]
    mark_y_up: tuple[float, ...]  # (L,) landmark y [m] in our frame (up): the server's negated
    mark_pad: tuple[float, ...]  # (L,) zeros: the landmarks' "headings", never read
    mark_names: tuple[str, ...]  # (L,)


Marks = tuple[tuple[int, float, float, str, str], ...]
"""A see's landmarks, as :class:`SeeConsts` holds them."""

_LayoutKey = tuple[int, tuple[int, ...], int, tuple[float, float]]
_LAYOUTS: dict[_LayoutKey, tuple[tuple[PlayerRef, ...], Marks, _Layout]] = {}
"""The layouts by the identity of the players and marks (each arena and SeeConsts keeps its
tuples): hashing the players' tuple, as the cache of :func:`_layout` does, costs more."""


def _layout_of(
    players: tuple[PlayerRef, ...],
    observers: tuple[int, ...],
    marks: Marks,
    steps: tuple[float, float],
) -> _Layout:
    """:func:`_layout`, looked up by the identity of `players` and `marks`."""
    key = (id(players), observers, id(marks), steps)
    hit = _LAYOUTS.get(key)
    if hit is not None and hit[0] is players and hit[1] is marks:
        return hit[2]
    layout = _layout(players, observers, marks, steps)
    if len(_LAYOUTS) >= 64:
        _LAYOUTS.clear()
    _LAYOUTS[key] = (players, marks, layout)  # holds them, so that their ids stay theirs
    return layout


@lru_cache(maxsize=64)
def _layout(
    players: tuple[PlayerRef, ...],
    observers: tuple[int, ...],
    marks: Marks,
    steps: tuple[float, float],
) -> _Layout:
    """The columns of each observer: the ball, the other players in row order, the landmarks.

    `steps` is the quantisation step of ball and players, then of flags and goals.
    """
    n, k = len(players), len(observers)
    kept = [m for m in marks if m[3][0] in "fg" and len(m[3]) > 1]  # what a percept keeps
    others = [[row for row in range(1, n + 1) if row != me] for me in observers]
    columns = [[0, *rows, *range(n + 1, n + 1 + len(kept))] for rows in others]
    m = n + len(kept)
    flat_steps = np.tile(np.array([steps[0]] * n + [steps[1]] * len(kept)), k)
    return _Layout(
        observer_rows=tuple(observers),
        observer_column=np.array(observers, dtype=np.intp).reshape(k, 1),
        columns=np.array(columns, dtype=np.intp).reshape(k, m),
        feels=np.array([True] * n + [False] * len(kept)),
        flat_column=np.tile(np.arange(m, dtype=np.intp), k),
        flat_steps=flat_steps,
        flat_log_edge=0.5 - 2.0 * SAFE_MARGIN_LOG / flat_steps,
        row_starts=np.arange(k + 1, dtype=np.intp) * m,
        team_draws=tuple(tuple(2 * row - 1 for row in rows) for rows in others),
        ids=tuple(
            tuple((players[r - 1].team, players[r - 1].number) for r in rows) for rows in others
        ),
        mark_x=tuple(float(m[1]) for m in kept),
        mark_y_up=tuple(-float(m[2]) for m in kept),
        mark_pad=(0.0,) * len(kept),
        mark_names=tuple(m[3] for m in kept),
    )


class _Geometry(NamedTuple):
    """Offsets of every (observer, column) pair in the server frame, (K, M) arrays."""

    dx: Array  # [m]
    dy: Array  # [m], server y (down)
    d2: Array  # squared distance [m²]
    heading: Array  # (K, 1) the observers' headings, server frame (clockwise in ours) [rad]

    @classmethod
    def of(cls, layout: _Layout, bodies: Bodies) -> _Geometry:
        """The offsets, computed as ``observe`` does (the negations are exact).

        x, y and heading of every object and landmark make one (3, N + L) array, so that one
        negation gives the server's y and headings (the landmarks' y go in ours, so that it
        gives theirs back bit for bit) and one gather and one subtraction both offsets.
        """
        p = np.array(
            (
                [*bodies.x, *layout.mark_x],
                [*bodies.y, *layout.mark_y_up],
                [*bodies.heading, *layout.mark_pad],
            ),
            dtype=np.float64,
        )
        np.negative(p[1:], out=p[1:])
        me = p.take(layout.observer_column, axis=1)  # (3, K, 1)
        d = p[:2].take(layout.columns, axis=1) - me[:2]
        dx, dy = d[0], d[1]
        return cls(dx, dy, dx * dx + dy * dy, me[2])


_numpy_atan2 = np.arctan2
"""numpy's own kernels: fast, but their last bits depend on the CPU (:mod:`field_models.fpmath`);
module names so that a test can perturb them."""
_numpy_log = np.log

SAFE_MARGIN_RAD = 1e-9
"""How near a cone edge, a degree boundary or ±π an angle from numpy's ``arctan2`` may come before
the scalar ``fpmath.atan2`` decides it. The two differ by a few units in the last place (below
1e-14 rad for angles within ±2π), so outside this margin they report the same cone test and the
same whole degrees."""
SAFE_MARGIN_LOG = 1e-9
"""The same for a distance's log index ``round(ln(d + EPS) / step)``: how near (in ln) to a half
step the logarithm may come. numpy's and fdlibm's logarithms differ by a few units in the last
place, below 1e-13 for any distance below 10^6 m."""


class _Angles(NamedTuple):
    """Each pair's direction from the observer's view (server frame, [-π, π)), (K, M) arrays."""

    size: Array  # its magnitude: the cone test is size < half angle
    degrees: Array  # in the server's degrees, before truncating or rounding


def _view_angles(c: SeeConsts, g: _Geometry) -> _Angles:
    """Each pair's direction from the observer's view (server frame, [-π, π)), as ``observe``.

    Perfect perception reports the angle itself, so every bit comes from
    :func:`field_models.fpmath.atan2_array`. Otherwise a see reports only the cone test (§3.2)
    and whole degrees (truncated or rounded), so numpy's faster ``arctan2`` gives the same
    report except within :data:`SAFE_MARGIN_RAD` of a boundary; those few pairs (about one in
    ten million) take the scalar ``atan2``.
    """
    if c.perfect:
        ang = wrap_angle(fpmath.atan2_array(g.dy, g.dx) - g.heading)
        return _Angles(np.abs(ang), ang * RAD2DEG)
    ang = wrap_angle(_numpy_atan2(g.dy, g.dx) - g.heading)
    size = np.abs(ang)
    deg = ang * RAD2DEG
    edge = deg if c.truncate else deg + 0.5  # truncation flips at whole degrees, rounding at halves
    near = np.abs(size - c.half_angle) < SAFE_MARGIN_RAD
    # On an axis: signed zeros, exact constants. A product that underflows to 0 also takes the
    # scalar rule, which is never wrong.
    near |= g.dx * g.dy == 0.0
    near |= np.abs(edge - np.rint(edge)) < SAFE_MARGIN_RAD * RAD2DEG
    if not c.truncate:  # where ±π wraps, rounding flips sign (truncation: ±180 is a boundary)
        near |= np.abs(size - math.pi) < SAFE_MARGIN_RAD
    if near.any():
        for k, j in zip(*np.nonzero(near), strict=True):
            exact = fpmath.atan2(float(g.dy[k, j]), float(g.dx[k, j])) - float(g.heading[k, 0])
            exact = wrap_angle(exact)
            size[k, j], deg[k, j] = abs(exact), exact * RAD2DEG
    return _Angles(size, deg)


def _log_indices(exact: Array, steps: Array, edge: Array) -> list[int]:
    """``round(fpmath.log(d + EPS) / step)`` per distance (§3.3), through numpy's ``log``.

    As for angles, only a logarithm within :data:`SAFE_MARGIN_LOG` of a half step takes the
    scalar one: elsewhere both round to the same index. There ``|q - rint(q)|`` of the quotient
    ``q`` is within the margin (in steps) of 0.5; `edge` is 0.5 less twice that (a superset:
    the rounding of these few operations is far below the margin).

    Raises:
        ValueError: A distance that is not finite (a position became NaN or inf).
    """
    quotient = _numpy_log(exact + EPS) / steps
    if not np.isfinite(quotient).all():
        raise ValueError("see: a distance that is not finite (a position became NaN or inf)")
    index = np.rint(quotient)
    for p in np.flatnonzero(np.abs(quotient - index) > edge):
        index[p] = round(fpmath.log(float(exact[p]) + EPS) / float(steps[p]))
    out: list[int] = index.astype(np.intp).tolist()
    return out


class _Pairs(NamedTuple):
    """The (observer, column) pairs a percept shows, in percept order (observer, then column).

    ``angle`` is in our CCW radians, from the reported direction.
    """

    bounds: list[int]  # observer k's pairs are bounds[k]:bounds[k + 1]
    column: list[int]
    exact: list[float]  # the exact distance [m] in perfect perception (else empty)
    log_index: list[int]  # otherwise the log index of the quantised distance (§3.3)
    angle: list[float]
    in_cone: list[bool]  # False: felt (close, outside the cone): no team, number or changes


class _Builder:
    """Turns the shown pairs of one cycle into percepts: distances, fading, ball changes."""

    def __init__(
        self,
        c: SeeConsts,
        params: SensingParams,
        layout: _Layout,
        geometry: _Geometry,
        bodies: Bodies,
    ) -> None:
        self.c, self.params, self.layout, self.geometry = c, params, layout, geometry
        self.bodies = bodies
        self.first_mark = layout.columns.shape[1] - len(layout.mark_names)
        # Within both fading lengths a player shows team and number: far_probability is 0.
        self.near = math.inf if c.perfect else min(c.team_far, c.unum_far)
        self.fading = (c.team_far, c.team_too_far, c.unum_far, c.unum_too_far)

    def pairs(self) -> _Pairs:
        """The pairs shown, with the operations of ``observe`` (arrays over all pairs first)."""
        c, layout, g = self.c, self.layout, self.geometry
        size, degrees = _view_angles(c, g)
        in_cone = size < c.half_angle  # -half < angle < half
        shown = in_cone | ((g.d2 <= c.vis_dist2) & layout.feels)
        if not c.high:
            shown[...] = False  # low quality: no distances, and a percept keeps none without
        flat = np.flatnonzero(shown)  # row-major: each observer's pairs in column order
        exact = np.sqrt(g.d2.ravel()[flat])
        deg = degrees.ravel()[flat]
        exact_list: list[float] = []
        index: list[int] = []
        if c.perfect:
            exact_list, direction = exact.tolist(), deg
        else:
            index = _log_indices(exact, layout.flat_steps[flat], layout.flat_log_edge[flat])
            direction = np.trunc(deg) if c.truncate else np.rint(deg)
        bounds = np.searchsorted(flat, layout.row_starts)
        # Server degrees -> our CCW radians: -(d * r) is d * -r bit for bit; + 0.0 clears -0.
        angle = direction * -_DEG2RAD + 0.0
        return _Pairs(
            bounds.tolist(),
            layout.flat_column[flat].tolist(),
            exact_list,
            index,
            angle.tolist(),
            in_cone.ravel()[flat].tolist(),
        )

    def percepts(
        self, players: tuple[PlayerRef, ...], draws: tuple[list[float], int], when: When
    ) -> list[Percept]:
        """Every observer's percept; `draws` is the cycle's block and each see's share of it.

        Each observer's ball, players and landmarks in the see's order, from its shown pairs
        (one loop for the cycle: the locals are read once, not once per observer).
        """
        pairs = self.pairs()
        qds = self.distances(pairs)
        time, heard = when
        block, per_see = draws
        layout, near = self.layout, self.near
        first_mark, names = self.first_mark, layout.mark_names
        tf, ttf, uf, utf = self.fading
        bounds, columns, angles, cones = pairs.bounds, pairs.column, pairs.angle, pairs.in_cone
        team: str | None
        number: int | None
        out: list[Percept] = []
        for k, row in enumerate(layout.observer_rows):
            ids, team_draws, start = layout.ids[k], layout.team_draws[k], k * per_see
            ball: SeenBall | None = None
            others: list[SeenPlayer] = []
            marks: list[SeenLandmark] = []
            for p in range(bounds[k], bounds[k + 1]):
                j, qd, angle = columns[p], qds[p], angles[p]
                if j >= first_mark:
                    marks.append(_make_mark(names[j - first_mark], qd, angle))
                elif not j:
                    ball = self.ball(k, (qd, angle, cones[p]), block[start])
                elif not cones[p]:
                    others.append(_make_player(qd, angle, None, None))  # felt "(P)"
                elif qd <= near:
                    team, number = ids[j - 1]
                    others.append(_make_player(qd, angle, team, number))
                else:
                    # The fading of §3.5 (the team first), as decide(far_probability(qd, far,
                    # too_far), u) in line: withheld beyond too_far, kept up to far.
                    u = start + team_draws[j - 1]
                    team, number = ids[j - 1]
                    if qd > tf and (qd >= ttf or decide(far_probability(qd, tf, ttf), block[u])):
                        team = number = None
                    elif qd > uf and (
                        qd >= utf or decide(far_probability(qd, uf, utf), block[u + 1])
                    ):
                        number = None
                    others.append(_make_player(qd, angle, team, number))
            seen = (ball, tuple(others), heard[k], tuple(marks), 0.0)
            out.append(_make_percept(players[row - 1], time, time, *seen))
        return out

    def distances(self, pairs: _Pairs) -> list[float]:
        """Each pair's reported distance: exact when perfect, else its log index's (§3.3)."""
        c = self.c
        if c.perfect:
            return pairs.exact
        get, get_l, first_mark = c.table.get, c.table_l.get, self.first_mark
        found = [
            (get_l if j >= first_mark else get)(m)
            for j, m in zip(pairs.column, pairs.log_index, strict=True)
        ]
        if None not in found:
            return found  # type: ignore[return-value]
        return [
            self.distance(j >= first_mark, m) if qd is None else qd
            for j, m, qd in zip(pairs.column, pairs.log_index, found, strict=True)
        ]

    def distance(self, mark: bool, index: int) -> float:
        """The reported distance of a log index not yet in the memo (§3.3)."""
        c = self.c
        return quantised_distance_for_index(self.params, index, c.q_l if mark else c.q)

    def ball(self, k: int, seen: tuple[float, float, bool], u: float) -> SeenBall:
        """Observer `k`'s ball, with its changes where the see reports them (§3.4)."""
        qd, angle, in_cone = seen
        c = self.c
        reports = c.changes and in_cone  # a felt ball carries no changes
        if reports and not c.perfect:
            reports = not decide(far_probability(qd, c.unum_far, c.unum_too_far), u)
        if not reports:
            return _make_ball(qd, angle, None, None)
        g, b, row = self.geometry, self.bodies, self.layout.observer_rows[k]
        # Velocity relative to the observer in the server frame (y down), as observe has it.
        wx = b.vx[0] - b.vx[row]
        wy = -b.vy[0] - -b.vy[row]
        dx, dy = float(g.dx[k, 0]), float(g.dy[k, 0])
        dist_chg, dir_chg = see_changes(c, dx, dy, wx, wy, math.sqrt(dx * dx + dy * dy), qd)
        cycle_s = self.params.simulator_step_ms / 1000.0
        dir_rad = -(dir_chg * _DEG2RAD) + 0.0  # server degrees -> our CCW radians
        return _make_ball(qd, angle, dist_chg / cycle_s, dir_rad / cycle_s)
