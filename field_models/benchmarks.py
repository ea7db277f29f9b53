"""What every field model's speed benchmarks share: a load to drive it with, and medians.

A field model's entry module (:mod:`field_models.registry`) offers ``benchmarks(quick)``: its
engine's own speed figures (simulated seconds per wall second, cycles per second, ...). They
need players that move, so this module has the simplest client that does: chase the ball as it
is perceived. It is a load generator for benchmarks, not a skill.

These are benchmarks, not tests: machines are shared and noisy, so every figure is the median of
several repeats and no test asserts a speed.
"""

from __future__ import annotations

import statistics
from collections.abc import Callable

from field_models.arena import Arena
from field_models.protocol import Action, Dash, Percept, PlayerRef, Turn

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
