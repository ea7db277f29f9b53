"""What every field model's speed benchmarks share: a load to drive it with, and medians.

A field model's entry module (:mod:`field_models.registry`) offers ``benchmarks(quick)``: its
engine's own speed figures (simulated seconds per wall second, cycles per second, ...). They
need players that move, so this module has the simplest client that does: chase the ball as it
is perceived. It is a load generator for benchmarks, not a skill.

These are benchmarks, not tests: machines are shared and noisy, so every figure is the median of
several repeats and no test asserts a speed.
"""

from __future__ import annotations

import math
import statistics
import time
from collections.abc import Callable, Sequence

from field_models.arena import Arena
from field_models.protocol import Action, Dash, Percept, PlayerRef, Turn
from field_models.seeding import TrialRngs

CHASE_TOLERANCE_RAD = 0.3
"""The chaser turns toward the ball when it is more than this off its heading [rad]."""


class ChaseLoad:
    """Drive at the perceived ball: turn when it is off by more than a tolerance, else dash."""

    def act(self, percept: Percept) -> tuple[Action, ...]:
        """One decision per percept."""
        if percept.ball is None:
            return (Turn(0.5),)
        if abs(percept.ball.angle_rad) > CHASE_TOLERANCE_RAD:
            return (Turn(percept.ball.angle_rad),)
        return (Dash(100.0),)


def drive(arena: Arena, minds: dict[PlayerRef, ChaseLoad], ticks: int) -> None:
    """Step `arena` for `ticks`, every percept answered by its player's mind."""
    for _ in range(ticks):
        for percept in arena.step():
            arena.submit(percept.player, minds[percept.player].act(percept))


def median_of(repeats: int, measure: Callable[[], float]) -> float:
    """Median of `repeats` calls of `measure`."""
    return statistics.median(measure() for _ in range(repeats))


RALLY_CYCLES = 200
"""A fresh rally every this many cycles keeps the players running, turning and seeing."""


def rally_cycles_per_s(
    arena: Arena, players: Sequence[PlayerRef], cycles: int, rngs: TrialRngs
) -> float:
    """Cycles per wall second of a Soccer Server pitch whose two players chase the ball.

    Every :data:`RALLY_CYCLES` the coach kicks the ball off from a random spot (about 5% of
    the time goes to placement) and puts the players back 40 m either side of the centre.
    """
    minds = {ref: ChaseLoad() for ref in players}
    rng = rngs["placement"]
    start = time.perf_counter()
    done = 0
    while done < cycles:
        arena.place_ball(float(rng.uniform(-30, 30)), float(rng.uniform(-20, 20)), 2.0, 1.0)
        arena.place_player(players[0], -40.0, 0.0, 0.0)
        arena.place_player(players[1], 40.0, 0.0, math.pi)
        drive(arena, minds, RALLY_CYCLES)
        done += RALLY_CYCLES
    return done / (time.perf_counter() - start)
