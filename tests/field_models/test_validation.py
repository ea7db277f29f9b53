"""Every physical parameter is checked at load: finite, signed and in a sane range (issue 30).

A value out of range is refused in one line naming the file and the key, before it can reach
Chipmunk's C asserts, a cast of NaN to an integer or a loop that never ends.
"""

from __future__ import annotations

import dataclasses
import math
import typing
from pathlib import Path
from typing import Any

import pytest

from field_models.arena import FieldOptions
from field_models.presets import MAX_PRESET_BYTES, PresetError, RecordError, bounds_of
from field_models.robot_physics.config import RobotPhysicsPreset, load_preset
from field_models.soccer_server import server_conf
from field_models.soccer_server.params import ServerPreset, load_server_preset


def _records(root: type) -> list[type]:
    """`root` and every record type nested in it."""
    found: list[type] = []
    todo = [root]
    while todo:
        cls = todo.pop()
        if cls in found:
            continue
        found.append(cls)
        for hint in typing.get_type_hints(cls).values():
            for arg in (hint, *typing.get_args(hint)):
                if dataclasses.is_dataclass(arg) and isinstance(arg, type):
                    todo.append(arg)
    return found


@pytest.mark.parametrize("root", [RobotPhysicsPreset, ServerPreset])
def test_every_number_of_a_preset_states_its_range(root: type) -> None:
    for cls in _records(root):
        hints = typing.get_type_hints(cls)
        for fld in dataclasses.fields(cls):
            if hints[fld.name] in (int, float):
                assert bounds_of(fld) is not None, f"{cls.__name__}.{fld.name} has no range"


def _error(load: Any, text: str, tmp_path: Path, name: str = "bad.toml") -> str:
    path = tmp_path / name
    path.write_text(text)
    with pytest.raises(PresetError) as err:
        load(str(path))
    message = str(err.value)
    assert "\n" not in message and str(path) in message
    return message


@pytest.mark.parametrize(
    ("table", "key", "value"),
    [
        ("robot", "mass_kg", "inf"),
        ("robot", "mass_kg", "nan"),
        ("robot", "mass_kg", "-inf"),
        ("timing", "physics_hz", "2.4e7"),
        ("timing", "solver_iterations", "1000000000"),
        ("robot", "size_m", "10"),
        ("camera", "position_sigma_m", "inf"),
        ("camera", "latency_s", "inf"),
        ("camera", "latency_s", "1" + "0" * 400),
        ("ball", "motion_noise", "1e308"),
        ("field", "length_m", "1e300"),
    ],
)
def test_an_absurd_robot_value_is_refused_naming_file_and_key(
    tmp_path: Path, table: str, key: str, value: str
) -> None:
    text = f'base = "small_size_1997"\n[{table}]\n{key} = {value}\n'
    message = _error(load_preset, text, tmp_path)
    assert f"key '{table}.{key}'" in message
    assert len(message) < 200


def test_a_robot_too_large_for_its_table_is_refused(tmp_path: Path) -> None:
    text = 'base = "small_size_1997"\n[robot]\nsize_m = 0.5\ntrack_m = 0.5\n'
    assert "key 'robot.size_m': expected at most field.width_m" in _error(
        load_preset, text, tmp_path
    )


@pytest.mark.parametrize(
    ("key", "value"),
    [
        ("dash_power_rate_m_per_cycle2", "inf"),
        ("ball_rand", "nan"),
        ("simulator_step_ms", "1" + "0" * 300),
        ("ball_speed_max_m_per_cycle", "inf"),
        ("maxmoment_deg", "1" + "0" * 400),
    ],
)
def test_an_absurd_server_value_is_refused_naming_file_and_key(
    tmp_path: Path, key: str, value: str
) -> None:
    text = f'base = "soccer_server_1996"\n[dynamics]\n{key} = {value}\n'
    message = _error(load_server_preset, text, tmp_path)
    assert f"key 'dynamics.{key.replace('_deg', '')}" in message


def test_no_acceleration_cap_is_still_written_inf() -> None:
    dynamics = load_server_preset("soccer_server_1996").dynamics
    assert math.isinf(dynamics.ball_accel_max_m_per_cycle2)
    assert math.isinf(dynamics.player_accel_max_m_per_cycle2)


@pytest.mark.parametrize(
    ("line", "key"),
    [
        ("server::player_rand = 1e999", "server::player_rand"),
        ("server::dash_power_rate = 1e999", "server::dash_power_rate"),
        ("server::wind_force = -1e999", "server::wind_force"),  # ignored, yet not a number
        ("server::simulator_step = 1e300", "server::simulator_step"),
        ("server::port = 1" + "0" * 5000, "server::port"),
        ("server::ball_decay = 1" + "0" * 400, "server::ball_decay"),
        ("server::visible_angle = 1e300", "server::visible_angle"),
    ],
)
def test_an_overflowing_server_conf_number_is_refused(tmp_path: Path, line: str, key: str) -> None:
    message = _error(server_conf.load_preset, f"{line}\n", tmp_path, "server.conf")
    assert f"server.conf:1: key '{key}'" in message and len(message) < 300


@pytest.mark.parametrize(
    "text",
    ["(server_param (player_rand 1e999))", "(server_param (ball_rand 1" + "0" * 400 + "))"],
)
def test_an_overflowing_server_param_number_is_refused(text: str) -> None:
    with pytest.raises(PresetError, match="finite"):
        server_conf.load_preset(text)


def test_files_that_are_not_presets_are_refused(tmp_path: Path) -> None:
    garbage = tmp_path / "garbage.toml"
    garbage.write_bytes(b"\xcc\xff\xfe" * 50)
    with pytest.raises(PresetError, match="not UTF-8"):
        load_preset(str(garbage))
    nested = tmp_path / "nested.toml"
    nested.write_text("a = " + "[" * 5000 + "]" * 5000 + "\n")
    with pytest.raises(PresetError, match="nested too deeply"):
        load_preset(str(nested))
    digits = tmp_path / "digits.toml"
    digits.write_text("a = 1" + "0" * 5000 + "\n")
    with pytest.raises(PresetError, match="too many digits"):
        load_preset(str(digits))
    huge = tmp_path / "huge.toml"
    huge.write_text("#" * (MAX_PRESET_BYTES + 1))
    with pytest.raises(PresetError, match="larger than"):
        load_preset(str(huge))
    with pytest.raises(PresetError, match="cannot read"):
        load_preset(str(tmp_path))  # a folder
    with pytest.raises(PresetError, match="not a server configuration"):
        server_conf.load_preset(str(huge.rename(tmp_path / "huge.conf")))


@pytest.mark.skipif(not Path("/dev/zero").exists(), reason="no /dev/zero")
def test_dev_zero_as_a_preset_is_refused_without_reading_it_all() -> None:
    with pytest.raises(PresetError, match="larger than"):
        load_preset("/dev/zero")


def test_replace_checks_ranges_too() -> None:
    robot = load_preset().robot
    with pytest.raises(RecordError, match="mass_kg"):
        dataclasses.replace(robot, mass_kg=math.inf)
    with pytest.raises(RecordError, match="ball_rand"):
        load_server_preset().replace_dynamics(ball_rand=math.nan)
    with pytest.raises(ValueError, match="ball_noise"):
        FieldOptions(ball_noise=1e308)


@pytest.mark.parametrize(
    ("table", "key", "value", "why"),
    [
        ("ball", "noise_period_s", "1e-9", "positive number in"),
        ("firmware", "timeout_s", "1e-3", "whole number"),
        ("link", "packets_per_s", "5e-324", "positive number in"),
        ("camera", "frame_rate_hz", "1000", "whole number"),
    ],
)
def test_a_period_shorter_than_a_tick_is_refused(
    tmp_path: Path, table: str, key: str, value: str, why: str
) -> None:
    text = f'base = "small_size_1997"\n[{table}]\n{key} = {value}\n'
    message = _error(load_preset, text, tmp_path)
    assert f"key '{table}.{key}'" in message and why in message


def test_ticks_refuse_a_period_of_no_tick_or_an_infinite_one() -> None:
    preset = load_preset()
    with pytest.raises(PresetError, match="at least 1"):
        preset.ticks(1e-9, "ball.noise_period_s", least=1)
    with pytest.raises(PresetError, match="whole number"):
        preset.ticks(math.inf, "link.packets_per_s")


def test_a_vanishing_mass_is_refused_before_chipmunk_sees_it(tmp_path: Path) -> None:
    text = 'base = "small_size_1997"\n[robot]\nmass_kg = 5e-324\n'
    assert "key 'robot.mass_kg'" in _error(load_preset, text, tmp_path)


def test_a_see_of_a_nan_position_raises_instead_of_looping() -> None:
    import numpy as np

    from field_models.soccer_server.batch_sensing import quantised_distances

    sensing = load_server_preset().sensing
    with pytest.raises(ValueError, match="not finite"):
        quantised_distances(sensing, np.array([1.0, np.nan]))
    with pytest.raises(ValueError, match="not finite"):
        quantised_distances(sensing, np.array([np.inf]))


def test_a_field_wider_than_long_is_refused(tmp_path: Path) -> None:
    robot = 'base = "small_size_1997"\n[field]\nwidth_m = 3.0\n'
    assert "key 'field.width_m'" in _error(load_preset, robot, tmp_path)
    server = 'base = "soccer_server_1996"\n[dynamics]\npitch_width_m = 300.0\n'
    assert "key 'dynamics.pitch_width_m'" in _error(load_server_preset, server, tmp_path)
