"""The ``rcssserver`` field model's registry entry: a Soccer Server driven over UDP.

See :class:`field_models.registry.FieldModelEntry`. A preset (``field_models/presets/rcssserver``)
names the server and the Soccer Server preset it runs:

.. code-block:: toml

    [server]
    start = "served"          # served: our model on the wire, in this process, one per arena
                              # address: a server already running at host:port (synch mode,
                              #          server::coach=true)
                              # binary: start a real rcssserver per arena (RCSSSERVER or binary)
    model_preset = "rcssserver_19"   # the soccer_server preset of the server (and of the facts)
    host = "127.0.0.1"
    port = 6000               # address: the player port; the trainer port is trainer_port
    trainer_port = 6001
    binary = ""               # binary: the executable; empty: the RCSSSERVER environment variable
    options = []              # binary: extra "server::name=value" options
    client_version = 17       # the arena's protocol (< 18: a real server sends no synch_see)
    timeout_s = 5.0           # longest wait for any answer

The facts are the Soccer Server model's of ``model_preset`` (a real binary is started with that
preset's parameters as ``server::`` options, so the facts describe it too); the model name is
``rcssserver``. Options: ``ball_noise`` becomes ``ball_rand``; ``perfect_perception`` runs our
served model without quantisation, and asks a real server for the finest quantisation it has
(``quantize_step`` 1e-4; it still rounds directions to degrees and fades identities).
"""

from __future__ import annotations

import dataclasses
import math
import os
import shutil
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path
from typing import Any, Literal

from field_models.arena import Arena, FieldFacts, FieldOptions
from field_models.presets import PresetError, preset_path, read_preset
from field_models.protocol import PlayerRef
from field_models.seeding import TrialRngs
from field_models.soccer_server import model as served_model
from field_models.soccer_server.params import ServerPreset

NAME = "rcssserver"
"""The registered name."""
DEFAULT_PRESET = "served"
"""Our own model on the wire, started in-process: needs nothing installed."""
BENCH_DRILLS = False
"""``robotsoccer bench`` times this model's cycles (:mod:`.bench`), not its drills."""
ENV_BINARY = "RCSSSERVER"
"""The environment variable that names a real rcssserver executable."""

Start = Literal["served", "address", "binary"]


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
    base = served_model.load(str(server.get("model_preset", "rcssserver_19")), options)
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
        client_version=int(server.get("client_version", 17)),
        timeout_s=float(server.get("timeout_s", 5.0)),
    )


def unavailable(preset: WirePreset) -> str | None:
    """Why this preset's server cannot be reached here (None: it can be tried)."""
    if preset.start == "binary" and not preset.binary:
        return f"no rcssserver executable: set {ENV_BINARY} (or the preset's binary) to one"
    return None


def conformance_limits(preset: WirePreset) -> dict[str, str]:
    """What the conformance suite cannot ask of this preset's server, and why.

    ``served`` keeps every promise. A real rcssserver 19.0.0 takes no random seed, so the same
    seed cannot replay; and it drops a seen player's uniform number with probability
    (d - unum_far_length) / (unum_too_far_length - unum_far_length) on its *noisy* distance d
    even with the finest quantisation (``VisualSenderPlayerV1::sendLowPlayer``): at the
    percept check's 20 m, unum_far_length, about one see in a hundred names the team only.
    A server already running (``address``) is seeded by whoever started it, not the trial.
    """
    if preset.start == "served":
        return {}
    if preset.start == "address":
        return {"check_determinism": "a running server's noise is not seeded by the trial"}
    return {
        "check_determinism": "rcssserver 19.0.0 takes no random seed: its noise differs "
        "from run to run",
        "identity": "rcssserver fades a player's number beyond unum_far_length (20 m) on its "
        "noisy distance, also with the finest quantisation",
    }


@lru_cache(maxsize=32)
def facts(preset: WirePreset) -> FieldFacts:
    """The Soccer Server model's facts of the preset's server, under this model's name."""
    return dataclasses.replace(served_model.facts(preset.server), model=NAME, preset=preset.name)


def build(
    preset: WirePreset,
    facts: FieldFacts,
    players: tuple[PlayerRef, ...],
    rngs: TrialRngs,
    *,
    keep_events: bool,
    trace: bool,
) -> Arena:
    """A fresh arena: its own server (served, binary) or new clients of a running one.

    Raises:
        RuntimeError: The server cannot be reached (:func:`unavailable`, or no answer).
    """
    from field_models.rcssserver.arena import WireArena

    why = unavailable(preset)
    if why is not None:
        raise RuntimeError(f"{NAME} preset {preset.name}: {why}")
    return WireArena(preset, facts, players, rngs, keep_events=keep_events, trace=trace)


def benchmarks(quick: bool = False) -> dict[str, Any]:
    """Cycles per second over the wire beside the in-process arena (:mod:`.bench`)."""
    from field_models.rcssserver.bench import benchmarks as measure

    return measure(quick)


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
