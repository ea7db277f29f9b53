"""Paper-style traces (Figure 4) on both field models, and that tracing changes no trial."""

from __future__ import annotations

import pytest

from field_models.commands import parse_command
from field_models.soccer_server.messages import parse_see
from robotsoccer.cli import main
from robotsoccer.replay.trace import trace_trial
from robotsoccer.runs.runner import TrialSpec, build_trial, play, run_trial

MODELS = ("soccer_server", "robot_physics")


def spec(field_model: str, drill: str = "shootout") -> TrialSpec:
    return TrialSpec(drill=drill, field_model=field_model, seed=5)


@pytest.mark.parametrize("field_model", MODELS)
@pytest.mark.parametrize("drill", ["shootout", "intercept"])
def test_tracing_does_not_change_a_trial(field_model: str, drill: str) -> None:
    for i in range(3):
        rngs, d, arena = build_trial(spec(field_model, drill), i, trace=True)
        d.setup(arena, rngs)
        verdict = play(arena, d, d.minds(arena, rngs))
        plain = run_trial(spec(field_model, drill), i)
        assert (verdict.label, arena.tick) == (plain.label, plain.ticks)


def test_server_trace_prints_the_clients_see_messages_and_commands() -> None:
    lines = trace_trial(spec("soccer_server"), 0)
    sees = [line for line in lines if line.startswith("(see")]
    commands = [line.removeprefix("**-> ") for line in lines if line.startswith("**-> (")]
    assert sees and commands
    for line in sees:
        parse_see(line)  # the server's own text format
    for command in commands:
        parse_command(command)  # the client's command text
    assert lines[-1].startswith("coach: ")


def test_robot_trace_shows_percepts_commands_and_primitives() -> None:
    lines = trace_trial(spec("robot_physics"), 0)
    assert any(line.startswith("(see ") and "((ball)" in line for line in lines)
    commands = [line.removeprefix("**-> ") for line in lines if line.startswith("**-> ")]
    assert commands and all(parse_command(c) for c in commands)
    assert any(line.startswith("  link: left1 ") for line in lines)
    assert lines[-1].startswith("coach: ")


def test_trace_command(capsys) -> None:
    assert main(["trace", "--seed", "5", "--player", "right1"]) == 0
    out = capsys.readouterr().out
    assert "(see " in out and "coach:" in out
    assert main(["trace", "--player", "nobody"]) == 2
