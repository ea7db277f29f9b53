"""The pass-evaluation decision tree of layer 2 (paper §6, Figure 14): C4.5 as closely as we can.

The paper trains "standard off-the-shelf C4.5 code with all of the default parameters" (release 8:
``-m 2``, ``-c 25``) to predict whether a pass to a receiver ends in SUCCESS, FAILURE or MISS from
174 continuous attributes, players out of sight giving *unknown* values (NaN here). Its pruned tree
had 87 nodes and 26% training error; the passer used the tree's confidence to pick a receiver
(Table 2).

The tree is a :class:`PassTree` (this module): plain arrays, evaluated by a short loop over nodes
with no scikit-learn call. Its other jobs sit beside it:

* growing: :func:`learning.pass_tree_grow.fit_pass_tree` grows a tree with scikit-learn on the
  NaN-containing rows (no imputation) and copies it into a :class:`PassTree`;
* pruning: :mod:`learning.c45`, C4.5's own error-based pruning
  (:func:`~learning.c45.pessimistic_errors`) and release 8's charge for thresholds;
* printing: :mod:`learning.pass_tree_text`, Figure 14's layout (:meth:`PassTree.render`);
* the file format: :mod:`learning.pass_tree_file`, JSON, never pickled, refused with
  :class:`~learning.features.ModelFileError` naming the file when corrupt, for another format
  version or for another attribute schema.

What differs from C4.5:

* **Split criterion.** scikit-learn chooses splits by entropy *gain*; C4.5 by gain *ratio* (gain
  over split information) among tests of at least average gain. For two-way splits on continuous
  attributes the two usually agree on the best test, but not always.
* **Tests.** Both make binary tests ``attribute <= t`` on continuous attributes (all 174 here are).
  scikit-learn puts ``t`` midway between neighbouring training values, C4.5 at the largest
  training value below the cut. Prediction here uses the midpoint, as scikit-learn learned it;
  :meth:`PassTree.render` shows C4.5's value (:attr:`PassTree.shown_threshold`), the largest
  training value not above the midpoint, so a printed test reads like Figure 14's (``<= 0`` for a
  count cut at 0.5) and selects the same training cases.
* **Unknown values.** C4.5 sends a case with an unknown value down *every* branch with fractional
  weights (hence Figure 14's fractional leaf counts such as ``1054.6/290.5``) and blends the
  leaves' class distributions when classifying. scikit-learn sends all unknown cases down *one*
  branch, learned at fit time (:attr:`PassTree.missing_left`), so our counts are whole cases and a
  row always reaches exactly one leaf. scikit-learn may also split on "known versus unknown"
  (threshold +inf: known values go left, unknown right), a test C4.5 cannot make.
* **Release 8's charge for thresholds.** C4.5 release 8 takes log2(N - 1) / |D| off the gain of a
  test on a continuous attribute (N distinct values, |D| cases at the node) and does not split a
  node whose tests then gain nothing. scikit-learn has no such charge; ``fit_pass_tree``
  applies it after growing, top-down, turning such nodes into leaves before the error-based
  pruning (:func:`~learning.c45.release8_stop`). The charge is computed for the test
  scikit-learn chose, not for every candidate test as C4.5 does.
* **Confidence.** C4.5 reports a leaf's raw class shares; the passer ranks receivers by
  :meth:`PassTree.success_confidence`, the Laplace-corrected share, because our leaves are smaller
  than C4.5's (see there).
* **No subtree raising.** C4.5 may also replace a node by its largest branch; only the replacement
  of subtrees by leaves is done here.
* **Minimum cases.** ``min_cases`` becomes ``min_samples_leaf``: *both* branches of a test need
  that many cases; C4.5's ``-m 2`` asks for at least two branches with two or more cases each,
  which for binary tests is the same except that C4.5 counts fractional cases.
* **Precision.** scikit-learn grows the tree on float32 copies of the rows; :class:`PassTree`
  casts its inputs to float32 the same way, so a row goes where scikit-learn would send it.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np
import numpy.typing as npt

from learning.pass_tree_text import render_tree

LABELS: tuple[str, ...] = ("SUCCESS", "FAILURE", "MISS")
"""The pass outcomes (paper §6), in the column order of every probability and count array."""

Setting = str | int | float | bool
"""Value types of :attr:`PassTree.settings` (JSON scalars)."""


@dataclass(frozen=True, eq=False)
class PassTree:
    """A fitted, pruned tree as plain arrays (no sklearn object needed to evaluate it).

    Nodes are numbered in preorder from the root, node 0. A row goes left at an internal node
    when its value is ``<= threshold`` and right when above; a NaN (*unknown*) goes where
    :attr:`missing_left` says. A threshold of +inf is a "known versus unknown" test. Inputs are
    cast to float32 first, as scikit-learn grew the tree on float32 values.

    Attributes:
        feature_names: Attribute names, one per input column.
        schema: The attribute schema id (e.g. ``"pass-attributes/1"``), stored and checked.
        feature: int32 (n_nodes,): the column tested at each node, -1 at leaves.
        threshold: float64 (n_nodes,): the cut at each internal node, NaN at leaves.
        left: int32 (n_nodes,): the child for ``x <= threshold``, -1 at leaves.
        right: int32 (n_nodes,): the child for ``x > threshold``, -1 at leaves.
        missing_left: bool (n_nodes,): whether a NaN goes left at this node (False at leaves).
        counts: float64 (n_nodes, 3): training cases of each label (:data:`LABELS` order)
            reaching each node.
        shown_threshold: float64 (n_nodes,): the cut as C4.5 prints it, the largest training
            value not above :attr:`threshold` (+inf for known/unknown tests, NaN at leaves).
            Display only; see the module docstring.
        settings: How the tree was grown (confidence, min_cases, seed, ...), JSON scalars.

    Raises:
        ValueError: The arrays do not describe one tree rooted at node 0 (lengths, index
            ranges, leaves without cases, counts that do not add up, ...).
    """

    feature_names: tuple[str, ...]
    schema: str
    feature: npt.NDArray[np.int32]
    threshold: npt.NDArray[np.float64]
    left: npt.NDArray[np.int32]
    right: npt.NDArray[np.int32]
    missing_left: npt.NDArray[np.bool_]
    counts: npt.NDArray[np.float64]
    shown_threshold: npt.NDArray[np.float64]
    settings: Mapping[str, Setting] = field(default_factory=dict)

    def __post_init__(self) -> None:
        set_ = object.__setattr__  # frozen: normalise once, here
        set_(self, "feature_names", tuple(self.feature_names))
        set_(self, "settings", dict(self.settings))
        for name, dtype in (
            ("feature", np.int32),
            ("threshold", np.float64),
            ("left", np.int32),
            ("right", np.int32),
            ("missing_left", np.bool_),
            ("counts", np.float64),
            ("shown_threshold", np.float64),
        ):
            array = np.array(getattr(self, name), dtype=dtype)
            array.flags.writeable = False
            set_(self, name, array)
        _check_structure(self)

    def __repr__(self) -> str:
        return (
            f"PassTree({self.n_nodes} nodes, {self.n_leaves} leaves, "
            f"{len(self.feature_names)} features, schema={self.schema!r})"
        )

    @property
    def n_nodes(self) -> int:
        """Number of nodes, leaves included (the paper's tree had 87)."""
        return int(self.feature.shape[0])

    @property
    def n_leaves(self) -> int:
        """Number of leaves."""
        return int(np.count_nonzero(self.feature < 0))

    @cached_property
    def node_proba(self) -> npt.NDArray[np.float64]:
        """(n_nodes, 3): each node's class shares, the leaf's confidence in each label.

        C4.5 release 8 (classify.c) reports a leaf's ``ClassDist[c] / Items``: these shares.
        """
        totals = self.counts.sum(axis=1, keepdims=True)
        shares: npt.NDArray[np.float64] = self.counts / np.where(totals > 0.0, totals, 1.0)
        shares.flags.writeable = False
        return shares

    @cached_property
    def _walk(self) -> tuple[list[int], list[float], list[int], list[int], list[bool]]:
        # Plain lists: indexing them in the per-row loop is several times faster than numpy.
        return (
            self.feature.tolist(),
            self.threshold.tolist(),
            self.left.tolist(),
            self.right.tolist(),
            self.missing_left.tolist(),
        )

    def leaf_index(self, x: npt.ArrayLike) -> int | npt.NDArray[np.intp]:
        """The leaf reached: an int for one row (n_features,), an array for rows (n, n_features).

        Raises:
            ValueError: The rows do not have one value per feature.
        """
        rows = self._rows(x)
        if rows.ndim == 1:
            return self._leaf_of_row(rows.tolist())
        return self._leaves_of_rows(rows)

    def success_confidence(self, x: npt.ArrayLike) -> float:
        """The Laplace-corrected share of SUCCESS at the leaf one row reaches: (s + 1) / (n + 3).

        C4.5 reports a leaf's raw class shares; its pruned leaves are large and impure (Figure
        14: 704 cases, 140 errors). scikit-learn's grower leaves small pure leaves that C4.5's
        pruning keeps, whose raw share of 1.0 says nothing. The Laplace correction ranks them by
        their evidence (Provost & Domingos 2003, "Tree induction for probability-based ranking").
        """
        leaf = int(self.leaf_index(x))
        cases = self.counts[leaf]
        return float((cases[0] + 1.0) / (cases.sum() + len(LABELS)))

    def predict_proba(self, x: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """Class shares of the leaf each row reaches, in :data:`LABELS` order.

        Args:
            x: One row (n_features,) or rows (n, n_features); NaN is *unknown*.

        Returns:
            (3,) for one row, (n, 3) for rows.
        """
        rows = self._rows(x)
        if rows.ndim == 1:
            return self.node_proba[self._leaf_of_row(rows.tolist())].copy()
        return self.node_proba[self._leaves_of_rows(rows)]

    def predict(self, x: npt.ArrayLike) -> npt.NDArray[np.intp]:
        """Index into :data:`LABELS` of the most frequent label at each row's leaf.

        Ties go to the label earlier in :data:`LABELS`. Returns a 0-d array for one row.
        """
        return np.asarray(np.argmax(self.predict_proba(x), axis=-1), dtype=np.intp)

    def training_error(self, x: npt.ArrayLike, y: Sequence[str] | npt.ArrayLike) -> float:
        """Share of rows whose :meth:`predict` is not their label (the paper reports 26%).

        Args:
            x: Rows (n, n_features).
            y: Labels: strings from :data:`LABELS` or indices into it.
        """
        rows = self._rows(x)
        if rows.ndim != 2:
            raise ValueError(f"need rows (n, {len(self.feature_names)}), got {rows.shape}")
        labels = label_indices(y)
        if labels.shape[0] != rows.shape[0] or rows.shape[0] == 0:
            raise ValueError(f"{rows.shape[0]} rows but {labels.shape[0]} labels")
        return float(np.mean(self.predict(rows) != labels))

    def render(self, max_depth: int | None = None) -> str:
        """The tree as text, in the style of C4.5's output (paper Figure 14).

        See :func:`learning.pass_tree_text.render_tree`, which prints it.

        Args:
            max_depth: Show this many levels of tests; deeper subtrees print as ``...``.
        """
        return render_tree(self, LABELS, max_depth)

    def _rows(self, x: npt.ArrayLike) -> npt.NDArray[np.float32]:
        rows = np.asarray(x, dtype=np.float32)
        n_features = len(self.feature_names)
        if rows.ndim not in (1, 2) or rows.shape[-1] != n_features:
            raise ValueError(
                f"need (n_features,) or (n, n_features), n_features={n_features}; got {rows.shape}"
            )
        return rows

    def _leaf_of_row(self, row: list[float]) -> int:
        feature, threshold, left, right, missing_left = self._walk
        node = 0
        f = feature[0]
        while f >= 0:
            v = row[f]
            if v != v:  # NaN: the side scikit-learn learned for unknowns at this node
                node = left[node] if missing_left[node] else right[node]
            else:
                node = left[node] if v <= threshold[node] else right[node]
            f = feature[node]
        return node

    def _leaves_of_rows(self, rows: npt.NDArray[np.float32]) -> npt.NDArray[np.intp]:
        # Level by level: every row still at an internal node takes one step per pass.
        node = np.zeros(rows.shape[0], dtype=np.intp)
        active = np.flatnonzero(self.feature[node] >= 0)
        while active.size:
            at = node[active]
            values = rows[active, self.feature[at]].astype(np.float64)
            go_left = np.where(
                np.isnan(values), self.missing_left[at], values <= self.threshold[at]
            )
            node[active] = np.where(go_left, self.left[at], self.right[at])
            active = active[self.feature[node[active]] >= 0]
        return node


def _check_structure(tree: PassTree) -> None:
    names, n_features = tree.feature_names, len(tree.feature_names)
    if n_features == 0 or not all(isinstance(n, str) and n for n in names):
        raise ValueError("feature_names must be non-empty strings, at least one")
    if len(set(names)) != n_features:
        raise ValueError("feature_names must be unique")
    if not isinstance(tree.schema, str) or not tree.schema:
        raise ValueError("schema must be a non-empty string")
    n = tree.feature.shape[0] if tree.feature.ndim == 1 else -1
    if n < 1:
        raise ValueError(f"feature must be a non-empty 1-D array, got shape {tree.feature.shape}")
    for name in ("threshold", "left", "right", "missing_left", "shown_threshold"):
        shape = getattr(tree, name).shape
        if shape != (n,):
            raise ValueError(f"{name} has shape {shape}, not ({n},) like feature")
    if tree.counts.shape != (n, len(LABELS)):
        raise ValueError(f"counts has shape {tree.counts.shape}, not ({n}, {len(LABELS)})")
    leaf = tree.feature < 0
    if np.any(tree.feature < -1) or np.any(tree.feature >= n_features):
        raise ValueError(f"a feature index is outside -1..{n_features - 1}")
    if np.any((tree.left < 0) != leaf) or np.any((tree.right < 0) != leaf):
        raise ValueError("leaves (feature -1) and nodes without children (-1) disagree")
    internal = np.flatnonzero(~leaf)
    for side in (tree.left, tree.right):
        child = side[internal]
        if np.any(child <= internal) or np.any(child >= n):
            raise ValueError(f"a child index is out of range (each must be in parent+1..{n - 1})")
    parents = np.bincount(np.concatenate([tree.left[internal], tree.right[internal]]), minlength=n)
    if parents[0] != 0 or np.any(parents[1:] != 1):
        raise ValueError("nodes do not form one tree rooted at node 0 (a node has 0 or 2 parents)")
    for name in ("threshold", "shown_threshold"):
        values = getattr(tree, name)
        if np.any(~np.isnan(values[leaf])) or np.any(np.isnan(values[~leaf])):
            raise ValueError(f"{name} must be NaN exactly at leaves")
        if np.any(np.isneginf(values)):
            raise ValueError(f"{name} holds -inf")
    if np.any(tree.missing_left[leaf]):
        raise ValueError("missing_left is set at a leaf")
    counts = tree.counts
    if not np.isfinite(counts).all() or np.any(counts < 0.0):
        raise ValueError("counts must be finite and >= 0")
    totals = counts.sum(axis=1)
    if np.any(totals[leaf] <= 0.0):
        raise ValueError("a leaf has no training cases")
    children_sum = counts[tree.left[internal]] + counts[tree.right[internal]]
    if not np.allclose(counts[internal], children_sum, rtol=1e-9, atol=1e-6):
        raise ValueError("a node's counts are not the sum of its children's")


def label_indices(y: Sequence[str] | npt.ArrayLike) -> npt.NDArray[np.intp]:
    """Labels as indices into :data:`LABELS`: from strings of it, or checked integer indices."""
    array = np.asarray(y)
    if array.ndim != 1:
        raise ValueError(f"labels must be one-dimensional, got shape {array.shape}")
    if array.dtype.kind in "iu":
        if np.any(array < 0) or np.any(array >= len(LABELS)):
            raise ValueError(f"label indices must be in 0..{len(LABELS) - 1}")
        return array.astype(np.intp)
    index = {label: i for i, label in enumerate(LABELS)}
    try:
        return np.array([index[str(v)] for v in array.tolist()], dtype=np.intp)
    except KeyError as exc:
        raise ValueError(f"label {exc.args[0]!r} is not one of {LABELS}") from None
