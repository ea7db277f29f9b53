"""The statistics every report uses: Wilson intervals and reliability tables."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

from robotsoccer.stats import reliability, wilson_interval, wilson_intervals


def test_wilson_interval_known_value() -> None:
    assert [round(v, 4) for v in wilson_interval(53, 100)] == [0.4329, 0.6249]
    assert wilson_interval(0, 0) == (0.0, 1.0)


def test_wilson_interval_ends_exactly_at_0_and_1() -> None:
    # In floating point the formula gave 5.6e-17 and 0.9999999999999999 here, so an error bar
    # came out at -5e-15 and matplotlib refused the plot (issue 30)
    assert wilson_interval(0, 3)[0] == 0.0
    assert wilson_interval(10, 10)[1] == 1.0
    with pytest.raises(ValueError, match="successes"):
        wilson_interval(4, 3)


def test_every_interval_up_to_2000_trials_holds_its_share() -> None:
    n, k = np.tril_indices(2001)  # every (k, n) with 0 <= k <= n <= 2000
    n, k = n[n > 0], k[n > 0]
    low, high = wilson_intervals(k, n)
    share = k / n
    assert np.all((low >= 0.0) & (low <= share) & (share <= high) & (high <= 1.0))
    assert np.all(low[k == 0] == 0.0) and np.all(high[k == n] == 1.0)
    assert np.all(low[k > 0] > 0.0) and np.all(high[k < n] < 1.0)
    assert np.all(share - low >= 0.0) and np.all(high - share >= 0.0)  # error bars
    for i in np.random.default_rng(0).integers(0, k.shape[0], 200):  # the scalar form agrees
        assert wilson_interval(int(k[i]), int(n[i])) == (low[i], high[i])


def test_reliability_of_a_calibrated_sample() -> None:
    rng = np.random.default_rng(5)
    confidence = rng.random(20_000)
    success = rng.random(20_000) < confidence
    edges = np.linspace(0.0, 1.0, 11)
    table = reliability(confidence, success, edges)
    assert len(table) == 10
    assert sum(b.n for b in table) == 20_000
    assert [(b.lo, b.hi) for b in table] == list(itertools.pairwise(edges))
    for b in table:
        assert b.lo <= b.mean_confidence < b.hi
        assert b.observed == pytest.approx(b.mean_confidence, abs=0.035)
        assert b.observed_low < b.observed < b.observed_high
        assert b.observed_high - b.observed_low < 0.06


def test_reliability_edges_and_empty_bins() -> None:
    table = reliability([0.65, 0.7, 0.9, 0.9], [1, 0, 1, 1], [0.6, 0.7, 0.8, 0.9])
    assert [b.n for b in table] == [1, 1, 2]  # [lo, hi) except the last bin, which holds 0.9
    assert [b.observed for b in table] == [1.0, 0.0, 1.0]
    empty = reliability([0.95], [True], [0.0, 0.5, 1.0])[0]
    assert empty.n == 0 and math.isnan(empty.observed) and math.isnan(empty.mean_confidence)
    assert (empty.observed_low, empty.observed_high) == (0.0, 1.0)
    with pytest.raises(ValueError, match="lie in"):
        reliability([0.95], [True], [0.0, 0.5])
    with pytest.raises(ValueError, match="increasing"):
        reliability([0.5], [True], [0.0, 1.0, 1.0])
    with pytest.raises(ValueError, match="outcomes"):
        reliability([0.5], [2], [0.0, 1.0])
