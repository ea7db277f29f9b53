"""Collisions of the Soccer Server (spec §4): overlapping objects pushed apart, velocities × −0.1.

Functions over the single-trial model's plain lists of positions and velocities (row 0 the
ball, rows 1..N the players), as :class:`~field_models.soccer_server.dynamics.SoccerServerModel`
holds them; they change the lists in place. Pairs come from :func:`collision_pairs`, in the
server's order.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from functools import lru_cache
from typing import NamedTuple

from field_models.soccer_server.cycle_rules import (
    COLLISION_PASSES,
    COLLISION_VELOCITY_FACTOR,
    EPS,
    SEPARATION_RETRIES,
)

Pair = tuple[int, int, float, float]
"""Two rows (a < b), the square of their radii's sum, and the sum."""


def collision_pairs(sizes: list[float]) -> list[Pair]:
    """Pairs in the server's order: ball–player, then player–player (a < b); radii sum²."""
    n = len(sizes)
    pairs = [(0, b) for b in range(1, n)]
    pairs += [(a, b) for a in range(1, n) for b in range(a + 1, n)]
    return [(a, b, (sizes[a] + sizes[b]) ** 2, sizes[a] + sizes[b]) for a, b in pairs]


def any_overlap(pairs: Sequence[Pair], x: list[float], y: list[float]) -> bool:
    """Whether any pair overlaps at positions `x`, `y`.

    Every pair in turn: the specification of :func:`any_overlap_swept`.
    """
    for a, b, reach2, _ in pairs:
        dx, dy = x[b] - x[a], y[b] - y[a]
        if dx * dx + dy * dy < reach2:
            return True
    return False


class Sweep(NamedTuple):
    """A set of objects' pairs and what :func:`any_overlap_swept` needs; shared, never changed."""

    pairs: tuple[Pair, ...]  # every pair (collision_pairs): the collision rules' table
    rows: tuple[int, ...]  # 0 .. n-1
    reach2: tuple[tuple[float, ...], ...]  # reach2[a][b]: the pair's square of radii's sum
    cut: float  # an x gap beyond which no pair can overlap (the largest reach, and a margin)


@lru_cache(maxsize=16)
def sweep_of(sizes: tuple[float, ...]) -> Sweep:
    """The pairs and sweep table of objects of radii `sizes` (row 0 the ball).

    Cached: every trial's model of one preset shares them (a trial used to build its 66
    pairs anew).
    """
    n = len(sizes)
    pairs = tuple(collision_pairs(list(sizes)))
    reach2 = [[0.0] * n for _ in range(n)]
    reach = 0.0
    for a, b, r2, r in pairs:
        reach2[a][b] = reach2[b][a] = r2
        reach = max(reach, r)
    # A gap dx >= cut has dx * dx >= fl(cut * cut) > every reach2 (which is fl(reach ** 2)),
    # so the pair's test is False there: the margin keeps that true through the rounding.
    table = tuple(tuple(row) for row in reach2)
    return Sweep(pairs, tuple(range(n)), table, reach * (1.0 + 1e-9))


def any_overlap_swept(sweep: Sweep, x: list[float], y: list[float]) -> bool:
    """:func:`any_overlap` (the same answer, bit for bit) by sort and sweep along x.

    Objects sorted by x; each is tested only against those after it less than ``sweep.cut``
    further along, with the pair's own test (``dx * dx + dy * dy < reach2``: the square of a
    difference does not depend on its sign, so the order of the two does not matter). On a
    pitch of 12 objects that is a few pairs instead of 66.
    """
    if math.isnan(sum(x)):  # NaN does not sort: every pair, as any_overlap (NaN overlaps none)
        return any_overlap(sweep.pairs, x, y)
    rows = sorted(sweep.rows, key=x.__getitem__)
    cut, table = sweep.cut, sweep.reach2
    for i in range(len(rows) - 1):
        a = rows[i]
        xa, ya, reach2 = x[a], y[a], table[a]
        for b in rows[i + 1 :]:
            dx = x[b] - xa
            if dx >= cut:
                break
            dy = y[b] - ya
            if dx * dx + dy * dy < reach2[b]:
                return True
    return False


def catch_passing_ball(
    pairs: Sequence[Pair], xy: tuple[list[float], list[float]], xy0: tuple[list[float], list[float]]
) -> None:
    """Swept ball–player check (``swept_ball_collisions``): rewind a pair that met mid-cycle.

    Both objects moved on straight lines during the cycle, from `xy0` to `xy`; if their relative
    path came closer than the sum of radii although they no longer overlap, both are put back
    where they were at the closest approach, so that :func:`resolve_collisions` treats the pair
    as overlapping (push apart, velocities × −0.1) — "moved back until they do not overlap" in
    the manual's words (§4).
    """
    x, y = xy
    x0, y0 = xy0
    for a, b, reach2, _ in pairs:
        if a != 0:
            continue  # ball (row 0) against a player only
        ex, ey = x[b] - x[a], y[b] - y[a]
        if ex * ex + ey * ey < reach2:
            continue  # overlapping at the end: the ordinary check handles it
        sx, sy = x0[b] - x0[a], y0[b] - y0[a]
        dx, dy = ex - sx, ey - sy
        d2 = dx * dx + dy * dy
        if d2 == 0.0:
            continue
        t = min(1.0, max(0.0, -(sx * dx + sy * dy) / d2))
        cx, cy = sx + t * dx, sy + t * dy
        if cx * cx + cy * cy >= reach2:
            continue
        for i in (a, b):
            x[i] = x0[i] + t * (x[i] - x0[i])
            y[i] = y0[i] + t * (y[i] - y0[i])


def resolve_collisions(
    pairs: Sequence[Pair],
    xy: tuple[list[float], list[float]],
    vxy: tuple[list[float], list[float]],
    play_on: bool,
) -> None:
    """Push overlapping pairs apart (mean of proposals, ≤ 10 passes), velocities × −0.1.

    Outside ``play_on`` the ball stays and a player touching it is pushed away from it.
    """
    x, y = xy
    vx, vy = vxy
    n = len(x)
    collided = [False] * n
    for _ in range(COLLISION_PASSES):
        sx, sy, count = [0.0] * n, [0.0] * n, [0] * n
        for a, b, reach2, reach in pairs:
            dx, dy = x[b] - x[a], y[b] - y[a]
            if dx * dx + dy * dy >= reach2:
                continue
            collided[a] = collided[b] = True
            if a == 0 and not play_on:
                pa, pb = (x[0], y[0]), _push_from(x[0], y[0], dx, dy, reach + EPS)
            else:
                pa, pb = _separate(x[a], y[a], x[b], y[b], reach, reach2)
            sx[a] += pa[0]
            sy[a] += pa[1]
            count[a] += 1
            sx[b] += pb[0]
            sy[b] += pb[1]
            count[b] += 1
        if not any(count):
            break
        for i in range(n):
            if count[i]:
                x[i], y[i] = sx[i] / count[i], sy[i] / count[i]
    for i in range(n):
        if collided[i]:
            vx[i] *= COLLISION_VELOCITY_FACTOR
            vy[i] *= COLLISION_VELOCITY_FACTOR


def _separate(
    ax: float, ay: float, bx: float, by: float, reach: float, reach2: float
) -> tuple[tuple[float, float], tuple[float, float]]:
    """Both objects at (reach/2 + EPS) from their midpoint, on their line of centres (§4)."""
    mx, my = (ax + bx) / 2.0, (ay + by) / 2.0
    ux, uy, wx, wy = ax - mx, ay - my, bx - mx, by - my
    half = reach / 2.0 + EPS
    ru, rw = math.sqrt(ux * ux + uy * uy), math.sqrt(wx * wx + wy * wy)
    if (ax == bx and ay == by) or (ru < EPS and rw < EPS) or ru == 0.0 or rw == 0.0:
        ux, uy, wx, wy = half, 0.0, -half, 0.0  # coincident: along +x (the server: random)
    else:
        ux, uy = ux * (half / ru), uy * (half / ru)
        wx, wy = wx * (half / rw), wy * (half / rw)
    for _ in range(SEPARATION_RETRIES):
        dx, dy = (mx + wx) - (mx + ux), (my + wy) - (my + uy)
        if dx * dx + dy * dy >= reach2:
            break
        ux, uy, wx, wy = ux * 1.0001, uy * 1.0001, wx * 1.0001, wy * 1.0001
    return (mx + ux, my + uy), (mx + wx, my + wy)


def _push_from(bx: float, by: float, dx: float, dy: float, dist: float) -> tuple[float, float]:
    """The point `dist` from (bx, by) along (dx, dy); along +x if that is zero."""
    r = math.sqrt(dx * dx + dy * dy)
    if r == 0.0:
        return bx + dist, by
    return bx + dx * (dist / r), by + dy * (dist / r)
