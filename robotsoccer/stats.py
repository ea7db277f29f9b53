"""Proportions with honest intervals: every percentage we print carries its n and a 95% interval.

* :func:`wilson_interval` — the interval of one share;
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

    Args:
        successes: Count of the outcome.
        trials: Number of trials (0 gives the uninformative interval (0, 1)).
        z: Normal quantile; the default gives a 95% interval.

    Returns:
        (low, high) as fractions in [0, 1].

    >>> [round(v, 4) for v in wilson_interval(53, 100)]
    [0.4329, 0.6249]
    """
    if trials <= 0:
        return 0.0, 1.0
    p = successes / trials
    denom = 1.0 + z * z / trials
    centre = (p + z * z / (2 * trials)) / denom
    half = z * math.sqrt(p * (1 - p) / trials + z * z / (4 * trials * trials)) / denom
    return max(0.0, centre - half), min(1.0, centre + half)


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
