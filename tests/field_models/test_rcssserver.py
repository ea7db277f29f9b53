"""The rcssserver field model: a Soccer Server over UDP behind the Arena interface.

The conformance suite runs on it in ``tests/field_models/test_conformance.py`` (the ``served``
preset: our model served in-process; the ``binary`` preset when ``RCSSSERVER`` names a real
rcssserver, skipped otherwise). These tests cover what is particular to the wire.
"""

from __future__ import annotations

import math
import os
import socket
import threading
import time

import pytest

from field_models.checker import QUIET
from field_models.presets import PresetError
from field_models.protocol import LEFT, RIGHT, BodyState, Dash, PlayerRef
from field_models.rcssserver.client import WireError
from field_models.rcssserver.launch import free_port_triple
from field_models.rcssserver.wire_text import head_angle, move_text, parse_look, sense_time
from field_models.registry import DEFAULT_OPTIONS, entry, make_arena
from field_models.seeding import TrialRngs


def test_a_trial_with_gaps_in_the_numbers_connects_and_closes_its_server() -> None:
    players = (PlayerRef(LEFT, 2), PlayerRef(RIGHT, 1))
    before = threading.active_count()
    arena = make_arena("rcssserver", "served", players, TrialRngs.for_trial(0, 0))
    arena.place_player(players[0], -5.0, 0.0, 0.0)
    arena.place_player(players[1], 5.0, 0.0, math.pi)
    arena.place_ball(0.0, 3.0)
    assert set(arena.truth().players) == set(players)  # the filler (left 1) said bye
    seen = []
    for _ in range(10):
        for percept in arena.step():
            seen.append(percept)
            arena.submit(percept.player, (Dash(50.0),))
    assert {p.player for p in seen} == set(players)
    assert arena.player_state(players[0]).x > -5.0  # dashed toward +x
    arena.close()  # type: ignore[attr-defined]
    assert threading.active_count() == before


def test_the_binary_preset_says_why_it_cannot_run_without_rcssserver() -> None:
    if os.environ.get("RCSSSERVER"):
        pytest.skip("RCSSSERVER is set: the conformance suite runs the real server")
    module = entry("rcssserver")
    preset = module.load("binary", DEFAULT_OPTIONS)
    with pytest.raises(RuntimeError, match="RCSSSERVER"):
        make_arena("rcssserver", "binary", (PlayerRef(LEFT, 1),), TrialRngs.for_trial(0, 0))
    assert "RCSSSERVER" in (module.unavailable(preset) or "")  # type: ignore[attr-defined]


@pytest.mark.parametrize("stale", [(LEFT,), (LEFT, RIGHT)], ids=["left", "both"])
def test_a_stale_think_from_before_the_first_step_is_read_past(stale) -> None:
    """A real rcssserver sends ``(think)`` to the players it waits for during the set-up.

    Emulated on the served server: its own port sends a cycle-0 ``sense_body`` and ``(think)``
    to some clients before the first step. Every step still ends on the server's new cycle, so
    a ball rolls one cycle per step and both players' sees are of the same cycle.
    """
    players = (PlayerRef(LEFT, 1), PlayerRef(RIGHT, 1))
    rngs = TrialRngs.for_trial(0, 0)
    arena = make_arena("rcssserver", "served", players, rngs, QUIET, trace=True)
    arena.place_player(players[0], 0.0, 0.0, 0.0)
    arena.place_player(players[1], 10.0, 5.0, math.pi)
    arena.place_ball(-20.0, 0.0, 10.0, 0.0)
    _, _, server = next(r for r in arena._resources if isinstance(r, tuple))  # type: ignore[attr-defined]
    for ref in players:
        if ref.team in stale:
            address = arena._clients[ref].sock.getsockname()  # type: ignore[attr-defined]
            own = next(own for own, addr in server._route.values() if addr == address)
            own.sendto(b"(sense_body 0 (view_mode high normal))\0", address)
            own.sendto(b"(think)\0", address)
    time.sleep(0.05)
    percepts = []
    for _ in range(10):
        percepts += arena.step()
    ball = arena.ball_state()
    assert math.isclose(ball.x + 20.0, 10.0 * 0.1 * (1 - 0.94**10) / 0.06, rel_tol=1e-4)
    sees: dict[int, set[str]] = {}
    for event in arena.drain_events():  # type: ignore[attr-defined]
        if event.channel == "see":
            sees.setdefault(event.tick, set()).add(event.text.split()[1])
    assert sees and all(times == {str(tick)} for tick, times in sees.items())
    assert all(p.observed_tick == p.tick for p in percepts)
    arena.close()  # type: ignore[attr-defined]


@pytest.mark.parametrize("version", [0, 20])
def test_a_protocol_version_the_server_does_not_speak_is_refused(tmp_path, version) -> None:
    wire = tmp_path / "wire.toml"
    wire.write_text(f'[server]\nstart = "served"\nclient_version = {version}\n')
    with pytest.raises(
        PresetError, match=rf"client_version': expected a protocol version 1 to 19, got {version}$"
    ):
        entry("rcssserver").load(str(wire), DEFAULT_OPTIONS)
    sensing = tmp_path / "sensing.toml"
    sensing.write_text(f'base = "rcssserver_19"\n[sensing]\nprotocol_version = {version}\n')
    with pytest.raises(PresetError, match=r"protocol_version.*\[1, 19\]"):
        entry("soccer_server").load(str(sensing), DEFAULT_OPTIONS)


def test_the_trainers_move_and_look_texts_convert_frames_both_ways() -> None:
    dt = 0.5  # a cycle length that keeps the velocities exact
    assert move_text(1.0, 2.0, math.pi / 2, 3.0, -4.0, dt) == "1.0 -2.0 -90.0 1.5 2.0"
    look = (
        "(ok look 7 ((g r) 52.5 0) ((b) 1 -2 1.5 2) "
        '((p "left" 2 0) 5 6 -0.5 1 -90 0) ((p "other" 1 0) 0 0 0 0 0 0))'
    )
    ball, players = parse_look(look, dt)
    assert ball == BodyState(1.0, 2.0, 0.0, 3.0, -4.0)
    assert list(players) == [PlayerRef(LEFT, 2)]
    left = players[PlayerRef(LEFT, 2)]
    assert (left.x, left.y, left.vx, left.vy) == (5.0, -6.0, -1.0, -2.0)
    assert left.heading == pytest.approx(math.pi / 2)
    with pytest.raises(WireError, match="unreadable look"):
        parse_look("(ok look 7 ((b) 1", dt)


def test_a_sense_body_gives_the_last_time_and_neck_of_a_batch() -> None:
    batch = [
        "(sense_body 3 (view_mode high normal) (head_angle 10))",
        "(hear 3 referee play_on)",
        "(sense_body 4 (view_mode high normal) (head_angle -30))",
    ]
    assert sense_time(batch) == 4
    assert head_angle(batch) == pytest.approx(math.radians(30.0))
    assert sense_time(["(hear 3 referee play_on)"]) is None
    assert head_angle(["(sense_body 5 (view_mode high normal))"]) == 0.0


def test_a_free_port_triple_has_three_free_consecutive_ports() -> None:
    base = free_port_triple()
    sockets = [socket.socket(socket.AF_INET, socket.SOCK_DGRAM) for _ in range(3)]
    try:
        for offset, s in enumerate(sockets):
            s.bind(("127.0.0.1", base + offset))  # raises if one was taken
    finally:
        for s in sockets:
            s.close()
