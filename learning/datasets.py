"""Interception datasets: feature rows, turn angles, and where they came from, saved safely.

A dataset is what the paper's training drill collects (§5, Figure 6): one row per *save* made
with a random turn angle, X = (BD, BA, previous BD) in the columns of
:data:`learning.features.FEATURE_NAMES` (plain metres and radians, never scaled) and y = the TA
that produced the save. Its :class:`Provenance` records the field model, preset, seed, ball noise
and behaviour, so every trained model can say what it learned from.

Files are ``.npz`` archives of plain arrays plus one JSON metadata string, read with
``allow_pickle=False``: loading a dataset never runs code. Any corrupt or mismatched file raises
:class:`DatasetError` naming the file and the problem.
"""

from __future__ import annotations

import dataclasses
import json
import os
import zipfile
import zlib
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from types import UnionType
from typing import Any

import numpy as np
import numpy.typing as npt

from learning.features import (
    DECISIONS,
    SCHEMA_VERSION,
    SchemaError,
    check_feature_rows,
    decision_of,
)

DATASET_FORMAT = "robotsoccer/interception-dataset"
"""Format tag stored in every dataset file."""

DATASET_FORMAT_VERSION = 1
"""Version of the file layout (not of the features: that is the schema version)."""

ExtraValue = str | float | int
"""The value types allowed in :attr:`Provenance.extra` (JSON scalars)."""


class DatasetError(ValueError):
    """A dataset is malformed, or its file is corrupt, truncated or for another schema."""


@dataclass(frozen=True)
class Provenance:
    """Where a dataset (and the model trained on it) came from.

    Attributes:
        field_model: The field model that produced it (``"soccer_server"``, ``"robot_physics"``).
        preset: The field model's preset name.
        seed: The experiment seed the trials were spawned from.
        ball_noise: The ball's movement noise (Soccer Server ``ball_rand``, or the robot
            field's equivalent) during collection.
        behaviour: The defender behaviour that collected it (e.g. ``"random_ta"``).
        n_trials: Trials run to collect it (saves *and* failures).
        schema_version: Feature schema version of the rows.
        created_by: The program or command that wrote it.
        extra: Further scalar facts (e.g. the TA range, the range BD threshold).
    """

    field_model: str
    preset: str
    seed: int
    ball_noise: float
    behaviour: str
    n_trials: int
    schema_version: int = SCHEMA_VERSION
    created_by: str = "learning"
    extra: dict[str, ExtraValue] = field(default_factory=dict)

    def to_dict(self) -> dict[str, Any]:
        """The record as plain JSON types."""
        return {**dataclasses.asdict(self), "extra": dict(self.extra)}

    @classmethod
    def from_dict(cls, data: Mapping[str, Any]) -> Provenance:
        """Read a record written by :meth:`to_dict`, checking every field's type.

        Raises:
            DatasetError: A field is missing, unknown or of the wrong type.
        """
        expected = {f.name for f in dataclasses.fields(cls)}
        if set(data) != expected:
            raise DatasetError(
                f"provenance fields differ: missing {sorted(expected - set(data))}, "
                f"unknown {sorted(set(data) - expected)}"
            )
        for name in ("field_model", "preset", "behaviour", "created_by"):
            _check_type(name, data[name], str)
        for name in ("seed", "n_trials", "schema_version"):
            _check_type(name, data[name], int)
        _check_type("ball_noise", data["ball_noise"], int | float)
        extra = data["extra"]
        if not isinstance(extra, dict) or not all(
            isinstance(k, str) and _is_scalar(v) for k, v in extra.items()
        ):
            raise DatasetError(f"provenance extra must map str to str/int/float, got {extra!r}")
        return cls(**{**data, "ball_noise": float(data["ball_noise"]), "extra": dict(extra)})


def _is_scalar(value: object) -> bool:
    return isinstance(value, str | int | float) and not isinstance(value, bool)


def _check_type(name: str, value: object, kind: type | UnionType) -> None:
    # bool is an int subclass: a True seed is a mistake, not a number.
    if isinstance(value, bool) or not isinstance(value, kind):
        raise DatasetError(f"provenance field {name!r} has the wrong type: {value!r}")


@dataclass(frozen=True, eq=False)
class InterceptionDataset:
    """Interception training rows with their provenance.

    Attributes:
        x: (N, 3) float64 rows in :data:`FEATURE_NAMES` order [m, rad, m].
        y: (N,) float64 turn angles TA [rad, left positive].
        provenance: Where the rows came from.
    """

    x: npt.NDArray[np.float64]
    y: npt.NDArray[np.float64]
    provenance: Provenance
    decision: str = "turn"
    """What the rows are (:data:`~learning.features.DECISIONS`): ``turn`` or ``lead``."""

    def __post_init__(self) -> None:
        if self.decision not in DECISIONS:
            raise DatasetError(
                f"unknown decision {self.decision!r} (known: {', '.join(DECISIONS)})"
            )
        # Own read-only float64 copies: a dataset is a value, and callers keep their arrays.
        x, y = _float_copy(self.x, "rows"), _float_copy(self.y, "targets")
        _check_rows(x, y)
        if self.provenance.schema_version != SCHEMA_VERSION:
            raise DatasetError(
                f"provenance schema version {self.provenance.schema_version} is not "
                f"{SCHEMA_VERSION}"
            )
        x.flags.writeable = False
        y.flags.writeable = False
        object.__setattr__(self, "x", x)
        object.__setattr__(self, "y", y)

    def __len__(self) -> int:
        return int(self.y.shape[0])

    def subset(self, n: int, rng: np.random.Generator) -> InterceptionDataset:
        """`n` rows drawn without replacement, kept in their original order.

        The paper trains nets on 100 to 4773 saves (Figure 7); this draws such a subset.
        ``extra["subset_of_n"]`` records the size of the parent.

        Raises:
            DatasetError: `n` is negative or larger than the dataset.
        """
        if not 0 <= n <= len(self):
            raise DatasetError(f"cannot draw {n} rows from a dataset of {len(self)}")
        rows = np.sort(rng.choice(len(self), size=n, replace=False))
        extra = {**self.provenance.extra, "subset_of_n": len(self)}
        return InterceptionDataset(
            self.x[rows],
            self.y[rows],
            dataclasses.replace(self.provenance, extra=extra),
            self.decision,
        )

    def save(self, path: str | os.PathLike[str]) -> Path:
        """Write the dataset to `path` (an ``.npz`` archive; the name is kept as given).

        The file is written beside its final name and renamed into place, so an interrupted
        run never leaves a half-written dataset under the real name.

        Returns:
            The path written.
        """
        meta = {
            "format": DATASET_FORMAT,
            "format_version": DATASET_FORMAT_VERSION,
            "schema_version": SCHEMA_VERSION,
            "feature_names": list(DECISIONS[self.decision][0]),
            "target_name": DECISIONS[self.decision][1],
            "provenance": self.provenance.to_dict(),
        }
        arrays = {"x": self.x, "y": self.y}
        return write_npz(Path(path), arrays, meta)

    @classmethod
    def load(cls, path: str | os.PathLike[str]) -> InterceptionDataset:
        """Read a dataset written by :meth:`save`, checking format, schema, keys and shapes.

        Raises:
            DatasetError: The file is missing, corrupt, truncated, of another format or
                schema, or its arrays have the wrong shapes.
        """
        path = Path(path)
        arrays, meta = read_npz(path, ("x", "y"), DatasetError)
        try:
            decision = _check_meta(meta)
            provenance = Provenance.from_dict(meta["provenance"])
            return cls(arrays["x"], arrays["y"], provenance, decision)
        except DatasetError as exc:
            raise DatasetError(f"{path}: {exc}") from None


def concatenate(
    parts: Sequence[InterceptionDataset], provenance: Provenance | None = None
) -> InterceptionDataset:
    """Join datasets row-wise.

    Args:
        parts: The datasets, in order.
        provenance: The joined dataset's provenance. If None, the parts must agree on every
            provenance field except ``n_trials`` (summed) and ``extra`` (merged; a key with two
            different values is an error).

    Raises:
        DatasetError: No parts, or their provenances disagree and none was given.
    """
    if not parts:
        raise DatasetError("cannot concatenate zero datasets")
    if provenance is None:
        provenance = _merged_provenance([p.provenance for p in parts])
    x = np.concatenate([p.x for p in parts], axis=0)
    y = np.concatenate([p.y for p in parts], axis=0)
    return InterceptionDataset(x, y, provenance)


def _merged_provenance(records: Sequence[Provenance]) -> Provenance:
    first = records[0]
    for name in ("field_model", "preset", "seed", "ball_noise", "behaviour", "created_by"):
        values = {getattr(r, name) for r in records}
        if len(values) > 1:
            raise DatasetError(
                f"datasets differ in provenance {name!r} ({sorted(map(str, values))}); "
                "pass provenance= explicitly"
            )
    extra: dict[str, ExtraValue] = {}
    for record in records:
        for key, value in record.extra.items():
            if key in extra and extra[key] != value:
                raise DatasetError(f"datasets differ in provenance extra {key!r}")
            extra[key] = value
    n_trials = sum(r.n_trials for r in records)
    return dataclasses.replace(first, n_trials=n_trials, extra=extra)


def _float_copy(values: npt.ArrayLike, what: str) -> npt.NDArray[np.float64]:
    array = np.asarray(values)
    if array.dtype.kind not in "iuf":
        raise DatasetError(f"{what} must be numbers, got dtype {array.dtype}")
    return np.array(array, dtype=np.float64)


def _check_rows(x: npt.NDArray[np.float64], y: npt.NDArray[np.float64]) -> None:
    try:
        check_feature_rows(x)
    except ValueError as exc:
        raise DatasetError(str(exc)) from None
    if y.shape != (x.shape[0],):
        raise DatasetError(f"targets must have shape ({x.shape[0]},), got {y.shape}")
    if not np.isfinite(y).all():
        raise DatasetError("targets hold NaN or infinite values")


def _check_meta(meta: Mapping[str, Any]) -> str:
    """Check a dataset file's metadata; return the decision its columns are."""
    if meta.get("format") != DATASET_FORMAT:
        raise DatasetError(f"format tag {meta.get('format')!r} is not {DATASET_FORMAT!r}")
    if meta.get("format_version") != DATASET_FORMAT_VERSION:
        raise DatasetError(f"unsupported dataset format version {meta.get('format_version')!r}")
    if meta.get("schema_version") != SCHEMA_VERSION:
        raise DatasetError(
            f"feature schema version {meta.get('schema_version')!r} does not match this "
            f"code's version {SCHEMA_VERSION}"
        )
    try:
        decision = decision_of(meta.get("feature_names"), meta.get("target_name"))
    except SchemaError as exc:
        raise DatasetError(str(exc)) from None
    if not isinstance(meta.get("provenance"), dict):
        raise DatasetError("metadata lacks the provenance record")
    return decision


# ----------------------------------------------------------------------------- safe .npz files


def write_npz(path: Path, arrays: Mapping[str, npt.NDArray[Any]], meta: Mapping[str, Any]) -> Path:
    """Write arrays plus a JSON metadata string to `path`, atomically.

    Shared by the dataset and the interception-net files. Metadata must be plain JSON types
    (``allow_nan=False``: a NaN in metadata is a bug, not data).
    """
    text = json.dumps(meta, sort_keys=True, allow_nan=False)
    tmp = path.with_name(path.name + ".tmp")
    members: dict[str, Any] = {"metadata": np.array(text), **arrays}
    with tmp.open("wb") as fh:
        np.savez(fh, allow_pickle=False, **members)
    os.replace(tmp, path)
    return path


def read_npz(
    path: Path, keys: Sequence[str], error: type[Exception]
) -> tuple[dict[str, npt.NDArray[Any]], dict[str, Any]]:
    """Read the arrays `keys` and the JSON metadata object from an ``.npz`` file, never unpickling.

    Args:
        path: The file.
        keys: Arrays that must be present (besides ``metadata``).
        error: The exception raised, with a message naming the file, for any failure.
    """
    try:
        archive = np.load(path, allow_pickle=False)
    except FileNotFoundError:
        raise error(f"{path}: file not found") from None
    except (OSError, ValueError, EOFError, zipfile.BadZipFile) as exc:
        # numpy reads unknown bytes as a possible pickle and suggests allow_pickle: never do that.
        reason = "garbage or pickled data, never loaded" if "pickle" in str(exc) else str(exc)
        raise error(f"{path}: not a readable .npz file ({reason})") from None
    if not isinstance(archive, np.lib.npyio.NpzFile):
        raise error(f"{path}: not an .npz archive")
    with archive:
        if "metadata" not in archive.files:
            raise error(f"{path}: no metadata record: a foreign .npz or zip, not written here")
        missing = [k for k in keys if k not in archive.files]
        if missing:
            raise error(f"{path}: arrays {missing} are missing")
        try:
            # .npz members are read lazily: read them all here so corruption surfaces now.
            arrays = {k: archive[k] for k in keys}
            meta = json.loads(str(archive["metadata"]), parse_constant=_reject_constant)
        except (OSError, ValueError, EOFError, zipfile.BadZipFile, zlib.error) as exc:
            raise error(f"{path}: corrupt .npz member ({exc})") from None
    if not isinstance(meta, dict):
        raise error(f"{path}: metadata is not a JSON object")
    return arrays, meta


def _reject_constant(token: str) -> Any:
    # json.loads accepts NaN/Infinity; a NaN scale or noise must not pass as valid metadata.
    raise ValueError(f"non-finite number {token} in metadata")
