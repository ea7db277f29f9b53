"""Layer 2's learning steps: the passes as a dataset, and the models fitted on them (§6).

What :mod:`robotsoccer.experiments.layer2` runs between collecting passes and testing the
choosers: a pass trial's attributes and label as a row (:func:`dataset_from`), the C4.5-like
tree with a held-out error (:func:`train_tree`), the gradient-boosted trees
(:func:`train_boost`), the passer's half alone (:func:`passer_half_only`) and which side's
attributes a tree tests (:func:`tests_by_side`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from learning.pass_boost import PassBoost, fit_pass_boost, save_pass_boost
from learning.pass_dataset import PassDataset
from learning.pass_features import ATTRIBUTE_NAMES, HALF, PASS_SCHEMA
from learning.pass_tree import PassTree
from learning.pass_tree_file import save_pass_tree
from learning.pass_tree_grow import fit_pass_tree
from robotsoccer.runs.runner import TrialResult

HEAD = 4
"""Leading values of a pass trial's data before the attributes: receiver, confidence,
candidates, reports (:meth:`robotsoccer.drills.passing.PassDrill.data`)."""


def passes(results: Sequence[TrialResult]) -> list[TrialResult]:
    """The trials in which the passer passed (their data carry the attributes)."""
    return [r for r in results if len(r.data) == HEAD + len(ATTRIBUTE_NAMES)]


def dataset_from(results: Sequence[TrialResult], provenance: dict[str, Any]) -> PassDataset:
    """The passes' attributes and labels, in trial order."""
    done = passes(results)
    x = np.array([r.data[HEAD:] for r in done], dtype=np.float64).reshape(
        len(done), len(ATTRIBUTE_NAMES)
    )
    y = np.array([r.label for r in done], dtype=str)
    return PassDataset(x, y, provenance)


HOLDOUT_SHARE = 0.3
"""The last share of the training passes that a second tree, fitted on the rest, is tested on."""


def train_tree(dataset: PassDataset, path: Path, seed: int) -> tuple[PassTree, float]:
    """Fit the C4.5-like tree on the dataset, save it with its provenance; measure generality.

    Returns:
        The tree and the error of the same procedure on held-out passes: a tree fitted on the
        first 70% (trial order) and tested on the last 30%. The paper gives only the training
        error; a held-out error says how much of ours is memorised.
    """
    tree = fit_pass_tree(dataset.x, dataset.y, ATTRIBUTE_NAMES, schema=PASS_SCHEMA, seed=seed)
    provenance = {**dataset.provenance, "rows": len(dataset)}
    save_pass_tree(tree, path, provenance)
    cut = round((1.0 - HOLDOUT_SHARE) * len(dataset))
    if cut < 2 or cut >= len(dataset):
        return tree, math.nan
    part = fit_pass_tree(
        dataset.x[:cut], dataset.y[:cut], ATTRIBUTE_NAMES, schema=PASS_SCHEMA, seed=seed
    )
    return tree, part.training_error(dataset.x[cut:], dataset.y[cut:])


def train_boost(dataset: PassDataset, path: Path, seed: int) -> PassBoost:
    """Fit gradient-boosted trees on the dataset and save them with its provenance."""
    model = fit_pass_boost(dataset.x, dataset.y, ATTRIBUTE_NAMES, schema=PASS_SCHEMA, seed=seed)
    save_pass_boost(model, path, {**dataset.provenance, "rows": len(dataset)})
    return model


def passer_half_only(dataset: PassDataset) -> PassDataset:
    """The dataset with the receivers' half unknown: what a passer that hears no report has."""
    x = dataset.x.copy()
    x[:, HALF:] = np.nan
    return PassDataset(x, dataset.y, {**dataset.provenance, "receiver_half": "ignored"})


def tests_by_side(tree: PassTree) -> tuple[int, int]:
    """How many of the tree's tests use the passer's attributes, and how many the receiver's."""
    used = [tree.feature_names[f] for f in tree.feature.tolist() if f >= 0]
    passer = sum(1 for name in used if name.startswith("passer"))
    return passer, len(used) - passer
