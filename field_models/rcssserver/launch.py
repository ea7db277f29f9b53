"""The wire arena's server and clients: started, connected, and shut down again.

A :class:`~field_models.rcssserver.arena.WireArena` gets its server by the preset's ``start``
(:func:`start_server`: our served model in a thread, a real rcssserver binary, or one already
running), connects one client per player (:func:`connect_players`), and records everything it
opened in one list of resources, which :func:`shut` closes, newest first, when the arena is
closed or collected.
"""

from __future__ import annotations

import contextlib
import os
import socket
import subprocess
import tempfile
import threading

from field_models.protocol import LEFT, RIGHT, PlayerRef
from field_models.rcssserver.client import WireClient, WireError
from field_models.rcssserver.config import WirePreset, server_options
from field_models.rcssserver.wire_text import TEAM_NAMES
from field_models.seeding import TrialRngs


def start_server(
    preset: WirePreset, rngs: TrialRngs, resources: list[object]
) -> tuple[str, int, int]:
    """Start (or find) the preset's server; its host, player port and trainer port.

    What it starts goes to `resources`: a binary's process and its home folder, or a served
    model's stop flag, thread and UDP server. A served model draws its noise from `rngs`.
    """
    p = preset
    if p.start == "address":
        return p.host, p.port, p.trainer_port
    if p.start == "binary":
        port = free_port_triple()
        # rcssserver writes its ~/.rcssserver/*.conf on start (a literal "~" folder in the
        # working directory where it does not expand it) and reads them back: a folder of
        # its own keeps a user's configuration out, and nothing is left behind.
        home = tempfile.TemporaryDirectory(prefix="rcssserver-")
        resources.append(home)
        process = subprocess.Popen(
            [p.binary, *server_options(p, port)],
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
            cwd=home.name,
            env={**os.environ, "HOME": home.name},
        )
        resources.append(process)
        return "127.0.0.1", port, port + 1
    # Imported here: the served model is needed only by this kind of preset.
    from field_models.soccer_server.serving import ServedGame
    from field_models.soccer_server.udp import UdpServer

    game = ServedGame(p.server, rngs=rngs, synch=True)
    # The arena is the only client: the server never needs to step without it.
    server = UdpServer(
        game, port=0, trainer_port=0, olcoach_port=0, synch_timeout_s=3600.0,
        idle_timeout_s=3600.0,
    )  # fmt: skip
    stop = threading.Event()
    thread = threading.Thread(
        target=server.serve, kwargs={"stop": stop.is_set}, daemon=True, name="served"
    )
    thread.start()
    resources.append((stop, thread, server))
    player, trainer, _ = server.ports
    return "127.0.0.1", player, trainer


def connect_players(
    preset: WirePreset,
    players: tuple[PlayerRef, ...],
    address: tuple[str, int],
    resources: list[object],
) -> dict[PlayerRef, WireClient]:
    """One client per player at `address` (host, player port), the left team first.

    Uniform numbers come from the server in order, so each team connects 1..N and says
    ``bye`` for the numbers not in `players`. Every client goes to `resources`.

    Raises:
        field_models.rcssserver.client.WireError: The server gave an unexpected number.
    """
    host, port = address
    version, timeout = preset.client_version, preset.timeout_s
    clients: dict[PlayerRef, WireClient] = {}
    for team in (LEFT, RIGHT):
        wanted = sorted(ref.number for ref in players if ref.team == team)
        if not wanted:
            continue
        fillers = []
        for number in range(1, wanted[-1] + 1):
            client = WireClient(host, port, timeout)
            resources.append(client)
            client.send(f"(init {TEAM_NAMES[team]} (version {version}))")
            reply = client.until("(init ")[-1]
            if reply.split()[2] != str(number):
                raise WireError(f"expected uniform number {number}, the server gave {reply}")
            ref = PlayerRef(team, number)
            if ref in players:
                clients[ref] = client
            else:
                fillers.append(client)
        for client in fillers:
            client.send("(bye)")  # a number the trial does not use: its slot stays empty
    return clients


def shut(resources: list[object]) -> None:
    """Close what an arena opened, newest first (kept apart from the arena: a finalizer)."""
    for item in reversed(resources):
        if isinstance(item, WireClient):
            with contextlib.suppress(OSError):
                item.send("(bye)")
            item.close()
        elif isinstance(item, subprocess.Popen):
            item.terminate()
            try:
                item.wait(timeout=5.0)
            except subprocess.TimeoutExpired:
                item.kill()
        elif isinstance(item, tempfile.TemporaryDirectory):
            item.cleanup()
        elif isinstance(item, tuple):
            stop, thread, server = item
            stop.set()
            thread.join(timeout=5.0)
            server.close()
    resources.clear()


def free_port_triple() -> int:
    """A port p with p, p+1 and p+2 free now (a real server's player, trainer, coach ports)."""
    for _ in range(100):
        probe = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        probe.bind(("127.0.0.1", 0))
        base = int(probe.getsockname()[1])
        probe.close()
        if base + 2 > 65535:
            continue
        held = []
        try:
            for p in (base, base + 1, base + 2):
                s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
                held.append(s)
                s.bind(("127.0.0.1", p))
            return base
        except OSError:
            continue
        finally:
            for s in held:
                s.close()
    raise WireError("no three free consecutive UDP ports")
