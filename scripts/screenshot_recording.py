"""Screenshot a rerun recording as a person sees it: the web viewer in headless Chromium.

Usage::

    .venv/bin/python scripts/screenshot_recording.py RECORDING.rrd SHOT.png [--wait 25]

Serves the recording with the venv's ``rerun --web-viewer`` bound to 127.0.0.1, opens the
viewer in headless Chromium with a software GL backend (no GPU, no display), waits in real time
for the viewer to load and play the recording to its end, and saves a PNG.

Why a script and not ``chromium --screenshot``: that flag shoots as soon as the page has loaded,
before the viewer's WebAssembly has drawn anything, and ``--virtual-time-budget`` does not advance
the viewer's clock. Chrome's DevTools protocol lets us wait in real time and then capture; the
small WebSocket client below keeps the script free of dependencies.
"""

from __future__ import annotations

import argparse
import base64
import json
import os
import shutil
import socket
import struct
import subprocess
import sys
import tempfile
import time
import urllib.request
from pathlib import Path
from typing import Any

CHROMIUM_FLAGS = (
    "--headless=new",
    "--use-gl=angle",
    "--use-angle=swiftshader",
    "--enable-unsafe-swiftshader",
    "--no-sandbox",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--remote-allow-origins=*",
)


class DevTools:
    """A minimal WebSocket client for one Chrome DevTools page target (text frames only)."""

    def __init__(self, ws_url: str) -> None:
        host_port, path = ws_url.split("://", 1)[1].split("/", 1)
        host, port = host_port.split(":")
        self._sock = socket.create_connection((host, int(port)))
        key = base64.b64encode(os.urandom(16)).decode()
        self._sock.sendall(
            (
                f"GET /{path} HTTP/1.1\r\nHost: {host_port}\r\nUpgrade: websocket\r\n"
                f"Connection: Upgrade\r\nSec-WebSocket-Key: {key}\r\n"
                "Sec-WebSocket-Version: 13\r\n\r\n"
            ).encode()
        )
        buf = b""
        while b"\r\n\r\n" not in buf:
            buf += self._sock.recv(4096)
        self._buf = buf.split(b"\r\n\r\n", 1)[1]
        self._next_id = 0

    def _read(self, n: int) -> bytes:
        while len(self._buf) < n:
            chunk = self._sock.recv(1 << 20)
            if not chunk:
                raise EOFError("DevTools connection closed")
            self._buf += chunk
        data, self._buf = self._buf[:n], self._buf[n:]
        return data

    def _send(self, text: str) -> None:
        payload = text.encode()
        n = len(payload)
        if n < 126:
            header = bytes([0x81, 0x80 | n])
        elif n < 65536:
            header = bytes([0x81, 0x80 | 126]) + struct.pack(">H", n)
        else:
            header = bytes([0x81, 0x80 | 127]) + struct.pack(">Q", n)
        mask = os.urandom(4)  # clients must mask every frame (RFC 6455 §5.3)
        self._sock.sendall(header + mask + bytes(b ^ mask[i % 4] for i, b in enumerate(payload)))

    def _receive(self) -> str:
        parts = b""
        while True:
            first, second = self._read(2)
            n = second & 0x7F
            if n == 126:
                n = struct.unpack(">H", self._read(2))[0]
            elif n == 127:
                n = struct.unpack(">Q", self._read(8))[0]
            parts += self._read(n)
            if first & 0x80:  # FIN: the message is complete
                return parts.decode()

    def call(self, method: str, **params: Any) -> dict[str, Any]:
        """Send one DevTools command and return its reply (events in between are skipped)."""
        self._next_id += 1
        self._send(json.dumps({"id": self._next_id, "method": method, "params": params}))
        while True:
            message: dict[str, Any] = json.loads(self._receive())
            if message.get("id") == self._next_id:
                return message


def _page_target(port: int, timeout_s: float = 30.0) -> str:
    """The WebSocket URL of Chromium's first page, once its DevTools endpoint answers."""
    deadline = time.monotonic() + timeout_s
    while True:
        try:
            with urllib.request.urlopen(f"http://127.0.0.1:{port}/json") as reply:
                targets = json.load(reply)
            return str(next(t for t in targets if t["type"] == "page")["webSocketDebuggerUrl"])
        except (OSError, StopIteration):
            if time.monotonic() > deadline:
                raise
            time.sleep(0.2)


def screenshot(recording: Path, out: Path, *, wait_s: float, width: int, height: int) -> None:
    """Serve `recording`, load the viewer in headless Chromium, wait `wait_s`, save `out`."""
    rerun = Path(sys.executable).parent / "rerun"
    grpc_port, web_port, cdp_port = 9876, 9090, 9333
    viewer = subprocess.Popen(
        [str(rerun), "--web-viewer", "--bind", "127.0.0.1", "--port", str(grpc_port),
         "--web-viewer-port", str(web_port), str(recording)],
        env={**os.environ, "CI": "true"},  # no analytics files
        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True,
    )  # fmt: skip
    profile = tempfile.mkdtemp()
    browser = subprocess.Popen(
        ["chromium", *CHROMIUM_FLAGS, f"--window-size={width},{height}",
         f"--user-data-dir={profile}", f"--remote-debugging-port={cdp_port}", "about:blank"],
        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True,
    )  # fmt: skip
    try:
        page = DevTools(_page_target(cdp_port))
        page.call("Emulation.setDeviceMetricsOverride", width=width, height=height,
                  deviceScaleFactor=1, mobile=False)  # fmt: skip
        time.sleep(2.0)  # let the viewer's servers come up
        source = f"rerun%2Bhttp://127.0.0.1:{grpc_port}/proxy"
        page.call("Page.navigate", url=f"http://127.0.0.1:{web_port}/?url={source}")
        time.sleep(wait_s)
        shot = page.call("Page.captureScreenshot", format="png")
        out.write_bytes(base64.b64decode(shot["result"]["data"]))
    finally:
        for proc in (browser, viewer):
            os.killpg(proc.pid, 15)
            proc.wait()
        shutil.rmtree(profile, ignore_errors=True)


def main() -> int:
    """Parse the command line and take the screenshot."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("recording", type=Path, help="a .rrd file")
    parser.add_argument("out", type=Path, help="the PNG to write")
    parser.add_argument("--wait", type=float, default=25.0, help="seconds to wait (default 25)")
    parser.add_argument("--size", type=int, nargs=2, default=(1600, 1000), metavar=("W", "H"))
    args = parser.parse_args()
    if not args.recording.is_file():
        parser.error(f"no such recording: {args.recording}")
    if shutil.which("chromium") is None:
        parser.error("chromium is not installed (Debian: apt install chromium)")
    screenshot(args.recording, args.out, wait_s=args.wait, width=args.size[0], height=args.size[1])
    print(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
