"""Speed of the Soccer Server model (the ``soccer_server`` figures).

* ``cycles_per_s.2_players`` — one trial at a time through the arena: 2 players and the ball,
  both receiving percepts on their see timer and acting on them (dynamics, sensing, hearing and
  the command queue all running).
* ``object_cycles_per_s.batch`` — many trials stepped together as arrays
  (:class:`~field_models.soccer_server.batch.BatchSoccerServer`), objects × cycles per second.
"""

from __future__ import annotations

import math
import time
from typing import Any

import numpy as np

from field_models.benchmarks import median_of, rally_cycles_per_s
from field_models.protocol import LEFT, RIGHT, PlayerRef
from field_models.registry import make_arena
from field_models.seeding import TrialRngs
from field_models.soccer_server.batch import BatchSoccerServer
from field_models.soccer_server.dynamics import SoccerServerModel
from field_models.soccer_server.params import load_server_preset

PLAYERS = (PlayerRef(LEFT, 1), PlayerRef(RIGHT, 1))


def arena_cycles_per_s(cycles: int, preset: str = "soccer_server_1996", seed: int = 0) -> float:
    """Cycles per wall second of a 2-player arena whose players chase the ball."""
    rngs = TrialRngs.for_trial(seed, 0)
    arena = make_arena("soccer_server", preset, PLAYERS, rngs)
    return rally_cycles_per_s(arena, PLAYERS, cycles, rngs)


def _drill_like_trial(model: SoccerServerModel | BatchSoccerServer, cycles: int) -> None:
    """A shooter kicks, a defender dashes every cycle and turns every fifth (noise, referee on)."""
    model.move_ball(-20.0, 0.0)
    model.move_player(1, -20.5, 0.0, 0.0)
    model.move_player(2, 5.0, 1.0, math.pi)
    model.kick(1, 80.0, 0.0)
    for t in range(cycles):
        if t % 5 == 0:
            model.turn(2, 0.05)
        else:
            model.dash(2, 60.0)
        model.step()


def dynamics_cycles_per_s(cycles: int, preset: str = "soccer_server_1996") -> float:
    """Cycles per wall second of the bare dynamics (no sensing) for 2 players + ball."""
    model = SoccerServerModel(load_server_preset(preset), PLAYERS, np.random.default_rng(0))
    rounds = max(1, cycles // 100)
    start = time.perf_counter()
    for _ in range(rounds):
        _drill_like_trial(model, 100)
    return rounds * 100 / (time.perf_counter() - start)


def batch_object_cycles_per_s(
    cycles: int, trials: int = 2000, preset: str = "soccer_server_1996"
) -> float:
    """Object-cycles per wall second of `trials` 2-player trials stepped as arrays."""
    rngs = [np.random.default_rng([1, k]) for k in range(trials)]
    batch = BatchSoccerServer(load_server_preset(preset), PLAYERS, rngs)
    start = time.perf_counter()
    _drill_like_trial(batch, cycles)
    return trials * (len(PLAYERS) + 1) * cycles / (time.perf_counter() - start)


def benchmarks(quick: bool = False) -> dict[str, Any]:
    """The Soccer Server figures (medians of 3 repeats; 1 when `quick`)."""
    repeats = 1 if quick else 3
    cycles = 4000 if quick else 20000
    single = median_of(repeats, lambda: arena_cycles_per_s(cycles))
    batch = median_of(repeats, lambda: batch_object_cycles_per_s(100 if quick else 300))
    return {
        "cycles_per_s": {"2_players": round(single)},
        "object_cycles_per_s": {"batch": round(batch)},
    }
