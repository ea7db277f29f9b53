"""Growing the pass-evaluation tree (paper §6): scikit-learn grows, C4.5 prunes, arrays keep it.

:func:`fit_pass_tree` grows a tree with scikit-learn on the NaN-containing rows (no imputation),
prunes it with C4.5's own rules (:mod:`learning.c45`) and copies the kept nodes into a
:class:`~learning.pass_tree.PassTree`. The module docstring of :mod:`learning.pass_tree` lists
everything that differs from C4.5.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

from learning.c45 import check_confidence, prune_subtrees, release8_stop
from learning.pass_tree import LABELS, PassTree, Setting, label_indices


def fit_pass_tree(
    x: npt.ArrayLike,
    y: Sequence[str] | npt.ArrayLike,
    feature_names: Sequence[str],
    *,
    schema: str,
    seed: int = 0,
    confidence: float = 0.25,
    min_cases: int = 2,
    prune: bool = True,
) -> PassTree:
    """Grow a tree with scikit-learn, prune it as C4.5 does, and copy it into a :class:`PassTree`.

    Growing: ``DecisionTreeClassifier(criterion="entropy", min_samples_leaf=min_cases)`` on the
    rows as they are, NaN included (scikit-learn's native handling of missing values; nothing is
    imputed). Pruning: C4.5's error-based pruning (Quinlan 1993, ch. 4; release 8 prune.c),
    bottom-up: a subtree becomes a leaf when the leaf's
    :func:`~learning.c45.pessimistic_errors` are at most
    the summed predicted errors of the subtree's leaves + 0.1. Subtree raising is omitted. See
    :mod:`learning.pass_tree` for everything that differs from C4.5.

    Args:
        x: Rows (n, n_features) of attributes; NaN is *unknown*, ±inf is refused.
        y: The n labels: strings from :data:`LABELS`, or an integer array of indices into it.
        feature_names: One name per column.
        schema: The attribute schema id stored in the tree (e.g. ``"pass-attributes/1"``).
        seed: scikit-learn's random_state (it only breaks ties between equally good tests).
        confidence: C4.5's pruning confidence factor CF (0.25, its default ``-c 25``).
        min_cases: Least training cases in each branch of a test (C4.5's ``-m``, default 2).
        prune: False keeps the tree as scikit-learn grew it (for checks against it).

    Returns:
        The tree; :attr:`PassTree.settings` records the arguments, the number of training rows
        and the node count before pruning.

    Raises:
        ValueError: Mismatched or malformed rows, labels or names, or bad settings.
    """
    # Imported here: evaluating a saved tree (the passer's decision) needs no scikit-learn.
    from sklearn.tree import DecisionTreeClassifier

    check_confidence(confidence)
    if isinstance(min_cases, bool) or not isinstance(min_cases, int) or min_cases < 1:
        raise ValueError(f"min_cases must be an int >= 1, got {min_cases!r}")
    rows = np.array(x, dtype=np.float64)
    names = tuple(feature_names)
    if rows.ndim != 2 or rows.shape[0] == 0 or rows.shape[1] != len(names):
        raise ValueError(f"need rows (n >= 1, {len(names)}) matching the names, got {rows.shape}")
    if np.isinf(rows).any():
        raise ValueError("rows hold infinite values (unknowns must be NaN)")
    labels = label_indices(y)
    if labels.shape[0] != rows.shape[0]:
        raise ValueError(f"{rows.shape[0]} rows but {labels.shape[0]} labels")

    model = DecisionTreeClassifier(
        criterion="entropy", splitter="best", min_samples_leaf=min_cases, random_state=seed
    ).fit(rows, labels)
    sk = model.tree_
    # scikit-learn >= 1.4 stores class *fractions* in value; times the node's weight = counts.
    counts = np.zeros((sk.node_count, len(LABELS)), dtype=np.float64)
    counts[:, model.classes_] = sk.value[:, 0, :] * sk.weighted_n_node_samples[:, None]
    counts = np.rint(counts)  # unit weights: whole cases, minus float noise of the fractions
    left = np.asarray(sk.children_left, dtype=np.intp)
    right = np.asarray(sk.children_right, dtype=np.intp)
    is_leaf = left < 0
    if prune:
        is_leaf = release8_stop(model, rows, labels, left, right, is_leaf)
        is_leaf = prune_subtrees(left, right, counts, confidence, is_leaf)
    rows32 = rows.astype(np.float32)
    grown = _Grown(
        left=left,
        right=right,
        is_leaf=is_leaf,
        feature=np.asarray(sk.feature),
        threshold=np.asarray(sk.threshold, dtype=np.float64),
        missing_left=np.asarray(sk.missing_go_to_left).astype(bool),
        counts=counts,
    )
    tree = _compact(
        grown,
        names=names,
        schema=schema,
        rows32=rows32,
        settings={
            "grower": "sklearn.DecisionTreeClassifier(criterion=entropy)",
            "confidence": float(confidence),
            "min_cases": min_cases,
            "seed": int(seed),
            "pruned": bool(prune),
            "n_train": int(rows.shape[0]),
            "n_nodes_unpruned": int(sk.node_count),
        },
    )
    return tree


@dataclass(frozen=True)
class _Grown:
    """scikit-learn's node arrays after pruning: which nodes are leaves, and what each holds."""

    left: npt.NDArray[np.intp]
    right: npt.NDArray[np.intp]
    is_leaf: npt.NDArray[np.bool_]
    feature: npt.NDArray[Any]
    threshold: npt.NDArray[np.float64]
    missing_left: npt.NDArray[np.bool_]
    counts: npt.NDArray[np.float64]


def _compact(
    grown: _Grown,
    *,
    names: tuple[str, ...],
    schema: str,
    rows32: npt.NDArray[np.float32],
    settings: Mapping[str, Setting],
) -> PassTree:
    """Renumber the kept nodes in preorder and build the arrays (children after parents)."""
    left, right, is_leaf = grown.left, grown.right, grown.is_leaf
    feature, threshold, missing_left = grown.feature, grown.threshold, grown.missing_left
    counts = grown.counts
    order: list[int] = []
    stack = [0]
    while stack:
        node = stack.pop()
        order.append(node)
        if not is_leaf[node]:
            stack.extend((int(right[node]), int(left[node])))  # left popped first: preorder
    new_id = {old: new for new, old in enumerate(order)}
    kept = np.array(order, dtype=np.intp)
    internal = ~is_leaf[kept]
    new_left = np.full(len(order), -1, dtype=np.int32)
    new_right = np.full(len(order), -1, dtype=np.int32)
    for new, old in enumerate(order):
        if internal[new]:
            new_left[new], new_right[new] = new_id[int(left[old])], new_id[int(right[old])]
    cut = np.where(internal, threshold[kept], np.nan)
    shown = np.full(len(order), np.nan)
    sorted_columns: dict[int, npt.NDArray[np.float64]] = {}
    for node in np.flatnonzero(internal).tolist():
        f = int(feature[kept[node]])
        if math.isinf(cut[node]):
            shown[node] = cut[node]
            continue
        if f not in sorted_columns:
            column = rows32[:, f]
            sorted_columns[f] = np.sort(column[~np.isnan(column)]).astype(np.float64)
        values = sorted_columns[f]
        # C4.5 prints the largest training value below the cut (build.c, GreatestValueBelow).
        at = int(np.searchsorted(values, cut[node], side="right"))
        shown[node] = float(values[at - 1]) if at > 0 else cut[node]
    return PassTree(
        feature_names=names,
        schema=schema,
        feature=np.where(internal, feature[kept], -1).astype(np.int32),
        threshold=cut,
        left=new_left,
        right=new_right,
        missing_left=np.where(internal, missing_left[kept], False),
        counts=counts[kept],
        shown_threshold=shown,
        settings=settings,
    )
