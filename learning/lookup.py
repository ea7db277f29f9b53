"""The one-dimensional lookup table BA -> TA built from the interception net (paper §5, Table 1).

The paper noticed the net "focusses primarily upon the Ball's angle (BA)" and tried "a lookup
table mapping BA to the typical output of the NN for that BA ... for BA's ranging from -7 to 7"
(degrees); the defender did almost as well with it as with the net (Table 1).

Here the table holds grid angles in radians (left positive) and the turn angle at each.
:meth:`LookupTable.from_model` defines "typical output" as the **median** of the net's outputs
over a set of (BD, previous BD) conditions with BA set to the grid angle; pass the training saves'
BD and previous BD columns to get the typical output over the situations the net was trained on,
or single values (e.g. their medians) to read the net at one point.

Between grid angles the table interpolates linearly; outside the grid it holds the end values
(clamping: beyond ±7° the net was not tabulated, and the nearest entry is the best guess that
cannot run away). Tables are saved as JSON and refused with
:class:`~learning.features.ModelFileError` when corrupt or for another feature schema.
"""

from __future__ import annotations

import bisect
import itertools
import json
import math
import os
from collections.abc import Callable, Iterable, Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from learning.features import SCHEMA_VERSION, TARGET_NAME, ModelFileError, read_model_json

LOOKUP_FORMAT = "robotsoccer/interception-lookup"
"""Format tag stored in every lookup-table file."""

LOOKUP_FORMAT_VERSION = 1
"""Version of the file layout."""

PAPER_GRID_DEG = range(-7, 8)
"""The paper's grid: BA from -7 to 7 degrees, every degree."""

Note = str | float | int
"""Value types of :attr:`LookupTable.built_from` (JSON scalars)."""


class LookupTable:
    """A piecewise-linear map BA [rad] -> TA [rad], clamped to its end values outside the grid.

    Args:
        ball_angle_rad: Grid angles, strictly increasing, at least two [rad, left positive].
        turn_angle_rad: Turn angle at each grid angle [rad, left positive].
        built_from: Scalars describing how the table was made (stored in its file).

    Raises:
        ValueError: The grid is not strictly increasing, too short, of a different length than
            the values, or holds non-finite numbers.
    """

    def __init__(
        self,
        ball_angle_rad: Iterable[float],
        turn_angle_rad: Iterable[float],
        built_from: Mapping[str, Note] | None = None,
    ) -> None:
        self.ball_angle_rad = tuple(float(a) for a in ball_angle_rad)
        self.turn_angle_rad = tuple(float(t) for t in turn_angle_rad)
        self.built_from: dict[str, Note] = dict(built_from or {})
        _check_grid(self.ball_angle_rad, self.turn_angle_rad)

    def __repr__(self) -> str:
        return f"LookupTable({len(self.ball_angle_rad)} angles, built_from={self.built_from!r})"

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, LookupTable):
            return NotImplemented
        mine = (self.ball_angle_rad, self.turn_angle_rad, self.built_from)
        return mine == (other.ball_angle_rad, other.turn_angle_rad, other.built_from)

    __hash__ = None  # type: ignore[assignment]  # built_from is a mutable dict

    @classmethod
    def from_model(
        cls,
        fn: Callable[[float, float, float], float],
        ba_deg: Iterable[float] = PAPER_GRID_DEG,
        *,
        ball_distance_m: float | Sequence[float],
        previous_ball_distance_m: float | Sequence[float],
        built_from: Mapping[str, Note] | None = None,
    ) -> LookupTable:
        """Tabulate a turn-angle function over BA: each entry is its median over the conditions.

        Args:
            fn: ``f(BD [m], BA [rad], previous BD [m]) -> TA [rad]``, e.g.
                :meth:`learning.interception.InterceptionModel.as_function`.
            ba_deg: Grid of ball angles [deg] (the paper's -7..7); converted to radians.
            ball_distance_m: One BD, or the BD of each condition (e.g. the training saves') [m].
            previous_ball_distance_m: The previous BD, one value or one per condition [m].
            built_from: Extra scalars recorded in :attr:`built_from`.

        Returns:
            The table; :attr:`built_from` records the statistic, the number of conditions and
            the median BD and previous BD.
        """
        bd = np.atleast_1d(np.asarray(ball_distance_m, dtype=np.float64))
        prev = np.atleast_1d(np.asarray(previous_ball_distance_m, dtype=np.float64))
        if bd.ndim != 1 or bd.shape != prev.shape or bd.size == 0:
            raise ValueError(f"need matching 1-D distances, got {bd.shape} and {prev.shape}")
        angles = sorted(math.radians(a) for a in ba_deg)
        conditions = list(zip(bd.tolist(), prev.tolist(), strict=True))
        turns = [float(np.median([fn(d, a, p) for d, p in conditions])) for a in angles]
        notes: dict[str, Note] = {
            "statistic": "median",
            "n_conditions": len(conditions),
            "ball_distance_median_m": float(np.median(bd)),
            "previous_ball_distance_median_m": float(np.median(prev)),
            **(built_from or {}),
        }
        return cls(angles, turns, notes)

    def __call__(self, ball_angle_rad: float) -> float:
        """TA [rad] for one BA [rad]: linear between grid angles, end values outside, NaN kept."""
        if ball_angle_rad != ball_angle_rad:  # NaN: as np.interp, never a made-up turn
            return math.nan
        grid, values = self.ball_angle_rad, self.turn_angle_rad
        i = bisect.bisect_right(grid, ball_angle_rad)
        if i == 0:
            return values[0]
        if i == len(grid):
            return values[-1]
        a0, a1 = grid[i - 1], grid[i]
        t = (ball_angle_rad - a0) / (a1 - a0)
        return values[i - 1] + t * (values[i] - values[i - 1])

    def predict(self, ball_angle_rad: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """TA [rad] for an array of BA [rad]: the batch form of calling the table.

        The same operations as :meth:`__call__` element by element (not ``np.interp``, whose
        formula differs in the last bit), so a trial gives the same TA alone or in a batch.
        """
        ba = np.asarray(ball_angle_rad, dtype=np.float64)
        grid = np.asarray(self.ball_angle_rad)
        values = np.asarray(self.turn_angle_rad)
        i = np.searchsorted(grid, ba, side="right")  # bisect_right
        j = np.clip(i, 1, len(grid) - 1)
        a0, a1, v0, v1 = grid[j - 1], grid[j], values[j - 1], values[j]
        with np.errstate(invalid="ignore"):
            inner = v0 + (ba - a0) / (a1 - a0) * (v1 - v0)
        out = np.where(i == 0, values[0], np.where(i == len(grid), values[-1], inner))
        return np.where(np.isnan(ba), np.nan, out)

    def save(self, path: str | os.PathLike[str]) -> Path:
        """Write the table as JSON to `path` (floats round-trip exactly).

        Returns:
            The path written.
        """
        doc = {
            "format": LOOKUP_FORMAT,
            "format_version": LOOKUP_FORMAT_VERSION,
            "schema_version": SCHEMA_VERSION,
            "input_name": "ball_angle_rad",
            "target_name": TARGET_NAME,
            "ball_angle_rad": list(self.ball_angle_rad),
            "turn_angle_rad": list(self.turn_angle_rad),
            "built_from": self.built_from,
        }
        path = Path(path)
        tmp = path.with_name(path.name + ".tmp")
        tmp.write_text(json.dumps(doc, indent=1, allow_nan=False) + "\n", encoding="utf-8")
        os.replace(tmp, path)
        return path

    @classmethod
    def load(cls, path: str | os.PathLike[str]) -> LookupTable:
        """Read a table written by :meth:`save`.

        Raises:
            ModelFileError: The file is missing, not JSON, not a lookup table, for another
                feature schema, or its grid is malformed.
        """
        path = Path(path)
        doc = read_model_json(path, "lookup-table")
        try:
            return cls._from_doc(doc)
        except (ModelFileError, ValueError) as exc:
            raise ModelFileError(f"{path}: {exc}") from None

    @classmethod
    def _from_doc(cls, doc: Any) -> LookupTable:
        if not isinstance(doc, dict) or doc.get("format") != LOOKUP_FORMAT:
            raise ModelFileError(f"not a lookup table (format tag is not {LOOKUP_FORMAT!r})")
        if doc.get("format_version") != LOOKUP_FORMAT_VERSION:
            raise ModelFileError(f"unsupported lookup format version {doc.get('format_version')!r}")
        if doc.get("schema_version") != SCHEMA_VERSION:
            raise ModelFileError(
                f"feature schema version {doc.get('schema_version')!r} does not match this "
                f"code's version {SCHEMA_VERSION}"
            )
        if doc.get("input_name") != "ball_angle_rad" or doc.get("target_name") != TARGET_NAME:
            raise ModelFileError(
                f"maps {doc.get('input_name')!r} -> {doc.get('target_name')!r}, "
                f"not 'ball_angle_rad' -> {TARGET_NAME!r}"
            )
        angles, turns = doc.get("ball_angle_rad"), doc.get("turn_angle_rad")
        if not (isinstance(angles, list) and isinstance(turns, list)):
            raise ModelFileError("ball_angle_rad and turn_angle_rad must be lists")
        if not all(_is_number(v) for v in (*angles, *turns)):
            raise ModelFileError("ball_angle_rad and turn_angle_rad must hold only numbers")
        notes = doc.get("built_from")
        if not isinstance(notes, dict) or not all(_is_note(v) for v in notes.values()):
            raise ModelFileError("built_from must map names to strings or numbers")
        return cls(angles, turns, notes)


def _check_grid(angles: Sequence[float], turns: Sequence[float]) -> None:
    if len(angles) < 2 or len(angles) != len(turns):
        raise ValueError(f"need >= 2 grid angles and as many values: {len(angles)}, {len(turns)}")
    if not all(math.isfinite(v) for v in (*angles, *turns)):
        raise ValueError("grid angles and values must be finite")
    if any(b <= a for a, b in itertools.pairwise(angles)):
        raise ValueError("grid angles must be strictly increasing")


def _is_number(value: object) -> bool:
    return isinstance(value, int | float) and not isinstance(value, bool)


def _is_note(value: object) -> bool:
    return isinstance(value, str | int | float) and not isinstance(value, bool)
