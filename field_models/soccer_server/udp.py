"""The served Soccer Server on UDP sockets, as rcssserver listens: one port per client.

:class:`UdpServer` puts a :class:`~field_models.soccer_server.serving.ServedGame` on the wire
(standard library ``socket`` and ``selectors``, no threads of its own):

* the **player port** (6000) takes players' ``init``/``reconnect`` and monitors' ``dispinit``;
  the **trainer port** (6001) the trainer's ``init``; the **online-coach port** (6002) answers
  ``(error unknown_command)`` (online coaches are not modelled). rcssserver's ports and roles
  (``server::port``, ``coach_port``, ``olcoach_port``); monitors use the player port there too.
* Each client that joins gets **its own socket** (a fresh port): its replies come from there,
  and, as rcssserver requires of protocol >= 8 clients, everything after its ``init`` goes
  there. Datagrams from a known client that still arrive on the shared port are taken too
  (rcssserver's ``undedicatedRecv``).
* **Synch mode**: a cycle runs as soon as every player (and a trainer with ``eye on``) has
  answered ``(think)`` with ``(done)``, or :attr:`UdpServer.synch_timeout_s` after the last
  cycle if one has not (rcssserver's synch timeout); with no such client the clock waits.
  **Real time**: a cycle every ``simulator_step`` ms of wall time.
* A client silent for :attr:`UdpServer.idle_timeout_s` is dropped, with a log line.
* Any datagram is survivable: text is cut at a NUL and at 8192 bytes, decoded as ASCII with
  replacements, and handed to the game, whose replies to a bad one are ``(error ...)``; a
  socket error while sending is logged and the client kept (UDP gives no promise anyway).

Binds 127.0.0.1 unless told otherwise. Port 0 picks free ports (tests); :attr:`ports` then says
which.
"""

from __future__ import annotations

import selectors
import socket
import time
from collections.abc import Callable
from dataclasses import dataclass

from field_models.soccer_server.serving import ServedGame
from field_models.soccer_server.serving_state import Client, Log
from field_models.soccer_server.wire import decode

READS_PER_WAKE = 512
"""Most datagrams read from one socket before the loop looks at the clock again."""


@dataclass(slots=True)
class ServeStats:
    """What a :meth:`UdpServer.serve` run did.

    Attributes:
        cycles: Cycles stepped.
        datagrams: Datagrams received.
        errors: Error replies sent (``(error ...)`` and ``(warning ...)``).
        wall_s: Wall time of the run [s].
    """

    cycles: int = 0
    datagrams: int = 0
    errors: int = 0
    wall_s: float = 0.0


class UdpServer:
    """A :class:`ServedGame` on UDP (module docstring).

    Args:
        game: The game to serve.
        host: Address to bind (127.0.0.1 by default: only this machine).
        port, trainer_port, olcoach_port: The shared ports (0: any free port).
        synch_timeout_s: Synch mode: step anyway this long after the last cycle.
        idle_timeout_s: Drop a client silent this long.
        log: Where lines about clients and refused datagrams go.
    """

    def __init__(
        self,
        game: ServedGame,
        *,
        host: str = "127.0.0.1",
        port: int = 6000,
        trainer_port: int = 6001,
        olcoach_port: int = 6002,
        synch_timeout_s: float = 1.25,
        idle_timeout_s: float = 30.0,
        log: Log | None = None,
    ) -> None:
        self.game = game
        self.host = host
        self.synch_timeout_s = synch_timeout_s
        self.idle_timeout_s = idle_timeout_s
        self.log: Log = log or game.log
        self.stats = ServeStats()
        self._closed = False
        self._sel = selectors.DefaultSelector()
        self._shared: dict[str, socket.socket] = {}
        for role, number in (
            ("player", port),
            ("trainer", trainer_port),
            ("olcoach", olcoach_port),
        ):
            sock = self._open(number)
            self._shared[role] = sock
            self._sel.register(sock, selectors.EVENT_READ, ("shared", role))
        self._by_addr: dict[tuple[str, int], Client] = {}
        self._route: dict[int, tuple[socket.socket, tuple[str, int]]] = {}

    def _open(self, port: int) -> socket.socket:
        sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        try:
            sock.bind((self.host, port))
            sock.setblocking(False)
        except OSError:
            sock.close()
            self.close()
            raise
        return sock

    @property
    def ports(self) -> tuple[int, int, int]:
        """The bound player, trainer and online-coach ports."""
        player, trainer, olcoach = (
            int(self._shared[r].getsockname()[1]) for r in ("player", "trainer", "olcoach")
        )
        return player, trainer, olcoach

    # ------------------------------------------------------------------ the loop

    def serve(
        self,
        *,
        cycles: int | None = None,
        seconds: float | None = None,
        stop: Callable[[], bool] | None = None,
        on_step: Callable[[ServedGame], None] | None = None,
    ) -> ServeStats:
        """Serve until `cycles` cycles ran, `seconds` passed, or `stop()` says so.

        `on_step` is called after every cycle (recordings). Returns the run's counts.
        """
        start = time.monotonic()
        end = start + seconds if seconds is not None else None
        dt = self.game.dt_s
        next_step = start + dt
        last_step = start
        next_idle_check = start + 1.0
        ran = 0
        while not self._closed:
            now = time.monotonic()
            if (cycles is not None and ran >= cycles) or (end is not None and now >= end):
                break
            if stop is not None and stop():
                break
            if self.game.synch:
                if self.game.ready() or (
                    self.game.has_synched() and now - last_step >= self.synch_timeout_s
                ):
                    if not self.game.ready():
                        self.log(f"synch: stepped cycle {self.game.time + 1} without every (done)")
                    self._step(on_step)
                    ran += 1
                    last_step = time.monotonic()
                    continue
                wait = self.synch_timeout_s - (now - last_step)
                wait = min(max(wait, 0.0), 0.05)
            else:
                if now >= next_step:
                    self._step(on_step)
                    ran += 1
                    next_step += dt
                    if next_step < now:  # fell behind (a slow machine): do not race to catch up
                        next_step = now + dt
                    continue
                wait = min(next_step - now, 0.05)
            if end is not None:
                wait = min(wait, max(0.0, end - now))
            self._pump(wait)
            if now >= next_idle_check:
                self._drop_idle(now)
                next_idle_check = now + 1.0
        self.stats.cycles += ran
        self.stats.wall_s += time.monotonic() - start
        return self.stats

    def _step(self, on_step: Callable[[ServedGame], None] | None) -> None:
        self.game.step()
        self._flush()
        if on_step is not None:
            on_step(self.game)

    def _pump(self, wait: float) -> None:
        """Wait up to `wait` seconds for datagrams; handle every one that came."""
        for key, _ in self._sel.select(wait):
            sock = key.fileobj
            assert isinstance(sock, socket.socket)
            kind, role = key.data
            for _ in range(READS_PER_WAKE):
                try:
                    data, addr = sock.recvfrom(65536)
                except (BlockingIOError, InterruptedError):
                    break
                except OSError as exc:  # e.g. an ICMP "port unreachable" reported on Linux
                    self.log(f"socket error on receive: {exc}")
                    break
                self.stats.datagrams += 1
                self._datagram(kind, role, sock, data, addr)
        self._flush()

    def _datagram(
        self, kind: str, role: str, sock: socket.socket, data: bytes, addr: tuple[str, int]
    ) -> None:
        text = decode(data)
        client = self._by_addr.get(addr)
        if client is not None:
            client.last_seen = time.monotonic()
            self.game.receive(client, text)
            return
        if kind == "own":
            return  # a stranger on a client's own port: not a client of ours
        if role == "olcoach":
            self.log(f"online coach from {addr[0]}:{addr[1]} refused: not modelled")
            self._send_raw(sock, addr, "(error unknown_command)")
            return
        joined, reply = self.game.join("trainer" if role == "trainer" else "player", text)
        if joined is None:
            self._send_raw(sock, addr, reply)
            return
        own = self._open(0)
        self._sel.register(own, selectors.EVENT_READ, ("own", role))
        joined.last_seen = time.monotonic()
        self._by_addr[addr] = joined
        self._route[joined.id] = (own, addr)

    def _flush(self) -> None:
        for client, text in self.game.drain():
            route = self._route.get(client.id)
            if route is not None:
                self._send_raw(*route, text)
        self._forget_departed()

    def _send_raw(self, sock: socket.socket, addr: tuple[str, int], text: str) -> None:
        if text.startswith(("(error", "(warning")):
            self.stats.errors += 1
        try:
            sock.sendto(text.encode("ascii", errors="replace") + b"\0", addr)
        except OSError as exc:
            self.log(f"socket error sending to {addr[0]}:{addr[1]}: {exc}")

    def _forget_departed(self) -> None:
        """Close the own sockets of clients the game no longer has (bye, dispbye, replaced)."""
        live = {c.id for c in self.game.clients()}
        for addr, client in list(self._by_addr.items()):
            if client.id not in live:
                del self._by_addr[addr]
                own, _ = self._route.pop(client.id)
                self._sel.unregister(own)
                own.close()

    def _drop_idle(self, now: float) -> None:
        for client in self.game.clients():
            if now - client.last_seen > self.idle_timeout_s:
                self.game.leave(client, f"silent for {self.idle_timeout_s:g} s")
        self._flush()

    def close(self) -> None:
        """Close every socket (the shared ports and each client's own)."""
        self._closed = True
        for key in list(self._sel.get_map().values()):
            sock = key.fileobj
            self._sel.unregister(sock)
            assert isinstance(sock, socket.socket)
            sock.close()
        self._sel.close()

    def __enter__(self) -> UdpServer:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()
