"""The learned layers as estimators: features, datasets, the interception net, lookup, analytic.

Layer 2's estimators live in their own modules: :mod:`learning.pass_features` (the 174 attributes),
:mod:`learning.pass_codec` (the report's say codec), :mod:`learning.pass_tree` (the C4.5-like tree,
grown in :mod:`learning.pass_tree_grow`, pruned by :mod:`learning.c45`, printed by
:mod:`learning.pass_tree_text`, saved by :mod:`learning.pass_tree_file`), :mod:`learning.pass_boost`
(gradient-boosted trees) and :mod:`learning.pass_dataset`.

Takes arrays, returns arrays; imports no pymunk, no rerun and nothing from `robotsoccer`.

Importing torch takes seconds, so the net's names (`InterceptionModel`, `InterceptionNet`, ...)
are imported from :mod:`learning.interception` on first use; the features, datasets, lookup
table and analytic predictor never load torch.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

from learning.analytic import (
    MOTION_MULTIPLIER,
    analytic_turn_angle,
    analytic_turn_angle_xy,
    predicted_ball_position,
)
from learning.datasets import DatasetError, InterceptionDataset, Provenance, concatenate
from learning.features import (
    FEATURE_NAMES,
    SCHEMA_VERSION,
    TARGET_NAME,
    FeatureSchema,
    ModelFileError,
    SchemaError,
    feature_matrix,
    feature_row,
)
from learning.lookup import PAPER_GRID_DEG, LookupTable

if TYPE_CHECKING:
    from learning.interception import InterceptionModel, InterceptionNet, TurnAngleFunction

_LAZY = {
    "InterceptionModel": "learning.interception",
    "InterceptionNet": "learning.interception",
    "TurnAngleFunction": "learning.interception",
}

__all__ = [
    "FEATURE_NAMES",
    "MOTION_MULTIPLIER",
    "PAPER_GRID_DEG",
    "SCHEMA_VERSION",
    "TARGET_NAME",
    "DatasetError",
    "FeatureSchema",
    "InterceptionDataset",
    "InterceptionModel",
    "InterceptionNet",
    "LookupTable",
    "ModelFileError",
    "Provenance",
    "SchemaError",
    "TurnAngleFunction",
    "analytic_turn_angle",
    "analytic_turn_angle_xy",
    "concatenate",
    "feature_matrix",
    "feature_row",
    "predicted_ball_position",
]


def __getattr__(name: str) -> Any:
    """Import the torch-based names on first use (PEP 562)."""
    if name in _LAZY:
        return getattr(importlib.import_module(_LAZY[name]), name)
    raise AttributeError(f"module 'learning' has no attribute {name!r}")
