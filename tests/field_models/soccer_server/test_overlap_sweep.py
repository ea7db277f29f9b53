"""The sort-and-sweep overlap check gives any_overlap's answer on every state."""

from __future__ import annotations

import math

import numpy as np
import pytest

from field_models.soccer_server.collisions import (
    any_overlap,
    any_overlap_swept,
    collision_pairs,
    sweep_of,
)

SIZES = {
    "server": [0.085] + [0.3] * 11,
    "mixed": [0.085, 0.3, 0.5, 0.2, 1.0, 0.3, 0.05],
    "two": [0.1, 0.3],
}


def states(g: np.random.Generator, n: int, count: int) -> list[tuple[list[float], list[float]]]:
    """Spread, crowded, coincident and touching states of `n` objects."""
    out = []
    for case in range(count):
        spread = (52.5, 34.0) if case % 3 == 0 else (1.5, 1.5)
        x = g.uniform(-spread[0], spread[0], n).tolist()
        y = g.uniform(-spread[1], spread[1], n).tolist()
        if case % 4 == 1:  # two objects on one spot, one exactly at a sum of radii along x
            x[n - 1], y[n - 1] = x[0], y[0]
        out.append((x, y))
    return out


@pytest.mark.parametrize("kind", sorted(SIZES))
def test_the_sweep_answers_as_every_pair_does(kind: str) -> None:
    sizes = SIZES[kind]
    pairs, sweep = collision_pairs(sizes), sweep_of(tuple(sizes))
    g = np.random.default_rng(len(sizes))
    answers = []
    for x, y in states(g, len(sizes), 3000):
        want = any_overlap(pairs, x, y)
        assert any_overlap_swept(sweep, x, y) == want, (x, y)
        answers.append(want)
    assert any(answers) and not all(answers)  # both answers were exercised
    assert sweep.pairs == tuple(pairs) and sweep_of(tuple(sizes)) is sweep  # shared


def test_pairs_exactly_at_their_reach_and_just_inside() -> None:
    sizes = SIZES["server"]
    pairs, sweep = collision_pairs(sizes), sweep_of(tuple(sizes))
    x = [30.0 * i for i in range(len(sizes))]
    y = [0.0] * len(sizes)
    for reach in (0.6, math.nextafter(0.6, 0.0), 0.385, math.nextafter(0.385, 0.0)):
        for a, b in ((1, 2), (0, 1)):
            xs = list(x)
            xs[b] = xs[a] + reach
            assert any_overlap_swept(sweep, xs, y) == any_overlap(pairs, xs, y)
            ys = list(y)  # the same along y: the x gap is 0 there
            xs[b], ys[b] = xs[a], y[a] + reach
            assert any_overlap_swept(sweep, xs, ys) == any_overlap(pairs, xs, ys)


def test_positions_that_are_not_numbers_fall_back_to_every_pair() -> None:
    sizes = SIZES["server"]
    pairs, sweep = collision_pairs(sizes), sweep_of(tuple(sizes))
    x = [float(i) for i in range(len(sizes))]
    y = [0.0] * len(sizes)
    x[3] = math.nan
    x[7], x[8] = 20.0, 20.1  # an overlap that a NaN-scrambled sort could hide
    assert any_overlap(pairs, x, y) and any_overlap_swept(sweep, x, y)
    x[8] = 25.0
    assert any_overlap_swept(sweep, x, y) == any_overlap(pairs, x, y)
