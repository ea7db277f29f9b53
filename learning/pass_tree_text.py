"""The pass-evaluation tree printed in the style of C4.5's output (paper §6, Figure 14).

:meth:`learning.pass_tree.PassTree.render` calls :func:`render_tree`. The printer reads the tree's
arrays through :class:`PrintableTree`, so it needs nothing from the tree's own module (which
imports this one).
"""

from __future__ import annotations

import math
from typing import Protocol

import numpy as np
import numpy.typing as npt


class PrintableTree(Protocol):
    """The arrays of a pass tree that printing reads (see :class:`~learning.pass_tree.PassTree`)."""

    @property
    def feature_names(self) -> tuple[str, ...]:
        """Attribute names, one per input column."""
        ...

    @property
    def feature(self) -> npt.NDArray[np.int32]:
        """The column tested at each node, -1 at leaves."""
        ...

    @property
    def threshold(self) -> npt.NDArray[np.float64]:
        """The cut at each internal node (+inf: a known/unknown test), NaN at leaves."""
        ...

    @property
    def shown_threshold(self) -> npt.NDArray[np.float64]:
        """The cut as C4.5 prints it, NaN at leaves."""
        ...

    @property
    def left(self) -> npt.NDArray[np.int32]:
        """The child for ``x <= threshold``, -1 at leaves."""
        ...

    @property
    def right(self) -> npt.NDArray[np.int32]:
        """The child for ``x > threshold``, -1 at leaves."""
        ...

    @property
    def missing_left(self) -> npt.NDArray[np.bool_]:
        """Whether an unknown value goes left at each node."""
        ...

    @property
    def counts(self) -> npt.NDArray[np.float64]:
        """Training cases of each label reaching each node, (n_nodes, n_labels)."""
        ...


def render_tree(tree: PrintableTree, labels: tuple[str, ...], max_depth: int | None = None) -> str:
    """The tree as text, in the style of C4.5's output (paper Figure 14).

    One line per test, indented 4 spaces per level: ``name <= t`` or ``name > t``, with ``t`` as
    the shown threshold (up to 3 decimals, no trailing zeros). A branch ending in a leaf reads
    ``... : S (cases/errors)``: the leaf's label initial, its training cases and those not of its
    label, one decimal each. As C4.5 does, a node's leaf branches are printed before its
    subtrees. ``[or unknown]`` marks the branch an unknown value follows; known/unknown tests
    read ``name is known`` / ``name is unknown``. A tree that is a single leaf prints just
    ``S (cases/errors)``.

    Args:
        tree: The tree's arrays.
        labels: The label names, in the column order of ``tree.counts``.
        max_depth: Show this many levels of tests; deeper subtrees print as ``...``.

    Raises:
        ValueError: ``max_depth`` is negative.
    """
    if max_depth is not None and max_depth < 0:
        raise ValueError(f"max_depth must be >= 0, got {max_depth}")
    lines: list[str] = []
    if tree.feature[0] < 0:
        return _leaf_text(tree, labels, 0)
    _render_node(tree, labels, 0, 0, max_depth, lines)
    return "\n".join(lines)


def _leaf_text(tree: PrintableTree, labels: tuple[str, ...], node: int) -> str:
    counts = tree.counts[node]
    label = int(np.argmax(counts))
    cases = float(counts.sum())
    return f"{labels[label][0]} ({cases:.1f}/{cases - float(counts[label]):.1f})"


def _render_node(
    tree: PrintableTree,
    labels: tuple[str, ...],
    node: int,
    depth: int,
    max_depth: int | None,
    lines: list[str],
) -> None:
    indent = "    " * depth
    if max_depth is not None and depth >= max_depth:
        lines.append(f"{indent}...")
        return
    children = (int(tree.left[node]), int(tree.right[node]))
    # C4.5 release 8 (trees.c, Show) prints a node's leaf branches before its subtrees.
    order = sorted((0, 1), key=lambda side: tree.feature[children[side]] >= 0)
    for side in order:
        child = children[side]
        test = _test_text(tree, node, side)
        if tree.feature[child] < 0:
            lines.append(f"{indent}{test} : {_leaf_text(tree, labels, child)}")
        else:
            lines.append(f"{indent}{test} :")
            _render_node(tree, labels, child, depth + 1, max_depth, lines)


def _test_text(tree: PrintableTree, node: int, side: int) -> str:
    name = tree.feature_names[int(tree.feature[node])]
    if math.isinf(float(tree.threshold[node])):
        return f"{name} is known" if side == 0 else f"{name} is unknown"
    op = "<=" if side == 0 else ">"
    unknown = " [or unknown]" if bool(tree.missing_left[node]) == (side == 0) else ""
    return f"{name} {op} {_format_number(float(tree.shown_threshold[node]))}{unknown}"


def _format_number(value: float) -> str:
    text = f"{value:.3f}".rstrip("0").rstrip(".")
    return "0" if text == "-0" else text
