"""Collisions of many Soccer Server trials at once (spec §4), as numpy arrays.

The vectorised twin of :mod:`field_models.soccer_server.collisions`: the same operations in the
same order on arrays of shape (K, N+1) (trials × rows; row 0 the ball), so a trial of
:class:`~field_models.soccer_server.batch.BatchSoccerServer` collides exactly as the single
model does.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from field_models.soccer_server.cycle_rules import (
    COLLISION_PASSES,
    COLLISION_VELOCITY_FACTOR,
    EPS,
    SEPARATION_RETRIES,
)

Arrays = tuple[np.ndarray, np.ndarray]
"""Two (K, N+1) arrays: x and y, or vx and vy."""


@dataclass(frozen=True)
class PairTable:
    """Every pair of rows that may collide, in the server's order (ball–player, then players).

    Attributes:
        pairs: (a, b) rows with a < b.
        reach: Sum of the two radii of each pair [m].
        reach2: Its square.
    """

    pairs: list[tuple[int, int]]
    reach: list[float]
    reach2: list[float]

    @classmethod
    def of(cls, sizes: list[float]) -> PairTable:
        """The pairs of objects of radii `sizes` (row 0 the ball)."""
        n = len(sizes)
        pairs = [(0, b) for b in range(1, n)]
        pairs += [(a, b) for a in range(1, n) for b in range(a + 1, n)]
        reach = [sizes[a] + sizes[b] for a, b in pairs]
        reach2 = [(sizes[a] + sizes[b]) ** 2 for a, b in pairs]
        return cls(pairs, reach, reach2)


def _overlaps(xy: Arrays, a: int, b: int, reach2: float) -> np.ndarray:
    x, y = xy
    dx = x[:, b] - x[:, a]
    dy = y[:, b] - y[:, a]
    return np.asarray(dx * dx + dy * dy < reach2)


def collide(
    table: PairTable, xy: Arrays, vxy: Arrays, trials: np.ndarray, play_on: np.ndarray
) -> tuple[Arrays, Arrays]:
    """Resolve overlaps in the given trials, as the single model does (§4).

    Args:
        table: The pairs.
        xy: Positions (K, N+1) [m].
        vxy: Stored velocities (K, N+1) [m/cycle].
        trials: (K,) the trials that move this cycle.
        play_on: (K,) the trials in ``play_on`` (elsewhere the ball stays put).

    Returns:
        The new positions and velocities (the arrays given when nothing overlaps).
    """
    x, y = xy
    vx, vy = vxy
    k, n = x.shape
    if not any(
        (_overlaps((x, y), a, b, q) & trials).any()
        for (a, b), q in zip(table.pairs, table.reach2, strict=True)
    ):
        return xy, vxy
    collided = np.zeros((k, n), dtype=bool)
    for _ in range(COLLISION_PASSES):
        sx, sy = np.zeros((k, n)), np.zeros((k, n))
        count = np.zeros((k, n), dtype=int)
        for (a, b), reach, reach2 in zip(table.pairs, table.reach, table.reach2, strict=True):
            hit = _overlaps((x, y), a, b, reach2) & trials
            if not hit.any():
                continue
            collided[:, a] |= hit
            collided[:, b] |= hit
            (pax, pay), (pbx, pby) = _proposals((x, y), (a, b), reach, reach2, play_on)
            for col, px, py in ((a, pax, pay), (b, pbx, pby)):
                sx[:, col] = np.where(hit, sx[:, col] + px, sx[:, col])
                sy[:, col] = np.where(hit, sy[:, col] + py, sy[:, col])
                count[:, col] += hit
        moved = count > 0
        if not moved.any():
            break
        with np.errstate(divide="ignore", invalid="ignore"):
            x = np.where(moved, sx / count, x)
            y = np.where(moved, sy / count, y)
    vx = np.where(collided, vx * COLLISION_VELOCITY_FACTOR, vx)
    vy = np.where(collided, vy * COLLISION_VELOCITY_FACTOR, vy)
    return (x, y), (vx, vy)


def _proposals(
    xy: Arrays, pair: tuple[int, int], reach: float, reach2: float, play_on: np.ndarray
) -> tuple[Arrays, Arrays]:
    x, y = xy
    a, b = pair
    ax, ay, bx, by = x[:, a], y[:, a], x[:, b], y[:, b]
    sep_a, sep_b = _separate(ax, ay, bx, by, reach, reach2)
    if a != 0:
        return sep_a, sep_b
    push = _push_from(ax, ay, bx - ax, by - ay, reach + EPS)
    return (
        (np.where(play_on, sep_a[0], ax), np.where(play_on, sep_a[1], ay)),
        (np.where(play_on, sep_b[0], push[0]), np.where(play_on, sep_b[1], push[1])),
    )


def _separate(
    ax: np.ndarray, ay: np.ndarray, bx: np.ndarray, by: np.ndarray, reach: float, reach2: float
) -> tuple[tuple[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]]:
    """Vectorised ``collisions._separate``: same operations, same order."""
    mx, my = (ax + bx) / 2.0, (ay + by) / 2.0
    ux, uy, wx, wy = ax - mx, ay - my, bx - mx, by - my
    half = reach / 2.0 + EPS
    ru, rw = np.sqrt(ux * ux + uy * uy), np.sqrt(wx * wx + wy * wy)
    same = ((ax == bx) & (ay == by)) | ((ru < EPS) & (rw < EPS)) | (ru == 0.0) | (rw == 0.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        ux, uy = np.where(same, half, ux * (half / ru)), np.where(same, 0.0, uy * (half / ru))
        wx, wy = np.where(same, -half, wx * (half / rw)), np.where(same, 0.0, wy * (half / rw))
    done = np.zeros(ax.shape, dtype=bool)
    for _ in range(SEPARATION_RETRIES):
        dx, dy = (mx + wx) - (mx + ux), (my + wy) - (my + uy)
        done |= dx * dx + dy * dy >= reach2
        if done.all():
            break
        ux, uy = np.where(done, ux, ux * 1.0001), np.where(done, uy, uy * 1.0001)
        wx, wy = np.where(done, wx, wx * 1.0001), np.where(done, wy, wy * 1.0001)
    return (mx + ux, my + uy), (mx + wx, my + wy)


def _push_from(
    bx: np.ndarray, by: np.ndarray, dx: np.ndarray, dy: np.ndarray, dist: float
) -> tuple[np.ndarray, np.ndarray]:
    """Vectorised ``collisions._push_from``."""
    r = np.sqrt(dx * dx + dy * dy)
    with np.errstate(divide="ignore", invalid="ignore"):
        return (
            np.where(r == 0.0, bx + dist, bx + dx * (dist / r)),
            np.where(r == 0.0, by, by + dy * (dist / r)),
        )
