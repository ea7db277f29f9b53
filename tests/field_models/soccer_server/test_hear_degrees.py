"""A hear's direction through the C library's atan2 equals the CPU-independent rule's degrees."""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
import pytest

from field_models import fpmath
from field_models.protocol import wrap_angle
from field_models.soccer_server import hearing
from field_models.soccer_server.hearing import hear_degrees
from field_models.soccer_server.see_numbers import degrees


def scalar_rule(dy: float, dx: float, heading: float, truncate: bool) -> int:
    """The specification: fdlibm's atan2 (field_models.fpmath), as hearing had it."""
    return degrees(wrap_angle(-(fpmath.atan2(dy, dx) - heading)), truncate)


def cases(count: int, seed: int) -> list[tuple[float, float, float]]:
    """Random offsets and headings, then directions on whole and half degrees, axes and ±π."""
    g = np.random.default_rng(seed)
    out = [
        (float(dy), float(dx), float(h))
        for dy, dx, h in zip(
            g.uniform(-60, 60, count),
            g.uniform(-60, 60, count),
            g.uniform(-math.pi, math.pi, count),
            strict=True,
        )
    ]
    for tenths in range(-1800, 1801, 5):  # every half degree of direction, heading 0
        a = math.radians(tenths / 10.0)
        out.append((7.0 * math.sin(a), 7.0 * math.cos(a), 0.0))
        out.append((3.0 * math.sin(a), 3.0 * math.cos(a), math.radians(30.0)))
    out += [(0.0, 5.0, 0.0), (-0.0, -5.0, 0.0), (0.0, -5.0, 0.0), (5.0, 0.0, 0.0), (1.0, 1.0, 0.0)]
    out += [(0.0, -2.0, math.pi - 1e-17), (1e-300, -2.0, 0.0), (-1e-300, -2.0, 0.0)]
    return out


@pytest.mark.parametrize("truncate", [True, False])
def test_the_fast_route_gives_the_scalar_rules_degrees(
    truncate: bool, monkeypatch: pytest.MonkeyPatch
) -> None:
    want = [scalar_rule(dy, dx, h, truncate) for dy, dx, h in cases(20000, int(truncate))]
    calls = []
    scalar = fpmath.atan2

    def counted(y: float, x: float) -> float:
        calls.append((y, x))
        return scalar(y, x)

    monkeypatch.setattr(fpmath, "atan2", counted)
    got = [hear_degrees(dy, dx, h, truncate) for dy, dx, h in cases(20000, int(truncate))]
    assert got == want
    assert 700 < len(calls) < 2000  # the boundaries took the scalar rule; the rest did not


def _mismatches(monkeypatch: pytest.MonkeyPatch, scale: float) -> int:
    g = np.random.default_rng(3)
    fast: Callable[[float, float], float] = math.atan2

    def perturbed(y: float, x: float) -> float:
        return fast(y, x) * (1.0 + scale * float(g.uniform(-1.0, 1.0)))

    monkeypatch.setattr(hearing, "_fast_atan2", perturbed)
    return sum(
        hear_degrees(dy, dx, h, t) != scalar_rule(dy, dx, h, t)
        for dy, dx, h in cases(3000, 5)
        for t in (True, False)
    )


def test_a_c_library_that_rounds_otherwise_changes_nothing(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """Within the margin another libm's last bits change nothing; far beyond it they show."""
    assert _mismatches(monkeypatch, 1e-13) == 0
    assert _mismatches(monkeypatch, 1e-4) > 0


def test_a_direction_that_is_not_a_number_is_refused_as_before() -> None:
    with pytest.raises(ValueError):
        scalar_rule(math.nan, 1.0, 0.0, True)
    with pytest.raises(ValueError):
        hear_degrees(math.nan, 1.0, 0.0, True)
