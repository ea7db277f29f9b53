"""Property tests of every input a user gives the field models (issue 30), sized for CI.

A preset file, a server.conf, a ``server_param`` message or a command text either loads to
values inside their stated ranges or is refused with the documented error; nothing else. The
longer fuzz for release checks is ``scripts/fuzz.py``.
"""

from __future__ import annotations

import dataclasses
import math
import typing
from pathlib import Path
from typing import Any

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from field_models.commands import CommandParseError, parse_command, render_command
from field_models.presets import PresetError, bounds_of, range_problem
from field_models.protocol import Dash, Kick, Say, Turn
from field_models.robot_physics.config import RobotPhysicsPreset, load_preset
from field_models.soccer_server.params import load_server_preset
from field_models.soccer_server.server_conf import MAPPED
from field_models.soccer_server.server_param_table import SERVER_PARAMS

QUICK = settings(
    max_examples=60, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture]
)

NASTY = [
    "inf", "-inf", "nan", "+nan", "1e999", "-1e999", "1e300", "-1e300", "1e-300", "0", "-0.0",
    "1" + "0" * 400, "-1" + "0" * 400, "1" + "0" * 5000, "2.4e7", "1000000000", "10", "-1",
    "0.5", "true", '"text"', "[1, 2]", "{ a = 1 }", "1979-05-27", "0x10", "1_000",
]  # fmt: skip
"""Values a hostile user writes: non-finite, overflowing, huge, negative, of the wrong type."""

number_text = st.one_of(
    st.sampled_from(NASTY),
    st.floats(allow_nan=True, allow_infinity=True).map(repr),
    st.integers(-(10**30), 10**30).map(str),
    st.from_regex(r"[-+]?[0-9]{1,4}(\.[0-9]{1,4})?([eE][-+]?[0-9]{1,4})?", fullmatch=True),
)


def _numeric_keys(cls: type, prefix: str = "") -> list[str]:
    """The dotted keys of every number in record `cls` and the records inside it."""
    hints = typing.get_type_hints(cls)
    keys = []
    for fld in dataclasses.fields(cls):  # type: ignore[arg-type]
        hint = hints[fld.name]
        if bounds_of(fld) is not None:
            keys.append(prefix + fld.name)
        elif dataclasses.is_dataclass(hint) and isinstance(hint, type):
            keys += _numeric_keys(hint, f"{prefix}{fld.name}.")
    return keys


def in_range(record: Any) -> None:
    """Assert every number of `record` (and the records inside it) is inside its bounds."""
    for fld in dataclasses.fields(record):
        value = getattr(record, fld.name)
        if dataclasses.is_dataclass(value):
            in_range(value)
        else:
            assert range_problem(bounds_of(fld), value) is None, (fld.name, value)


ROBOT_KEYS = _numeric_keys(RobotPhysicsPreset)
SERVER_KEYS = [
    f"{table}.{f.name}"
    for table, preset in (("dynamics", load_server_preset().dynamics),
                          ("sensing", load_server_preset().sensing))
    for f in dataclasses.fields(preset)
    if bounds_of(f) is not None
]  # fmt: skip


def one_line_naming(err: PresetError, file: str) -> None:
    """The refusal is one line that names the file (and the key, where there is one)."""
    message = str(err)
    assert "\n" not in message and f"/{file}" in message.split(": ")[0], message


@pytest.fixture(scope="module")
def folder(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return tmp_path_factory.mktemp("presets")


def _write(folder: Path, name: str, text: str | bytes) -> Path:
    path = folder / name
    if isinstance(text, bytes):
        path.write_bytes(text)
    else:
        path.write_text(text)
    return path


def test_the_key_lists_cover_the_records() -> None:
    assert {"robot.mass_kg", "timing.physics_hz", "camera.latency_s"} <= set(ROBOT_KEYS)
    assert {"dynamics.ball_rand", "sensing.send_step_ms"} <= set(SERVER_KEYS)


@QUICK
@given(st.lists(st.tuples(st.sampled_from(ROBOT_KEYS), number_text), min_size=1, max_size=3))
def test_a_robot_preset_loads_in_range_or_is_refused(
    folder: Path, edits: list[tuple[str, str]]
) -> None:
    tables: dict[str, list[str]] = {}
    for dotted, value in edits:
        table, key = dotted.split(".")
        tables.setdefault(table, []).append(f"{key} = {value}")
    text = 'base = "small_size_1997"\n' + "".join(
        f"[{t}]\n" + "\n".join(dict.fromkeys(lines)) + "\n" for t, lines in tables.items()
    )
    try:
        preset = load_preset(str(_write(folder, "robot.toml", text)))
    except PresetError as err:
        one_line_naming(err, "robot.toml")
        return
    in_range(preset)


@QUICK
@given(st.sampled_from(SERVER_KEYS), number_text)
def test_a_server_preset_loads_in_range_or_is_refused(
    folder: Path, dotted: str, value: str
) -> None:
    table, key = dotted.split(".")
    text = f'base = "soccer_server_1996"\n[{table}]\n{key} = {value}\n'
    try:
        preset = load_server_preset(str(_write(folder, "server.toml", text)))
    except PresetError as err:
        one_line_naming(err, "server.toml")
        return
    in_range(preset.dynamics)
    in_range(preset.sensing)


server_names = st.sampled_from(sorted(MAPPED)) | st.sampled_from(SERVER_PARAMS)


@QUICK
@given(st.lists(st.tuples(server_names, number_text), min_size=1, max_size=4))
def test_a_server_conf_loads_in_range_or_is_refused(
    folder: Path, settings_: list[tuple[str, str]]
) -> None:
    text = "".join(f"server::{name} = {value}\n" for name, value in settings_)
    message = "(server_param " + " ".join(f"({n} {v})" for n, v in settings_) + ")"
    for source in (str(_write(folder, "server.conf", text)), message):
        try:
            preset = load_server_preset(source)
        except PresetError as err:
            assert "\n" not in str(err)
            continue
        in_range(preset.dynamics)
        in_range(preset.sensing)


@QUICK
@given(st.binary(max_size=300))
def test_any_bytes_as_a_preset_or_server_conf_are_refused_cleanly(
    folder: Path, data: bytes
) -> None:
    for name, load in (("any.toml", load_preset), ("any.conf", load_server_preset)):
        try:
            load(str(_write(folder, name, data)))
        except PresetError as err:
            one_line_naming(err, name)


# ----------------------------------------------------------------------------- commands


@settings(max_examples=300, deadline=None)
@given(st.text(min_size=1, max_size=30))
def test_every_say_survives_render_and_parse(message: str) -> None:
    said = Say(message)
    assert parse_command(render_command(said)) == said


tenths = st.integers(-(10**7), 10**7).map(lambda n: n / 10)


@settings(max_examples=200, deadline=None)
@given(
    st.one_of(
        st.builds(lambda a: f"(turn {a})", tenths),
        st.builds(lambda p, d: f"(dash {p} {d})", tenths, tenths),
        st.builds(lambda p: f"(dash {p})", tenths),
        st.builds(lambda p, d: f"(kick {p} {d})", tenths, tenths),
    )
)
def test_a_parsed_command_survives_render_and_parse(text: str) -> None:
    action = parse_command(text)
    assert parse_command(render_command(action)) == action


finite = st.floats(allow_nan=False, allow_infinity=False, min_value=-1e12, max_value=1e12)


@settings(max_examples=200, deadline=None)
@given(
    st.one_of(
        st.builds(Turn, finite),
        st.builds(Dash, finite, finite),
        st.builds(Kick, finite, finite),
    )
)
def test_rendering_is_a_fixed_point_after_one_round(action: Turn | Dash | Kick) -> None:
    text = render_command(action)
    assert render_command(parse_command(text)) == text


@settings(max_examples=200, deadline=None)
@given(st.text(max_size=40), st.sampled_from(["turn", "dash", "kick", "say"]))
def test_any_command_text_parses_to_finite_numbers_or_is_refused(text: str, name: str) -> None:
    for candidate in (text, f"({name} {text})"):
        try:
            action = parse_command(candidate)
        except CommandParseError:
            continue
        for value in dataclasses.astuple(action):
            assert isinstance(value, str) or math.isfinite(value)
