"""The pass-evaluation tree's file format: JSON with a format tag, version and provenance.

Trees are saved as JSON (:func:`save_pass_tree`), never pickled, and refused with
:class:`~learning.features.ModelFileError` naming the file when corrupt, for another format
version or for another attribute schema (:func:`load_pass_tree`). JSON has no NaN or infinity:
leaves store their threshold as ``null`` and known/unknown tests their cut as ``"inf"``.
"""

from __future__ import annotations

import json
import math
import os
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np

from learning.features import ModelFileError, read_model_json
from learning.pass_tree import LABELS, PassTree

TREE_FORMAT = "robotsoccer/pass-tree"
"""Format tag stored in every pass-tree file."""

TREE_FORMAT_VERSION = 1
"""Version of the file layout (not of the attributes: that is the tree's ``schema``)."""

Note = str | int | float
"""Value types of a tree file's provenance record (JSON scalars)."""


def tree_to_json(tree: PassTree) -> dict[str, Any]:
    """The tree as plain JSON types, with format tag and version (no provenance)."""
    return {
        "format": TREE_FORMAT,
        "format_version": TREE_FORMAT_VERSION,
        "schema": tree.schema,
        "labels": list(LABELS),
        "feature_names": list(tree.feature_names),
        "settings": dict(tree.settings),
        "feature": tree.feature.tolist(),
        "threshold": [_encode_float(v) for v in tree.threshold.tolist()],
        "shown_threshold": [_encode_float(v) for v in tree.shown_threshold.tolist()],
        "left": tree.left.tolist(),
        "right": tree.right.tolist(),
        "missing_left": tree.missing_left.tolist(),
        "counts": tree.counts.tolist(),
    }


def tree_from_json(data: Any, source: str) -> PassTree:
    """Read a tree written by :func:`tree_to_json`, checking everything.

    Args:
        data: The parsed JSON object.
        source: What it was read from (a file name), named in every error.

    Raises:
        ModelFileError: Not a pass tree, another format version, or any field missing,
            mistyped or inconsistent with the others.
    """
    try:
        return _from_doc(data)
    except (ModelFileError, ValueError, TypeError) as exc:
        raise ModelFileError(f"{source}: {exc}") from None


def _from_doc(doc: Any) -> PassTree:
    if not isinstance(doc, dict) or doc.get("format") != TREE_FORMAT:
        raise ModelFileError(f"not a pass tree (format tag is not {TREE_FORMAT!r})")
    if doc.get("format_version") != TREE_FORMAT_VERSION:
        raise ModelFileError(f"unsupported pass-tree format version {doc.get('format_version')!r}")
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
    return PassTree(
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
    doc = {**tree_to_json(tree), "provenance": notes}
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
    tree = tree_from_json(doc, source=str(path))
    notes = doc.get("provenance")
    if not isinstance(notes, dict) or not all(_is_note(v) for v in notes.values()):
        raise ModelFileError(f"{path}: provenance must map names to strings or numbers")
    if schema is not None and tree.schema != schema:
        raise ModelFileError(f"{path}: trained on attribute schema {tree.schema!r}, not {schema!r}")
    return tree, notes


# ----------------------------------------------------------------------------- helpers

# ----------------------------------------------------------------------------- helpers


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
