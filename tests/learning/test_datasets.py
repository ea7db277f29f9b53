"""Interception datasets and the feature schema: round trips, refusals, subsets, joins."""

from __future__ import annotations

import dataclasses
import json
import math
from pathlib import Path

import numpy as np
import pytest

from learning.datasets import (
    DatasetError,
    InterceptionDataset,
    Provenance,
    concatenate,
    write_npz,
)
from learning.features import (
    FEATURE_NAMES,
    SCHEMA_VERSION,
    FeatureSchema,
    SchemaError,
    feature_matrix,
    feature_row,
)


def provenance(**changes: object) -> Provenance:
    base = Provenance(
        field_model="soccer_server",
        preset="rcss_1996",
        seed=7,
        ball_noise=0.05,
        behaviour="random_ta",
        n_trials=40,
        created_by="tests",
        extra={"ta_range_deg": 45, "range_m": 14.0, "note": "drill v0"},
    )
    return dataclasses.replace(base, **changes)  # type: ignore[arg-type]


def dataset(n: int = 10, seed: int = 0, **changes: object) -> InterceptionDataset:
    rng = np.random.default_rng(seed)
    bd = rng.uniform(5.0, 14.0, n)
    x = np.stack([bd, rng.uniform(-0.2, 0.2, n), bd + rng.uniform(0.5, 2.0, n)], axis=1)
    return InterceptionDataset(x, rng.uniform(-0.78, 0.78, n), provenance(**changes))


def meta(**changes: object) -> dict[str, object]:
    base: dict[str, object] = {
        "format": "robotsoccer/interception-dataset",
        "format_version": 1,
        "schema_version": SCHEMA_VERSION,
        "feature_names": list(FEATURE_NAMES),
        "target_name": "turn_angle_rad",
        "provenance": provenance().to_dict(),
    }
    return {**base, **changes}


# ----------------------------------------------------------------------------- features


def test_feature_row_divides_distances_by_the_scale() -> None:
    assert feature_row(14.0, -0.1, 15.5) == (14.0, -0.1, 15.5)
    assert feature_row(1.0, 0.3, 1.5, distance_scale_m=0.5) == (2.0, 0.3, 3.0)


def test_feature_matrix_matches_rows_and_checks_lengths() -> None:
    x = feature_matrix([10.0, 4.0], [0.1, -0.2], [12.0, 5.0], distance_scale_m=2.0)
    assert x.shape == (2, 3) and x.dtype == np.float64
    assert x.tolist() == [list(feature_row(10.0, 0.1, 12.0, 2.0)), [2.0, -0.2, 2.5]]
    with pytest.raises(ValueError, match="differ in length"):
        feature_matrix([1.0, 2.0], [0.0], [1.0, 2.0])


def test_schema_round_trip_and_mismatches() -> None:
    schema = FeatureSchema(distance_scale_m=105.0)
    assert FeatureSchema.from_dict(schema.to_dict()) == schema
    good = schema.to_dict()
    with pytest.raises(SchemaError, match="version 2 does not match"):
        FeatureSchema.from_dict({**good, "version": 2})
    with pytest.raises(SchemaError, match=r"'ball_angle_deg'.*are none of"):
        FeatureSchema.from_dict({**good, "feature_names": ["ball_distance_m", "ball_angle_deg"]})
    with pytest.raises(SchemaError, match="'turn_angle_deg' are none of"):
        FeatureSchema.from_dict({**good, "target_name": "turn_angle_deg"})
    with pytest.raises(SchemaError, match="'lead_time_s' are none of"):  # turn inputs, lead output
        FeatureSchema.from_dict({**good, "target_name": "lead_time_s"})
    with pytest.raises(SchemaError, match="lacks"):
        FeatureSchema.from_dict({"version": SCHEMA_VERSION})
    with pytest.raises(SchemaError, match="distance_scale_m"):
        FeatureSchema.from_dict({**good, "distance_scale_m": 0.0})
    with pytest.raises(SchemaError, match="distance_scale_m"):
        FeatureSchema(distance_scale_m=math.inf)


# ----------------------------------------------------------------------------- records


def test_dataset_owns_read_only_float64_copies() -> None:
    x = np.array([[10, 0, 11], [9, 0, 10]])
    y = np.array([0.1, -0.1])
    data = InterceptionDataset(x, y, provenance())
    x[0, 0] = 99
    assert data.x.dtype == np.float64 and data.x[0, 0] == 10.0 and len(data) == 2
    with pytest.raises(ValueError):
        data.x[0, 0] = 1.0


@pytest.mark.parametrize(
    ("x", "y", "message"),
    [
        (np.zeros((3, 2)), np.zeros(3), "shape"),
        (np.zeros((3, 3)), np.zeros(2), "targets must have shape"),
        (np.full((1, 3), np.nan), np.zeros(1), "NaN"),
        (np.zeros((1, 3)), np.array([np.inf]), "NaN or infinite"),
        (np.array([["a", "b", "c"]]), np.zeros(1), "numbers"),
    ],
)
def test_dataset_refuses_bad_arrays(x: np.ndarray, y: np.ndarray, message: str) -> None:
    with pytest.raises(DatasetError, match=message):
        InterceptionDataset(x, y, provenance())


def test_dataset_refuses_another_schema_version() -> None:
    with pytest.raises(DatasetError, match="schema version"):
        dataset(schema_version=SCHEMA_VERSION + 1)


# ----------------------------------------------------------------------------- files


def test_save_load_round_trip_is_exact(tmp_path: Path) -> None:
    data = dataset(25)
    path = data.save(tmp_path / "saves.npz")
    assert path == tmp_path / "saves.npz" and not list(tmp_path.glob("*.tmp"))
    back = InterceptionDataset.load(path)
    assert np.array_equal(back.x, data.x) and np.array_equal(back.y, data.y)
    assert back.provenance == data.provenance
    assert isinstance(back.provenance.extra["ta_range_deg"], int)


def test_save_keeps_the_name_as_given(tmp_path: Path) -> None:
    path = dataset().save(tmp_path / "saves.data")
    assert path.exists() and not (tmp_path / "saves.data.npz").exists()
    assert len(InterceptionDataset.load(path)) == 10


def _corrupt_files(tmp_path: Path) -> dict[str, Path]:
    good = dataset(50).save(tmp_path / "good.npz").read_bytes()
    files = {
        "truncated": good[: len(good) // 2],
        "garbage": bytes(range(256)) * 8,
        "empty": b"",
        "flipped": good[:200] + bytes(b ^ 0xFF for b in good[200:400]) + good[400:],
    }
    paths = {}
    for name, blob in files.items():
        paths[name] = tmp_path / f"{name}.npz"
        paths[name].write_bytes(blob)
    pickled = tmp_path / "pickled.npy"
    np.save(pickled, np.array([{"x": 1}], dtype=object), allow_pickle=True)
    paths["pickle"] = pickled
    return paths


@pytest.mark.parametrize("kind", ["truncated", "garbage", "empty", "flipped", "pickle"])
def test_corrupt_files_are_refused(tmp_path: Path, kind: str) -> None:
    path = _corrupt_files(tmp_path)[kind]
    with pytest.raises(DatasetError, match=path.name):
        InterceptionDataset.load(path)


def test_missing_file_is_refused(tmp_path: Path) -> None:
    with pytest.raises(DatasetError, match="not found"):
        InterceptionDataset.load(tmp_path / "nope.npz")


@pytest.mark.parametrize(
    ("changes", "message"),
    [
        ({"schema_version": SCHEMA_VERSION + 1}, "schema version"),
        ({"format": "robotsoccer/interception-net"}, "format tag"),
        ({"format_version": 99}, "format version"),
        ({"feature_names": ["ball_distance_m", "ball_angle_deg", "x"]}, "columns"),
        ({"provenance": None}, "provenance"),
        ({"provenance": {**provenance().to_dict(), "seed": "seven"}}, "'seed'"),
        ({"provenance": {**provenance().to_dict(), "colour": "red"}}, "unknown"),
        ({"provenance": {**provenance().to_dict(), "extra": {"a": [1]}}}, "extra"),
    ],
)
def test_mismatched_metadata_is_refused(
    tmp_path: Path, changes: dict[str, object], message: str
) -> None:
    path = write_npz(tmp_path / "d.npz", {"x": np.zeros((2, 3)), "y": np.zeros(2)}, meta(**changes))
    with pytest.raises(DatasetError, match=message):
        InterceptionDataset.load(path)


@pytest.mark.parametrize(
    ("arrays", "message"),
    [
        ({"x": np.zeros((2, 3))}, "missing"),
        ({"x": np.zeros((2, 4)), "y": np.zeros(2)}, "shape"),
        ({"x": np.zeros((2, 3)), "y": np.zeros(3)}, "targets must have shape"),
        ({"x": np.full((2, 3), np.nan), "y": np.zeros(2)}, "NaN"),
    ],
)
def test_wrong_arrays_are_refused(
    tmp_path: Path, arrays: dict[str, np.ndarray], message: str
) -> None:
    path = write_npz(tmp_path / "d.npz", arrays, meta())
    with pytest.raises(DatasetError, match=message):
        InterceptionDataset.load(path)


def test_non_finite_metadata_is_refused(tmp_path: Path) -> None:
    path = tmp_path / "d.npz"
    text = json.dumps(meta()).replace('"ball_noise": 0.05', '"ball_noise": NaN')
    assert "NaN" in text
    np.savez(path, metadata=np.array(text), x=np.zeros((2, 3)), y=np.zeros(2))
    with pytest.raises(DatasetError, match="non-finite"):
        InterceptionDataset.load(path)


# ----------------------------------------------------------------------------- subsets, joins


def test_subset_draws_distinct_rows_in_order_reproducibly() -> None:
    data = dataset(30)
    part = data.subset(12, np.random.default_rng(3))
    again = data.subset(12, np.random.default_rng(3))
    assert len(part) == 12 and np.array_equal(part.x, again.x)
    rows = [int(np.flatnonzero((data.x == r).all(axis=1))[0]) for r in part.x]
    assert rows == sorted(set(rows))
    assert np.array_equal(part.y, data.y[rows])
    assert part.provenance.extra["subset_of_n"] == 30
    assert part.provenance.seed == data.provenance.seed
    assert not np.array_equal(part.x, data.subset(12, np.random.default_rng(4)).x)
    with pytest.raises(DatasetError, match="cannot draw 31"):
        data.subset(31, np.random.default_rng(0))


def test_concatenate_sums_trials_and_merges_extra() -> None:
    a = dataset(4, seed=1)
    b = dataset(6, seed=2, n_trials=60, extra={"ta_range_deg": 45, "chunk": 2})
    both = concatenate([a, b])
    assert len(both) == 10
    assert np.array_equal(both.x, np.concatenate([a.x, b.x]))
    assert np.array_equal(both.y, np.concatenate([a.y, b.y]))
    assert both.provenance.n_trials == 100
    assert both.provenance.extra == {**a.provenance.extra, "chunk": 2}


def test_concatenate_refuses_different_provenance_unless_given() -> None:
    a, b = dataset(3), dataset(3, seed=1, ball_noise=0.1)
    with pytest.raises(DatasetError, match="ball_noise"):
        concatenate([a, b])
    with pytest.raises(DatasetError, match="extra 'note'"):
        concatenate([a, dataset(3, extra={"note": "other"})])
    with pytest.raises(DatasetError, match="zero"):
        concatenate([])
    mixed = provenance(behaviour="mixed", n_trials=80)
    assert concatenate([a, b], provenance=mixed).provenance == mixed


def test_the_lead_decisions_schema_and_dataset_round_trip(tmp_path) -> None:
    schema = FeatureSchema.for_decision("lead", distance_scale_m=0.026)
    assert schema.decision == "lead" and FeatureSchema().decision == "turn"
    assert FeatureSchema.from_dict(schema.to_dict()) == schema
    with pytest.raises(SchemaError, match="unknown decision"):
        FeatureSchema.for_decision("kick")
    rows = np.array([[0.5, 0.1, 0.52], [0.4, -0.2, 0.43]])
    provenance = Provenance("robot_physics", "small_size_1997_arc", 1, 0.05, "random_lead", 9)
    data = InterceptionDataset(rows, np.array([0.3, 0.2]), provenance, "lead")
    back = InterceptionDataset.load(data.save(tmp_path / "lead.npz"))
    assert back.decision == "lead" and np.array_equal(back.x, rows)
    assert (
        InterceptionDataset.load(
            InterceptionDataset(rows, np.array([0.1, 0.2]), provenance).save(tmp_path / "turn.npz")
        ).decision
        == "turn"
    )
