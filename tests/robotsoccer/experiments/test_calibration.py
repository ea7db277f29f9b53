"""Calibration: the fits are exact on their own laws, and recover a Soccer Server's parameters."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from field_models.registry import field_facts
from robotsoccer.experiments.calibration import gap_share
from robotsoccer.experiments.calibration_fit import (
    CYCLES_PER_SEE,
    calibrate,
    fit_dash,
    fit_geometric_decay,
    fit_quantize_step,
)
from robotsoccer.experiments.calibration_preset import preset_text, write_preset
from robotsoccer.experiments.calibration_traces import Traces, record_traces
from robotsoccer.runs.runner import TrialResult

KNOWN = {"ball_decay": 0.93, "player_decay": 0.55, "dash_power_rate": 0.007}


def server_preset(folder: Path) -> Path:
    """A Soccer Server preset with known dynamics, a see every two cycles and no motion noise."""
    path = folder / "known.toml"
    path.write_text(
        'base = "soccer_server_1996"\n\n[dynamics]\n'
        f"ball_decay = {KNOWN['ball_decay']}\nplayer_decay = {KNOWN['player_decay']}\n"
        f"dash_power_rate_m_per_cycle2 = {KNOWN['dash_power_rate']}\nplayer_rand = 0.0\n\n"
        f"[sensing]\nsend_step_ms = {100 * CYCLES_PER_SEE}\n"
    )
    return path


def test_the_decay_fit_is_exact_on_geometric_rolls() -> None:
    rolls = [[v * 0.9**n for n in range(30)] for v in (1.0, 2.5)]
    assert fit_geometric_decay(rolls) == pytest.approx(0.9, rel=1e-12)
    stopped = [[*rolls[0][:10], 0.0, 0.0, 0.0]]  # a stopped ball's zeros are left out
    assert fit_geometric_decay(stopped, floor=1e-9) == pytest.approx(0.9, rel=1e-12)
    with pytest.raises(ValueError, match="no speeds above the floor"):
        fit_geometric_decay([[0.0, 0.0]], floor=0.0)


def test_the_dash_fit_is_exact_on_the_servers_law() -> None:
    v, speeds = 0.0, []
    for _ in range(25):
        v = 0.4 * (v + 0.01 * 100.0)
        speeds.append(v)
    decay, rate, rms = fit_dash(speeds, 100.0)
    assert decay == pytest.approx(0.4, rel=1e-9)
    assert rate == pytest.approx(0.01, rel=1e-9)
    assert rms < 1e-12
    with pytest.raises(ValueError, match="at least three speeds"):
        fit_dash([0.1, 0.2], 100.0)


def test_the_quantize_fit_gives_the_step_of_a_uniform_rounding_error() -> None:
    errors = np.random.default_rng(0).uniform(-0.05, 0.05, 200_000)
    assert fit_quantize_step(list(errors)) == pytest.approx(0.1, rel=0.01)
    with pytest.raises(ValueError, match="at least two percepts"):
        fit_quantize_step([0.1])


def test_the_fit_recovers_a_soccer_servers_own_parameters(tmp_path: Path) -> None:
    """Closed form: traces of the server model with known parameters give them back."""
    preset = str(server_preset(tmp_path))
    traces = record_traces("soccer_server", preset, (10.0, 20.0, 30.0), seed=3)
    cal = calibrate(traces, field_facts("soccer_server", preset))
    assert cal.cycle_ticks == 1 and cal.cycle_ms == 100
    assert cal.ball_decay == pytest.approx(KNOWN["ball_decay"], rel=1e-9)
    assert cal.player_decay == pytest.approx(KNOWN["player_decay"], rel=1e-9)
    assert cal.dash_power_rate == pytest.approx(KNOWN["dash_power_rate"], rel=1e-9)
    assert cal.ball_rms < 1e-9 and cal.dash_rms < 1e-9
    assert cal.latency_s == 0.0
    assert cal.geometry["goal_width_m"] == pytest.approx(14.02)
    # The written preset loads, and says it was fitted and from what.
    written = write_preset(
        cal, tmp_path / "out" / "calibrated.toml", "soccer_server_1996", "a test"
    )
    text = written.read_text()
    assert "FITTED" in text and "seed 3" in text and "a test" in text
    facts = field_facts("soccer_server", str(written))
    assert facts.dt_s == pytest.approx(0.1)
    assert facts.sensor_period_s == pytest.approx(0.1 * CYCLES_PER_SEE)
    assert facts.ball.decay_per_tick == pytest.approx(KNOWN["ball_decay"], rel=1e-5)


def test_robot_traces_give_a_preset_at_the_cameras_rate(tmp_path: Path) -> None:
    preset = "small_size_1997_arc"
    facts = field_facts("robot_physics", preset)
    speeds = (0.6 / facts.unit_m, 1.2 / facts.unit_m)
    traces = record_traces("robot_physics", preset, speeds, seed=1)
    again = record_traces("robot_physics", preset, speeds, seed=1)
    assert traces == again  # deterministic by seed
    cal = calibrate(traces, facts)
    assert cal.cycle_ticks * CYCLES_PER_SEE * facts.dt_s == pytest.approx(facts.sensor_period_s)
    assert cal.latency_s == pytest.approx(facts.sensor_latency_s)
    # The table's ball loses 0.1 m/s per second: about 1% of a 0.9 m/s ball's speed in 0.1 s.
    per_100ms = cal.ball_decay ** (0.1 / (cal.cycle_ticks * facts.dt_s))
    assert 0.97 < per_100ms < 1.0
    top = cal.player_speed_max / (cal.cycle_ticks * facts.dt_s) * facts.unit_m
    assert top == pytest.approx(facts.player_top_speed_mps, rel=0.02)
    assert 0.0 < cal.quantize_step < 0.1
    loaded = field_facts(
        "soccer_server", str(write_preset(cal, tmp_path / "c.toml", "soccer_server_1996", "t"))
    )
    assert loaded.pitch.goal_width_m == pytest.approx(facts.pitch.goal_width_m / facts.unit_m)
    assert "not covered" in preset_text(cal, "soccer_server_1996", "t").lower()


def test_bad_input_is_refused_in_one_line() -> None:
    with pytest.raises(ValueError, match="launch speeds must be positive"):
        record_traces("soccer_server", "soccer_server_1996", (), seed=0)
    empty = Traces("x", "y", 0, 1.0, 0.1, ((1.0, 0.9),), (1.0,), (1.0,) * 5, (4,), (0,), (0.0,))
    with pytest.raises(ValueError, match="fewer than two percepts"):
        calibrate(empty, field_facts("soccer_server"))


def _trials(saves: list[bool]) -> list[TrialResult]:
    return [
        TrialResult(i, "SAVE" if s else "GOAL", "", 1, 0.1, (), ()) for i, s in enumerate(saves)
    ]


def test_the_share_of_the_gap_closed_is_paired_and_bounded() -> None:
    n = 200
    uncalibrated = _trials([False] * n)
    native = _trials([True] * n)
    calibrated = _trials([i % 2 == 0 for i in range(n)])
    found = gap_share(uncalibrated, calibrated, native, seed=0)
    assert found is not None
    share, low, high = found
    assert share == pytest.approx(0.5) and low < 0.5 < high and low > 0.3 and high < 0.7
    assert gap_share(uncalibrated, calibrated, uncalibrated, seed=0) is None  # no gap
    assert gap_share(native, calibrated, uncalibrated, seed=0) is None  # the moved net better
    assert gap_share(uncalibrated, calibrated, native, seed=0) == found  # seeded
    assert math.isfinite(share)
