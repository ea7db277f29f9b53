"""A minimal rcssserver client: one UDP socket, the server's reply port, reads with a deadline.

The over-the-wire field model drives one :class:`WireClient` per player and one for the trainer;
the speed benchmark uses the same client. It speaks the protocol's framing only (datagrams of
NUL-terminated text, replies from the client's own server port); what the messages mean is the
arena's business.
"""

from __future__ import annotations

import socket
import time


class WireError(RuntimeError):
    """The server did not answer as the protocol says (a timeout, an error reply)."""


class WireClient:
    """One client connection to a Soccer Server.

    Args:
        host: The server's address.
        port: The port to send the first message to (player or trainer port).
        timeout_s: How long a read waits before :class:`WireError`.
    """

    def __init__(self, host: str, port: int, timeout_s: float = 5.0) -> None:
        self.sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.sock.bind(("127.0.0.1" if host in ("127.0.0.1", "localhost") else "", 0))
        self.dest = (host, port)
        self.timeout_s = timeout_s

    def send(self, text: str) -> None:
        """Send one datagram (NUL-terminated, as the server's own clients send)."""
        self.sock.sendto(text.encode("ascii") + b"\0", self.dest)

    def receive(self) -> str:
        """The next message; the first reply also fixes the port later messages go to.

        Raises:
            WireError: Nothing came within the timeout.
        """
        self.sock.settimeout(self.timeout_s)
        try:
            data, addr = self.sock.recvfrom(65536)
        except TimeoutError:
            raise WireError(
                f"no message from {self.dest[0]}:{self.dest[1]} in {self.timeout_s} s"
            ) from None
        if addr[0] == self.dest[0] or self.dest[0] == "localhost":
            self.dest = addr  # the server answers from the client's own port (protocol >= 8)
        return data.split(b"\0", 1)[0].decode("ascii", errors="replace")

    def until(self, prefix: str, limit: int = 10_000) -> list[str]:
        """Messages up to and including the first that starts with `prefix`.

        Raises:
            WireError: An ``(error ...)`` reply, a timeout, or `limit` messages without it.
        """
        got: list[str] = []
        deadline = time.monotonic() + self.timeout_s
        while len(got) < limit and time.monotonic() < deadline:
            text = self.receive()
            got.append(text)
            if text.startswith(prefix):
                return got
            if text.startswith("(error"):
                raise WireError(f"the server answered {text} while waiting for {prefix}")
        raise WireError(f"no {prefix} from the server")

    def poll(self) -> list[str]:
        """The messages that have arrived, without waiting."""
        got = []
        self.sock.setblocking(False)
        try:
            while True:
                data, _ = self.sock.recvfrom(65536)
                got.append(data.split(b"\0", 1)[0].decode("ascii", errors="replace"))
        except (BlockingIOError, InterruptedError):
            pass
        finally:
            self.sock.setblocking(True)
        return got

    def close(self) -> None:
        """Close the socket."""
        self.sock.close()
