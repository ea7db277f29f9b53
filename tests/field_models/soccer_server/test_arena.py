"""The Soccer Server arena: same runner and drill as the robots, queued commands, hearing, trace."""

from __future__ import annotations

import math

import pytest

from field_models.protocol import LEFT, RIGHT, Dash, PlayerRef, Say, Turn
from field_models.seeding import TrialRngs
from field_models.soccer_server.arena import SoccerServerArena
from field_models.soccer_server.messages import parse_see
from field_models.soccer_server.params import load_server_preset
from robotsoccer.cli import main
from robotsoccer.drills import make_drill
from robotsoccer.replay.trace import trace_trial
from robotsoccer.runs.pool import run_trials
from robotsoccer.runs.runner import TrialSpec, play, run_trial

SPEC = TrialSpec(field_model="soccer_server", preset="soccer_server_1996", seed=5)
A, B = PlayerRef(LEFT, 1), PlayerRef(RIGHT, 1)


def arena(preset: str = "soccer_server_1996", noise: bool = True) -> SoccerServerArena:
    loaded = load_server_preset(preset)
    if not noise:
        loaded = loaded.replace_dynamics(player_rand=0.0, ball_rand=0.0)
    a = SoccerServerArena(loaded, (A, B), TrialRngs.for_trial(0, 0))
    a.place_player(A, -10.0, 0.0, 0.0)
    a.place_player(B, 10.0, 0.0, math.pi)
    a.place_ball(0.0, 20.0)
    return a


def test_the_demo_drill_runs_unchanged_on_the_soccer_server() -> None:
    results = [run_trial(SPEC, i) for i in range(6)]
    assert {r.label for r in results} <= {"SAVE", "GOAL", "MISS"}
    assert all(r.ticks > 0 and r.time_s == pytest.approx(0.1 * r.ticks) for r in results)


def test_tracing_does_not_change_a_trial() -> None:
    for i in range(3):
        rngs = TrialRngs.for_trial(SPEC.seed, i)
        drill = make_drill("shootout")
        traced = SoccerServerArena.from_preset(SPEC.preset, drill.players(), rngs, trace=True)
        drill.setup(traced, rngs)
        verdict = play(traced, drill, drill.minds(traced, rngs))
        plain = run_trial(SPEC, i)
        assert (verdict.label, traced.tick) == (plain.label, plain.ticks)


@pytest.mark.slow
def test_one_and_two_workers_give_identical_tables() -> None:
    one = run_trials(SPEC, 8, workers=1, progress=False)
    two = run_trials(SPEC, 8, workers=2, progress=False, chunk_size=1)
    assert one == two


def test_body_actions_of_one_decision_run_one_per_cycle_in_order() -> None:
    a = arena(noise=False)
    a.submit(A, (Turn(math.radians(30.0)), Dash(100.0)))
    a.step()
    after_turn = a.player_state(A)
    assert after_turn.heading == pytest.approx(math.radians(30.0))
    assert after_turn.speed == 0.0
    a.step()
    moving = a.player_state(A)
    assert moving.speed > 0.0
    assert math.atan2(moving.vy, moving.vx) == pytest.approx(math.radians(30.0), abs=0.1)


def test_a_new_decision_replaces_the_rest_of_the_old_one() -> None:
    a = arena(noise=False)
    a.submit(A, (Turn(math.radians(-20.0)), Dash(100.0), Dash(100.0)))
    a.step()
    a.submit(A, (Turn(math.radians(40.0)),))  # replaces the two queued dashes
    a.step()
    a.step()
    state = a.player_state(A)
    assert state.heading == pytest.approx(math.radians(20.0))
    assert state.speed == 0.0  # no dash ran


def test_a_say_is_heard_with_the_next_percept_and_the_referee_by_all() -> None:
    a = arena("rcssserver_19")
    a.submit(A, (Say("pass"),))
    heard = []
    for _ in range(10):
        for percept in a.step():
            heard += [(percept.player, h.text) for h in percept.heard]
    assert (B, "pass") in heard
    a.place_ball(52.0, 0.0, 5.0, 0.0)  # rolling into the right goal
    texts = []
    for _ in range(10):
        for percept in a.step():
            texts += [h.text for h in percept.heard if h.sender is None]
    assert any(t.startswith("goal_l") for t in texts)


def test_trace_prints_the_clients_see_messages_and_commands() -> None:
    lines = trace_trial(SPEC, 0)
    sees = [line for line in lines if line.startswith("(see")]
    commands = [line for line in lines if line.startswith("**-> (")]
    assert sees and commands
    for line in sees:
        parse_see(line)  # the server's own text format
    assert lines[-1].startswith("coach: ")


def test_trace_command(capsys) -> None:
    assert main(["trace", "--seed", "5", "--player", "right1"]) == 0
    out = capsys.readouterr().out
    assert "(see " in out and "coach:" in out
    assert main(["trace", "--player", "nobody"]) == 2
