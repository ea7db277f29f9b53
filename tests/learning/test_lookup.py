"""The one-dimensional BA -> TA lookup table: hand-computed values, building, files."""

from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from learning.features import SCHEMA_VERSION, ModelFileError
from learning.lookup import PAPER_GRID_DEG, LookupTable

TABLE = LookupTable((-0.1, 0.0, 0.1), (0.2, 0.0, -0.4))


@pytest.mark.parametrize(
    ("ba_rad", "ta_rad"),
    [
        (-0.1, 0.2),  # grid points are exact
        (0.0, 0.0),
        (0.1, -0.4),
        (-0.05, 0.1),  # halfway between -0.1 -> 0.2 and 0 -> 0
        (0.025, -0.1),  # a quarter of the way from 0 -> 0 to 0.1 -> -0.4
        (0.075, -0.3),
        (-1.0, 0.2),  # clamped below the grid
        (0.5, -0.4),  # clamped above the grid
    ],
)
def test_hand_computed_turn_angles(ba_rad: float, ta_rad: float) -> None:
    assert TABLE(ba_rad) == pytest.approx(ta_rad, abs=1e-15)
    assert TABLE.predict([ba_rad])[0] == pytest.approx(ta_rad, abs=1e-15)


def test_nan_stays_nan_and_batch_equals_calls() -> None:
    assert math.isnan(TABLE(math.nan))
    angles = np.linspace(-0.3, 0.3, 61)
    assert np.allclose(TABLE.predict(angles), [TABLE(a) for a in angles], rtol=0, atol=1e-15)


@pytest.mark.parametrize(
    ("angles", "turns", "message"),
    [
        ((0.0,), (0.0,), ">= 2"),
        ((0.0, 0.1), (0.0,), ">= 2"),
        ((0.1, 0.0), (0.0, 0.0), "strictly increasing"),
        ((0.0, 0.0), (0.0, 0.0), "strictly increasing"),
        ((0.0, math.nan), (0.0, 0.0), "finite"),
    ],
)
def test_malformed_grids_are_refused(
    angles: tuple[float, ...], turns: tuple[float, ...], message: str
) -> None:
    with pytest.raises(ValueError, match=message):
        LookupTable(angles, turns)


def _net_like(bd: float, ba: float, prev_bd: float) -> float:
    return -2.0 * ba + 0.01 * (bd - prev_bd)


def test_from_model_at_one_condition_tabulates_minus_7_to_7_degrees() -> None:
    table = LookupTable.from_model(_net_like, ball_distance_m=10.0, previous_ball_distance_m=11.0)
    assert len(table.ball_angle_rad) == 15 == len(PAPER_GRID_DEG)
    assert table.ball_angle_rad[0] == math.radians(-7)
    assert table.ball_angle_rad[-1] == math.radians(7)
    for deg, ba, ta in zip(PAPER_GRID_DEG, table.ball_angle_rad, table.turn_angle_rad, strict=True):
        assert ba == pytest.approx(math.radians(deg), abs=1e-15)
        assert ta == pytest.approx(-2.0 * math.radians(deg) - 0.01, abs=1e-15)
    assert table(math.radians(2.5)) == pytest.approx(-2.0 * math.radians(2.5) - 0.01, abs=1e-12)
    assert table.built_from["n_conditions"] == 1
    assert table.built_from["ball_distance_median_m"] == 10.0


def test_from_model_takes_the_median_over_conditions() -> None:
    # f = BA * BD over BD in {1, 2, 10}: the median is 2 * BA for either sign of BA.
    table = LookupTable.from_model(
        lambda bd, ba, prev: ba * bd,
        ba_deg=[3, -5],  # unsorted on purpose
        ball_distance_m=[1.0, 10.0, 2.0],
        previous_ball_distance_m=[0.0, 0.0, 0.0],
        built_from={"model": "net.npz"},
    )
    assert table.ball_angle_rad == (math.radians(-5), math.radians(3))
    assert table.turn_angle_rad == pytest.approx((2 * math.radians(-5), 2 * math.radians(3)))
    assert table.built_from == {
        "statistic": "median",
        "n_conditions": 3,
        "ball_distance_median_m": 2.0,
        "previous_ball_distance_median_m": 0.0,
        "model": "net.npz",
    }


def test_from_model_refuses_unpaired_distances() -> None:
    with pytest.raises(ValueError, match="matching"):
        LookupTable.from_model(
            _net_like, ball_distance_m=[1.0, 2.0], previous_ball_distance_m=[1.0]
        )


def test_lookup_and_the_package_do_not_import_torch() -> None:
    # The table and the analytic predictor are cheap behaviours: no 2.5 s torch import for them.
    code = "import sys, learning, learning.lookup, learning.analytic; print('torch' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


# ----------------------------------------------------------------------------- files


def test_save_load_round_trip_is_exact(tmp_path: Path) -> None:
    table = LookupTable.from_model(_net_like, ball_distance_m=9.3, previous_ball_distance_m=10.7)
    path = table.save(tmp_path / "table.json")
    back = LookupTable.load(path)
    assert back == table
    assert back.ball_angle_rad == table.ball_angle_rad
    assert back.turn_angle_rad == table.turn_angle_rad


def _doc(**changes: object) -> dict[str, object]:
    doc: dict[str, object] = {
        "format": "robotsoccer/interception-lookup",
        "format_version": 1,
        "schema_version": SCHEMA_VERSION,
        "input_name": "ball_angle_rad",
        "target_name": "turn_angle_rad",
        "ball_angle_rad": [-0.1, 0.1],
        "turn_angle_rad": [0.2, -0.2],
        "built_from": {},
    }
    return {**doc, **changes}


def test_hand_written_file_loads(tmp_path: Path) -> None:
    path = tmp_path / "t.json"
    path.write_text(json.dumps(_doc()))
    assert LookupTable.load(path)(0.0) == 0.0


@pytest.mark.parametrize(
    ("text", "message"),
    [
        (json.dumps(_doc(schema_version=SCHEMA_VERSION + 1)), "schema version"),
        (json.dumps(_doc(format="robotsoccer/interception-net")), "format tag"),
        (json.dumps(_doc(format_version=2)), "format version"),
        (json.dumps(_doc(target_name="turn_angle_deg")), "turn_angle_deg"),
        (json.dumps(_doc(ball_angle_rad=[0.1, -0.1])), "strictly increasing"),
        (json.dumps(_doc(ball_angle_rad=[0.1])), ">= 2"),
        (json.dumps(_doc(turn_angle_rad=["a", 0.0])), "only numbers"),
        (json.dumps(_doc(turn_angle_rad=None)), "must be lists"),
        (json.dumps(_doc(built_from={"a": [1]})), "built_from"),
        (json.dumps(_doc()).replace("0.2", "NaN"), "non-finite"),
        (json.dumps(_doc())[:40], "not a readable"),
        ("[1, 2, 3]", "not a lookup table"),
    ],
)
def test_corrupt_or_mismatched_files_are_refused(tmp_path: Path, text: str, message: str) -> None:
    path = tmp_path / "t.json"
    path.write_text(text)
    with pytest.raises(ModelFileError, match=message):
        LookupTable.load(path)


def test_binary_garbage_and_missing_files_are_refused(tmp_path: Path) -> None:
    path = tmp_path / "t.json"
    path.write_bytes(bytes(range(128, 256)))
    with pytest.raises(ModelFileError, match="not a readable"):
        LookupTable.load(path)
    with pytest.raises(ModelFileError, match="not found"):
        LookupTable.load(tmp_path / "none.json")
