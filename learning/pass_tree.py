"""The pass-evaluation decision tree of layer 2 (paper §6, Figure 14): C4.5 as closely as we can.

The paper trains "standard off-the-shelf C4.5 code with all of the default parameters" (release 8:
``-m 2``, ``-c 25``) to predict whether a pass to a receiver ends in SUCCESS, FAILURE or MISS from
174 continuous attributes, players out of sight giving *unknown* values (NaN here). Its pruned tree
had 87 nodes and 26% training error; the passer used the tree's confidence to pick a receiver
(Table 2).

:func:`fit_pass_tree` grows a tree with scikit-learn on the NaN-containing rows (no imputation),
then prunes it with C4.5's own error-based pruning (:func:`pessimistic_errors`) and copies it into
a :class:`PassTree`: plain arrays, evaluated by a short loop over nodes with no scikit-learn call.
Trees are saved as JSON (:func:`save_pass_tree`), never pickled, and refused with
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
  node whose tests then gain nothing. scikit-learn has no such charge; :func:`fit_pass_tree`
  applies it after growing, top-down, turning such nodes into leaves before the error-based
  pruning (``_release8_stop``). The charge is computed for the test scikit-learn chose, not for
  every candidate test as C4.5 does.
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

import itertools
import json
import math
import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from learning.features import ModelFileError, read_model_json

LABELS: tuple[str, ...] = ("SUCCESS", "FAILURE", "MISS")
"""The pass outcomes (paper §6), in the column order of every probability and count array."""

TREE_FORMAT = "robotsoccer/pass-tree"
"""Format tag stored in every pass-tree file."""

TREE_FORMAT_VERSION = 1
"""Version of the file layout (not of the attributes: that is the tree's ``schema``)."""

Note = str | int | float
"""Value types of a tree file's provenance record (JSON scalars)."""

Setting = str | int | float | bool
"""Value types of :attr:`PassTree.settings` (JSON scalars)."""

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


# ----------------------------------------------------------------------------- C4.5 pruning


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
    _check_confidence(confidence)
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


def _check_confidence(confidence: float) -> None:
    if not 0.0 < confidence < 1.0:
        raise ValueError(f"confidence factor must be in (0, 1), got {confidence!r}")


# ----------------------------------------------------------------------------- the tree


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
        labels = _label_indices(y)
        if labels.shape[0] != rows.shape[0] or rows.shape[0] == 0:
            raise ValueError(f"{rows.shape[0]} rows but {labels.shape[0]} labels")
        return float(np.mean(self.predict(rows) != labels))

    def render(self, max_depth: int | None = None) -> str:
        """The tree as text, in the style of C4.5's output (paper Figure 14).

        One line per test, indented 4 spaces per level: ``name <= t`` or ``name > t``, with
        ``t`` as :attr:`shown_threshold` (up to 3 decimals, no trailing zeros). A branch ending in
        a leaf reads ``... : S (cases/errors)``: the leaf's label initial, its training cases and
        those not of its label, one decimal each. As C4.5 does, a node's leaf branches are printed
        before its subtrees. ``[or unknown]`` marks the branch an unknown value follows;
        known/unknown tests read ``name is known`` / ``name is unknown``. A tree that is a single
        leaf prints just ``S (cases/errors)``.

        Args:
            max_depth: Show this many levels of tests; deeper subtrees print as ``...``.
        """
        if max_depth is not None and max_depth < 0:
            raise ValueError(f"max_depth must be >= 0, got {max_depth}")
        lines: list[str] = []
        if self.feature[0] < 0:
            return self._leaf_text(0)
        self._render_node(0, 0, max_depth, lines)
        return "\n".join(lines)

    def to_json(self) -> dict[str, Any]:
        """The tree as plain JSON types, with format tag and version (no provenance)."""
        return {
            "format": TREE_FORMAT,
            "format_version": TREE_FORMAT_VERSION,
            "schema": self.schema,
            "labels": list(LABELS),
            "feature_names": list(self.feature_names),
            "settings": dict(self.settings),
            "feature": self.feature.tolist(),
            "threshold": [_encode_float(v) for v in self.threshold.tolist()],
            "shown_threshold": [_encode_float(v) for v in self.shown_threshold.tolist()],
            "left": self.left.tolist(),
            "right": self.right.tolist(),
            "missing_left": self.missing_left.tolist(),
            "counts": self.counts.tolist(),
        }

    @classmethod
    def from_json(cls, data: Any, source: str) -> PassTree:
        """Read a tree written by :meth:`to_json`, checking everything.

        Args:
            data: The parsed JSON object.
            source: What it was read from (a file name), named in every error.

        Raises:
            ModelFileError: Not a pass tree, another format version, or any field missing,
                mistyped or inconsistent with the others.
        """
        try:
            return cls._from_doc(data)
        except (ModelFileError, ValueError, TypeError) as exc:
            raise ModelFileError(f"{source}: {exc}") from None

    @classmethod
    def _from_doc(cls, doc: Any) -> PassTree:
        if not isinstance(doc, dict) or doc.get("format") != TREE_FORMAT:
            raise ModelFileError(f"not a pass tree (format tag is not {TREE_FORMAT!r})")
        if doc.get("format_version") != TREE_FORMAT_VERSION:
            raise ModelFileError(
                f"unsupported pass-tree format version {doc.get('format_version')!r}"
            )
        if doc.get("labels") != list(LABELS):
            raise ModelFileError(f"labels {doc.get('labels')!r} are not {list(LABELS)}")
        schema, names, settings = doc.get("schema"), doc.get("feature_names"), doc.get("settings")
        if not isinstance(schema, str):
            raise ModelFileError("schema must be a string")
        if not isinstance(names, list) or not all(isinstance(n, str) for n in names):
            raise ModelFileError("feature_names must be a list of strings")
        if not isinstance(settings, dict) or not all(
            isinstance(v, str | int | float) for v in settings.values()
        ):
            raise ModelFileError("settings must map names to strings, numbers or booleans")
        ints = {k: _int_list(doc.get(k), k) for k in ("feature", "left", "right")}
        floats = {k: _float_list(doc.get(k), k) for k in ("threshold", "shown_threshold")}
        missing = doc.get("missing_left")
        if not isinstance(missing, list) or not all(isinstance(v, bool) for v in missing):
            raise ModelFileError("missing_left must be a list of booleans")
        counts = doc.get("counts")
        if not isinstance(counts, list) or not all(
            isinstance(row, list) and len(row) == len(LABELS) and all(_is_number(v) for v in row)
            for row in counts
        ):
            raise ModelFileError(f"counts must be a list of [{len(LABELS)} numbers] per node")
        return cls(
            feature_names=tuple(names),
            schema=schema,
            feature=np.array(ints["feature"], dtype=np.int64).astype(np.int32),
            threshold=np.array(floats["threshold"], dtype=np.float64),
            left=np.array(ints["left"], dtype=np.int64).astype(np.int32),
            right=np.array(ints["right"], dtype=np.int64).astype(np.int32),
            missing_left=np.array(missing, dtype=np.bool_),
            counts=np.array(counts, dtype=np.float64).reshape(len(counts), len(LABELS)),
            shown_threshold=np.array(floats["shown_threshold"], dtype=np.float64),
            settings=settings,
        )

    # ------------------------------------------------------------------------- evaluation

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

    # ------------------------------------------------------------------------- rendering

    def _leaf_text(self, node: int) -> str:
        counts = self.counts[node]
        label = int(np.argmax(counts))
        cases = float(counts.sum())
        return f"{LABELS[label][0]} ({cases:.1f}/{cases - float(counts[label]):.1f})"

    def _render_node(self, node: int, depth: int, max_depth: int | None, lines: list[str]) -> None:
        indent = "    " * depth
        if max_depth is not None and depth >= max_depth:
            lines.append(f"{indent}...")
            return
        children = (int(self.left[node]), int(self.right[node]))
        # C4.5 release 8 (trees.c, Show) prints a node's leaf branches before its subtrees.
        order = sorted((0, 1), key=lambda side: self.feature[children[side]] >= 0)
        for side in order:
            child = children[side]
            test = self._test_text(node, side)
            if self.feature[child] < 0:
                lines.append(f"{indent}{test} : {self._leaf_text(child)}")
            else:
                lines.append(f"{indent}{test} :")
                self._render_node(child, depth + 1, max_depth, lines)

    def _test_text(self, node: int, side: int) -> str:
        name = self.feature_names[int(self.feature[node])]
        if math.isinf(float(self.threshold[node])):
            return f"{name} is known" if side == 0 else f"{name} is unknown"
        op = "<=" if side == 0 else ">"
        unknown = " [or unknown]" if bool(self.missing_left[node]) == (side == 0) else ""
        return f"{name} {op} {_format_number(float(self.shown_threshold[node]))}{unknown}"


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


# ----------------------------------------------------------------------------- fitting


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
    bottom-up: a subtree becomes a leaf when the leaf's :func:`pessimistic_errors` are at most
    the summed predicted errors of the subtree's leaves + 0.1. Subtree raising is omitted. See
    the module docstring for everything that differs from C4.5.

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

    _check_confidence(confidence)
    if isinstance(min_cases, bool) or not isinstance(min_cases, int) or min_cases < 1:
        raise ValueError(f"min_cases must be an int >= 1, got {min_cases!r}")
    rows = np.array(x, dtype=np.float64)
    names = tuple(feature_names)
    if rows.ndim != 2 or rows.shape[0] == 0 or rows.shape[1] != len(names):
        raise ValueError(f"need rows (n >= 1, {len(names)}) matching the names, got {rows.shape}")
    if np.isinf(rows).any():
        raise ValueError("rows hold infinite values (unknowns must be NaN)")
    labels = _label_indices(y)
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
        is_leaf = _release8_stop(model, rows, labels, left, right, is_leaf)
        is_leaf = _c45_prune(left, right, counts, confidence, is_leaf)
    rows32 = rows.astype(np.float32)
    tree = _compact(
        names=names,
        schema=schema,
        left=left,
        right=right,
        is_leaf=is_leaf,
        feature=np.asarray(sk.feature),
        threshold=np.asarray(sk.threshold, dtype=np.float64),
        missing_left=np.asarray(sk.missing_go_to_left).astype(bool),
        counts=counts,
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


def _entropy(labels: npt.NDArray[np.intp]) -> float:
    """Entropy [bits] of some labels."""
    if labels.shape[0] == 0:
        return 0.0
    p = np.bincount(labels, minlength=len(LABELS)) / labels.shape[0]
    p = p[p > 0.0]
    return float(-(p * np.log2(p)).sum())


def _release8_stop(
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
            split = _entropy(y) - sum(
                g.shape[0] / n_known * _entropy(g) for g in (y[low], y[~low])
            )
            distinct = np.unique(values).shape[0]
            gain = n_known / n * split - math.log2(max(distinct - 1, 1)) / n
        if gain <= 0.0:
            out[node] = True
        else:
            stack.extend((int(left[node]), int(right[node])))
    return out


def _c45_prune(
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


def _compact(
    *,
    names: tuple[str, ...],
    schema: str,
    left: npt.NDArray[np.intp],
    right: npt.NDArray[np.intp],
    is_leaf: npt.NDArray[np.bool_],
    feature: npt.NDArray[Any],
    threshold: npt.NDArray[np.float64],
    missing_left: npt.NDArray[np.bool_],
    counts: npt.NDArray[np.float64],
    rows32: npt.NDArray[np.float32],
    settings: Mapping[str, Setting],
) -> PassTree:
    """Renumber the kept nodes in preorder and build the arrays (children after parents)."""
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


# ----------------------------------------------------------------------------- files


def save_pass_tree(
    tree: PassTree, path: str | os.PathLike[str], provenance: Mapping[str, Note]
) -> Path:
    """Write `tree` and its provenance as JSON to `path`, atomically (temporary file + replace).

    Args:
        tree: The tree.
        path: Where to write it.
        provenance: Where the training data came from (field model, seed, trials, ...): names
            mapped to strings or finite numbers.

    Returns:
        The path written.

    Raises:
        ValueError: A provenance value is not a string or finite number.
    """
    notes = dict(provenance)
    if not all(isinstance(k, str) and _is_note(v) for k, v in notes.items()):
        raise ValueError("provenance must map names to strings or finite numbers")
    doc = {**tree.to_json(), "provenance": notes}
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(path.name + ".tmp")
    tmp.write_text(json.dumps(doc, indent=1, allow_nan=False) + "\n", encoding="utf-8")
    os.replace(tmp, path)
    return path


def load_pass_tree(
    path: str | os.PathLike[str], *, schema: str | None = None
) -> tuple[PassTree, dict[str, Any]]:
    """Read a tree written by :func:`save_pass_tree`.

    Args:
        path: The file.
        schema: If given, the attribute schema id the tree must have been trained on.

    Returns:
        The tree and its provenance record.

    Raises:
        ModelFileError: The file is missing, truncated or not JSON, not a pass tree, of another
            format version, inconsistent, or for another schema; the message names the file.
    """
    path = Path(path)
    doc = read_model_json(path, "pass-tree")
    tree = PassTree.from_json(doc, source=str(path))
    notes = doc.get("provenance")
    if not isinstance(notes, dict) or not all(_is_note(v) for v in notes.values()):
        raise ModelFileError(f"{path}: provenance must map names to strings or numbers")
    if schema is not None and tree.schema != schema:
        raise ModelFileError(f"{path}: trained on attribute schema {tree.schema!r}, not {schema!r}")
    return tree, notes


# ----------------------------------------------------------------------------- helpers


def _label_indices(y: Sequence[str] | npt.ArrayLike) -> npt.NDArray[np.intp]:
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


def _format_number(value: float) -> str:
    text = f"{value:.3f}".rstrip("0").rstrip(".")
    return "0" if text == "-0" else text


def _encode_float(value: float) -> float | str | None:
    # JSON has no NaN or infinity: leaves have no threshold (null), known/unknown tests cut at +inf.
    if math.isnan(value):
        return None
    return "inf" if math.isinf(value) else value


def _float_list(values: Any, name: str) -> list[float]:
    if not isinstance(values, list):
        raise ModelFileError(f"{name} must be a list")
    out = []
    for v in values:
        if v is None:
            out.append(math.nan)
        elif v == "inf":
            out.append(math.inf)
        elif _is_number(v):
            out.append(float(v))
        else:
            raise ModelFileError(f"{name} holds {v!r}, not a number, null or 'inf'")
    return out


def _int_list(values: Any, name: str) -> list[int]:
    if not isinstance(values, list) or not all(
        isinstance(v, int) and not isinstance(v, bool) for v in values
    ):
        raise ModelFileError(f"{name} must be a list of integers")
    if any(abs(v) >= 2**31 for v in values):
        raise ModelFileError(f"{name} holds an index beyond int32")
    return values


def _is_number(value: object) -> bool:
    return isinstance(value, int | float) and not isinstance(value, bool)


def _is_note(value: object) -> bool:
    if isinstance(value, float):
        return math.isfinite(value)
    return isinstance(value, str | int) and not isinstance(value, bool)
