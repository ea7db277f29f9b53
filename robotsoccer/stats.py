"""Proportions with honest intervals: every percentage we print carries its n and a 95% interval.

* :func:`wilson_interval` — the interval of one share (:func:`wilson_intervals`: of many);
* :func:`reliability` — predicted probabilities against observed shares, bin by bin (a learned
  evaluator's calibration, e.g. the pass tree's success confidence).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import NamedTuple

import numpy as np
import numpy.typing as npt

Z_95 = 1.959963984540054
"""Two-sided 95% normal quantile."""


def wilson_interval(successes: int, trials: int, z: float = Z_95) -> tuple[float, float]:
    """Wilson score interval for a binomial proportion (good at small n and near 0 or 1).

    The interval always holds the observed share: it starts at exactly 0 when nothing
    succeeded and ends at exactly 1 when everything did (:func:`wilson_intervals`).

    Args:
        successes: Count of the outcome, 0 ≤ successes ≤ trials.
        trials: Number of trials (0 gives the uninformative interval (0, 1)).
        z: Normal quantile; the default gives a 95% interval.

    Returns:
        (low, high) as fractions in [0, 1].

    Raises:
        ValueError: `successes` is negative or above `trials`.

    >>> [round(v, 4) for v in wilson_interval(53, 100)]
    [0.4329, 0.6249]
    >>> wilson_interval(0, 3)[0], wilson_interval(10, 10)[1]
    (0.0, 1.0)
    """
    if trials <= 0:
        return 0.0, 1.0
    if not 0 <= successes <= trials:
        raise ValueError(f"{successes} successes in {trials} trials: need 0 <= successes <= trials")
    low, high = wilson_intervals(np.array([successes]), np.array([trials]), z)
    return float(low[0]), float(high[0])


def wilson_intervals(
    successes: npt.ArrayLike, trials: npt.ArrayLike, z: float = Z_95
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """:func:`wilson_interval` of many (successes, trials) pairs at once, elementwise.

    In exact arithmetic the Wilson interval holds the share k/n and touches 0 at k = 0 and 1 at
    k = n; in floating point ``centre - half`` comes out a few ulps above 0 (and ``centre +
    half`` below 1), which made error bars of -5e-15 that matplotlib refuses. So the bounds are
    pinned: at most the share below, at least the share above (exactly 0 and 1 at the ends).

    Args:
        successes: (m,) counts, each 0 ≤ k ≤ its n (not checked here).
        trials: (m,) trial counts; where n ≤ 0 the interval is (0, 1).
        z: Normal quantile.

    Returns:
        (low, high), each (m,) fractions in [0, 1].
    """
    k = np.asarray(successes, dtype=np.float64)
    n = np.asarray(trials, dtype=np.float64)
    empty = n <= 0
    n = np.where(empty, 1.0, n)  # any positive n: the result is replaced below
    p = k / n
    denom = 1.0 + z * z / n
    centre = (p + z * z / (2 * n)) / denom
    half = z * np.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / denom
    low = np.minimum(np.maximum(0.0, centre - half), p)
    high = np.maximum(np.minimum(1.0, centre + half), p)
    return np.where(empty, 0.0, low), np.where(empty, 1.0, high)


class ReliabilityBin(NamedTuple):
    """One confidence bin of :func:`reliability` (paper Table 2's columns)."""

    lo: float
    """Lower edge of the bin (included)."""
    hi: float
    """Upper edge (excluded, except for the last bin)."""
    n: int
    """Cases whose confidence falls in the bin."""
    mean_confidence: float
    """Their mean predicted confidence (NaN when n = 0)."""
    observed: float
    """Share of them that succeeded (NaN when n = 0)."""
    observed_low: float
    """Lower end of the Wilson 95% interval of the observed share (0 when n = 0)."""
    observed_high: float
    """Upper end of that interval (1 when n = 0)."""


def reliability(
    confidence: npt.ArrayLike,
    success: npt.ArrayLike,
    bins: Sequence[float] | npt.NDArray[np.float64],
) -> list[ReliabilityBin]:
    """Observed success share against predicted confidence, bin by bin (paper Table 2).

    Args:
        confidence: (n,) predicted probability of success of each pass.
        success: (n,) whether each pass succeeded (bool or 0/1).
        bins: Bin edges, strictly increasing; every confidence must lie within the outer edges.
            Bins are ``[lo, hi)``, the last one ``[lo, hi]``.

    Returns:
        One :class:`ReliabilityBin` per bin, with the Wilson 95% interval of the observed share.

    Raises:
        ValueError: Mismatched lengths, NaN confidences, non-0/1 outcomes, bad edges, or a
            confidence outside the bins.
    """
    conf = np.asarray(confidence, dtype=np.float64).reshape(-1)
    outcome = np.asarray(success).reshape(-1)
    edges = np.asarray(bins, dtype=np.float64)
    if conf.shape != outcome.shape:
        raise ValueError(f"{conf.shape[0]} confidences but {outcome.shape[0]} outcomes")
    if not np.isin(outcome, (0, 1)).all():
        raise ValueError("outcomes must be booleans or 0/1")
    if edges.ndim != 1 or edges.shape[0] < 2 or not np.isfinite(edges).all():
        raise ValueError("need at least two finite bin edges")
    if np.any(np.diff(edges) <= 0.0):
        raise ValueError("bin edges must be strictly increasing")
    if np.isnan(conf).any() or np.any(conf < edges[0]) or np.any(conf > edges[-1]):
        raise ValueError(f"confidences must lie in [{edges[0]}, {edges[-1]}] (and not be NaN)")
    which = np.clip(np.searchsorted(edges, conf, side="right") - 1, 0, edges.shape[0] - 2)
    won = outcome.astype(bool)
    result = []
    for b in range(edges.shape[0] - 1):
        mask = which == b
        n = int(mask.sum())
        successes = int(won[mask].sum())
        mean = float(conf[mask].mean()) if n else math.nan
        observed = successes / n if n else math.nan
        low, high = wilson_interval(successes, n)
        result.append(
            ReliabilityBin(float(edges[b]), float(edges[b + 1]), n, mean, observed, low, high)
        )
    return result
