"""The interception feature schema: names with units, its version, the distance scale, the rows.

Layer 1 of the paper (§5, "Learning a Low-level Skill") maps what the defender sees when the ball
comes within range — the ball's distance BD, its angle BA and the previous sighting's distance —
to the turn angle TA, "the angle to turn *after* facing the ball". The paper works in Soccer
Server units and degrees; inside this project every column is SI and radians, counter-clockwise
(left) positive, and the schema below names each column with its unit.

The schema is versioned: every dataset and model file records :data:`SCHEMA_VERSION` and the
column names, and loaders refuse a file written for another schema (:class:`SchemaError`).

Distance scale (the transfer study): the Soccer Server field is 105 m long and the robot table
2.74 m, far apart. A model's distance inputs are the metre distances divided by its
``distance_scale_m`` (default 1, i.e. plain metres), so a model trained on one field can be
applied to the other by giving it that field's scale (e.g. each field's length). Datasets always
store plain metres; the scale belongs to the model that reads them.
"""

from __future__ import annotations

import json
import math
import os
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

SCHEMA_VERSION = 1
"""Version of the interception feature schema; bump it when a column's meaning changes."""

FEATURE_NAMES = ("ball_distance_m", "ball_angle_rad", "previous_ball_distance_m")
"""The input columns, in order: BD [m], BA [rad, left positive], previous BD [m] (paper §5)."""

TARGET_NAME = "turn_angle_rad"
"""The output: TA, the turn after facing the ball [rad, left positive] (paper §5)."""

DISTANCE_COLUMNS = (0, 2)
"""Indices of the columns divided by the distance scale."""

LEAD_FEATURE_NAMES = ("ball_distance_m", "ball_track_angle_rad", "previous_ball_distance_m")
"""The lead decision's inputs: BD [m], the ball's track angle [rad, left positive: the angle at
the ball from its velocity to the line to the player], previous BD [m]
(:mod:`robotsoccer.skills.lead`). Same shape and distance columns as the turn decision's."""

LEAD_TARGET_NAME = "lead_time_s"
"""The lead decision's output: how far ahead in time along the ball's track to aim [s]."""

DECISIONS: dict[str, tuple[tuple[str, ...], str]] = {
    "turn": (FEATURE_NAMES, TARGET_NAME),
    "lead": (LEAD_FEATURE_NAMES, LEAD_TARGET_NAME),
}
"""What a layer-1 model decides, by name: its (input names, output name). ``turn`` is the
paper's TA (§5); ``lead`` the meeting horizon of the robot-native decision."""


def decision_of(feature_names: object, target_name: object) -> str:
    """The decision whose columns these are.

    Raises:
        SchemaError: They are no decision's columns.
    """
    listed = tuple(feature_names) if isinstance(feature_names, list | tuple) else None
    for decision, (names, target) in DECISIONS.items():
        if listed == names and target_name == target:
            return decision
    known = "; ".join(f"{list(n)} -> {t!r}" for n, t in DECISIONS.values())
    raise SchemaError(f"columns {feature_names!r} -> {target_name!r} are none of: {known}")


class SchemaError(ValueError):
    """A file's feature schema is not the one this code reads (version, names or scale)."""


class ModelFileError(ValueError):
    """A model file (interception net or lookup table) is corrupt, mismatched or not a model.

    Defined here, beside the schema, so the torch-free lookup table can raise it without
    importing the torch-based net.
    """


def read_model_json(path: str | os.PathLike[str], what: str, *, finite: bool = True) -> Any:
    """The parsed JSON document of a model file (lookup table, pass tree, boosted trees).

    With `finite` (the default) NaN and Infinity are refused: ``json.loads`` accepts them, but
    in most model files a non-finite threshold, count or table entry is corruption, not data.
    (Boosted trees keep scikit-learn's infinite thresholds, so they read with ``finite=False``.)

    Raises:
        ModelFileError: The file is missing or not readable JSON; the message names the file
            and `what` it should have been.
    """
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
        return json.loads(text, parse_constant=_reject_constant) if finite else json.loads(text)
    except FileNotFoundError:
        raise ModelFileError(f"{path}: file not found") from None
    except (OSError, ValueError) as exc:  # JSON and Unicode decode errors are ValueErrors
        raise ModelFileError(f"{path}: not a readable {what} file ({exc})") from None
    except RecursionError:  # json parses nested arrays recursively
        raise ModelFileError(f"{path}: not a readable {what} file (nested too deeply)") from None


def _reject_constant(token: str) -> Any:
    raise ValueError(f"non-finite number {token}")


@dataclass(frozen=True, slots=True)
class FeatureSchema:
    """The interception features a model reads, as recorded in its file.

    Attributes:
        version: Schema version (:data:`SCHEMA_VERSION`).
        feature_names: Input column names with units (:data:`FEATURE_NAMES`).
        target_name: Output name with unit (:data:`TARGET_NAME`).
        distance_scale_m: Distances are divided by this before entering the model [m]; 1 means
            plain metres. See the module docstring (transfer between fields).
    """

    version: int = SCHEMA_VERSION
    feature_names: tuple[str, ...] = FEATURE_NAMES
    target_name: str = TARGET_NAME
    distance_scale_m: float = 1.0

    def __post_init__(self) -> None:
        check_distance_scale(self.distance_scale_m)

    def to_dict(self) -> dict[str, Any]:
        """The schema as plain JSON types."""
        return {
            "version": self.version,
            "feature_names": list(self.feature_names),
            "target_name": self.target_name,
            "distance_scale_m": self.distance_scale_m,
        }

    @classmethod
    def from_dict(cls, data: Mapping[str, Any]) -> FeatureSchema:
        """Read a schema written by :meth:`to_dict` and check it is the one this code reads.

        Raises:
            SchemaError: A key is missing, or the version, names or scale do not match.
        """
        missing = {"version", "feature_names", "target_name", "distance_scale_m"} - set(data)
        if missing:
            raise SchemaError(f"feature schema lacks {sorted(missing)}")
        if data["version"] != SCHEMA_VERSION:
            raise SchemaError(
                f"feature schema version {data['version']!r} does not match this code's "
                f"version {SCHEMA_VERSION}"
            )
        decision = decision_of(data["feature_names"], data["target_name"])
        scale = data["distance_scale_m"]
        if isinstance(scale, bool) or not isinstance(scale, int | float):
            raise SchemaError(f"distance_scale_m {scale!r} is not a number")
        return cls.for_decision(decision, float(scale))

    @classmethod
    def for_decision(cls, decision: str, distance_scale_m: float = 1.0) -> FeatureSchema:
        """The schema of a decision (:data:`DECISIONS`).

        Raises:
            SchemaError: An unknown decision.
        """
        if decision not in DECISIONS:
            raise SchemaError(f"unknown decision {decision!r} (known: {', '.join(DECISIONS)})")
        names, target = DECISIONS[decision]
        return cls(feature_names=names, target_name=target, distance_scale_m=distance_scale_m)

    @property
    def decision(self) -> str:
        """``"turn"`` (the paper's TA) or ``"lead"`` (:data:`DECISIONS`)."""
        return decision_of(self.feature_names, self.target_name)


def check_distance_scale(distance_scale_m: float) -> None:
    """Raise :class:`SchemaError` unless the distance scale is a finite number > 0 [m]."""
    if not (math.isfinite(distance_scale_m) and distance_scale_m > 0.0):
        raise SchemaError(f"distance_scale_m must be finite and > 0, got {distance_scale_m!r}")


def feature_row(
    ball_distance_m: float,
    ball_angle_rad: float,
    previous_ball_distance_m: float,
    distance_scale_m: float = 1.0,
) -> tuple[float, float, float]:
    """One interception feature row (BD, BA, previous BD), distances divided by the scale.

    Plain floats, for the control loop.

    Args:
        ball_distance_m: BD, the ball's distance now [m].
        ball_angle_rad: BA, the ball's direction from the heading, left positive [rad].
        previous_ball_distance_m: BD at the previous sighting [m].
        distance_scale_m: Divisor of both distances [m] (1: plain metres).

    Returns:
        The row in :data:`FEATURE_NAMES` order.

    >>> feature_row(14.0, 0.1, 15.5, distance_scale_m=2.0)
    (7.0, 0.1, 7.75)
    """
    return (
        ball_distance_m / distance_scale_m,
        ball_angle_rad,
        previous_ball_distance_m / distance_scale_m,
    )


def feature_matrix(
    ball_distance_m: npt.ArrayLike,
    ball_angle_rad: npt.ArrayLike,
    previous_ball_distance_m: npt.ArrayLike,
    distance_scale_m: float = 1.0,
) -> npt.NDArray[np.float64]:
    """Many feature rows at once: the batch form of :func:`feature_row`.

    Args:
        ball_distance_m: (N,) BD [m].
        ball_angle_rad: (N,) BA [rad].
        previous_ball_distance_m: (N,) previous BD [m].
        distance_scale_m: Divisor of both distances [m].

    Returns:
        (N, 3) float64 rows in :data:`FEATURE_NAMES` order.
    """
    columns = [
        np.asarray(ball_distance_m, dtype=np.float64).reshape(-1),
        np.asarray(ball_angle_rad, dtype=np.float64).reshape(-1),
        np.asarray(previous_ball_distance_m, dtype=np.float64).reshape(-1),
    ]
    if len({c.shape[0] for c in columns}) != 1:
        raise ValueError(f"feature columns differ in length: {[c.shape[0] for c in columns]}")
    return scale_distances(np.stack(columns, axis=1), distance_scale_m)


def scale_distances(x: npt.ArrayLike, distance_scale_m: float) -> npt.NDArray[np.float64]:
    """A float64 copy of (N, 3) feature rows with the distance columns divided by the scale [m]."""
    rows = np.array(x, dtype=np.float64)
    check_feature_rows(rows)
    if distance_scale_m != 1.0:
        rows[:, DISTANCE_COLUMNS] /= distance_scale_m
    return rows


def check_feature_rows(x: npt.NDArray[np.float64]) -> None:
    """Raise ValueError unless `x` is an (N, 3) array of finite numbers."""
    if x.ndim != 2 or x.shape[1] != len(FEATURE_NAMES):
        raise ValueError(f"feature rows must have shape (N, {len(FEATURE_NAMES)}), got {x.shape}")
    if not np.isfinite(x).all():
        raise ValueError("feature rows hold NaN or infinite values")
