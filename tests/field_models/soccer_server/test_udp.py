"""The served game on real UDP sockets (127.0.0.1, free ports), every loop bounded in time."""

from __future__ import annotations

import socket
import threading
from collections.abc import Iterator
from contextlib import contextmanager

import numpy as np

from field_models.soccer_server.params import load_server_preset
from field_models.soccer_server.serving import ServedGame
from field_models.soccer_server.udp import ServeStats, UdpServer
from tests.field_models.soccer_server.test_serving import fuzz_datagrams

HOST = "127.0.0.1"


@contextmanager
def served(
    synch: bool = False, seconds: float = 5.0, **kw: float
) -> Iterator[tuple[UdpServer, list[str]]]:
    """A server on free ports in a thread, stopped (at the latest after `seconds`) on exit."""
    lines: list[str] = []
    game = ServedGame(load_server_preset("rcssserver_19_async"), synch=synch, log=lines.append)
    server = UdpServer(game, port=0, trainer_port=0, olcoach_port=0, **kw)
    stop = threading.Event()
    result: list[ServeStats] = []
    thread = threading.Thread(
        target=lambda: result.append(server.serve(seconds=seconds, stop=stop.is_set))
    )
    thread.start()
    try:
        yield server, lines
    finally:
        stop.set()
        thread.join(timeout=seconds + 2.0)
        server.close()


class Peer:
    """A client socket: send to the server's port, read replies until a prefix comes."""

    def __init__(self, port: int) -> None:
        self.sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.sock.settimeout(4.0)
        self.dest: tuple[str, int] = (HOST, port)

    def send(self, text: str | bytes) -> None:
        data = text.encode() + b"\0" if isinstance(text, str) else text
        self.sock.sendto(data, self.dest)

    def until(self, prefix: str, limit: int = 200) -> list[str]:
        got = []
        for _ in range(limit):
            data, addr = self.sock.recvfrom(65536)
            text = data.rstrip(b"\0").decode()
            got.append(text)
            if text.startswith(prefix):
                self.dest = addr  # talk to the port the server answered from
                return got
        raise AssertionError(f"no {prefix!r} in {limit} messages")

    def close(self) -> None:
        self.sock.close()


def test_each_client_is_answered_from_its_own_port_and_is_heard_there() -> None:
    with served() as (server, _):
        port, trainer_port, _ = server.ports
        player, trainer = Peer(port), Peer(trainer_port)
        try:
            player.send("(init WIRE (version 19))")
            assert player.until("(init ")[-1] == "(init l 1 before_kick_off)"
            assert player.dest[1] not in server.ports
            trainer.send("(init (version 19))")
            trainer.until("(init ok)")
            trainer.send("(move (player WIRE 1) -10 0 0)")
            assert trainer.until("(ok ")[-1] == "(ok move)"
            trainer.send("(look)")
            assert '((p "WIRE" 1) -10 0 0 0 0 0)' in trainer.until("(ok look")[-1]
            player.send("(score)")
            assert player.until("(score ")[-1].endswith(" 0 0)")
        finally:
            player.close()
            trainer.close()


def test_synch_mode_steps_when_the_player_is_done() -> None:
    with served(synch=True) as (server, _):
        player = Peer(server.ports[0])
        try:
            player.send("(init S (version 19))")
            player.until("(init ")
            for cycle in range(1, 6):
                player.send("(dash 50)(done)")
                got = [t for t in player.until("(think)") if t.startswith("(sense_body")]
                assert got[0].startswith(f"(sense_body {cycle} ")
        finally:
            player.close()


def test_a_silent_client_is_dropped() -> None:
    with served(idle_timeout_s=0.2, seconds=2.0) as (server, lines):
        player = Peer(server.ports[0])
        try:
            player.send("(init QUIET (version 19))")
            player.until("(init ")
            deadline = 400
            while not any("silent" in line for line in lines) and deadline:
                deadline -= 1
                threading.Event().wait(0.005)
            assert any("player QUIET 1 left: silent" in line for line in lines)
        finally:
            player.close()


def test_the_online_coach_port_answers_and_hostile_datagrams_do_no_harm() -> None:
    # Fuzzed inits may join players that never say (done): the synch timeout steps anyway.
    with served(synch=True, synch_timeout_s=0.2) as (server, _lines):
        port, trainer_port, olcoach_port = server.ports
        coach = Peer(olcoach_port)
        coach.send("(init T (version 19))")
        assert coach.until("(error")[-1] == "(error unknown_command)"
        player = Peer(port)
        player.send("(init FUZZ (version 19))")
        player.until("(init ")
        hostile = fuzz_datagrams(np.random.default_rng(3), 300)
        others = [Peer(port), Peer(trainer_port)]
        try:
            for i, data in enumerate(hostile):
                target = player if i % 3 == 0 else others[i % 2]
                target.sock.sendto(data, target.dest)
            player.send("(done)")
            player.until("(think)")  # still stepping, still answering
            fresh = Peer(port)
            fresh.send("(init LATE (version 8))")
            answer = fresh.until("(")[-1]  # a fuzzed init may have taken the right side
            assert answer.startswith("(init r ") or answer == "(error no_more_team)"
            fresh.close()
        finally:
            for peer in (coach, player, *others):
                peer.close()
        assert server.stats.errors > 0
