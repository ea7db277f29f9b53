"""The Soccer Server arena: queued commands, hearing, the fast path equal to the text route."""

from __future__ import annotations

import math

import pytest

from field_models.benchmarks import ChaseLoad
from field_models.protocol import LEFT, RIGHT, Dash, Kick, Percept, PlayerRef, Say, Turn
from field_models.seeding import TrialRngs
from field_models.soccer_server import model as server_model
from field_models.soccer_server.arena import SoccerServerArena
from field_models.soccer_server.params import load_server_preset

A, B = PlayerRef(LEFT, 1), PlayerRef(RIGHT, 1)


def arena(
    preset: str = "soccer_server_1996", noise: bool = True, trace: bool = False, seed: int = 0
) -> SoccerServerArena:
    loaded = load_server_preset(preset)
    if not noise:
        loaded = loaded.replace_dynamics(player_rand=0.0, ball_rand=0.0)
    facts = server_model.facts(loaded)
    a = SoccerServerArena(loaded, facts, (A, B), TrialRngs.for_trial(seed, 0), trace=trace)
    a.place_player(A, -10.0, 0.0, 0.0)
    a.place_player(B, 10.0, 0.0, math.pi)
    a.place_ball(0.0, 20.0)
    return a


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


def test_the_arena_counts_commands_as_the_server_carries_them_out() -> None:
    from field_models.arena import COMMAND_COUNTERS, CountsCommands

    a = arena(noise=False)
    assert isinstance(a, CountsCommands)
    kick, dash, turn, say = (COMMAND_COUNTERS.index(c) for c in ("kick", "dash", "turn", "say"))
    a.submit(A, (Turn(math.radians(-20.0)), Dash(100.0), Dash(100.0), Say("hi")))
    a.step()  # the turn runs; the say goes out
    a.submit(A, (Turn(math.radians(40.0)),))  # the two dashes are never sent
    a.step()
    a.step()
    counts = a.command_tally()[A].counts
    assert len(counts) == len(COMMAND_COUNTERS)
    assert (counts[turn], counts[dash], counts[say], counts[kick]) == (2, 0, 1, 0)
    assert sum(counts) == 3 and sum(a.command_tally()[B].counts) == 0
    # A kick with the ball at the feet takes effect, flagged for that tick only; one out of
    # reach is carried out (and counted) but misses.
    a.place_ball(-9.5, 0.0)
    a.submit(A, (Kick(50.0, 0.0),))
    a.step()
    tally = a.command_tally()[A]
    assert (tally.kicked, tally.kick_missed, tally.counts[kick]) == (True, False, 1)
    a.step()
    assert not a.command_tally()[A].kicked
    a.submit(B, (Kick(50.0, 0.0),))
    a.step()
    tally = a.command_tally()[B]
    assert (tally.kicked, tally.kick_missed, tally.counts[kick]) == (False, True, 1)


def test_a_say_is_heard_with_the_next_percept_and_the_referee_by_all() -> None:
    a = arena("rcssserver_19_async")
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
    assert a.score() == (1, 0)


def _run(traced: bool) -> list[Percept]:
    a = arena(trace=traced, seed=3)
    a.place_ball(-5.0, 3.0, 8.0, -2.0)
    minds = {ref: ChaseLoad() for ref in (A, B)}
    seen = []
    for _ in range(120):
        for percept in a.step():
            seen.append(percept)
            a.submit(percept.player, minds[percept.player].act(percept))
    return seen


def test_the_fast_path_gives_the_percepts_the_text_route_gives() -> None:
    """Tracing takes percepts from the rendered and parsed see text; without it the structured
    fast path runs. Same seeds, same actions: the same ball, players and goals."""
    fast, text = _run(False), _run(True)
    assert len(fast) == len(text) > 20
    for f, t in zip(fast, text, strict=True):
        goals = tuple(m for m in t.landmarks if m.name in ("g l", "g r"))
        assert (f.tick, f.ball, f.players, f.heard) == (t.tick, t.ball, t.players, t.heard)
        assert f.landmarks == goals


def test_events_are_command_text_and_sees_when_tracing() -> None:
    a = arena(trace=True)
    a.submit(A, (Turn(math.radians(30.0)), Dash(100.0, math.radians(-90.0)), Say("hi")))
    for _ in range(3):
        a.step()
    events = a.drain_events()
    commands = [e.text for e in events if e.channel == "command"]
    assert commands == ["(turn -30)", "(dash 100 90)", "(say hi)"]
    assert any(e.channel == "see" and e.text.startswith("(see ") for e in events)
    assert a.drain_events() == []
