"""A modern pass evaluator beside the paper's tree: gradient-boosted trees, saved as JSON.

scikit-learn's ``HistGradientBoostingClassifier`` handles unknown (NaN) attributes natively, as
the tree does, and predicts class probabilities from a sum of small regression trees (one per
class per boosting round) through a softmax. :func:`fit_pass_boost` fits it and copies every tree
into plain arrays (:class:`PassBoost`). The arrays are saved as JSON (:func:`save_pass_boost`),
never pickled, and evaluated without scikit-learn, all trees at once, level by level.

The model is judged beside the tree by success rate (as the passer's chooser) and by
calibration (its probabilities against observed success).
"""

from __future__ import annotations

import json
import math
import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from learning.features import ModelFileError, read_model_json
from learning.pass_tree import LABELS

BOOST_FORMAT = "robotsoccer/pass-boost"
"""Format tag stored in every boosted-model file."""

BOOST_FORMAT_VERSION = 2
"""Version 2 writes strict JSON: an infinite threshold (scikit-learn splits off unknown values
at +inf) is the string ``"Infinity"`` (``"-Infinity"``), not JSON's missing Infinity token.
Version 1 files, which hold those tokens, still load."""
READABLE_VERSIONS = (1, 2)
"""The format versions :func:`load_pass_boost` reads."""
_INFINITIES = {"Infinity": math.inf, "-Infinity": -math.inf}

_FIELDS = ("feature", "threshold", "missing_left", "left", "right", "value")


@dataclass(frozen=True)
class PassBoost:
    """Boosted trees as padded arrays: (n_trees, n_nodes) each; tree k adds to class k % 3.

    Attributes:
        feature_names: One name per attribute column.
        schema: The attribute schema id (e.g. ``"pass-attributes/1"``).
        baseline: The raw score each class starts from, in :data:`LABELS` order.
        feature: Attribute tested at each node (-1 at leaves and padding).
        threshold: Go left when the value is at most this.
        missing_left: Where an unknown value goes.
        left: Left child (-1 at leaves).
        right: Right child (-1 at leaves).
        value: A leaf's contribution to its class's raw score.
        tree_class: The class (index into :data:`LABELS`) each tree adds to.
        settings: How it was fitted.
    """

    feature_names: tuple[str, ...]
    schema: str
    baseline: npt.NDArray[np.float64]
    feature: npt.NDArray[np.int32]
    threshold: npt.NDArray[np.float64]
    missing_left: npt.NDArray[np.bool_]
    left: npt.NDArray[np.int32]
    right: npt.NDArray[np.int32]
    value: npt.NDArray[np.float64]
    tree_class: npt.NDArray[np.int32]
    settings: Mapping[str, Any]

    @property
    def n_trees(self) -> int:
        """Trees in the ensemble (rounds × classes)."""
        return int(self.feature.shape[0])

    def predict_proba(self, x: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """Class probabilities in :data:`LABELS` order: (3,) for one row, (n, 3) for rows."""
        rows = np.asarray(x, dtype=np.float64)
        one = rows.ndim == 1
        rows = np.atleast_2d(rows)
        if rows.shape[1] != len(self.feature_names):
            raise ValueError(f"need {len(self.feature_names)} values per row, got {rows.shape[1]}")
        raw = np.tile(self.baseline, (rows.shape[0], 1))
        trees = np.arange(self.n_trees)
        for r in range(rows.shape[0]):
            node = np.zeros(self.n_trees, dtype=np.intp)
            while True:
                f = self.feature[trees, node]
                inner = f >= 0
                if not inner.any():
                    break
                v = rows[r, np.where(inner, f, 0)]
                go_left = np.where(
                    np.isnan(v), self.missing_left[trees, node], v <= self.threshold[trees, node]
                )
                nxt = np.where(go_left, self.left[trees, node], self.right[trees, node])
                node = np.where(inner, nxt, node)
            np.add.at(raw[r], self.tree_class, self.value[trees, node])
        z = raw - raw.max(axis=1, keepdims=True)
        p = np.exp(z)
        p /= p.sum(axis=1, keepdims=True)
        return p[0] if one else p

    def success_confidence(self, x: npt.ArrayLike) -> float:
        """The probability of SUCCESS for one row."""
        return float(self.predict_proba(x)[LABELS.index("SUCCESS")])

    def to_json(self) -> dict[str, Any]:
        """The model as JSON types (unknown thresholds at leaves stored as 0)."""
        return {
            "format": BOOST_FORMAT,
            "version": BOOST_FORMAT_VERSION,
            "schema": self.schema,
            "feature_names": list(self.feature_names),
            "baseline": self.baseline.tolist(),
            "tree_class": self.tree_class.tolist(),
            "settings": dict(self.settings),
            **{name: getattr(self, name).tolist() for name in _FIELDS},
            "threshold": _encode_floats(self.threshold),
        }

    @classmethod
    def from_json(cls, data: Any, source: str) -> PassBoost:
        """Rebuild a model from :meth:`to_json`'s output; ModelFileError naming `source`."""

        def bad(what: str) -> ModelFileError:
            return ModelFileError(f"{source}: {what}")

        if not isinstance(data, dict) or data.get("format") != BOOST_FORMAT:
            raise bad("not a pass-boost file")
        if data.get("version") not in READABLE_VERSIONS:
            raise bad(f"format version {data.get('version')!r}, expected {BOOST_FORMAT_VERSION}")
        try:
            names = tuple(str(n) for n in data["feature_names"])
            arrays: dict[str, Any] = {
                "feature": np.asarray(data["feature"], dtype=np.int32),
                "threshold": np.asarray(_decode_floats(data["threshold"]), dtype=np.float64),
                "missing_left": np.asarray(data["missing_left"], dtype=bool),
                "left": np.asarray(data["left"], dtype=np.int32),
                "right": np.asarray(data["right"], dtype=np.int32),
                "value": np.asarray(data["value"], dtype=np.float64),
            }
            baseline = np.asarray(data["baseline"], dtype=np.float64)
            tree_class = np.asarray(data["tree_class"], dtype=np.int32)
            model = cls(names, str(data["schema"]), baseline, tree_class=tree_class,
                        settings=dict(data.get("settings", {})), **arrays)  # fmt: skip
        except (KeyError, TypeError, ValueError, RecursionError) as err:
            raise bad(f"malformed ({err})") from None
        _check(model, bad)
        return model


def _encode_floats(values: npt.NDArray[np.float64]) -> list[Any]:
    """A float array as strict JSON: numbers, and ±inf as the strings ``"(-)Infinity"``.

    Raises:
        ValueError: A NaN, which no model holds (a bug, not data).
    """
    if np.isnan(values).any():
        raise ValueError("a NaN threshold cannot be saved")
    out = values.astype(object)  # Python floats: written exactly as tolist() writes them
    out[np.isposinf(values)] = "Infinity"
    out[np.isneginf(values)] = "-Infinity"
    encoded: list[Any] = out.tolist()
    return encoded


def _decode_floats(value: Any) -> Any:
    """Nested lists of numbers back from :func:`_encode_floats` (and version 1's bare infinities).

    Raises:
        ValueError: A string other than ``"Infinity"`` or ``"-Infinity"``.
    """
    if isinstance(value, list):
        return [_decode_floats(v) for v in value]
    if isinstance(value, str):
        if value not in _INFINITIES:
            raise ValueError(f"{value[:20]!r} is not a number")
        return _INFINITIES[value]
    return value


def _check(model: PassBoost, bad: Any) -> None:
    """Refuse arrays that do not fit together or point outside their tree."""
    shape = model.feature.shape
    if len(shape) != 2 or any(getattr(model, n).shape != shape for n in _FIELDS):
        raise bad("node arrays of different shapes")
    if model.baseline.shape != (len(LABELS),) or model.tree_class.shape != (shape[0],):
        raise bad("baseline or tree classes of the wrong length")
    if np.any((model.tree_class < 0) | (model.tree_class >= len(LABELS))):
        raise bad("a tree adds to an unknown class")
    inner = model.feature >= 0
    if np.any(model.feature >= len(model.feature_names)):
        raise bad("a node tests an attribute that does not exist")
    for child in (model.left, model.right):
        if np.any(inner & ((child <= 0) | (child >= shape[1]))):
            raise bad("a node index out of range")
    if not np.all(np.isfinite(model.value)) or not np.all(np.isfinite(model.baseline)):
        raise bad("non-finite leaf values")
    if np.isnan(model.threshold).any():
        raise bad("a NaN threshold")


def fit_pass_boost(
    x: npt.ArrayLike,
    y: Sequence[str] | npt.ArrayLike,
    feature_names: Sequence[str],
    *,
    schema: str,
    seed: int = 0,
    max_iter: int = 100,
) -> PassBoost:
    """Fit ``HistGradientBoostingClassifier`` (defaults otherwise) and copy it into arrays."""
    from sklearn.ensemble import HistGradientBoostingClassifier

    rows = np.asarray(x, dtype=np.float64)
    labels = np.asarray(y).astype(str)
    # A column never known (e.g. a 9th teammate where only 5 play) breaks scikit-learn's
    # binning; it can tell nothing anyway, so the model is fitted without it.
    kept = np.flatnonzero(~np.all(np.isnan(rows), axis=0))
    model = HistGradientBoostingClassifier(max_iter=max_iter, random_state=seed)
    model.fit(rows[:, kept], labels)
    order = [list(model.classes_).index(label) if label in model.classes_ else -1
             for label in LABELS]  # fmt: skip
    predictors = model._predictors  # one list per round: a tree per class (private, stable)
    width = max(len(tree.nodes) for trees in predictors for tree in trees)
    n_classes = len(model.classes_)
    flat = [tree.nodes for trees in predictors for tree in trees]
    pad: dict[str, Any] = {
        "feature": np.full((len(flat), width), -1, dtype=np.int32),
        "threshold": np.zeros((len(flat), width)),
        "missing_left": np.zeros((len(flat), width), dtype=bool),
        "left": np.full((len(flat), width), -1, dtype=np.int32),
        "right": np.full((len(flat), width), -1, dtype=np.int32),
        "value": np.zeros((len(flat), width)),
    }
    for t, nodes in enumerate(flat):
        k = len(nodes)
        leaf = nodes["is_leaf"].astype(bool)
        pad["feature"][t, :k] = np.where(leaf, -1, kept[nodes["feature_idx"]])
        pad["threshold"][t, :k] = np.where(leaf, 0.0, nodes["num_threshold"])
        pad["missing_left"][t, :k] = nodes["missing_go_to_left"].astype(bool)
        pad["left"][t, :k] = np.where(leaf, -1, nodes["left"])
        pad["right"][t, :k] = np.where(leaf, -1, nodes["right"])
        pad["value"][t, :k] = np.where(leaf, nodes["value"], 0.0)
    # scikit-learn's column k of the raw score is classes_[k]; ours is LABELS order.
    sk_class = np.tile(np.arange(n_classes), len(predictors))
    to_ours = {sk: ours for ours, sk in enumerate(order) if sk >= 0}
    baseline = np.full(len(LABELS), -math.inf)
    base = np.asarray(model._baseline_prediction).reshape(-1)
    for sk, ours in to_ours.items():
        baseline[ours] = base[sk] if n_classes > 2 else 0.0
    if n_classes == 2:  # binary: one tree per round, on the second class's log-odds
        raise ValueError("the boosted evaluator needs all three labels in its training data")
    baseline[~np.isfinite(baseline)] = -30.0  # a label never seen: probability ~0
    tree_class = np.array([to_ours[int(k)] for k in sk_class], dtype=np.int32)
    return PassBoost(
        tuple(feature_names),
        schema,
        baseline,
        tree_class=tree_class,
        settings={
            "learner": "sklearn.HistGradientBoostingClassifier",
            "max_iter": max_iter,
            "seed": int(seed),
            "n_train": int(rows.shape[0]),
        },
        **pad,
    )


def save_pass_boost(
    model: PassBoost, path: str | os.PathLike[str], provenance: Mapping[str, Any]
) -> Path:
    """Write the model and its provenance as strict JSON (no NaN or Infinity), atomically.

    Raises:
        ValueError: A NaN or infinity in the provenance (a bug, not data).
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    partial = path.with_name(path.name + ".tmp")
    doc = {**model.to_json(), "provenance": dict(provenance)}
    partial.write_text(json.dumps(doc, allow_nan=False))
    partial.replace(path)
    return path


def load_pass_boost(
    path: str | os.PathLike[str], *, schema: str | None = None
) -> tuple[PassBoost, dict[str, Any]]:
    """Read a model saved by :func:`save_pass_boost`, and its provenance.

    Raises:
        ModelFileError: The file is missing, not JSON, not a boosted model, inconsistent, or
            of another attribute schema.
    """
    path = Path(path)
    data = read_model_json(path, "pass-boost", finite=False)
    model = PassBoost.from_json(data, str(path))
    if schema is not None and model.schema != schema:
        raise ModelFileError(f"{path}: attributes of schema {model.schema!r}, expected {schema!r}")
    provenance = data.get("provenance", {})
    return model, dict(provenance) if isinstance(provenance, dict) else {}
