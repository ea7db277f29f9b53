"""The ``rcssserver`` field model's registry entry: a Soccer Server driven over UDP.

See :class:`field_models.registry.FieldModelEntry`. A preset (``field_models/presets/rcssserver``)
names the server and the Soccer Server preset it runs:

.. code-block:: toml

    [server]
    start = "served"          # served: our model on the wire, in this process, one per arena
                              # address: a server already running at host:port (synch mode,
                              #          server::coach=true)
                              # binary: start a real rcssserver per arena (RCSSSERVER or binary)
    model_preset = "rcssserver_19_async"  # the soccer_server preset of the server and the facts
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
from functools import lru_cache
from typing import Any

from field_models.arena import Arena, FieldFacts
from field_models.protocol import PlayerRef
from field_models.rcssserver.config import ENV_BINARY, NAME, WirePreset
from field_models.rcssserver.config import load as load  # the registry entry's loader
from field_models.seeding import TrialRngs
from field_models.soccer_server import model as served_model

DEFAULT_PRESET = "served"
"""Our own model on the wire, started in-process: needs nothing installed."""
BENCH_DRILLS = False
"""``robotsoccer bench`` times this model's cycles (:mod:`.bench`), not its drills."""


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
