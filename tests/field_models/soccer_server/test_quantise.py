"""Soccer Server distance quantisation, changes and the sensing parameter record (spec §3.3-3.4)."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from field_models.presets import PresetError, load_record
from field_models.protocol import PlayerRef
from field_models.soccer_server.params import load_server_preset
from field_models.soccer_server.see_numbers import far_probability, quantize, quantize_distance
from field_models.soccer_server.sensing import Bodies, observe
from field_models.soccer_server.sensing_params import (
    SENSING_19,
    SENSING_1996,
    SensingParams,
    sensing_params_for_era,
    sensing_table,
)

# spec §8.8: true distance -> (ball or player, flag)
SPEC_TABLE = [
    (1.0, 1.0, 1.0),
    (3.0, 3.0, 3.0),
    (9.5, 10.0, 9.5),
    (11.18, 11.0, 11.1),
    (20.0, 20.1, 20.1),
    (30.0, 30.0, 30.0),
    (50.0, 49.4, 49.9),
    (80.0, 81.5, 79.8),
    (100.0, 99.5, 100.5),
]


@pytest.mark.parametrize(("d", "movable", "landmark"), SPEC_TABLE)
def test_spec_quantisation_table_exactly(d: float, movable: float, landmark: float) -> None:
    assert quantize_distance(d, 0.1) == movable
    assert quantize_distance(d, 0.01) == landmark


def test_worked_examples_of_the_brief() -> None:
    assert (quantize_distance(11.18, 0.1), quantize_distance(11.18, 0.01)) == (11.0, 11.1)
    assert (quantize_distance(50.0, 0.1), quantize_distance(50.0, 0.01)) == (49.4, 49.9)
    assert (quantize_distance(9.5, 0.1), quantize_distance(9.5, 0.01)) == (10.0, 9.5)
    assert (quantize_distance(80.0, 0.1), quantize_distance(80.0, 0.01)) == (81.5, 79.8)


def test_quantised_values_are_the_printed_decimals() -> None:
    # The double must be the one float("%g") gives back, so text round-trips are exact.
    for d in np.linspace(0.05, 130.0, 2000).tolist():
        for q in (0.1, 0.01):
            v = quantize_distance(d, q)
            assert float(f"{v:g}") == v
            assert abs(v * 10 - round(v * 10)) < 1e-9


def test_quantize_rounds_half_to_even_like_rint() -> None:
    assert quantize(0.5, 1.0) == 0.0
    assert quantize(1.5, 1.0) == 2.0
    assert quantize(-2.5, 1.0) == -2.0
    assert quantize(0.26, 0.1) == pytest.approx(0.3)


@settings(max_examples=300, deadline=None)
@given(st.floats(0.2, 150.0))
def test_movable_quantisation_error_is_about_five_percent(d: float) -> None:
    qd = quantize_distance(d, 0.1)
    # log step 0.1 -> at most a factor exp(0.05), then 0.05 m from the final rounding.
    assert abs(qd - d) <= d * (math.exp(0.05) - 1.0) + 0.05 + 1e-9
    ql = quantize_distance(d, 0.01)
    assert abs(ql - d) <= d * (math.exp(0.005) - 1.0) + 0.05 + 1e-9


def test_far_probability_is_linear_and_a_step_for_equal_lengths() -> None:
    assert far_probability(10.0, 20.0, 40.0) == 0.0
    assert far_probability(20.0, 20.0, 40.0) == 0.0
    assert far_probability(30.0, 20.0, 40.0) == pytest.approx(0.5)
    assert far_probability(40.0, 20.0, 40.0) == 1.0
    assert far_probability(125.1, 125.1, 125.1) == 0.0
    assert far_probability(125.2, 125.1, 125.1) == 1.0


def _see_ball(bx: float, by: float, bvx: float, bvy: float) -> tuple[float | None, float | None]:
    """Distance and direction change of a ball seen from the origin facing +x."""
    players = (PlayerRef("left", 1),)
    info = observe(
        1,
        Bodies([bx, 0.0], [by, 0.0], [bvx, 0.0], [bvy, 0.0], [0.0, 0.0]),
        players,
        0,
        SENSING_19,
        np.random.default_rng(0),
        landmarks="none",
    )
    ball = info.find("b")
    assert ball is not None
    return ball.dist_change, ball.dir_change


def test_distance_change_of_an_approaching_ball() -> None:
    # 10 m ahead (reported 10.0), closing at 1 m/cycle: Q(-1/10, 0.02) * 10.0 = -1.0.
    assert _see_ball(10.0, 0.0, -1.0, 0.0) == (-1.0, 0.0)
    # Receding at 0.33 m/cycle: Q(0.033, 0.02) = 0.04 -> 0.4.
    assert _see_ball(10.0, 0.0, 0.33, 0.0) == (0.4, 0.0)


def test_direction_change_has_the_server_sign() -> None:
    # Ball 10 m ahead moving up (+y, our CCW = to the player's left) at 0.5 m/cycle:
    # 0.05 rad/cycle = 2.865 deg/cycle CCW; the server's y is down, so it reports -2.9.
    dist_chg, dir_chg = _see_ball(10.0, 0.0, 0.0, 0.5)
    assert dir_chg == -2.9
    assert dist_chg == 0.0


def test_era_values_load_through_the_preset_loader() -> None:
    for era in ("1996", "19"):
        params = sensing_params_for_era(era)
        assert load_record(SensingParams, sensing_table(params), file="mem.toml") == params
    assert SENSING_1996.see_interval_ms == 250
    assert SENSING_19.see_interval_ms == 150
    assert SENSING_19.half_angle_rad == pytest.approx(math.radians(45.0))
    assert SENSING_19.replace(view_width="wide").half_angle_rad == pytest.approx(math.pi / 2)
    assert SENSING_19.replace(view_width="narrow", view_quality="low").see_interval_ms == 37.5


def test_bad_sensing_values_are_refused_with_the_key() -> None:
    table = sensing_table(SENSING_19)
    with pytest.raises(PresetError, match=r"sensing\.quantize_step"):
        load_record(SensingParams, {**table, "quantize_step": -0.1}, file="x.toml", key="sensing")
    with pytest.raises(PresetError, match=r"sensing\.say_msg_size"):
        load_record(SensingParams, {**table, "say_msg_size": "10"}, file="x.toml", key="sensing")
    with pytest.raises(
        PresetError, match=r"sensing\.direction_mode': expected one of truncate, round; got 'floor'"
    ):
        load_record(
            SensingParams, {**table, "direction_mode": "floor"}, file="x.toml", key="sensing"
        )
    with pytest.raises(PresetError, match=r"x\.toml: key 'sensing\.landmark_set': expected one of"):
        load_record(SensingParams, {**table, "landmark_set": "1997"}, file="x.toml", key="sensing")
    with pytest.raises(PresetError, match=r"sensing\.view_width': expected one of narrow, normal"):
        load_record(SensingParams, {**table, "view_width": 2}, file="x.toml", key="sensing")
    with pytest.raises(ValueError, match="team_too_far"):
        dataclasses.replace(SENSING_19, team_too_far_length_m=10.0)


def test_shipped_presets_carry_these_sensing_values() -> None:
    assert load_server_preset("rcssserver_19_async").sensing == SENSING_19
    assert load_server_preset("soccer_server_1996").sensing == SENSING_1996
