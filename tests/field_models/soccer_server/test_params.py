"""Soccer Server presets: values from the spec, degrees → radians, errors that name file and key."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from field_models.presets import PRESET_DIR, PresetError
from field_models.soccer_server.params import (
    DynamicsParams,
    ParamError,
    ServerPreset,
    load_server_preset,
)
from field_models.soccer_server.sensing_params import sensing_params_for_era

SHIPPED = PRESET_DIR / "soccer_server"


def test_both_presets_load_with_their_era() -> None:
    old = load_server_preset("soccer_server_1996")
    new = load_server_preset("rcssserver_19_async")
    assert isinstance(old, ServerPreset) and isinstance(old.dynamics, DynamicsParams)
    assert (old.name, old.era) == ("soccer_server_1996", "1996")
    assert (new.name, new.era) == ("rcssserver_19_async", "19")
    assert old.source.endswith("soccer_server_1996.toml")


def test_1996_preset_is_the_papers_server() -> None:
    d = load_server_preset("soccer_server_1996").dynamics
    assert d.ball_rand == 0.05 and d.noise_model == "box" and d.kick_rand == 0.0
    assert (d.ball_decay, d.kick_power_rate_m_per_cycle2, d.dash_power_rate_m_per_cycle2) == (
        0.96,
        0.016,
        0.01,
    )
    assert math.isinf(d.ball_accel_max_m_per_cycle2)
    assert d.kickable_area_m == pytest.approx(0.8 + 0.085 + 1.0)
    assert d.after_goal_wait_cycles == 0  # Figure 4: goal_l_1 and kick_off_r at time 150
    assert d.dt_s == pytest.approx(0.1)


def test_19_preset_is_todays_defaults() -> None:
    d = load_server_preset("rcssserver_19_async").dynamics
    assert d.noise_model == "polar" and d.kick_rand == 0.1 and d.kick_reduction
    assert (d.ball_decay, d.ball_accel_max_m_per_cycle2, d.ball_speed_max_m_per_cycle) == (
        0.94,
        2.7,
        3.0,
    )
    assert d.kickable_area_m == pytest.approx(1.085)
    assert (d.min_dash_power, d.max_dash_power) == (0.0, 100.0)
    assert d.after_goal_wait_cycles == 50
    assert (d.side_dash_rate, d.back_dash_rate) == (0.4, 0.7)
    assert d.dash_angle_step_rad == pytest.approx(math.radians(1.0))
    assert (d.min_dash_angle_rad, d.max_dash_angle_rad) == (-math.pi, math.pi)


def test_1996_preset_has_no_dash_direction() -> None:
    d = load_server_preset("soccer_server_1996").dynamics
    assert (d.min_dash_angle_rad, d.max_dash_angle_rad, d.dash_angle_step_rad) == (0.0, 0.0, 0.0)


def test_degrees_become_radians_once() -> None:
    for name in ("soccer_server_1996", "rcssserver_19_async"):
        preset = load_server_preset(name)
        assert preset.dynamics.maxmoment_rad == pytest.approx(math.pi)
        assert preset.dynamics.minmoment_rad == pytest.approx(-math.pi)
        assert preset.sensing.view_half_angle_rad == pytest.approx(math.pi / 4)


def test_sensing_tables_match_the_eras_values() -> None:
    assert load_server_preset("soccer_server_1996").sensing == sensing_params_for_era("1996")
    assert load_server_preset("rcssserver_19_async").sensing == sensing_params_for_era("19")
    assert load_server_preset("soccer_server_1996").sensing.send_step_ms == 250  # paper §5


def test_pitch_from_params() -> None:
    pitch = load_server_preset("rcssserver_19_async").dynamics.pitch()
    assert (pitch.length_m, pitch.width_m, pitch.goal_width_m) == (105.0, 68.0, 14.02)
    assert pitch.player_radius_m == 0.3 and pitch.ball_radius_m == 0.085
    assert pitch.goal_post_radius_m == 0.06  # the goal test's widening (§6)
    assert load_server_preset("soccer_server_1996").dynamics.pitch().goal_post_radius_m == 0.0


# ----------------------------------------------------------------------------- bad files


def _edited(tmp_path: Path, old: str, new: str, name: str = "rcssserver_19_async") -> Path:
    text = (SHIPPED / f"{name}.toml").read_text()
    assert old in text, old
    path = tmp_path / "bad.toml"
    path.write_text(text.replace(old, new, 1))
    return path


def _error(path: Path) -> str:
    with pytest.raises(PresetError) as info:
        load_server_preset(str(path))
    message = str(info.value)
    assert str(path) in message
    return message


def test_missing_key_names_file_and_key(tmp_path: Path) -> None:
    path = _edited(tmp_path, "ball_decay = 0.94\n", "")
    assert "dynamics.ball_decay" in _error(path)


def test_wrong_type_names_file_and_key(tmp_path: Path) -> None:
    path = _edited(tmp_path, "ball_decay = 0.94", 'ball_decay = "fast"')
    message = _error(path)
    assert "dynamics.ball_decay" in message and "number" in message


def test_negative_value_names_file_and_key(tmp_path: Path) -> None:
    path = _edited(tmp_path, "ball_rand = 0.05", "ball_rand = -0.05")
    message = _error(path)
    assert "dynamics.ball_rand" in message and ">= 0" in message


def test_bad_noise_model_names_key(tmp_path: Path) -> None:
    path = _edited(tmp_path, 'noise_model = "polar"', 'noise_model = "gauss"')
    message = _error(path)
    assert "key 'dynamics.noise_model': expected one of box, polar; got 'gauss'" in message


def test_degree_key_of_wrong_type_names_the_degree_key(tmp_path: Path) -> None:
    path = _edited(tmp_path, "maxmoment_deg = 180.0", 'maxmoment_deg = "half"')
    assert "dynamics.maxmoment_deg" in _error(path)


def test_degrees_and_radians_together_refused(tmp_path: Path) -> None:
    path = _edited(tmp_path, "maxmoment_deg = 180.0", "maxmoment_deg = 180.0\nmaxmoment_rad = 3.0")
    assert "dynamics.maxmoment_deg" in _error(path)


def test_unknown_key_refused(tmp_path: Path) -> None:
    path = _edited(tmp_path, "ball_rand = 0.05", "ball_rand = 0.05\nball_rnd = 0.1")
    assert "dynamics.ball_rnd" in _error(path)


def test_sensing_check_names_key(tmp_path: Path) -> None:
    path = _edited(tmp_path, 'direction_mode = "round"', 'direction_mode = "sideways"')
    message = _error(path)
    assert (
        "key 'sensing.direction_mode': expected one of truncate, round; got 'sideways'" in message
    )
    path = _edited(tmp_path, 'view_width = "normal"', "view_width = 1")
    assert "key 'sensing.view_width': expected one of narrow, normal, wide; got 1" in _error(path)


def test_missing_table_and_bad_era(tmp_path: Path) -> None:
    text = (SHIPPED / "rcssserver_19_async.toml").read_text()
    no_sensing = tmp_path / "no_sensing.toml"
    no_sensing.write_text(text.split("[sensing]")[0])
    assert "'sensing'" in _error(no_sensing)
    path = _edited(tmp_path, 'era = "19"', 'era = "2024"')
    assert "key 'era': expected one of 1996, 19; got '2024'" in _error(path)


def test_unknown_preset_name_lists_the_known_ones() -> None:
    with pytest.raises(PresetError, match="rcssserver_19_async"):
        load_server_preset("soccer_server_2042")


def test_record_checks_apply_to_replace() -> None:
    d = load_server_preset("rcssserver_19_async").dynamics
    with pytest.raises(ParamError, match="minpower"):
        d.replace(minpower=200.0)
    with pytest.raises(ParamError, match="min_dash_angle_rad"):
        d.replace(min_dash_angle_rad=1.0, max_dash_angle_rad=0.5)
    assert d.replace(ball_rand=0.0).ball_rand == 0.0


def test_dash_angles_in_degrees_and_their_order(tmp_path: Path) -> None:
    path = _edited(tmp_path, "max_dash_angle_deg = 180.0", "max_dash_angle_deg = -190.0")
    assert "key 'dynamics.min_dash_angle_rad': expected <= its maximum" in _error(path)
    path = _edited(tmp_path, "dash_angle_step_deg = 1.0", "dash_angle_step_deg = -1.0")
    assert "key 'dynamics.dash_angle_step_rad': expected a number >= 0" in _error(path)


def test_replace_sensing() -> None:
    preset = load_server_preset("rcssserver_19_async")
    perfect = preset.replace_sensing(perfect=True)
    assert perfect.sensing.perfect and not preset.sensing.perfect
    assert perfect.dynamics == preset.dynamics
