"""Client command text: actions written as a client sends them, and read back."""

from __future__ import annotations

import contextlib
import math

import pytest
from hypothesis import given
from hypothesis import strategies as st

from field_models.commands import CommandParseError, parse_command, render_command
from field_models.protocol import ChangeView, Dash, Kick, Say, Turn, TurnNeck


@pytest.mark.parametrize(
    ("text", "action"),
    [
        ("(turn 45)", Turn(-math.radians(45))),  # the server's +45 is clockwise: a right turn
        ("(turn -30.5)", Turn(math.radians(30.5))),
        ("(dash 100)", Dash(100.0)),
        ("(dash 100 30)", Dash(100.0, -math.radians(30))),
        ("(kick 80 -30)", Kick(80.0, math.radians(30))),
        ("(say hello world)", Say("hello world")),
        ('(say "pass (now)")', Say("pass (now)")),
        ("  (dash -30)\0", Dash(-30.0)),
        ("(turn_neck 30)", TurnNeck(-math.radians(30))),
        ("(change_view wide low)", ChangeView("wide", "low")),
        ("(change_view narrow)", ChangeView("narrow", "high")),  # the server's default quality
    ],
)
def test_client_commands_parse_into_our_frame(text: str, action: object) -> None:
    parsed = parse_command(text)
    assert type(parsed) is type(action)
    for name in action.__dataclass_fields__:  # type: ignore[attr-defined]
        expected = getattr(action, name)
        got = getattr(parsed, name)
        assert got == (pytest.approx(expected) if isinstance(expected, float) else expected)


@pytest.mark.parametrize(
    "action",
    [
        Turn(0.5),
        Turn(-3.0),
        Dash(100.0),
        Dash(60.0, -math.pi / 2),
        Kick(80.0, 0.4),
        Say("hi"),
        TurnNeck(-1.2),
        ChangeView("normal", "low"),
    ],
)
def test_render_and_parse_round_trip_to_the_printed_precision(action: object) -> None:
    text = render_command(action)  # type: ignore[arg-type]
    assert render_command(parse_command(text)) == text


@pytest.mark.parametrize(
    ("text", "why"),
    [
        ("dash 100", "in parentheses"),
        ("()", "empty"),
        ("(run 3)", "unknown command"),
        ("(turn)", "expected 1"),
        ("(kick 80)", "expected 2"),
        ("(dash 100 30 4)", "expected 1 or 2"),
        ("(turn left)", "not a number"),
        ("(turn nan)", "not a finite number"),
        ("(say)", "say without a message"),
        ("(say  )", "say without a message"),
        ("(turn_neck)", "expected 1"),
        ("(change_view)", "expected 1 or 2"),
        ("(change_view huge)", "view width 'huge'"),
        ("(change_view wide medium)", "view quality 'medium'"),
    ],
)
def test_bad_command_text_is_refused_with_the_reason(text: str, why: str) -> None:
    with pytest.raises(CommandParseError, match=why):
        parse_command(text)


@given(st.text(max_size=40))
def test_any_text_parses_or_raises_the_parse_error_only(text: str) -> None:
    with contextlib.suppress(CommandParseError):
        parse_command(text)


@pytest.mark.parametrize("message", [" x", "x ", " ", '"q"', '"', 'a"b', "a)", "\x1c", "hi there"])
def test_a_say_survives_render_and_parse_whitespace_and_quotes_included(message: str) -> None:
    assert parse_command(render_command(Say(message))) == Say(message)


def test_a_quoted_say_with_a_leading_space_round_trips() -> None:
    said = parse_command('(say " x")')
    assert said == Say(" x")
    assert parse_command(render_command(said)) == said
    assert render_command(Say("hi")) == "(say hi)"  # bare where that is safe, as before


def test_neck_and_view_commands_print_as_the_server_reads_them() -> None:
    assert render_command(TurnNeck(math.radians(30))) == "(turn_neck -30)"
    assert render_command(ChangeView("wide", "high")) == "(change_view wide high)"
    assert parse_command("(change_view wide high)") == ChangeView("wide", "high")
    with pytest.raises(ValueError, match="view width 'huge': expected one of"):
        ChangeView("huge")
