"""A real server's configuration as a preset: server.conf files and server_param messages."""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path
from typing import Any

import pytest

from field_models.presets import PresetError
from field_models.soccer_server.params import ServerPreset, load_server_preset
from field_models.soccer_server.server_conf import MAPPED, load_preset, load_server_conf
from field_models.soccer_server.server_conf_text import MESSAGE_SOURCE, parse_server_conf
from field_models.soccer_server.server_param_table import (
    BOOL_PARAMS,
    INT_PARAMS,
    SERVER_PARAMS,
    STR_PARAMS,
)

DEFAULTS = Path(__file__).parent / "data" / "rcssserver_19_defaults.conf"
"""rcssserver 19.0.0's defaults, written as the server writes its server.conf."""


def differences(a: Any, b: Any) -> dict[str, tuple[Any, Any]]:
    """The fields in which two records differ: name -> (a's value, b's value)."""
    return {
        f.name: (getattr(a, f.name), getattr(b, f.name))
        for f in dataclasses.fields(a)
        if getattr(a, f.name) != getattr(b, f.name)
    }


def message_from_conf(path: Path) -> str:
    """The (server_param ...) message a server with this server.conf sends (bools as 0/1)."""
    entries = []
    for s in parse_server_conf(path.read_text(), file=str(path)):
        if isinstance(s.value, bool):
            value = str(int(s.value))
        elif isinstance(s.value, str):
            value = f'"{s.value}"'
        else:
            value = f"{s.value:g}"
        entries.append(f"({s.name} {value})")
    return "(server_param " + " ".join(entries) + ")"


# ----------------------------------------------------------------------------- today's defaults


def test_the_parameter_list_is_rcssserver_19s() -> None:
    assert len(SERVER_PARAMS) == len(set(SERVER_PARAMS)) == 202
    assert {"ball_decay", "side_dash_rate", "stamina_capacity", "dist_noise_rate"} <= set(
        SERVER_PARAMS
    )
    assert set(SERVER_PARAMS) > (INT_PARAMS | BOOL_PARAMS | STR_PARAMS)
    assert set(MAPPED) < set(SERVER_PARAMS)


def test_server_conf_of_todays_defaults_is_the_rcssserver_19_preset() -> None:
    today = load_server_preset("rcssserver_19_async")
    loaded = load_server_conf(DEFAULTS)
    assert loaded.preset.dynamics == today.dynamics
    assert loaded.preset.sensing == today.sensing
    assert (loaded.preset.name, loaded.preset.era) == ("rcssserver_19_defaults", "19")
    assert loaded.preset.source == str(DEFAULTS)
    assert len(loaded.applied) + len(loaded.ignored) == len(SERVER_PARAMS)
    # The CLI's --field-preset goes through load_preset: a .conf path loads the same.
    assert load_preset(str(DEFAULTS)) == loaded.preset
    with pytest.raises(PresetError, match="not a preset file: load it with"):
        load_server_preset(str(DEFAULTS))


def test_every_server_parameter_we_model_comes_from_the_file() -> None:
    # Over the 1996 preset, the file sets every field the server has a parameter for; what
    # is left of 1996 is what server.conf cannot say (version rules, compiled constants).
    today = load_server_preset("rcssserver_19_async")
    old = load_server_preset("soccer_server_1996")
    loaded = load_server_conf(DEFAULTS, base=old).preset
    assert set(differences(loaded.dynamics, today.dynamics)) == {
        "goal_post_radius_m",
        "kick_reduction",
        "noise_model",
        "after_goal_wait_cycles",
    }
    assert set(differences(loaded.sensing, today.sensing)) == {
        "direction_mode",
        "protocol_version",
        "report_changes",
        "landmark_set",
        "team_far_length_m",  # player-type values, not server.conf
        "team_too_far_length_m",
        "hear_per_team",
    }
    assert loaded.era == "1996"


def test_server_param_message_of_todays_defaults_is_the_rcssserver_19_preset() -> None:
    text = message_from_conf(DEFAULTS)
    assert "(coach 0)" in text and '(text_log_dir "./")' in text
    loaded = load_server_conf(text, base="soccer_server_1996")
    today = load_server_preset("rcssserver_19_async")
    assert set(differences(loaded.preset.dynamics, today.dynamics)) == {
        "goal_post_radius_m",
        "kick_reduction",
        "noise_model",
        "after_goal_wait_cycles",
    }
    assert loaded.preset.sensing.view_half_angle_rad == today.sensing.view_half_angle_rad


# ----------------------------------------------------------------------------- changes


def test_server_param_changes_exactly_what_it_sets() -> None:
    base = load_server_preset("rcssserver_19_async")
    text = (
        "(server_param (ball_decay 0.9) (visible_angle 120) (maxmoment 90) (send_step 100) "
        "(simulator_step 50) (kick_rand 0) (stamina_max 4000) (coach 1) (landmark_file "
        '"~/x.xml"))\0'
    )
    loaded = load_server_conf(text)
    preset = loaded.preset
    assert differences(preset.dynamics, base.dynamics) == {
        "ball_decay": (0.9, 0.94),
        "maxmoment_rad": (math.pi / 2, math.pi),
        "simulator_step_ms": (50, 100),
        "kick_rand": (0.0, 0.1),
        "referee": (False, True),  # server::coach: no referee
    }
    assert differences(preset.sensing, base.sensing) == {
        "view_half_angle_rad": (math.radians(60.0), math.radians(45.0)),  # the full cone is 120
        "send_step_ms": (100, 150),
        "simulator_step_ms": (50, 100),
    }
    assert loaded.applied == (
        "ball_decay",
        "visible_angle",
        "maxmoment",
        "send_step",
        "simulator_step",
        "kick_rand",
        "coach",
    )
    assert loaded.ignored == ("stamina_max", "landmark_file")
    assert (preset.name, preset.source) == ("server_param", MESSAGE_SOURCE)
    assert load_preset(text) == preset


def test_dash_parameters_in_degrees_become_radians() -> None:
    text = "(server_param (dash_angle_step 45) (min_dash_angle -90) (max_dash_angle 90))"
    d = load_server_conf(text, base="soccer_server_1996").preset.dynamics
    assert d.dash_angle_step_rad == math.radians(45.0)
    assert (d.min_dash_angle_rad, d.max_dash_angle_rad) == (-math.pi / 2, math.pi / 2)


def test_referee_follows_coach_and_coach_w_referee() -> None:
    def referee(conf: str) -> bool:
        return load_server_conf(conf, base="rcssserver_19_async").preset.dynamics.referee

    assert referee("(server_param (coach 1))") is False
    assert referee("(server_param (coach 1) (coach_w_referee 1))") is True
    assert referee("(server_param (coach 0))") is True
    no_referee = load_server_preset("rcssserver_19_async").replace_dynamics(referee=False)
    loaded = load_server_conf("(server_param (coach_w_referee 0))", base=no_referee)
    assert loaded.preset.dynamics.referee is False  # neither decides: the base's value
    assert loaded.ignored == ("coach_w_referee",)


def test_server_conf_syntax(tmp_path: Path) -> None:
    path = tmp_path / "mine.conf"
    path.write_text(
        "/* server Configuration file\n   spanning lines */\n"
        "# server::ball_decay\n"
        "server::ball_decay = 0.5 // a comment after the value\n"
        "server::ball_decay=0.8\n"  # a later setting wins
        "  --server::player_rand   =   1e-02\n"
        "ball_rand = 0\n"  # no module: a server parameter
        "server::synch_mode = ON\n"
        "server::text_log_dir = '/tmp/it\\'s logs'\n"
        'server::game_log_dir = "./x y"\n'
        "server::log_date_format = %Y-%m\n"
        "server::version = '19.0.0'\n"
    )
    loaded = load_server_conf(path)
    d = loaded.preset.dynamics
    assert (d.ball_decay, d.player_rand, d.ball_rand) == (0.8, 0.01, 0.0)
    assert loaded.applied == ("ball_decay", "player_rand", "ball_rand")
    assert loaded.ignored == ("synch_mode", "text_log_dir", "game_log_dir", "log_date_format")
    values = {s.name: s.value for s in parse_server_conf(path.read_text(), file=str(path))}
    assert values["text_log_dir"] == "/tmp/it's logs" and values["synch_mode"] is True
    assert values["log_date_format"] == "%Y-%m" and "version" not in values


# ----------------------------------------------------------------------------- errors


def conf_error(tmp_path: Path, text: str) -> str:
    path = tmp_path / "server.conf"
    path.write_text(text)
    with pytest.raises(PresetError) as err:
        load_preset(str(path))
    message = str(err.value)
    assert str(path) in message
    return message


@pytest.mark.parametrize(
    ("line", "fragments"),
    [
        ("server::ball_decy = 0.9", ["key 'server::ball_decy'", "not a parameter"]),
        ("player::player_types = 18", ["key 'player::player_types'", "not a server parameter"]),
        ("server::ball_decay = fast", ["key 'server::ball_decay'", "expected a number"]),
        ("server::ball_decay = 1.5", ["key 'server::ball_decay'", "probability"]),
        ("server::ball_rand = -0.1", ["key 'server::ball_rand'", ">= 0"]),
        ("server::half_time = 1.5", ["key 'server::half_time'", "expected an integer"]),
        ("server::send_step = 0", ["key 'server::send_step'", "positive"]),
        ("server::coach = 2", ["key 'server::coach'", "true or false"]),
        ("server::text_log_dir = 3", ["key 'server::text_log_dir'", "expected a string"]),
        ("server::ball_decay 0.9", ["key 'server::ball_decay'", "'='"]),
        ("server::ball_decay =", ["key 'server::ball_decay'", "expected a value"]),
        ("include = 'other.conf'", ["key 'include'", "not supported"]),
        ("server::text_log_dir = 'open", ["key 'server::text_log_dir'", "unterminated"]),
        ("/* never closed", ["not closed"]),
    ],
)
def test_a_wrong_server_conf_names_the_file_line_and_key(
    tmp_path: Path, line: str, fragments: list[str]
) -> None:
    message = conf_error(tmp_path, f"# first line\n\n{line}\n")
    assert "server.conf:3" in message
    for fragment in fragments:
        assert fragment in message


def test_contradicting_settings_name_the_key(tmp_path: Path) -> None:
    message = conf_error(tmp_path, "server::minpower = 50\nserver::maxpower = 10\n")
    assert "key 'server::minpower'" in message and "maximum" in message


def test_a_wrong_server_param_message_names_the_key() -> None:
    for text, fragments in [
        ("(server_param (ball_decy 0.9))", ["key 'ball_decy'", "not a parameter"]),
        ('(server_param (ball_decay "0.9"))', ["key 'ball_decay'", "expected a number"]),
        ("(server_param (use_offside 3))", ["key 'use_offside'", "true or false"]),
        ("(server_param (ball_decay 0.9 1))", ["'(name value)'"]),
        ("(server_param (ball_decay 0.9)", ["not a server_param message"]),
    ]:
        with pytest.raises(PresetError) as err:
            load_preset(text)
        for fragment in [MESSAGE_SOURCE, *fragments]:
            assert fragment in str(err.value), (text, str(err.value))


def test_a_file_holding_a_server_param_message_and_a_missing_file(tmp_path: Path) -> None:
    path = tmp_path / "captured.txt"
    path.write_text("(server_param (player_decay 0.5) (wind_force 3))\n")
    loaded = load_server_conf(path)
    assert loaded.preset.dynamics.player_decay == 0.5 and loaded.ignored == ("wind_force",)
    with pytest.raises(PresetError, match="not found"):
        load_preset(str(tmp_path / "absent.conf"))


def test_a_loaded_base_preset_is_accepted() -> None:
    base: ServerPreset = load_server_preset("soccer_server_1996").replace_dynamics(ball_rand=0.0)
    loaded = load_server_conf("(server_param (player_rand 0))", base=base)
    assert loaded.preset.dynamics.ball_rand == 0.0 and loaded.preset.dynamics.player_rand == 0.0
    assert loaded.preset.era == "1996"
