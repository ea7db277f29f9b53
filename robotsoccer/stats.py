"""Proportions with honest intervals: every percentage we print carries its n and a 95% interval."""

from __future__ import annotations

import math

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
    [0.4328, 0.6248]
    """
    if trials <= 0:
        return 0.0, 1.0
    p = successes / trials
    denom = 1.0 + z * z / trials
    centre = (p + z * z / (2 * trials)) / denom
    half = z * math.sqrt(p * (1 - p) / trials + z * z / (4 * trials * trials)) / denom
    return max(0.0, centre - half), min(1.0, centre + half)

