"""Speed of a Soccer Server over the wire: synch-mode cycles per second beside in-process.

The same load both ways: 2 players chasing the ball (:class:`~field_models.benchmarks.ChaseLoad`)
on the ``rcssserver_19_async`` preset (the sensing a protocol-17 wire client gets), placed
afresh every
:data:`~field_models.benchmarks.RALLY_CYCLES` cycles. In process, the Soccer Server arena;
over the wire, the :class:`~field_models.rcssserver.arena.WireArena`: 1 trainer and 2 player
clients (the project's :class:`~field_models.rcssserver.client.WireClient`) talking
UDP to ``serve``'s game in synch mode. The served server runs in a thread of this process, so
server and clients share one interpreter (and its lock). The ratio is the figure to compare
across machines.

* ``cycles_per_s.wire`` — cycles per wall second over the wire (placements by the trainer
  included, 5 % of the cycles);
* ``cycles_per_s.in_process`` — the same minds on the in-process arena;
* ``ratio`` — wire / in-process.
"""

from __future__ import annotations

from typing import Any

from field_models.arena import Arena
from field_models.benchmarks import rally_cycles_per_s
from field_models.protocol import LEFT, RIGHT, PlayerRef
from field_models.registry import make_arena
from field_models.seeding import TrialRngs

PLAYERS = (PlayerRef(LEFT, 1), PlayerRef(RIGHT, 1))


def cycles_per_s(arena: Arena, cycles: int, rngs: TrialRngs) -> float:
    """Cycles per wall second of `arena` with two chasers, rallies restarted by the coach."""
    return rally_cycles_per_s(arena, PLAYERS, cycles, rngs)


def wire_and_local(cycles: int, preset: str = "served", seed: int = 0) -> tuple[float, float]:
    """(over the wire, in process) cycles per second, one arena each, the same seed."""
    rngs = TrialRngs.for_trial(seed, 0)
    wire = make_arena("rcssserver", preset, PLAYERS, rngs)
    try:
        over = cycles_per_s(wire, cycles, rngs)
    finally:
        close = getattr(wire, "close", None)
        if close is not None:
            close()
    rngs = TrialRngs.for_trial(seed, 0)
    local = make_arena("soccer_server", "rcssserver_19_async", PLAYERS, rngs)
    return over, cycles_per_s(local, cycles, rngs)


def benchmarks(quick: bool = False) -> dict[str, Any]:
    """The figures (module docstring); medians of 3 repeats (1 when quick)."""
    repeats = 1 if quick else 3
    cycles = 600 if quick else 3000
    runs = [wire_and_local(cycles) for _ in range(repeats)]
    wire = sorted(r[0] for r in runs)[len(runs) // 2]
    local = sorted(r[1] for r in runs)[len(runs) // 2]
    return {
        "cycles_per_s": {"wire": round(wire), "in_process": round(local)},
        "ratio": round(wire / local, 4),
    }
