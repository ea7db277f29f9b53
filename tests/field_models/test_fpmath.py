"""field_models.fpmath: one value in float and array form, close to the C library's."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from field_models import fpmath


def bits(values: np.ndarray) -> np.ndarray:
    return np.asarray(values, dtype=np.float64).view(np.int64)


def ulps(ours: np.ndarray, reference: np.ndarray) -> np.ndarray:
    return np.abs(ours - reference) / np.spacing(np.abs(reference))


def arguments(n: int, seed: int) -> tuple[np.ndarray, np.ndarray]:
    rng = np.random.default_rng(seed)
    scale = rng.choice([1e-300, 1e-8, 1.0, 1e3, 1e300], n)
    y = rng.normal(size=n) * scale
    x = rng.normal(size=n) * rng.choice([1e-8, 1.0, 1e3], n)
    specials = [0.0, -0.0, math.inf, -math.inf, 1.0, -1.0, 5e-324]
    y[: len(specials) ** 2] = np.repeat(specials, len(specials))
    x[: len(specials) ** 2] = np.tile(specials, len(specials))
    return y, x


def test_atan2_gives_the_same_bits_as_floats_and_as_arrays() -> None:
    y, x = arguments(50_000, seed=1)
    scalar = [fpmath.atan2(a, b) for a, b in zip(y.tolist(), x.tolist(), strict=True)]
    assert np.array_equal(bits(fpmath.atan2_array(y, x)), bits(scalar))


def test_atan2_is_within_two_ulps_of_the_c_library() -> None:
    y, x = arguments(50_000, seed=2)
    ours = fpmath.atan2_array(y, x)
    reference = np.array([math.atan2(a, b) for a, b in zip(y.tolist(), x.tolist(), strict=True)])
    assert ulps(ours, reference).max() <= 2.0
    exact = [(0.0, 1.0), (1.0, 0.0), (-0.0, -1.0), (0.0, -1.0), (-1.0, 0.0)]
    assert [fpmath.atan2(a, b) for a, b in exact] == [math.atan2(a, b) for a, b in exact]
    assert math.copysign(1.0, fpmath.atan2(-0.0, 1.0)) == -1.0


def test_atan2_quadrants_and_octants() -> None:
    for degrees in range(-179, 181):
        angle = math.radians(degrees)
        ours = fpmath.atan2(math.sin(angle), math.cos(angle))
        assert ours == pytest.approx(angle, abs=1e-15)


def test_log_gives_the_same_bits_as_floats_and_as_arrays() -> None:
    rng = np.random.default_rng(3)
    x = np.exp(rng.uniform(-700.0, 700.0, 50_000))
    x[:6] = [1.0, 2.0, 0.5, 5e-324, 1.7e308, 1.0 + 2.0**-52]
    scalar = [fpmath.log(v) for v in x.tolist()]
    assert np.array_equal(bits(fpmath.log_array(x)), bits(scalar))


def test_log_is_within_one_ulp_of_the_c_library() -> None:
    rng = np.random.default_rng(4)
    x = rng.uniform(0.01, 150.0, 50_000)  # the see's distances
    reference = np.array([math.log(v) for v in x.tolist()])
    assert ulps(fpmath.log_array(x), reference).max() <= 1.0
    assert fpmath.log(1.0) == 0.0
    assert fpmath.log(math.e) == pytest.approx(1.0, abs=2.3e-16)


def test_log_refuses_what_the_c_library_refuses() -> None:
    with pytest.raises(ValueError):
        fpmath.log(0.0)
    with pytest.raises(ValueError):
        fpmath.log(-1.0)
    assert fpmath.log(math.inf) == math.inf
    with pytest.raises(ValueError, match="positive and finite"):
        fpmath.log_array(np.array([1.0, 0.0]))


@settings(max_examples=300, deadline=None)
@given(
    st.floats(allow_nan=False, allow_infinity=True),
    st.floats(allow_nan=False, allow_infinity=True),
)
def test_atan2_forms_agree_on_any_pair(y: float, x: float) -> None:
    array = fpmath.atan2_array(np.array([y, 0.5]), np.array([x, -0.25]))[0]
    assert bits(np.array([array])) == bits(np.array([fpmath.atan2(y, x)]))


@settings(max_examples=300, deadline=None)
@given(st.floats(min_value=5e-324, max_value=1.7e308))
def test_log_forms_agree_on_any_positive_value(x: float) -> None:
    assert bits(fpmath.log_array(np.array([x]))) == bits(np.array([fpmath.log(x)]))
