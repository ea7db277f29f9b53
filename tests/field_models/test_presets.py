"""Preset files: shipped ones load; wrong ones fail naming the file and the key."""

from __future__ import annotations

import dataclasses
import re
from pathlib import Path
from typing import Literal

import pytest

from field_models.presets import PresetError, load_record
from field_models.robot_physics.config import load_preset

SHIPPED = Path(load_preset().source)


def broken(tmp_path: Path, old: str, new: str) -> Path:
    text = SHIPPED.read_text()
    assert re.search(old, text, flags=re.M), old
    path = tmp_path / "broken.toml"
    path.write_text(re.sub(old, new, text, count=1, flags=re.M))
    return path


@pytest.mark.parametrize("name", ["small_size_1997", "vss"])
def test_shipped_presets_load(name: str) -> None:
    preset = load_preset(name)
    assert preset.name == name
    assert preset.robot.kicker is None  # the 1997 robots pushed the ball
    assert preset.ball.motion_noise == 0.0


@pytest.mark.parametrize(
    ("old", "new", "key", "expected"),
    [
        (r"^mass_kg = 0\.3.*$", "", "robot.mass_kg", "missing"),
        (r"^mass_kg = 0\.3.*$", "mass_kg = -0.3", "robot.mass_kg", "positive"),
        (r"^mass_kg = 0\.3.*$", 'mass_kg = "heavy"', "robot.mass_kg", "number"),
        (r"^perfect = false", "perfect = 1", "camera.perfect", "true or false"),
        (r"^loss_prob = 0\.03", "loss_prob = 1.5", "link.loss_prob", "probability"),
        (r"^tyre_mu = 0\.8", "tyre_mu = 0.8\ntyre_grip = 1.0", "robot.tyre_grip", "unknown"),
        (r"^latency_s = 0\.05.*$", "latency_s = 0.051", "camera.latency_s", "whole number"),
        (r"^max_speed_mps = 4\.0", "max_speed_mps = 40.0", "ball.max_speed_mps", "tunnels"),
        (r"^tyre_mu = 0\.8", "tyre_mu = 0.8\nturn_style = 'drift'", "robot.turn_style", "arc"),
    ],
)
def test_wrong_preset_names_file_and_key(tmp_path, old, new, key, expected) -> None:
    path = broken(tmp_path, old, new)
    with pytest.raises(PresetError) as err:
        load_preset(str(path))
    message = str(err.value)
    assert str(path) in message
    assert f"'{key}'" in message
    assert expected in message


def test_unknown_preset_and_bad_toml(tmp_path) -> None:
    with pytest.raises(PresetError, match="unknown preset 'nope'"):
        load_preset("nope")
    bad = tmp_path / "bad.toml"
    bad.write_text("[field\nlength_m = 1")
    with pytest.raises(PresetError, match=re.escape(str(bad))):
        load_preset(str(bad))
    with pytest.raises(PresetError, match="not found"):
        load_preset(str(tmp_path / "absent.toml"))


@dataclasses.dataclass(frozen=True)
class _Options:
    mode: Literal["fast", "exact"]
    level: Literal[1, 2] = 1


@pytest.mark.parametrize(
    ("table", "message"),
    [
        ({"mode": "slow"}, "x.toml: key 'opts.mode': expected one of fast, exact; got 'slow'"),
        ({"mode": 1}, "x.toml: key 'opts.mode': expected one of fast, exact; got 1"),
        ({"mode": "fast", "level": 3}, "x.toml: key 'opts.level': expected one of 1, 2; got 3"),
        ({"mode": "fast", "level": True}, "key 'opts.level': expected one of 1, 2; got True"),
    ],
)
def test_an_option_outside_its_literal_names_the_key(table: dict, message: str) -> None:
    with pytest.raises(PresetError) as err:
        load_record(_Options, table, file="x.toml", key="opts")
    assert message in str(err.value)


def test_an_option_inside_its_literal_loads() -> None:
    assert load_record(_Options, {"mode": "exact", "level": 2}, file="x.toml") == _Options(
        "exact", 2
    )
