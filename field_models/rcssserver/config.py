"""The ``rcssserver`` field model's preset record: which server to drive, and how to start it.

The preset file's keys are listed in :mod:`field_models.rcssserver.model`'s docstring;
:func:`load` reads one (errors name the file and the key), :func:`server_options` gives the
``server::`` options that start a real rcssserver like it.
"""

from __future__ import annotations

import math
import os
import shutil
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path
from typing import Literal

from field_models.arena import FieldOptions
from field_models.presets import PresetError, preset_path, read_preset
from field_models.soccer_server import model as served_model
from field_models.soccer_server.params import ServerPreset

NAME = "rcssserver"
"""The field model's registered name (its presets' folder)."""

ENV_BINARY = "RCSSSERVER"
"""The environment variable naming a real rcssserver executable."""

Start = Literal["served", "address", "binary"]

MAX_PROTOCOL = 19
"""The newest client protocol rcssserver 19 speaks (``(init Team (version V))``, V from 1)."""


@dataclass(frozen=True)
class WirePreset:
    """A server to drive, and the Soccer Server preset it runs (module docstring).

    Attributes:
        name: The preset's name.
        start: ``served``, ``address`` or ``binary``.
        server: The Soccer Server preset (options applied).
        host, port, trainer_port: Where an ``address`` server listens.
        binary: The executable of a ``binary`` server ("" until resolved: not found).
        options: Extra ``server::`` options for a binary.
        client_version: The protocol version the arena's clients ask for.
        timeout_s: Longest wait for an answer [s].
    """

    name: str
    start: Start
    server: ServerPreset
    host: str = "127.0.0.1"
    port: int = 6000
    trainer_port: int = 6001
    binary: str = ""
    options: tuple[str, ...] = ()
    client_version: int = 17
    timeout_s: float = 5.0


_KEYS = {
    "start": str,
    "model_preset": str,
    "host": str,
    "port": int,
    "trainer_port": int,
    "binary": str,
    "options": list,
    "client_version": int,
    "timeout_s": float,
}


@lru_cache(maxsize=32)
def load(preset: str, options: FieldOptions) -> WirePreset:
    """The preset with the run's options applied to its Soccer Server preset.

    Raises:
        field_models.presets.PresetError: A missing or wrong preset file (naming the key).
        ValueError: An option the Soccer Server model refuses (a sensor latency, ...).
    """
    path = preset_path(preset, NAME)
    table = read_preset(path, NAME)
    name = str(table.pop("name", Path(path).stem))
    server = table.pop("server", None)
    if not isinstance(server, dict) or table:
        key = next(iter(table), "server")
        raise PresetError(f"{path}: key '{key}': expected one [server] table")
    for key, value in server.items():
        want = _KEYS.get(key)
        if want is None:
            raise PresetError(f"{path}: key 'server.{key}': unknown (known: {', '.join(_KEYS)})")
        ok = isinstance(value, want) or (want is float and isinstance(value, int))
        if not ok or isinstance(value, bool):
            raise PresetError(f"{path}: key 'server.{key}': expected {want.__name__}")
    start = server.get("start", "served")
    if start not in ("served", "address", "binary"):
        raise PresetError(f"{path}: key 'server.start': expected served, address or binary")
    version = server.get("client_version", 17)
    if not 1 <= version <= MAX_PROTOCOL:
        raise PresetError(
            f"{path}: key 'server.client_version': expected a protocol version 1 to "
            f"{MAX_PROTOCOL}, got {version}"
        )
    base = served_model.load(str(server.get("model_preset", "rcssserver_19_async")), options)
    binary = str(server.get("binary", "")) or os.environ.get(ENV_BINARY, "")
    found = shutil.which(binary) if binary else None
    return WirePreset(
        name=name,
        start=start,
        server=base,
        host=str(server.get("host", "127.0.0.1")),
        port=int(server.get("port", 6000)),
        trainer_port=int(server.get("trainer_port", 6001)),
        binary=found or "",
        options=tuple(str(o) for o in server.get("options", [])),
        client_version=int(version),
        timeout_s=float(server.get("timeout_s", 5.0)),
    )


def server_options(preset: WirePreset, port: int) -> list[str]:
    """The ``server::`` options that start a real server like the preset's (synch, trainer).

    Every parameter the Soccer Server preset holds is passed, so the binary runs the same
    numbers; the trainer is let in with the referee on or off as the preset says
    (``coach_w_referee`` or ``coach``). rcssserver
    19.0.0 takes no random seed (``random_seed`` is commented out of its parameters), so a
    real server's noise differs from run to run.
    """
    from field_models.soccer_server.wire import server_params

    params = server_params(preset.server)
    names = [
        "ball_decay",
        "ball_rand",
        "ball_size",
        "ball_speed_max",
        "ball_accel_max",
        "player_size",
        "player_decay",
        "player_rand",
        "player_speed_max",
        "player_accel_max",
        "inertia_moment",
        "dash_power_rate",
        "kick_power_rate",
        "kickable_margin",
        "kick_rand",
        "visible_angle",
        "visible_distance",
        "quantize_step",
        "quantize_step_l",
        "audio_cut_dist",
        "say_msg_size",
        "send_step",
    ]
    out = [f"server::{n}={_value(params[n])}" for n in names]
    if preset.server.sensing.perfect:
        out += ["server::quantize_step=0.0001", "server::quantize_step_l=0.0001"]
    out += [
        "server::synch_mode=true",
        "server::coach_w_referee=true" if preset.server.dynamics.referee else "server::coach=true",
        f"server::port={port}",
        f"server::coach_port={port + 1}",
        f"server::olcoach_port={port + 2}",
        "server::game_logging=false",
        "server::text_logging=false",
        *preset.options,
    ]
    return out


def _value(value: object) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float) and math.isfinite(value):
        return repr(value)
    return str(value)
