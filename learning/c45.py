"""C4.5's error-based pruning (Quinlan 1993, ch. 4; release 8 prune.c and stats.c).

The pass-evaluation tree of layer 2 (paper §6) is grown by scikit-learn and then pruned here as
C4.5 release 8 prunes: first release 8's charge for choosing a threshold stops splits that gain
nothing once charged (:func:`release8_stop`), then subtrees are replaced by leaves bottom-up
wherever the leaf's pessimistic errors (:func:`pessimistic_errors`) are at most the subtree's
(:func:`prune_subtrees`). The functions work on scikit-learn's node arrays, before the tree is
copied into a :class:`~learning.pass_tree.PassTree` (:mod:`learning.pass_tree_grow`).
"""

from __future__ import annotations

import itertools
import math
from typing import Any

import numpy as np
import numpy.typing as npt

# C4.5 release 8, stats.c: the normal deviate for a confidence factor CF is interpolated linearly
# in this table (Val[], Dev[]), not computed exactly; at CF = 0.25 it gives 0.6925, not 0.6745.
_CF_TABLE: tuple[tuple[float, float], ...] = (
    (0.0, 4.0),
    (0.001, 3.09),
    (0.005, 2.58),
    (0.01, 2.33),
    (0.05, 1.65),
    (0.10, 1.28),
    (0.20, 0.84),
    (0.40, 0.25),
    (1.00, 0.0),
)

_MERGE_SLACK = 0.1
"""C4.5 prune.c prunes when leaf errors <= subtree errors + 0.1 (a small bias to simpler trees)."""


def pessimistic_errors(cases: float, errors: float, confidence: float = 0.25) -> float:
    """C4.5's predicted errors ``N·U_CF(E, N)`` of a leaf with `cases` N and `errors` E.

    ``U_CF`` is the upper limit of the binomial confidence interval at level CF of the error
    rate E/N (Quinlan 1993, ch. 4). This is ``E + AddErrs(N, E)`` of C4.5 release 8's stats.c,
    formula for formula: for E = 0 the exact ``N·(1 - CF^(1/N))``; for 0 < E < 1 a linear
    interpolation between E = 0 and E = 1; for E + 0.5 >= N the extra errors ``0.67·(N - E)``;
    otherwise the normal approximation (with continuity correction 0.5) with the deviate taken
    from C4.5's table.

    Args:
        cases: N, the (possibly fractional) training cases reaching the leaf.
        errors: E, those not of the leaf's class (0 <= E <= N).
        confidence: CF, C4.5's ``-c`` option as a fraction (0.25 is ``-c 25``), in (0, 1).

    Returns:
        The predicted number of errors (0 for N <= 0).

    >>> round(pessimistic_errors(6, 0) / 6, 3), round(pessimistic_errors(16, 1) / 16, 3)
    (0.206, 0.157)
    """
    check_confidence(confidence)
    if cases <= 0.0:
        return 0.0
    return errors + _add_errors(cases, errors, confidence)


def upper_error_rate(cases: float, errors: float, confidence: float = 0.25) -> float:
    """``U_CF(E, N)``: the pessimistic error rate of a leaf, :func:`pessimistic_errors` over N.

    >>> round(upper_error_rate(9, 0), 3)
    0.143
    """
    if cases <= 0.0:
        return 0.0
    return pessimistic_errors(cases, errors, confidence) / cases


def _add_errors(n: float, e: float, cf: float) -> float:
    # C4.5 release 8 stats.c AddErrs(N, e): the extra errors above the observed e.
    if e < 1e-6:
        return n * (1.0 - math.exp(math.log(cf) / n))
    if e < 0.9999:
        base = n * (1.0 - math.exp(math.log(cf) / n))
        return base + e * (_add_errors(n, 1.0, cf) - base)
    if e + 0.5 >= n:
        return 0.67 * (n - e)
    coeff = _coefficient(cf)
    pr = (
        e + 0.5 + coeff / 2.0 + math.sqrt(coeff * ((e + 0.5) * (1.0 - (e + 0.5) / n) + coeff / 4.0))
    ) / (n + coeff)
    return n * pr - e


def _coefficient(cf: float) -> float:
    for (v0, d0), (v1, d1) in itertools.pairwise(_CF_TABLE):
        if cf <= v1:
            deviate = d0 + (d1 - d0) * (cf - v0) / (v1 - v0)
            return deviate * deviate
    raise ValueError(f"confidence {cf!r} is not in (0, 1)")  # unreachable after the check


def check_confidence(confidence: float) -> None:
    """Refuse a confidence factor CF outside (0, 1) with a one-line ValueError."""
    if not 0.0 < confidence < 1.0:
        raise ValueError(f"confidence factor must be in (0, 1), got {confidence!r}")


# ----------------------------------------------------------------------------- pruning a grown tree


def _entropy(labels: npt.NDArray[np.intp]) -> float:
    """Entropy [bits] of some labels."""
    if labels.shape[0] == 0:
        return 0.0
    # Classes absent from the labels add nothing: their zero shares are dropped below.
    p = np.bincount(labels) / labels.shape[0]
    p = p[p > 0.0]
    return float(-(p * np.log2(p)).sum())


def release8_stop(
    model: Any,
    rows: npt.NDArray[np.float64],
    labels: npt.NDArray[np.intp],
    left: npt.NDArray[np.intp],
    right: npt.NDArray[np.intp],
    is_leaf: npt.NDArray[np.bool_],
) -> npt.NDArray[np.bool_]:
    """Leaves where C4.5 release 8 would not have split: no positive corrected gain.

    Release 8 charges a test on a continuous attribute for choosing its threshold: the gain
    (on the cases whose value is known, times their share) loses log2(N - 1) / |D|, with N the
    attribute's distinct known values at the node and |D| the node's cases (Quinlan 1996,
    "Improved use of continuous attributes in C4.5"). A node whose test then gains nothing
    stays a leaf, and so does everything below it. Without this charge, scikit-learn splits
    small noisy nodes that release 8 leaves alone (the paper's 87-node tree came from it).
    """
    feature = model.tree_.feature
    threshold = model.tree_.threshold
    reach = model.decision_path(rows.astype(np.float32)).tocsc()
    out = is_leaf.copy()
    stack = [0]
    while stack:
        node = stack.pop()
        if out[node]:
            continue
        at = reach.indices[reach.indptr[node] : reach.indptr[node + 1]]
        column = rows[at, int(feature[node])].astype(np.float32)
        known = ~np.isnan(column)
        n, n_known = at.shape[0], int(known.sum())
        cut = float(threshold[node])
        if math.isinf(cut):  # sklearn's "known vs unknown" test: no threshold to charge for
            groups = [labels[at][known], labels[at][~known]]
            gain = _entropy(labels[at]) - sum(g.shape[0] / n * _entropy(g) for g in groups)
        elif n_known < 2:
            gain = 0.0
        else:
            values, y = column[known], labels[at][known]
            low = values <= cut
            split = _entropy(y) - sum(g.shape[0] / n_known * _entropy(g) for g in (y[low], y[~low]))
            distinct = np.unique(values).shape[0]
            gain = n_known / n * split - math.log2(max(distinct - 1, 1)) / n
        if gain <= 0.0:
            out[node] = True
        else:
            stack.extend((int(left[node]), int(right[node])))
    return out


def prune_subtrees(
    left: npt.NDArray[np.intp],
    right: npt.NDArray[np.intp],
    counts: npt.NDArray[np.float64],
    confidence: float,
    is_leaf: npt.NDArray[np.bool_] | None = None,
) -> npt.NDArray[np.bool_]:
    """Which nodes are leaves after C4.5's bottom-up replacement of subtrees by leaves."""
    n = left.shape[0]
    is_leaf = (left < 0) if is_leaf is None else is_leaf.copy()
    estimate = np.zeros(n, dtype=np.float64)
    totals = counts.sum(axis=1)
    as_leaf = [
        pessimistic_errors(float(totals[i]), float(totals[i] - counts[i].max()), confidence)
        for i in range(n)
    ]
    # Post-order without recursion (unpruned trees of noisy data can be deep).
    stack: list[tuple[int, bool]] = [(0, False)]
    while stack:
        node, children_done = stack.pop()
        if is_leaf[node]:
            estimate[node] = as_leaf[node]
        elif not children_done:
            stack.extend(((node, True), (int(left[node]), False), (int(right[node]), False)))
        else:
            subtree = estimate[left[node]] + estimate[right[node]]
            if as_leaf[node] <= subtree + _MERGE_SLACK:
                is_leaf[node] = True
                estimate[node] = as_leaf[node]
            else:
                estimate[node] = subtree
    return is_leaf
