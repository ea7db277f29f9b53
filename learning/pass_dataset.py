"""Pass-evaluation datasets: the 174 attributes of each pass, its label and where it came from.

One row per training pass of the paper's §6 drill (a receiver chosen at random): X in the
columns of :data:`learning.pass_features.ATTRIBUTE_NAMES` (NaN = unknown), y the coach's label
(SUCCESS, FAILURE or MISS). The file is an ``.npz`` of plain arrays plus one JSON metadata
string (the schema id, the column names and the provenance), read with ``allow_pickle=False``,
so loading a dataset never runs code. A corrupt or mismatched file raises
:class:`~learning.datasets.DatasetError` naming the file.
"""

from __future__ import annotations

import json
import os
import zipfile
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import numpy.typing as npt

from learning.datasets import DatasetError
from learning.pass_features import ATTRIBUTE_NAMES, PASS_SCHEMA
from learning.pass_tree import LABELS

PASS_DATASET_FORMAT = "robotsoccer/pass-dataset"
"""Format tag stored in every pass dataset file."""

Scalar = str | int | float


@dataclass(frozen=True)
class PassDataset:
    """Attributes, labels and provenance of some passes.

    Attributes:
        x: (n, 174) attributes, NaN where unknown.
        y: (n,) labels, each one of :data:`learning.pass_tree.LABELS`.
        provenance: Field model, preset, seed, chooser, interception net, trial count, ...
    """

    x: npt.NDArray[np.float64]
    y: npt.NDArray[np.str_]
    provenance: Mapping[str, Scalar] = field(default_factory=dict)

    def __post_init__(self) -> None:
        if self.x.ndim != 2 or self.x.shape[1] != len(ATTRIBUTE_NAMES):
            raise DatasetError(
                f"pass attributes must be (n, {len(ATTRIBUTE_NAMES)}), got {self.x.shape}"
            )
        if self.y.shape != (self.x.shape[0],):
            raise DatasetError(f"{self.x.shape[0]} rows but {self.y.shape} labels")
        unknown = sorted(set(self.y.tolist()) - set(LABELS))
        if unknown:
            raise DatasetError(f"unknown label {unknown[0]!r} (known: {', '.join(LABELS)})")

    def __len__(self) -> int:
        return int(self.x.shape[0])

    def shares(self) -> dict[str, float]:
        """Each label's share of the rows."""
        n = max(len(self), 1)
        return {label: float(np.sum(self.y == label)) / n for label in LABELS}

    def save(self, path: str | os.PathLike[str]) -> Path:
        """Write the dataset (atomically: a temporary file, then a rename)."""
        path = Path(path)
        path.parent.mkdir(parents=True, exist_ok=True)
        meta = {
            "format": PASS_DATASET_FORMAT,
            "schema": PASS_SCHEMA,
            "columns": list(ATTRIBUTE_NAMES),
            "provenance": dict(self.provenance),
        }
        partial = path.with_name(path.name + ".part")
        with partial.open("wb") as f:
            text = json.dumps(meta, allow_nan=False)  # strict JSON: a NaN in metadata is a bug
            np.savez_compressed(f, x=self.x, y=self.y.astype(str), meta=np.array(text))
        partial.replace(path)
        return path

    @classmethod
    def load(cls, path: str | os.PathLike[str]) -> PassDataset:
        """Read a dataset written by :meth:`save`.

        Raises:
            DatasetError: The file is missing, corrupt, of another format or schema.
        """
        path = Path(path)
        try:
            with np.load(path, allow_pickle=False) as data:
                x, y, raw = data["x"], data["y"], str(data["meta"])
            meta = json.loads(raw)
        except (OSError, ValueError, KeyError, zipfile.BadZipFile) as err:
            raise DatasetError(f"{path}: not a readable pass dataset ({err})") from None
        if not isinstance(meta, dict) or meta.get("format") != PASS_DATASET_FORMAT:
            raise DatasetError(f"{path}: not a pass dataset (format {meta.get('format')!r})")
        if meta.get("schema") != PASS_SCHEMA or meta.get("columns") != list(ATTRIBUTE_NAMES):
            raise DatasetError(
                f"{path}: attributes of schema {meta.get('schema')!r}, expected {PASS_SCHEMA!r}"
            )
        try:
            return cls(np.asarray(x, dtype=np.float64), np.asarray(y), meta.get("provenance", {}))
        except DatasetError as err:
            raise DatasetError(f"{path}: {err}") from None
