"""Speed of the robot testbed: simulated seconds per wall second (the ``robot_physics`` figures).

``realtime_factor.N_robots``: one process, N robots (two teams) placed at random, all chasing a
ball rolled from the centre, with camera, host, link and firmware running.
"""

from __future__ import annotations

import math
import time
from typing import Any

from field_models.benchmarks import ChaseLoad, drive, median_of
from field_models.protocol import LEFT, RIGHT, PlayerRef
from field_models.registry import make_arena
from field_models.seeding import TrialRngs


def realtime_factor(n_robots: int, sim_seconds: float = 20.0, seed: int = 0) -> float:
    """Simulated seconds per wall second with `n_robots` chasing the ball."""
    players = tuple(PlayerRef(LEFT if i % 2 == 0 else RIGHT, i // 2 + 1) for i in range(n_robots))
    rngs = TrialRngs.for_trial(seed, 0)
    arena = make_arena("robot_physics", "small_size_1997", players, rngs)
    rng = rngs["placement"]
    pitch = arena.facts.pitch
    hl, hw = pitch.half_length_m, pitch.half_width_m
    for ref in players:
        x, y = rng.uniform(-0.9 * hl, 0.9 * hl), rng.uniform(-0.9 * hw, 0.9 * hw)
        arena.place_player(ref, float(x), float(y), float(rng.uniform(-math.pi, math.pi)))
    arena.place_ball(0.0, 0.0, 1.0, 0.5)
    minds = {ref: ChaseLoad() for ref in players}
    ticks = round(sim_seconds / arena.facts.dt_s)
    start = time.perf_counter()
    drive(arena, minds, ticks)
    return ticks * arena.facts.dt_s / (time.perf_counter() - start)


def benchmarks(quick: bool = False) -> dict[str, Any]:
    """The robot figures: real-time factor with 2 and 12 robots (medians of 3; 1 when quick)."""
    repeats = 1 if quick else 3
    sim = 5.0 if quick else 20.0
    two = median_of(repeats, lambda: realtime_factor(2, sim))
    twelve = median_of(repeats, lambda: realtime_factor(12, sim / 2))
    return {"realtime_factor": {"2_robots": round(two, 1), "12_robots": round(twelve, 1)}}
