"""The served game (field_models.soccer_server.serving): joins, commands, replies, the cycle."""

from __future__ import annotations

import math

import numpy as np
import pytest

from field_models.protocol import LEFT, RIGHT, PlayerRef
from field_models.rcss_params import SERVER_PARAMS
from field_models.soccer_server.messages import parse_hear, parse_see
from field_models.soccer_server.params import load_server_preset
from field_models.soccer_server.serving import ServedGame
from field_models.soccer_server.serving_state import Client


def game(synch: bool = False, **kw) -> ServedGame:
    return ServedGame(load_server_preset("rcssserver_19_async"), synch=synch, **kw)


def texts(g: ServedGame, client: Client) -> list[str]:
    return [text for c, text in g.drain() if c is client]


def join_player(g: ServedGame, team: str, version: int = 19) -> Client:
    client, reply = g.join("player", f"(init {team} (version {version}))")
    assert client is not None, reply
    return client


def test_players_join_sides_and_numbers_as_the_server_assigns_them() -> None:
    g = game()
    a, b, c = join_player(g, "HELIOS"), join_player(g, "HELIOS"), join_player(g, "CYRUS", 8)
    assert (a.ref, b.ref, c.ref) == (PlayerRef(LEFT, 1), PlayerRef(LEFT, 2), PlayerRef(RIGHT, 1))
    out = g.drain()
    assert next(t for cl, t in out if cl is a) == "(init l 1 before_kick_off)"
    assert next(t for cl, t in out if cl is c) == "(init r 1 before_kick_off)"
    params = [t for cl, t in out if cl is a and t.startswith("(server_param ")]
    names = [p.split(" ")[0] for p in params[0][len("(server_param ") :].split("(")[1:]]
    assert names == sorted(names) == [n for n, v, _ in SERVER_PARAMS if v <= 19]
    types = [t for cl, t in out if cl is a and t.startswith("(player_type ")]
    assert len(types) == 18 and types[0].startswith("(player_type (id 0)(player_speed_max 1.05)")
    third, reply = g.join("player", "(init OTHER (version 19))")
    assert third is None and reply == "(error no_more_team)"


@pytest.mark.parametrize(
    ("text", "reply"),
    [
        ("(init)", "(error illegal_teamname)"),
        ("(init NAME_THAT_IS_TOO_LONG)", "(error illegal_teamname_or_too_long_teamname)"),
        ("(init T (version x))", "(error illegal_command_form)"),
        ("(init T (colour red))", "(error illegal_command_form)"),
        ("(hello)", "(error unknown_command)"),
        ("init T", "(error illegal_command_form)"),
        ("(dispinit)", "(error illegal_client_version)"),
        ("(dispinit version 2)", "(error illegal_client_version)"),
        ("(reconnect NOBODY 1)", "(error no_such_team_or_player)"),
    ],
)
def test_a_bad_first_message_gets_the_servers_error(text: str, reply: str) -> None:
    lines: list[str] = []
    client, answer = game(log=lines.append).join("player", text)
    assert client is None and answer == reply and lines


def test_player_commands_move_the_model_and_unmodelled_ones_are_answered() -> None:
    g = game(start_mode="play_on")
    a = join_player(g, "T")
    trainer, _ = g.join("trainer", "(init (version 19))")
    assert trainer is not None
    g.receive(trainer, "(move (player T 1) -10 0 0)(move (ball) -9 0)")
    g.drain()
    g.receive(a, "(kick 100 0)(dash 100)")  # the first body command of a cycle wins
    g.receive(a, "(turn_neck 30)(turn_neck 50)")  # goes with the kick; the first one wins
    g.receive(a, "(catch 0)")
    assert texts(g, a) == ["(error unknown_command)"]
    g.step()
    ball, _ = g.truth()
    assert ball.x > -9.0 + 2.0  # kicked
    sense = [t for t in texts(g, a) if t.startswith("(sense_body")]
    assert "(kick 1) (dash 0)" in sense[0]
    assert "(head_angle 30)" in sense[0] and "(turn_neck 1)" in sense[0]
    g.receive(a, "(turn_neck 100)")  # the neck stops at maxneckang
    g.step()
    sense = [t for t in texts(g, a) if t.startswith("(sense_body")]
    assert "(head_angle 90)" in sense[0] and "(turn_neck 2)" in sense[0]


def test_trainer_move_look_and_modes_follow_the_server_frame() -> None:
    g = game()
    a = join_player(g, "T")
    trainer, _ = g.join("trainer", "(init (version 19))")
    assert trainer is not None
    g.drain()
    g.receive(trainer, "(move (player T 1) 10 -5 90)(move (ball) 1 2 0 0.5 0)(look)")
    replies = texts(g, trainer)
    assert replies[:2] == ["(ok move)", "(ok move)"]
    assert replies[2] == (
        '(ok look 0 ((g l) -52.5 0) ((g r) 52.5 0) ((b) 1 2 0.5 0) ((p "T" 1) 10 -5 0 0 90 0))'
    )
    _, players = g.truth()
    state = players[a.ref]  # type: ignore[index]
    assert (state.x, state.y) == (10.0, 5.0) and math.isclose(state.heading, -math.pi / 2)
    g.receive(trainer, "(change_mode play_on)(change_mode penalty_kick_l)(eye on)")
    assert texts(g, trainer) == ["(ok change_mode)", "(error illegal_mode)"]
    g.receive(trainer, "(eye on)(ear on)(check_ball)(team_names)(recover)(start)(compression 1)")
    assert texts(g, trainer) == [
        "(ok eye on)",
        "(ok ear on)",
        "(ok check_ball 0 in_field)",
        "(ok team_names (team l T))",
        "(ok recover)",
        "(ok start)",
        "(warning compression_unsupported)",
    ]
    g.step()
    assert any(t.startswith("(see_global 1 ") for t in texts(g, trainer))


def test_sees_and_hears_follow_each_clients_protocol() -> None:
    g = game(start_mode="play_on")
    old, new = join_player(g, "A", 5), join_player(g, "B", 19)
    trainer, _ = g.join("trainer", "(init (version 19))")
    assert trainer is not None
    g.receive(trainer, "(move (player A 1) -5 0 0)(move (player B 1) 5 0 180)")
    g.receive(new, '(say "hello")')
    g.drain()
    g.step()
    got = texts(g, old)
    heard = [parse_hear(t) for t in got if t.startswith("(hear")]
    assert heard and heard[0].text == "hello" and heard[0].team is None
    sees = [t for t in got if t.startswith("(see")]
    assert sees and "(player B 1)" in sees[0]  # long names before protocol 6
    assert parse_see(sees[0]).find("p") is not None


def test_synch_mode_waits_for_every_done_and_sends_think() -> None:
    g = game(synch=True)
    a, b = join_player(g, "A"), join_player(g, "B")
    assert not g.ready()
    g.receive(a, "(done)")
    assert not g.ready()
    g.receive(b, "(dash 10)(done)")
    assert g.ready()
    g.drain()
    g.step()
    assert texts(g, a)[-1] == "(think)" and not g.ready()


def test_monitor_gets_parameters_and_a_show_of_22_slots_every_cycle() -> None:
    g = game()
    join_player(g, "A")
    monitor, _ = g.join("player", "(dispinit version 3)")
    assert monitor is not None
    first = texts(g, monitor)
    assert first[0].startswith("(server_param (audio_cut_dist 50)")
    g.step()
    show = next(t for t in texts(g, monitor) if t.startswith("(show"))
    assert show.startswith("(show 1 (pm 1) (tm A null 0 0) ((b) 0 0 0 0)")
    assert show.count("((l ") == 11 and show.count("((r ") == 11
    assert "((l 1) 0 0x1 -3 -37 0 0 0 0 (v h 90) (s 8000 1 1) (c 0 0 0 0 0 0 0 0 0 0 0))" in show


def test_bye_and_reconnect_keep_the_slots() -> None:
    g = game()
    a = join_player(g, "A")
    g.receive(a, "(bye)")
    assert PlayerRef(LEFT, 1) not in g.players
    back, _reply = g.join("player", "(reconnect A 1)")
    assert back is not None and back.ref == PlayerRef(LEFT, 1)
    assert texts(g, back) == ["(reconnect l before_kick_off)"]


# ----------------------------------------------------------------------------- fuzzing

VALID = (
    "(init T (version 19))",
    "(dash 100 30)",
    "(turn -45)",
    "(kick 80 10)",
    '(say "hi there")',
    "(move -10 5)",
    "(change_view wide low)",
    "(sense_body)",
    "(done)",
    "(move (ball) 1 2 0 0.5 -0.5)",
    "(move (player T 1) 3 4 90)",
    "(change_mode play_on)",
    "(look)",
    "(eye on)",
    "(dispinit version 3)",
    "(reconnect T 1)",
)
ALPHABET = b'()"\0 \t\nabcdeilmnoprstuvy0123456789.-+eE_\xff\x80'


def fuzz_datagrams(rng: np.random.Generator, n: int) -> list[bytes]:
    """`n` hostile datagrams: valid commands mutated, cut, glued, nested, or random bytes."""
    out: list[bytes] = []
    for _ in range(n):
        kind = rng.integers(6)
        base = bytearray(VALID[rng.integers(len(VALID))].encode())
        if kind == 0:  # flip bytes
            for _ in range(rng.integers(1, 4)):
                base[rng.integers(len(base))] = ALPHABET[rng.integers(len(ALPHABET))]
        elif kind == 1:  # cut short
            base = base[: rng.integers(len(base))]
        elif kind == 2:  # glue several, some wrong
            base = b"".join(VALID[rng.integers(len(VALID))].encode() for _ in range(5))
            base = bytearray(base)
            base.insert(rng.integers(len(base)), ALPHABET[rng.integers(len(ALPHABET))])
        elif kind == 3:  # deep nesting or a huge number
            depth = int(rng.integers(1, 40))
            base = bytearray(b"(dash " + b"(" * depth + b"1e999" + b")" * depth + b")")
        elif kind == 4:  # random bytes
            base = bytearray(rng.integers(0, 256, size=rng.integers(0, 200)).astype(np.uint8))
        else:  # an overlong datagram
            base = bytearray(b"(say " + b"a" * int(rng.integers(1, 20000)) + b")")
        out.append(bytes(base))
    return out


def fuzz_game(seed: int, n: int) -> tuple[int, int]:
    """Feed `n` fuzzed datagrams to every kind of client; returns (datagrams, error replies)."""
    from field_models.soccer_server.wire import decode

    rng = np.random.default_rng(seed)
    g = game(synch=True, start_mode="play_on")
    player = join_player(g, "T")
    trainer, _ = g.join("trainer", "(init (version 19))")
    monitor, _ = g.join("player", "(dispinit version 3)")
    assert trainer is not None and monitor is not None
    errors = 0
    for i, data in enumerate(fuzz_datagrams(rng, n)):
        text = decode(data)
        target = i % 4
        if target == 0 and player.ref in g.players:
            g.receive(player, text)
        elif target == 1 and g.trainer is trainer:
            g.receive(trainer, text)
        elif target == 2 and monitor in g.monitors:
            g.receive(monitor, text)
        else:
            _joined, reply = g.join("player" if i % 2 else "trainer", text)
            errors += reply.startswith("(error")
        if player.ref not in g.players:
            player = join_player(g, "T") if len(g.players) < 11 else player
        if i % 10 == 0:
            g.step()
        errors += sum(t.startswith("(error") for _, t in g.drain())
    return n, errors


def test_hostile_datagrams_get_errors_never_exceptions() -> None:
    sent, errors = fuzz_game(seed=7, n=3000)
    assert errors > sent // 4  # most of them are refused, each with an answer
